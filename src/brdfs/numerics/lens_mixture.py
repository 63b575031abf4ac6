"""A model's own albedo route, a single angle of a lens mixture compiled where numba is available.

The patch mixtures (:class:`brdfs.physics.models.patch.LensMixtureAlbedo`) integrate the lens areas a_R,
weighted by p(R), in R.  A single angle's call is one or two evaluations of a few hundred nodes, which numpy
spends mostly on the overhead of its ~80 calls of the lens's formulas; :func:`own_albedo_estimate` answers
it instead by :func:`compiled_lens_albedo`: the same first partition (compiled too), the same two passes (a
rough one at rtol 1e-4, the final one from its first evaluation, to the target the rough sum sets), the same
error terms, with the lens areas and the driver compiled (:mod:`.lens_mixture_compiled`) and the model's p(R)
evaluated in numpy on each round's nodes.  Everything else (a batch of angles, a model whose ``albedo_estimate`` is its
own, no numba, ``BRDFS_COMPILED=0``) is the model's ``albedo_estimate``.
"""
from __future__ import annotations

import numpy as np

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import Estimate
from brdfs.physics.geometry import sin_incidence
from brdfs.physics.models.patch import LensMixtureAlbedo
from brdfs.physics.patch_geometry import (CLOSED_FORM_RTOL, ROUGH_RTOL, _cos_incidence_near_grazing,
                                          lens_kink_levels)


def own_albedo_estimate(model, theta, rtol, atol):
    """``model.albedo_estimate(theta, rtol, atol)``; a single angle of a model whose own route is the lens
    mixture's (:class:`LensMixtureAlbedo`, not overridden) by :func:`compiled_lens_albedo` where the compiled
    routes are available."""
    if np.size(theta) == 1 and type(model).albedo_estimate is LensMixtureAlbedo.albedo_estimate \
            and compiled.available():
        return compiled_lens_albedo(model.lens_mixture(), theta, rtol, atol)
    return model.albedo_estimate(theta, rtol, atol)


def compiled_lens_albedo(mixture, theta_deg, rtol, atol):
    """:func:`brdfs.physics.patch_geometry.lens_mixture_albedo` of one angle with ``single_graded``, by the
    compiled lens areas and driver: an :class:`Estimate` of ``theta_deg``'s shape (value and error, as the
    numpy route's, without status: the front door judges it)."""
    gkc, lmc = _compiled()
    theta = np.asarray(theta_deg, float)
    d, mu = sin_incidence(theta).item(), _cos_incidence_near_grazing(theta).item()
    # as Python floats: a float32 p_diffuse would round the sum, value and error alike, to float32
    covered = None if mixture.covered is None else float(mixture.covered)
    p_diffuse = float(mixture.p_diffuse)
    steep = mixture.steep_layer is not None
    partition, *begun = lmc.start_rough_pass(np.array(mixture.points, float), d, steep,
                                             *(mixture.steep_layer if steep else (0.0, 0.0)),
                                             lens_kink_levels(rtol), ROUGH_RTOL, atol)
    first = []                                            # the rough pass's first evaluation
    value, error, _, _, rounds = _passes(gkc, lmc, *begun, mixture, d, mu, first)
    constant = p_diffuse if covered is None else covered
    target = max(0.5 * rtol * abs(value + constant), atol)
    if not (rounds == 0 and error <= 0.25 * target):      # else the rough answer is the final one, to the bit
        value, error = _passes(gkc, lmc, *lmc.start_final_pass(partition, target, *first), mixture, d, mu)[:2]
    rounding = abs(p_diffuse) if covered is None else abs(covered) + abs(p_diffuse)
    pair = np.array((value + constant, error + CLOSED_FORM_RTOL * rounding))     # one array, two views
    return Estimate(pair[:1].reshape(theta.shape), pair[1:].reshape(theta.shape))


def _passes(gkc, lmc, st, done, x, mixture, d, mu, first=None):
    """The compiled driver's rounds from state ``st`` (``done``: finished; ``x``: its pending nodes) to its
    result, p(R) in numpy on each round's nodes and the lens areas compiled; ``first`` (a list) receives the
    first round's (values, known errors)."""
    covered = mixture.covered is not None
    while not done:
        st, high, extra, done, next_x = lmc.absorb_lens_round(st, x, _weight_at(mixture.weight, x), d, mu, covered)
        if first is not None and not first:
            first += high, extra
        x = next_x
    return gkc.result(st)


def _compiled():
    """The compiled driver and lens areas, imported at the first compiled call (:func:`brdfs.core.compiled.module`)."""
    return (compiled.module("brdfs.core.gauss_kronrod_compiled"),
            compiled.module("brdfs.numerics.lens_mixture_compiled"))


def _weight_at(weight, x):
    """p(x) as the compiled round takes it: float64, C-ordered, of ``x``'s shape (a weight may return a
    broadcastable array or a number)."""
    w = weight(x)
    if np.iscomplexobj(w):                 # as the numpy route's float products refuse it
        raise TypeError(f"the weight p(R) must be real, got values of type {np.asarray(w).dtype}")
    if type(w) is np.ndarray and w.shape == x.shape and w.dtype == np.float64 and w.flags.c_contiguous:
        return w
    return np.ascontiguousarray(np.broadcast_to(np.asarray(w, float), x.shape))
