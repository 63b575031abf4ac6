"""Directional albedo with the azimuth integrated in closed form: one dimension instead of two.

A model declares ``closed_form_azimuth = (frame, kernel)`` when, in its lobe's frame (the lobe
variable t of :mod:`.lobes`, azimuth φ), the albedo integral (eq. 1.18) factors as

    a(θ) = ∫₀^{t_max} w(β) K(β, θ) dt,      K = 8 ∫₀^π (J/4) g(L, V) [N·V]₊ dφ  (half frame)
                                             K = ∫₀^{2π} g(L, V) [N·V]₊ dφ      (mirror frame)

with a radial weight w (``model.azimuth_weight(cos β)``) and a kernel g whose φ-integral is
known in closed form.  In both frames N·V = A + B cos φ; in the half frame L·H = P + Q cos φ
(A = cos 2δ cos θ, B = sin 2δ sin θ, P = cos δ cos θ, Q = sin δ sin θ, dω_V = 4 (L·H) dω_H,
so J = 4 L·H); in the mirror frame A = cos α cos θ, B = sin α sin θ, J = 1.  The kernels:

* ``"nv"`` (g = 1): reciprocal Phong (eq. 2.6 / 3.5), reciprocal Blinn (eq. 1.34 / 3.33) —
  J(A, B) = ∫ [A + B cos φ]₊ dφ, or I₂(φ_h) = ∫₀^{φ_h} L·H · N·V dφ (φ_h: N·V = 0).
* ``"nv/max"`` (g = 1/max(N·L, N·V), as N·V/max = min(N·V, N·L)/N·L): the new model (eq. 3.10),
  corrected Blinn (eq. 3.34), corrected Ward (eq. 3.36) — J(A, B) − J(A − cos θ, B) over cos θ, or
  I₁(φ_μ) + (I₂(φ_h) − I₂(φ_μ))/cos θ (φ_μ: N·V = N·L).
* ``"sqrt(nv/nl)"`` (g = 1/√(N·L N·V)): Ward (eq. 2.8) — ∫ L·H √(N·V) dφ is a complete elliptic
  integral (:mod:`.ward_azimuth`).
* ``"G/nl"``: Cook–Torrance with G of eq. 2.10 — L·H G / cos δ = min(L·H / cos δ, 2 N·V, 2 N·L)
  is the lower envelope of three functions linear in cos φ, integrated piece by piece
  (:func:`_lower_envelope_integral`), divided by N·L.
* ``"1/nl"``: Cook–Torrance with G = 1 — ∫ L·H / (cos δ N·L) dφ.

The radial weight turns the lobe's own density into dt: C cos^n β sin β dβ = C/(n+1) dt for the
cosine powers (:class:`.lobes.PowerCosine`), and for the Beckmann lobe (t = 1 − exp(−tan²δ/m²),
sin δ dδ/dt = m² cos³δ / (2 e^{−tan²δ/m²})) w = C cos³δ/(8π) (Ward, corrected Ward) or C/(8π)
(Cook–Torrance, whose D carries 1/cos⁴δ and whose kernel carries the remaining 1/cos δ).

The integrand in t has kinks where a level circle N·V = c (c = 0, cos θ) touches the circle of
radius β, and (Cook–Torrance) where a switch of eq. 2.10's minimum starts or stops cutting it:
the breakpoints of the 2-D engine (:func:`.hemisphere.radial_breakpoints_many`).  A single angle
finds the switch radii only as precisely as its tolerance needs (:func:`single_angle_root_rtol`) and
adds a bound of what a kink off its breakpoint costs to the error (:class:`_KinkProbes`).  Where a kernel
divides a difference by cos θ it loses ε / cos θ relative digits near grazing; that rounding is
added to the error, and the albedo front door integrates elements that miss their tolerance in
two dimensions instead.

A single angle of a model whose kernel, lobe and weight the compiled route replicates
(:func:`compiled_spec`: ``"nv"``, ``"nv/max"`` and ``"sqrt(nv/nl)"``, a cosine-power or Beckmann lobe,
a weight declared as a form) takes :mod:`.azimuthal_compiled` (numba, where
:func:`brdfs.core.compiled.available`): the same breakpoints and onset interval to the bit (their
arithmetic compiled, their transcendental functions numpy's), then the same onset map, kernel, rounding
bounds and driver decisions in one compiled call, within ulps of this module's numpy path, which stays
the reference and the fallback.

Independent of the engine's two-dimensional quadrature (:mod:`.hemisphere`) except for the
breakpoints; the tests compare the two, and the accuracy map compares both with :mod:`.disk`.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from brdfs.core import compiled
from brdfs.core.estimate import CONVERGED, STALLED
from brdfs.core.gauss_kronrod import FILL_CHEAP, Estimate, NodeValues, estimate_of_one, integrate, number_of_one
from brdfs.numerics.integrate.grouping import first_of_model, indices_by_model
from brdfs.numerics.integrate.hemisphere import (ONSET_MIN_SPAN, ROOT_RTOL, TAIL, has_searched_kinks, horizon_onset,
                                                 level_azimuth, level_cos, radial_breakpoints_many, square_root_onset)
from brdfs.numerics.integrate.mean import positive_part_azimuth
from brdfs.numerics.integrate.ward_azimuth import sqrt_positive_part_moment
from brdfs.physics.distributions import Beckmann
from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.physics.lobes import HALF, MIRROR, MicrofacetLobe, PowerCosine
from brdfs.physics.models.base import BRDF

_EPS = np.finfo(float).eps


def supports(model) -> bool:
    """Whether :func:`albedo_azimuthal` applies to ``model``: it declares ``closed_form_azimuth``
    (every model answers it; None by default)."""
    return model.closed_form_azimuth is not None


def albedo_azimuthal(model, theta_deg, rtol=1e-10, atol=1e-14) -> Estimate:
    """a(θ) (eq. 1.18) of a ``model`` with a closed-form azimuthal integral at ``theta_deg``.

    Returns an :class:`Estimate` of the shape of ``theta_deg``.

    Raises
    ------
    ValueError
        For a model :func:`supports` rejects, or an angle outside [0, 90] degrees.

    Examples
    --------
    The new model at grazing incidence, eq. 3.27: a(90°) = (n+2)/(2(n+1)) = 22/42 for n = 20.

    >>> from brdfs.physics.models import model
    >>> a = albedo_azimuthal(model("phong_cosmin", n=20), 90.0)
    >>> abs(float(a.value) - 22 / 42) <= float(a.error) < 1e-10
    True
    """
    theta_deg = np.asarray(theta_deg, float)
    est = albedo_many([model] * theta_deg.size, theta_deg.ravel(), rtol=rtol, atol=atol)
    return Estimate(est.value.reshape(theta_deg.shape), est.error.reshape(theta_deg.shape),
                    est.evaluations, est.status.reshape(theta_deg.shape))


def _check_incidence(theta_deg, single):
    """Refuse angles outside [0, 90] degrees (NaN included); one angle is checked as a Python float,
    since the array comparisons cost a single call more than its answer."""
    inside = (0.0 <= float(theta_deg[0]) <= 90.0) if single else np.all((theta_deg >= 0) & (theta_deg <= 90))
    if not inside:
        outside = ~((theta_deg >= 0) & (theta_deg <= 90))
        raise ValueError(f"theta_deg must lie in [0, 90] degrees, got {theta_deg[outside][:5]!r}")


def albedo_many(models, theta_deg, rtol=1e-10, atol=1e-14) -> Estimate:
    """Albedo of ``models[i]`` at ``theta_deg[i]`` (as :func:`.hemisphere.albedo_many`), in one
    adaptive run; ``evaluations`` counts the kernel's radial nodes."""
    models = list(models)
    theta_deg = np.asarray(theta_deg, float).ravel()
    if len(models) != theta_deg.size:
        raise ValueError("albedo_many needs one model per angle")
    bad = [m for m in models if not supports(m)]
    if bad:
        raise ValueError(f"albedo_azimuthal needs a model that declares closed_form_azimuth, "
                         f"got {bad[0].name!r}")
    single = theta_deg.size == 1
    _check_incidence(theta_deg, single)
    if single:       # cos θ = sin(90° − θ) and sin θ in one call, the angles in radians on floats: the same bits
        t = float(theta_deg[0])
        both = np.sin(np.array([math.radians(90.0 - t), math.radians(t)]))
        mu, st = both[:1], both[1:]
    else:
        mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    spec = compiled_spec(models[0]) if single else None
    if spec is not None and not has_searched_kinks(models[0], mu):
        est = _compiled_single(spec, models[0], theta_deg, mu, st, rtol, atol)
        if est is not None:
            return est
    if single:       # one angle: its kink radii only as precise as its tolerance needs, their brackets kept
        tight, tail, root_rtol = _single_angle_settings(rtol)
        bp, kinks, t0 = radial_breakpoints_many(models, mu, st, theta_deg, tail=tail, root_rtol=root_rtol, kinks=True,
                                                touch=True, graded=tight)
    else:
        tight = False
        (bp, t0), kinks = radial_breakpoints_many(models, mu, st, theta_deg, tail=BATCH_TAIL, touch=True), None
    bp, *onset = horizon_onset(bp, t0, min_span=TIGHT_ONSET_MIN_SPAN if tight else None)
    if spec is not None and not kinks.element.size:
        est = _compiled_single_on(spec, bp[0], *(float(x[0]) for x in onset), float(mu[0]), float(st[0]), rtol, atol)
        if est is not None:
            return est
    kernels = ({0: _RadialKernel.of(models[0])} if single else
               {members[0]: _RadialKernel.of(models[members[0]]) for members in indices_by_model(models)})
    if single:                             # one element: its cos θ and sin θ as a (1, 1) column, not gathered per node row
        kernel, mu_1, st_1 = kernels[0], mu[:, None], st[:, None]

        def integrand(t, elem):
            value, rounding = kernel(t, mu_1, st_1)
            return NodeValues(value, value, rounding)
    elif len(kernels) == 1:                # one model: no regrouping of the nodes by model
        (kernel,) = kernels.values()

        def integrand(t, elem):
            value, rounding = kernel(t, mu[elem, None], st[elem, None])
            return NodeValues(value, value, rounding)
    else:
        index = first_of_model(models)

        def integrand(t, elem):
            value, rounding = np.empty_like(t), np.empty_like(t)
            for k in np.unique(index[elem]):
                rows = index[elem] == k
                e = elem[rows]
                value[rows], rounding[rows] = kernels[k](t[rows], mu[e, None], st[e, None])
            return NodeValues(value, value, rounding)

    if kinks is None or not kinks.element.size:
        # at ROOT_RTOL a misplaced kink costs ~1e-18 of the integral, below the 50 ε Σ|f| floor already in
        return integrate(square_root_onset(integrand, *onset), bp, rtol=rtol, atol=atol, fill=FILL_CHEAP)
    probes = _KinkProbes(kinks)
    # the probes are points in t: they ride on the integrand before the substitution
    est = integrate(square_root_onset(probes.riding_on(integrand), *onset), bp, rtol=rtol, atol=atol,
                    fill=FILL_CHEAP)
    error = est.error + probes.misplaced_kink_error(theta_deg.size)
    status = np.where((np.asarray(est.status) == CONVERGED) & (error > np.maximum(rtol * np.abs(est.value), atol)),
                      STALLED, est.status)
    return Estimate(est.value, error, est.evaluations + probes.evaluations, status)


def compiled_spec(model):
    """What the compiled single-angle route (:mod:`.azimuthal_compiled`) needs of ``model``, read from
    its declarations, or None where that route does not replicate its numpy one (then numpy answers):
    numba not available or switched off (:func:`brdfs.core.compiled.available`); a kernel other than
    ``"nv"``, ``"nv/max"`` and ``"sqrt(nv/nl)"``; a lobe other than exactly :class:`~brdfs.physics.lobes.PowerCosine` or a
    :class:`~brdfs.physics.lobes.MicrofacetLobe` of exactly :class:`~brdfs.physics.distributions.Beckmann`;
    a weight not declared as a form (:attr:`~brdfs.physics.models.base.BRDF.azimuth_weight_form`) or an
    ``azimuth_weight`` overridden (a user's subclass: the compiled route could not know it).

    Returns (lobe code, n or α, the lobe's rounding, kernel code, c, k, d) of the weight c cos^k β / d."""
    if not compiled.available():
        return None
    declared = model.closed_form_azimuth            # (frame, kernel): a user's may be a list
    kernel = None if declared is None else COMPILED_KERNELS.get(tuple(declared))
    if kernel is None or type(model).azimuth_weight is not BRDF.azimuth_weight:
        return None
    lobe, form = model.lobe, model.azimuth_weight_form
    if form is None:
        return None
    if type(lobe) is PowerCosine:
        code, shape = COMPILED_POWER_COSINE, lobe.n
    elif type(lobe) is MicrofacetLobe and type(lobe.distribution) is Beckmann:
        code, shape = COMPILED_BECKMANN, lobe.distribution.alpha
    else:
        return None
    c, k, d = form
    return code, float(shape), float(lobe.rounding), kernel, float(c), float(k), float(d)


#: The codes of the kernels and lobes :mod:`.azimuthal_compiled` replicates (it reads them from here, so
#: that choosing the route does not import numba): ``closed_form_azimuth`` → kernel code.
COMPILED_KERNELS = {(MIRROR, "nv"): 0, (MIRROR, "nv/max"): 1, (HALF, "nv"): 2, (HALF, "nv/max"): 3,
                    (HALF, "sqrt(nv/nl)"): 4}
#: ... and the lobes': t = 1 − cos^(n+1) β (:class:`~brdfs.physics.lobes.PowerCosine`), or Beckmann's CDF.
COMPILED_POWER_COSINE, COMPILED_BECKMANN = 0, 1


def _compiled_single(spec, model, theta_deg, mu, st, rtol, atol):
    """One angle of a model without kinks found numerically on the compiled route, its breakpoints
    included (:func:`.azimuthal_compiled.breakpoints_of_one`: :func:`.hemisphere.radial_breakpoints_many`
    and :func:`.hemisphere.horizon_onset` of the numpy path, to the bit)."""
    tight, tail, _ = _single_angle_settings(rtol)
    row, lo, hi = _azimuthal_compiled().breakpoints_of_one(model, mu, st, theta_deg, tail, tight,
                                                          TIGHT_ONSET_MIN_SPAN if tight else ONSET_MIN_SPAN)
    return _compiled_single_on(spec, row, lo, hi, float(mu[0]), float(st[0]), rtol, atol)


def _compiled_single_on(spec, row, lo, hi, mu, st, rtol, atol):
    """One angle on the compiled route from its breakpoint ``row`` and onset interval [``lo``, ``hi``]:
    :func:`.hemisphere.square_root_onset`'s W of the onset interval as numpy computes it, then one
    compiled call (:func:`.azimuthal_compiled.albedo_one`); None where the onset interval is not one
    :func:`.hemisphere.horizon_onset` gives (numpy answers)."""
    if 0.0 < lo < hi:
        scale = float(np.arcsinh(math.sqrt((hi - lo) / lo))) / (hi - lo)
    elif math.isnan(lo):
        scale = 0.0
    else:
        return None
    value, error, evaluations, status = _azimuthal_compiled().albedo_one(
        row, mu, st, *spec, lo, hi, scale, number_of_one(rtol), number_of_one(atol), FILL_CHEAP)
    return estimate_of_one(value, error, int(evaluations), compiled.status_name(status))


def _azimuthal_compiled():
    """:mod:`.azimuthal_compiled`, imported on the first use (:func:`brdfs.core.compiled.module`)."""
    return compiled.module("brdfs.numerics.integrate.azimuthal_compiled")


def single_angle_root_rtol(rtol):
    """The precision of the numerically found kink radii (:func:`.hemisphere.radial_breakpoints_many`)
    for a single angle at ``rtol``: 10⁻² √rtol of their distance from the ends of [0, 1] (1e-7 at
    rtol 1e-10, 1e-5 at 1e-6), at least :data:`.hemisphere.ROOT_RTOL`.  A kink of slope jump J
    placed off by δ costs at most J δ² / 2 (:class:`_KinkProbes` adds a bound of it to the error); the radial integrand's slopes are of order |a| / min(t, 1 − t), so that is of order
    |a| 10⁻⁴ rtol, and each factor 64 of precision given up is one multisection round less (the
    Torrance–Sparrow switch radii: 4–5 rounds at ROOT_RTOL, a third of a single call's setup)."""
    return min(1e-3, max(ROOT_RTOL, 1e-2 * math.sqrt(_smallest(rtol))))


class _KinkProbes:
    """A bound, per element, of what its numerically found kinks cost for not sitting exactly on
    their breakpoints.  A kink at x₀ in the bracket [lo, hi] of width w, with the breakpoint at the
    bracket's midpoint, lies at most w/2 inside the interval next to the breakpoint; if no node falls
    between them, both rules integrate the function as if it had no kink there and miss
    J (w/2)² / 2 = J w² / 8, J the jump of the derivative (if nodes fall between, K − G sees it).
    J ≤ |f'₋| + |f'₊|, the one-sided slopes estimated by differences over [lo − 4w, lo] and
    [hi, hi + 4w] (each on one side of the kink), with the values' rounding bounds; the bound
    reported, (|f'₋| + |f'₊|) w² / 2, is four times the miss, for the slopes' own error.

    The four probe points of each kink ride on the driver's first evaluation of the integrand
    (:meth:`riding_on`): a kernel call costs more than its points (Cook–Torrance's lower envelope:
    a second call for the probes alone cost a fifth of a single-angle call)."""

    def __init__(self, kinks):
        self.kinks, self.width = kinks, kinks.hi - kinks.lo
        self.points = np.stack([np.maximum(kinks.lo - 4 * self.width, 0.0), kinks.lo, kinks.hi,
                                np.minimum(kinks.hi + 4 * self.width, 1.0)], -1)
        self.value = self.rounding = None
        self.evaluations = 0

    def riding_on(self, integrand):
        """``integrand`` whose first call also evaluates the probes (as extra rows of 21 nodes, the
        four points padded with the last)."""
        def first_with_probes(t, elem):
            if self.value is not None:
                return integrand(t, elem)
            rows = np.concatenate([self.points, np.repeat(self.points[:, -1:], t.shape[1] - 4, 1)], 1)
            value, _, rounding = integrand(np.concatenate([t, rows]), np.concatenate([elem, self.kinks.element]))
            m = t.shape[0]
            self.value, self.rounding = value[m:, :4], np.abs(rounding[m:, :4])
            self.evaluations = rows.size
            return NodeValues(value[:m], value[:m], rounding[:m])
        return first_with_probes

    def misplaced_kink_error(self, n_el):
        """The bound of the class docstring summed per element (``n_el`` elements)."""
        slopes = []
        for i, j in ((0, 1), (2, 3)):
            step = self.points[:, j] - self.points[:, i]
            with np.errstate(divide="ignore", invalid="ignore"):
                slope = (np.abs(self.value[:, j] - self.value[:, i]) + self.rounding[:, i] + self.rounding[:, j]) / step
            slopes.append(np.where(step > 0, slope, 0.0))
        cost = (slopes[0] + slopes[1]) * self.width ** 2 / 2
        return np.bincount(self.kinks.element, np.where(np.isfinite(cost), cost, np.inf), n_el)


#: Initial breakpoints 1 − t of the 1-D route on a batch of angles: 10^(−1), 10^(−2) ahead of the 2-D
#: route's :data:`.hemisphere.TAIL`.  An interval from a kink in the lobe's body to 1 − t = 10^(−3)
#: sees the lobe's far end (t = 1) at a thousandth of its length, and a kink's √ onset at the other
#: end: Cook–Torrance (eq. 2.10), m = 0.005027 at 89.9°: the first partition's [0.11356, 0.999] was
#: 4.0e-8 off with K − G 1.5e-8, 1.15× over-confident at rtol 1e-4 and 1e-6.
BATCH_TAIL = np.concatenate([10.0 ** -np.arange(1.0, 3.0), TAIL])
#: Initial breakpoints 1 − t of the 1-D route on a single angle: 10^(−1), 10^(−2) ahead of the 2-D
#: route's :data:`.hemisphere.TAIL` (10^(−3), 10^(−6), ...).  The radial integrand has an endpoint
#: singularity at t = 1 (Phong n = 150: cos α = (1 − t)^(1/151)), and one Gauss–Kronrod interval
#: [0, 1 − 10^(−3)] sees it at a thousandth of its length: K − G 1.5e-5 (48.5°), a refinement round
#: at every tolerance.  Graded by tens up to 10^(−3), and the lobe's core cut in quarters of t (a wide
#: lobe, corrected Blinn n = 2, has its features there), the first partition meets rtol 1e-6 on its own
#: (the five curves of ``bench_engine_speed``: 1.0–1.1 rounds at 1e-6 against 1.7–2.1 before).  Only
#: for one angle, as ``fill``: there a round costs more than its intervals, while the elements of a
#: batch share their rounds (and keep the values they had, to the bit).
SINGLE_ANGLE_TAIL = np.concatenate([[0.75, 0.5, 0.25], 10.0 ** -np.arange(1.0, 3.0), TAIL])
#: The first partition of a single angle at tight tolerances (rtol below :data:`TIGHT_RTOL`): the
#: lobe's core cut in sixteenths of t (a wide lobe, corrected Blinn n = 2: 2.4 → 1.9 rounds) and the
#: whole tail graded by half decades, 1 − t = 10^(−1), 10^(−1.5), ..., 10^(−12.5).  With decades the
#: interval [1 − 10^(−3), 1 − 10^(−6)] alone kept K − G 1.4e-8 (Phong n = 150, 48.5°) and 1e-10 took
#: 3 rounds; graded by half decades every interval meets its share of a 1e-10 budget on the first
#: evaluation for Phong, the new model and Ward in most cases (1.1–1.4 rounds a call at 0°–89°, was
#: 3.0, with fewer evaluations in all: the refinement rounds it saves cost 32 intervals each).  Loose
#: tolerances keep the coarser :data:`SINGLE_ANGLE_TAIL`, which meets them in one round already.
TIGHT_SINGLE_ANGLE_TAIL = np.concatenate([1.0 - np.arange(1, 16) / 16, 10.0 ** -np.arange(1.0, 13.0, 0.5)])
for _tail in (BATCH_TAIL, SINGLE_ANGLE_TAIL, TIGHT_SINGLE_ANGLE_TAIL):
    _tail.flags.writeable = False        # constants (hemisphere._ends_of_tail keeps their points)
#: The rtol below which a single angle starts from :data:`TIGHT_SINGLE_ANGLE_TAIL`, graded toward
#: the declared levels' tangency radii and the range's end (``radial_breakpoints_many(graded=True)``,
#: :data:`.hemisphere.LEVEL_GRADING`), with every horizon onset mapped (:data:`TIGHT_ONSET_MIN_SPAN`).
TIGHT_RTOL = 1e-7
#: ``horizon_onset``'s ``min_span`` for a single angle below :data:`TIGHT_RTOL`: every onset interval
#: is mapped, the short ones too (corrected Blinn, n = 2, 8°: [0.5692, 0.625], the onset at t0 and a
#: breakpoint of the tail 1.1 t0 beyond it, kept K − G 5.1e-9 and cost a second round).
TIGHT_ONSET_MIN_SPAN = 1.0


def _single_angle_settings(rtol):
    """A single angle's (:func:`_tight`, :func:`_single_angle_tail`, :func:`single_angle_root_rtol`) at
    ``rtol``, kept per float (a call's tolerance is one of a few)."""
    return (_single_angle_settings_of if type(rtol) is float else _single_angle_settings_of.__wrapped__)(rtol)


@functools.lru_cache(maxsize=64)
def _single_angle_settings_of(rtol):
    return _tight(rtol), _single_angle_tail(rtol), single_angle_root_rtol(rtol)


def _single_angle_tail(rtol):
    """The initial tail breakpoints 1 − t of a single-angle call at ``rtol``: finer where the
    tolerance is tight, so that the first evaluation meets it (a round costs more than its nodes)."""
    return TIGHT_SINGLE_ANGLE_TAIL if _tight(rtol) else SINGLE_ANGLE_TAIL


def _tight(rtol):
    """Whether a single angle at ``rtol`` starts from the tight first partition (:data:`TIGHT_RTOL`)."""
    return _smallest(rtol) < TIGHT_RTOL


def _smallest(rtol):
    """The smallest of ``rtol`` (a number or an array), as a Python float."""
    return float(rtol) if isinstance(rtol, float) else float(np.min(rtol))


@dataclass(frozen=True)
class _RadialKernel:
    """w(β) K(β, θ) of one model at the lobe variable t, with what depends on the model alone looked
    up once per call rather than once per round (the lobe, the kernel, the weight)."""

    lobe: object
    kernel: object
    weight: object

    @classmethod
    def of(cls, model):
        frame, kernel = model.closed_form_azimuth
        return cls(model.lobe, KERNELS[frame][kernel], model.azimuth_weight)

    def __call__(self, t, mu, st):
        """Values and rounding bounds at nodes t (m, 21) of elements at cos θ ``mu``, sin θ ``st``."""
        # one context for the lobe and the kernel (whose parts ask no other: ``quiet``), once per round
        with np.errstate(divide="ignore", invalid="ignore"):
            cb, sb = self.lobe.angle(np.minimum(t, 1.0 - _EPS))
            value, rounding = self.kernel(cb, sb, mu, st)
        weight = self.weight(cb)
        value = weight * np.where(t < 1.0, value, 0.0)
        rounding = weight * rounding + (self.lobe.rounding + 3) * _EPS * np.abs(value)
        return value, rounding


# --- the kernels: called by _RadialKernel under np.errstate(divide="ignore", invalid="ignore") ---

# --- mirror frame: V at angle α from R -------------------------------------------------------

def _mirror_nv(cb, sb, mu, st):
    """J(A, B) = ∫₀^{2π} [N·V]₊ dφ."""
    full = positive_part_azimuth(cb * mu, sb * st, quiet=True)
    return full, 4 * _EPS * np.abs(full)


def _mirror_nv_over_max(cb, sb, mu, st):
    """∫₀^{2π} [N·V]₊ / max(N·L, N·V) dφ = (J(A, B) − J(A − cos θ, B)) / cos θ."""
    a, b = cb * mu, sb * st
    full, low = positive_part_azimuth(np.stack((a, a - mu)), b, quiet=True)    # both in one pass (a − mu has a's shape)
    quotient = (full - low) / mu
    rounding = 8 * _EPS * (np.abs(full) + np.abs(low)) / mu
    if np.all(mu > 0):
        return quotient, rounding
    grazing = 2 * level_azimuth(a, b, 0.0, quiet=True)        # N·L = 0: N·V / max(0, N·V) = 1 where N·V > 0
    value = np.where(mu > 0, quotient, grazing)
    return value, np.where(mu > 0, rounding, 4 * _EPS * grazing)


# --- half frame: H at angle δ from N ---------------------------------------------------------

def _half_lines(cb, sb, mu, st):
    """(P, Q) of L·H = P + Q cos φ and (A, B) of N·V = A + B cos φ."""
    return cb * mu, sb * st, (cb - sb) * (cb + sb) * mu, 2 * sb * cb * st


def _i2(p, q, a, b, phi, sin_phi):
    """∫₀^φ L·H · N·V dφ, given sin φ."""
    return p * a * phi + (p * b + q * a) * sin_phi + q * b * (0.5 * phi + 0.25 * np.sin(2 * phi))


def _i2_rounding(p, q, a, b):
    """The scale of :func:`_i2`'s rounding: (|pa| + |pb + qa| + |qb|) π."""
    return (np.abs(p * a) + np.abs(p * b + q * a) + np.abs(q * b)) * np.pi


def _half_nv(cb, sb, mu, st):
    """8 I₂(φ_h)."""
    p, q, a, b = _half_lines(cb, sb, mu, st)
    phi = level_azimuth(a, b, 0.0, quiet=True)
    return 8 * _i2(p, q, a, b, phi, np.sin(phi)), 64 * _EPS * _i2_rounding(p, q, a, b)


def _half_nv_over_max(cb, sb, mu, st):
    """8 [I₁(φ_μ) + (I₂(φ_h) − I₂(φ_μ)) / cos θ]: L·H N·V / max(N·L, N·V)."""
    p, q, a, b = _half_lines(cb, sb, mu, st)
    # the two levels N·V = 0 and N·V = cos θ in one pass: (φ_h, φ_μ), their sines once for I₁ and I₂.
    # Near grazing the band (I₂(φ_h) − I₂(φ_μ)) / cos θ keeps its digits because both levels are
    # evaluated by the same operations on nearly equal angles (their roundings cancel): sin φ as
    # √(1 − cos² φ), exact for the exact angle, lost that (1e-6 relative at 90° − 1e-9, within the
    # ε / cos θ bound but 1e4 times the error of these same operations).
    phis = level_azimuth(a, b, np.stack((0.0 * mu, mu)), quiet=True)
    sines = np.sin(phis)
    i2_h, i2_mu = _i2(p, q, a, b, phis, sines)
    i1_h, i1_mu = p * phis + q * sines
    band = (i2_h - i2_mu) / mu
    rounding = 16 * _EPS * _i2_rounding(p, q, a, b) / mu
    value = np.where(mu > 0, i1_mu + band, i1_h)   # N·L = 0: the weight is 1 where N·V > 0
    return 8 * value, 8 * np.where(mu > 0, rounding + 4 * _EPS * np.abs(i1_mu), 4 * _EPS * np.abs(value))


def _half_sqrt(cb, sb, mu, st):
    """8 ∫₀^π L·H √([N·V]₊ / N·L) dφ (Ward, eq. 2.8): a complete elliptic integral."""
    p, q, a, b = _half_lines(cb, sb, mu, st)
    w, rounding = sqrt_positive_part_moment(p, q, a, b)
    root = np.sqrt(mu)
    return 8 * w / root, 8 * (rounding + _EPS * np.abs(w)) / root


def _half_torrance_sparrow(cb, sb, mu, st):
    """8 ∫₀^{φ_h} min(L·H / cos δ, 2 N·V, 2 N·L) dφ / N·L (eq. 2.10: L·H G = min(L·H, 2 N·H N·V,
    2 N·H N·L)); at N·L = 0 the minimum over N·L tends to 2 wherever N·V > 0."""
    _, _, a, b = _half_lines(cb, sb, mu, st)
    c_h = level_cos(a, b, 0.0, quiet=True)
    lines = [(mu, sb / cb * st), (2 * a, 2 * b), (2 * mu, 0.0)]
    integral, rounding = _lower_envelope_integral(lines, c_h)
    value = np.where(mu > 0, integral / mu, 2 * np.arccos(c_h))
    rounding = np.where(mu > 0, rounding / mu, 4 * _EPS * value)
    return 8 * value, 8 * rounding


def _half_over_nl(cb, sb, mu, st):
    """8 ∫₀^{φ_h} L·H / (cos δ N·L) dφ (Cook–Torrance with G = 1; infinite at N·L = 0)."""
    _, _, a, b = _half_lines(cb, sb, mu, st)
    phi_h = level_azimuth(a, b, 0.0, quiet=True)
    value = 8 * (phi_h + sb / cb * st * np.sin(phi_h) / mu)
    return value, 8 * _EPS * np.abs(value)


def _lower_envelope_integral(lines, c_end):
    """∫ min_j (α_j + β_j cos φ) dφ over cos φ ∈ [c_end, 1], for lines (α_j, β_j) (arrays broadcast
    together), with a rounding bound.

    The pieces are cut where two lines cross; on each the lowest line integrates to
    α Δφ + β Δsin φ.  Both differences are formed from the cosines c₁ > c₂ of the piece's ends
    (Δφ = atan2(s₂c₁ − c₂s₁, c₁c₂ + s₁s₂), Δsin φ = (c₁² − c₂²)/(s₁ + s₂)), not from the angles: near
    φ = π/2, where the envelope is of the size of N·L, an angle carries an absolute error ε that
    would cost ε / N·L relative digits at grazing incidence."""
    alpha = np.stack(np.broadcast_arrays(*[np.asarray(l[0], float) + 0 * c_end for l in lines]), -1)
    beta = np.stack(np.broadcast_arrays(*[np.asarray(l[1], float) + 0 * c_end for l in lines]), -1)
    c_end = np.broadcast_to(c_end, alpha.shape[:-1])
    cuts = [np.ones_like(c_end), c_end]
    k = len(lines)
    for i in range(k):
        for j in range(i + 1, k):
            c = (alpha[..., i] - alpha[..., j]) / (beta[..., j] - beta[..., i])
            cuts.append(np.minimum(np.maximum(np.nan_to_num(c, nan=1.0, posinf=1.0, neginf=1.0), c_end), 1.0))
    cuts = -np.sort(-np.stack(cuts, -1), -1)                     # descending cos φ: ascending φ
    c1, c2 = cuts[..., :-1], cuts[..., 1:]
    s1, s2 = np.sqrt((1 - c1) * (1 + c1)), np.sqrt((1 - c2) * (1 + c2))
    d_phi = np.arctan2(s2 * c1 - c2 * s1, c1 * c2 + s1 * s2)
    d_sin = np.where(s1 + s2 > 0, (c1 - c2) * (c1 + c2) / (s1 + s2), 0.0)
    levels = alpha[..., None, :] + beta[..., None, :] * (0.5 * (c1 + c2))[..., None]
    lowest = np.argmin(levels, axis=-1)[..., None]
    a_low = np.take_along_axis(np.broadcast_to(alpha[..., None, :], levels.shape), lowest, -1)[..., 0]
    b_low = np.take_along_axis(np.broadcast_to(beta[..., None, :], levels.shape), lowest, -1)[..., 0]
    pieces = a_low * d_phi + b_low * d_sin
    rounding = 8 * _EPS * (np.abs(a_low) * (d_phi + 4 * _EPS) + np.abs(b_low) * np.abs(d_sin))
    return pieces.sum(-1), rounding.sum(-1)


KERNELS = {
    MIRROR: {"nv": _mirror_nv, "nv/max": _mirror_nv_over_max},
    HALF: {"nv": _half_nv, "nv/max": _half_nv_over_max, "sqrt(nv/nl)": _half_sqrt,
             "G/nl": _half_torrance_sparrow, "1/nl": _half_over_nl},
}
