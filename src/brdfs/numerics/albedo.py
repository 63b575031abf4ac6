"""Directional albedo a(L) = ∫ f(L, V) cos θ_V dω_V (eq. 1.18): one front door, several methods.

:func:`albedo` answers every albedo question of the package with the method asked for, in the
colour-science manner (one function per method and a table of them, :data:`ALBEDO_METHODS`):

* ``auto`` — the default: the engine, then the disk for the values where the engine did not
  converge (the better of the two answers, by reported error, is kept);
* ``engine`` — the lobe-following adaptive Gauss–Kronrod of :mod:`brdfs.numerics.integrate`
  (the only method that meets 1e-10 nearly everywhere), one-dimensional where the azimuthal integral
  has a closed form (:mod:`brdfs.numerics.integrate.azimuthal`);
* ``engine_2d`` — the engine always in two dimensions; ``azimuthal`` — only the 1-D route;
* ``disk`` — the independent projected-disk integration (:mod:`brdfs.numerics.integrate.disk`);
* ``product_grid`` — an N × N Gauss–Legendre grid in (cos θ_V, φ_V), error |Q_N − Q_{N/2}|;
* ``midpoint_grid`` — the midpoint rule on n_θ × n_φ cells of (θ_V, φ_V), as a program of 2001
  could have computed it (error: a rounding bound only);
* ``dblquad`` — ``scipy.integrate.dblquad`` over (θ_V, φ_V) with its own error estimate;
* ``monte_carlo`` — sampling V (``sampler``: ``cosine``, ``uniform``, ``beckmann_half_vector``, or
  ``model`` for the model's own :meth:`~brdfs.physics.models.base.BRDF.sample`); error = standard error.

Every method returns an :class:`Estimate` with ``value`` and ``error`` shaped like ``theta_deg``,
its cost in BRDF evaluations (an integer: nodes of a closed-form inner integral count as such), a
``status`` per value and a ``route`` per value.  A method's own ``evaluations`` counts what the front
door cannot see (the closed-form kernel's nodes; 0 for a method that only evaluates the BRDF), to
which :func:`albedo` adds the BRDF values it counts.

Statuses (:mod:`brdfs.core.estimate`): ``converged`` (error ≤ max(rtol |a|, atol)); ``diverged``
(the integral is infinite: value +inf, error 0, an exact answer); ``budget_exhausted`` (the run
stopped on its budget of rounds, intervals or samples while it could still refine); ``stalled``
(no refinement could reduce the error further).  Whenever a value is ``budget_exhausted`` or
``stalled``, :func:`albedo` warns (:class:`NotConvergedWarning`), or raises
(:class:`NotConvergedError`) with ``strict=True``; the error it reports is still an honest bound.

Routes: ``engine/azimuthal`` (the 1-D closed-form-azimuth route), ``engine/hemisphere`` (2-D around R
or N), ``engine/scattering`` (2-D in the scattering-vector frame), ``engine/own`` (the model's own
``albedo_estimate``), ``disk``, ``product_grid``, ``midpoint_grid``, ``dblquad``, ``monte_carlo``;
``declared`` for a value the model's declaration gives (+inf where it ``diverges_at_grazing``); a
suffix ``:grazing_limit`` where, at exactly 90°, the model's ``grazing_limit_model()`` was integrated.

The ends, decided by what the model declares (never by its name), for every method: at exactly
θ = 90° a model that ``diverges_at_grazing`` has albedo +inf (status ``diverged``), and a model whose
BRDF is singular at N·L = 0 has the albedo of its ``grazing_limit_model()`` (the limit a(θ), θ → 90°).
A model evaluated from tables adds its ``evaluation_error(theta, a)`` to every error (a pumped
model: ``evaluation_rtol`` × |a|; a Kulla–Conty model: its E table's share):
the distance of the model evaluated to the exact model it stands for; where that takes the error
above the tolerance, the value is ``stalled`` (no refinement of the integral can help: ask less,
or build the model with finer tables).

The route of the engine is read from what the model declares, never from its name or type: its
own ``albedo_estimate`` (None: it has none), its ``closed_form_azimuth``, and its lobe's
:class:`~brdfs.physics.lobes.Frame`.

:func:`albedo_table` and :func:`albedo_pairs` are the engine's batch doors for the package's own
derived quantities: the same ends and model error, element by element, through the same code
(:func:`_at_the_ends`), but no warnings: read their ``status``.  ``albedo_pairs(as_evaluated=True)``
leaves the model error out (a table factory that carries it itself, :mod:`brdfs.numerics.pumping`).

A model whose lobe's coordinates stop short of the hemisphere (a lobe about R reaches R·V ≥ 0 only)
is integrated by the engine only if it declares ``zero_beyond_lobe`` (f vanishes beyond); otherwise
the engine refuses it and ``auto`` takes the disk.
"""
from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Annotated

import numpy as np

from brdfs.numerics.arguments import Above, AtLeast, OneOf, check_albedo_call, check_table_call
from brdfs.numerics.integrate import azimuthal, polar
from brdfs.numerics.integrate.disk import disk_albedo_many
from brdfs.numerics.integrate.grouping import indices_by_model
from brdfs.core.estimate import DIVERGED, STALLED
from brdfs.core.gauss_kronrod import BUDGET_EXHAUSTED, CONVERGED, Estimate
from brdfs.numerics.integrate.hemisphere import albedo_many
from brdfs.numerics.integrate.scattering import albedo_scattering
from brdfs.physics.geometry import light_direction
from brdfs.physics.lobes import SCATTERING
from brdfs.physics.models.base import counting_evaluations


class NotConvergedWarning(RuntimeWarning):
    """Some values of an :func:`albedo` call missed the tolerance asked for (status
    ``budget_exhausted`` or ``stalled``); their reported errors are still honest bounds."""


class NotConvergedError(RuntimeError):
    """:func:`albedo` with ``strict=True``: some values missed the tolerance.  ``estimate`` holds
    the whole answer (values, honest errors, statuses, routes)."""

    def __init__(self, message, estimate):
        super().__init__(message)
        self.estimate = estimate


class EngineCannotIntegrate(ValueError):
    """The engine cannot integrate this model (no lobe and no route of its own, or not symmetric
    about the plane of incidence); ``auto`` then takes the disk for every value."""


DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-14
_EPS = np.finfo(float).eps


def _check_angles(theta_deg):
    theta = np.asarray(theta_deg, float)
    bad = ~((theta >= 0) & (theta <= 90))
    if bad.any():
        raise ValueError(f"incidence angles must lie in [0, 90] degrees, got {theta[bad][:5]!r}")
    return theta


# --- the engine ------------------------------------------------------------------------------

def _albedo_pairs(models, theta, rtol, atol, closed_form_azimuth=True):
    """Albedo of ``models[i]`` at ``theta[i]``: the model's own route where it has one
    (``albedo_estimate`` returns an :class:`Estimate`, not None), else the density integrated in the
    coordinates its lobe asks for — a cosine-power lobe with a closed-form azimuthal integral in one dimension
    (:mod:`.integrate.azimuthal`, unless ``closed_form_azimuth`` is False), Kirchhoff lobes in the
    scattering-vector frame (:mod:`.integrate.scattering`), the others in two dimensions around R
    or N (:mod:`.integrate.hemisphere`) — plus the albedo of its Dirac part (``model.delta_albedo``,
    e.g. He–Torrance's specular term; zero for most models).

    Everything that depends on the model alone (its own route, a refusal, its scheme, its Dirac part)
    is decided once per distinct model object, never per element: a single angle pays for one model,
    a batch of one model (a curve) for one, and neither for per-element masks."""
    groups = [(models[rows[0]], np.asarray(rows)) for rows in indices_by_model(models)]
    answers = []                                     # (rows, Estimate with status and route)
    by_scheme = {}
    for m, rows in groups:
        own = m.albedo_estimate(theta if len(groups) == 1 else theta[rows], rtol, atol)
        if own is not None:
            # a route that reports no status is judged by its error, not taken as converged
            status = _status(own.value, own.error, rtol, atol) if own.status is None else np.asarray(own.status, str)
            answers.append((rows, Estimate(np.asarray(own.value, float), np.asarray(own.error, float), 0, status,
                                           np.full(rows.size, "engine/own"))))
            continue
        _refuse_what_the_engine_cannot_integrate(m)
        by_scheme.setdefault(_engine_scheme(m, closed_form_azimuth), []).append(rows)
    closed_form_nodes = 0          # the 1-D route evaluates a closed form, not the BRDF: count its nodes
    for (scheme, name), parts in by_scheme.items():
        rows = parts[0] if len(parts) == 1 else np.sort(np.concatenate(parts))
        these, angles = ([models[i] for i in rows], theta[rows]) if rows.size < theta.size else (models, theta)
        est = _in_chunks(scheme, these, angles, rtol, atol)
        if scheme is azimuthal.albedo_many or scheme is polar.albedo_many:
            closed_form_nodes += est.evaluations
            est = _short_ones_in_two_dimensions(est, these, angles, rtol, atol, name)
        route = est.route if est.route is not None else np.full(rows.size, f"engine/{name}")
        answers.append((rows, Estimate(est.value, est.error, 0, np.asarray(est.status, str), route)))
    if len(answers) == 1 and len(groups) == 1:       # one model (one angle, or a curve): taken whole
        est, delta = answers[0][1], groups[0][0].delta_albedo(theta)
        return Estimate(est.value + delta.value, est.error + delta.error, closed_form_nodes, est.status, est.route)
    value, error, status, route = _gathered(answers, theta.size)
    for m, rows in groups:
        delta = m.delta_albedo(theta[rows])
        value[rows] += delta.value
        error[rows] += delta.error
    return Estimate(value, error, closed_form_nodes, status, route)


#: The most elements one adaptive run integrates at once: the driver's budget of intervals is the run's
#: (100,000), so 7,000 angles of Phong n = 20 in one run exhausted it and every angle went to the disk
#: (35 s against 0.4 s for 5,000); in chunks the cost is linear in the angles and the memory bounded.
#: A call of at most this many elements runs whole, as before.
ENGINE_CHUNK = 2000


def _in_chunks(scheme, models, theta, rtol, atol):
    """``scheme(models, theta, rtol=, atol=)`` (an integrator of (model, angle) pairs) on at most
    :data:`ENGINE_CHUNK` elements at a time, the answers joined."""
    if theta.size <= ENGINE_CHUNK:
        return scheme(models, theta, rtol=rtol, atol=atol)
    parts = [scheme(models[k:k + ENGINE_CHUNK], theta[k:k + ENGINE_CHUNK], rtol=rtol, atol=atol)
             for k in range(0, theta.size, ENGINE_CHUNK)]
    join = lambda field: np.concatenate([np.asarray(getattr(p, field)) for p in parts])   # noqa: E731
    route = None if any(p.route is None for p in parts) else join("route")
    evaluations = sum(int(p.evaluations or 0) for p in parts)
    return Estimate(join("value"), join("error"), evaluations, join("status").astype(str), route)


def _refuse_what_the_engine_cannot_integrate(model):
    """Raise :class:`EngineCannotIntegrate` for a model (without a route of its own) that the engine's
    coordinates would get wrong: no lobe, not symmetric about the plane of incidence (the engine
    integrates φ over [0, π] and doubles it), or a lobe whose coordinates reach only part of the
    hemisphere while f may not vanish beyond it (they would silently leave part of f out)."""
    if model.lobe is None:
        raise EngineCannotIntegrate(f"{model.name!r} declares neither a lobe nor its own albedo route; "
                                    "use method='disk' (or 'auto')")
    if not model.symmetric_about_incidence_plane:
        raise EngineCannotIntegrate(f"{model.name!r} is not symmetric about the plane of incidence, "
                                    "which the engine assumes; use method='disk' (or 'auto')")
    if not model.lobe.reaches_hemisphere and not model.zero_beyond_lobe:
        raise EngineCannotIntegrate(f"{model.name!r} has a lobe whose coordinates reach only part "
                                    "of the hemisphere (about R: R·V ≥ 0) and does not declare "
                                    "zero_beyond_lobe; use method='disk' (or 'auto')")


def _short_ones_in_two_dimensions(est, models, theta, rtol, atol, name):
    """A 1-D route's answer with the elements that missed their tolerance integrated again in two
    dimensions, where that reports the smaller error: within ~1e-4 of grazing the 1-D route of
    max(N·L, N·V) models loses ε / cos θ to rounding and can stop short of the tolerance.  ``name``:
    the 1-D route's."""
    status = np.asarray(est.status, str)
    route = np.full(theta.size, f"engine/{name}")
    if _all_in(status, CONVERGED):
        return Estimate(est.value, est.error, est.evaluations, status, route)
    short = status != CONVERGED
    second = _in_chunks(albedo_many, [m for m, s in zip(models, short) if s], theta[short], rtol, atol)
    value, error = np.array(est.value, float), np.array(est.error, float)
    better = second.error < error[short]
    rows = np.flatnonzero(short)[better]
    value[rows], error[rows], status[rows] = second.value[better], second.error[better], second.status[better]
    route = route.astype(object)
    route[rows] = "engine/hemisphere"
    return Estimate(value, error, est.evaluations, status, route.astype(str))


def _gathered(answers, size):
    """The (rows, Estimate) answers of :func:`_albedo_pairs` as new element arrays (value, error,
    status, route)."""
    value, error = np.zeros(size), np.zeros(size)
    status, route = np.empty(size, object), np.empty(size, object)
    for rows, est in answers:
        value[rows], error[rows], status[rows], route[rows] = est.value, est.error, est.status, est.route
    return value, error, status.astype(str), route.astype(str)


def _engine_scheme(model, closed_form_azimuth=True):
    """The engine's integrator for a model without a route of its own, and its route's name: Kirchhoff
    lobes in the scattering-vector frame, a closed-form azimuth in one dimension (``azimuthal``), or
    f = D(H) S(N·L, N·V) in θ_V (``polar``, issue 24 E3), unless ``closed_form_azimuth`` is False;
    the others in two dimensions around R or N."""
    if model.lobe.frame is SCATTERING:
        return albedo_scattering, "scattering"
    if closed_form_azimuth and azimuthal.supports(model):
        return azimuthal.albedo_many, "azimuthal"
    if closed_form_azimuth and polar.supports(model):
        return polar.albedo_many, "polar"
    return albedo_many, "hemisphere"


def _engine(model, theta, rtol, atol):
    return _albedo_pairs([model] * theta.size, theta, rtol, atol)


def _engine_2d(model, theta, rtol, atol):
    return _albedo_pairs([model] * theta.size, theta, rtol, atol, closed_form_azimuth=False)


def _azimuthal(model, theta, rtol, atol):
    if not azimuthal.supports(model):
        raise ValueError(f"the azimuthal method needs a closed-form azimuth, which {model.name!r} lacks")
    return _albedo_pairs([model] * theta.size, theta, rtol, atol)


# --- independent and historical methods ------------------------------------------------------

def _all_in(status, *kinds) -> bool:
    """Whether every value's status is one of ``kinds`` (one value compared as a str: numpy's string
    comparison costs a single-angle call more than the answer it checks)."""
    status = np.asarray(status)
    if status.size == 1:
        return status.item() in kinds
    return bool(np.all(np.isin(status, kinds)))


def _status(value, error, rtol, atol):
    met = np.asarray(error) <= np.maximum(rtol * np.abs(value), atol)
    return np.where(met, CONVERGED, BUDGET_EXHAUSTED)


def _per_angle(one):
    """A method for one angle at a time, lifted to an array of angles."""
    def method(model, theta, rtol, atol, **options):
        pairs = [one(model, float(t), rtol, atol, **options) for t in theta]
        value = np.array([p[0] for p in pairs], float)
        error = np.array([p[1] for p in pairs], float)
        return Estimate(value, error, 0, _status(value, error, rtol, atol))
    method.__doc__ = one.__doc__
    method.__wrapped__ = one             # its options are one's (brdfs.numerics.arguments reads them)
    return method


def _disk(model, theta, rtol, atol):
    """The independent projected-disk reference (:func:`brdfs.numerics.integrate.disk.disk_albedo_many`);
    a value short of its tolerance keeps the driver's reason (``stalled`` or ``budget_exhausted``)."""
    est = _in_chunks(disk_albedo_many, [model] * theta.size, theta, rtol, atol)
    met = _status(est.value, est.error, rtol, atol) == CONVERGED
    reason = np.where(np.asarray(est.status) == CONVERGED, STALLED, np.asarray(est.status, str))
    evaluations = 0 if est.evaluations is None else est.evaluations
    return Estimate(est.value, est.error, evaluations, np.where(met, CONVERGED, reason), np.full(theta.size, "disk"))


def _auto(model, theta, rtol, atol):
    """The engine, then the disk for the values the engine left short of the tolerance (or for all,
    where the engine cannot integrate the model); each value keeps the answer with the smaller
    reported error, and its route says which."""
    try:
        first = _engine(model, theta, rtol, atol)
    except EngineCannotIntegrate:
        return _disk(model, theta, rtol, atol)
    if _all_in(first.status, CONVERGED):
        return first
    short = np.asarray(first.status) != CONVERGED
    second = _disk(model, theta[short], rtol, atol)
    value, error = np.array(first.value, float), np.array(first.error, float)
    status, route = np.array(first.status, object), np.array(first.route, object)
    engine_error = np.where(np.isfinite(error[short]), error[short], np.inf)
    better = (second.error < engine_error) | ((second.status == CONVERGED) & ~np.isfinite(value[short]))
    rows = np.flatnonzero(short)[better]
    value[rows], error[rows] = second.value[better], second.error[better]
    status[rows], route[rows] = second.status[better], "disk"
    return Estimate(value, error, first.evaluations + second.evaluations, status.astype(str), route.astype(str))


def _grid_sum(model, theta, n):
    x, w = np.polynomial.legendre.leggauss(n)
    u, wu = 0.5 * (x + 1), 0.5 * w
    phi, wphi = 0.5 * np.pi * (x + 1), 0.5 * np.pi * w
    U, P = np.meshgrid(u, phi, indexing="ij")
    s = np.sqrt((1 - U) * (1 + U))
    V = np.stack([s * np.cos(P), s * np.sin(P), U], -1)
    f = model.unchecked(light_direction(theta), V)
    return float(2 * np.einsum("i,j,ij->", wu, wphi, f * U))


@_per_angle
def _product_grid(model, theta, rtol, atol, n: Annotated[int, AtLeast(2)] = 64):
    """N × N Gauss–Legendre in (u = cos θ_V, φ_V ∈ [0, π]), doubled by symmetry; error |Q_N − Q_{N/2}|."""
    value = _grid_sum(model, theta, n)
    return value, abs(value - _grid_sum(model, theta, n // 2)) if n >= 2 else np.inf


@_per_angle
def _midpoint_grid(model, theta, rtol, atol, n_theta: Annotated[int, AtLeast(1)] = 90,
                   n_phi: Annotated[int, AtLeast(1)] = 360):
    """Midpoint rule on n_θ × n_φ cells of (θ_V, φ_V): Σ f cos θ_V sin θ_V Δθ Δφ; a rounding bound as error."""
    L = light_direction(theta)
    d_theta, d_phi = 0.5 * np.pi / n_theta, 2 * np.pi / n_phi
    phi = (np.arange(n_phi) + 0.5) * d_phi
    total = bound = 0.0
    rows_per_block = max(1, 2 ** 18 // n_phi)          # a block of rows at a time bounds the memory
    theta_v = (np.arange(n_theta) + 0.5) * d_theta
    for start in range(0, n_theta, rows_per_block):
        tv = theta_v[start:start + rows_per_block, None]
        V = np.stack(np.broadcast_arrays(np.sin(tv) * np.cos(phi), np.sin(tv) * np.sin(phi), np.cos(tv)), -1)
        rows = model.unchecked(L, V) * np.cos(tv) * np.sin(tv) * d_theta * d_phi
        # rows summed one by one, in order, as the row-by-row loop summed them
        for row_sum, row_abs in zip(rows.sum(axis=-1), np.abs(rows).sum(axis=-1)):
            total += row_sum
            bound += row_abs
    return total, 4 * _EPS * (np.log2(n_theta * n_phi) + 2) * bound


@_per_angle
def _dblquad(model, theta, rtol, atol, epsrel: Annotated[float | None, Above(0.0)] = None):
    """``scipy.integrate.dblquad`` over θ_V ∈ [0, π/2], φ_V ∈ [0, π] (doubled by symmetry)."""
    from scipy.integrate import IntegrationWarning, dblquad  # here: scipy.integrate costs a job ~0.2 s to import

    L = light_direction(theta)

    def integrand(phi, theta_v):
        st = np.sin(theta_v)
        V = np.array([st * np.cos(phi), st * np.sin(phi), np.cos(theta_v)])
        return float(model.unchecked(L, V)) * np.cos(theta_v) * st

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        value, err = dblquad(integrand, 0.0, np.pi / 2, 0.0, np.pi, epsabs=0.0, epsrel=epsrel or rtol)
    return 2 * value, 2 * err


#: Samplers of the Monte Carlo method that are a model's own strategies (``model.sample``).
_MODEL_STRATEGIES = {"model": None, "cosine": "cosine", "uniform": "uniform", "beckmann_half_vector": "beckmann"}


def _draw(sampler, model, L, rng, n):
    """Weights f cos θ_V / p(V) of ``n`` directions V drawn by ``sampler``: a strategy of the model's
    own :meth:`~brdfs.physics.models.base.BRDF.sample` (``uniform`` and ``cosine`` are every model's;
    ``model`` is its default)."""
    try:
        strategy = _MODEL_STRATEGIES[sampler]
    except KeyError:
        raise ValueError(f"unknown sampler {sampler!r}; choose one of {', '.join(_MODEL_STRATEGIES)}") from None
    if sampler == "model":
        u = rng.random((n, model.sample_dimension()))
    else:                                    # two streams, as the readings have always drawn them
        u = np.stack([rng.random(n), rng.random(n)], -1)
    return model.sample(L, u, strategy)[1]


@dataclass(frozen=True)
class MonteCarloEstimate(Estimate):
    """A Monte Carlo mean: ``error`` is its standard error (one standard deviation of the estimator),
    ``rounding`` a bound of the error of computing the sum of these samples (a seeded reading is a
    number in its own right, reproducible to that bound)."""

    rounding: float = 0.0


def monte_carlo_albedo(model, theta_deg, sampler, n_samples, seed_sequence, rtol=DEFAULT_RTOL,
                       atol=DEFAULT_ATOL) -> MonteCarloEstimate:
    """Monte Carlo albedo with ``n_samples`` drawn by ``sampler``: a :class:`MonteCarloEstimate` with the
    mean, its standard error, ``evaluations`` = ``n_samples`` and the status of that error against
    max(rtol |value|, atol)."""
    rng = np.random.default_rng(seed_sequence)
    L = light_direction(theta_deg)
    w = np.concatenate([_draw(sampler, model, L, rng, k) for k in _chunks(n_samples)])
    mean = w.mean()
    stderr = w.std(ddof=1) / np.sqrt(w.size) if w.size > 1 else np.inf
    return MonteCarloEstimate(mean, stderr, int(w.size), _status(mean, stderr, rtol, atol),
                              rounding=4 * _EPS * (np.log2(w.size) + 2) * np.abs(w).mean())


def _chunks(n, size=250_000):
    return [size] * (n // size) + ([n % size] if n % size else [])


def _monte_carlo(model, theta, rtol, atol, n_samples: Annotated[int, AtLeast(2)] = 100_000,
                 sampler: Annotated[str, OneOf(_MODEL_STRATEGIES)] = "cosine",
                 seed: Annotated[int | Sequence[int], AtLeast(0)] = 0):
    """Monte Carlo with ``n_samples`` per angle, the k-th angle seeded by ``[*seed, k]``;
    error = standard error (one standard deviation)."""
    root = [int(s) for s in np.atleast_1d(seed)]
    runs = [monte_carlo_albedo(model, float(t), sampler, n_samples, [*root, k], rtol, atol)
            for k, t in enumerate(theta)]
    value = np.array([float(r.value) for r in runs])
    error = np.array([float(r.error) for r in runs])
    return Estimate(value, error, 0, np.array([str(r.status) for r in runs]))


#: The albedo methods by name, ``auto`` (the default of :func:`albedo`) first:
#: ``method(model, theta (1-D), rtol, atol, **options) -> Estimate``.  A method's options are its
#: function's keyword parameters, whose annotations give their types and bounds
#: (:mod:`brdfs.numerics.arguments` checks a call against them); a method sets ``route`` where it
#: knows more than its own name (the engine's sub-routes), else the front door fills in the name.
ALBEDO_METHODS: dict[str, Callable[..., Estimate]] = {
    "auto": _auto,
    "engine": _engine,
    "engine_2d": _engine_2d,
    "azimuthal": _azimuthal,
    "disk": _disk,
    "product_grid": _product_grid,
    "midpoint_grid": _midpoint_grid,
    "dblquad": _dblquad,
    "monte_carlo": _monte_carlo,
}


# --- the front door --------------------------------------------------------------------------

def albedo(model, theta_deg, method="auto", *, rtol=None, atol=None, strict=False, warn=True,
           **options) -> Estimate:
    """Directional albedo a(θ) = ∫ f(L, V) cos θ_V dω_V (equation 1.18 of the thesis) by ``method``
    (:data:`ALBEDO_METHODS`), vectorised over ``theta_deg``.

    Parameters
    ----------
    model : BRDF
        A model object (``brdfs.model("phong", n=20)``), not its name.
    theta_deg : float or array
        Incidence angles in [0°, 90°].
    method : str
        A key of :data:`ALBEDO_METHODS`; ``"auto"`` (the engine, then the disk where the engine did
        not converge) by default.
    rtol, atol : float
        Target error max(rtol |a|, atol) (defaults :data:`DEFAULT_RTOL`, :data:`DEFAULT_ATOL`),
        both finite and > 0.
    strict : bool
        Raise :class:`NotConvergedError` (which holds the estimate) instead of warning when a value
        misses the tolerance.
    warn : bool
        Warn (:class:`NotConvergedWarning`) when a value misses the tolerance; False for callers
        that push a method past its limits on purpose and read ``status`` themselves.
    **options
        The method's own settings (``n`` for ``product_grid``, ``n_samples``, ``sampler`` and
        ``seed`` for ``monte_carlo``, ...); the valid ones are the method's keyword parameters.

    Returns
    -------
    Estimate
        ``value``, ``error``, ``status`` and ``route`` shaped like ``theta_deg``, and
        ``evaluations``, the number of BRDF values computed.  At exactly 90° a model that
        ``diverges_at_grazing`` gives +inf, error 0, status ``diverged`` (no warning: an exact
        answer), and a model with a ``grazing_limit_model()`` gives that limit's albedo.

    Raises
    ------
    brdfs.ArgumentError
        A bad argument, before any work (one line naming the argument and its value).
    NotConvergedError
        With ``strict=True``, when a value is ``budget_exhausted`` or ``stalled``.

    Warns
    -----
    NotConvergedWarning
        When a value is ``budget_exhausted`` or ``stalled`` (unless ``strict`` or ``warn=False``).

    Examples
    --------
    >>> from brdfs import model

    The reciprocal Phong with c = (n+2)/2π reflects everything at normal incidence (eq. 3.6):

    >>> est = albedo(model("phong", n=20), [0.0, 45.0])
    >>> round(float(est.value[0]), 9), [str(s) for s in est.status], [str(r) for r in est.route]
    (1.0, ['converged', 'converged'], ['engine/azimuthal', 'engine/azimuthal'])

    Ward's albedo diverges at grazing incidence (sec. 2.2.1):

    >>> est = albedo(model("ward", m=0.1), 90.0)
    >>> float(est.value), float(est.error), str(est.status), str(est.route)
    (inf, 0.0, 'diverged', 'declared')
    """
    check_albedo_call(model, theta_deg, method, rtol, atol, options, strict=strict, warn=warn)
    run = ALBEDO_METHODS[method]
    theta = np.asarray(theta_deg, float)
    rtol = DEFAULT_RTOL if rtol is None else rtol
    atol = DEFAULT_ATOL if atol is None else atol
    with counting_evaluations() as count:
        est = _at_the_ends(_one_model_at_a_time(run, rtol, atol, options), [model] * theta.size, theta.ravel(),
                           rtol, atol, method)
    shape = theta.shape
    est = Estimate(est.value.reshape(shape), est.error.reshape(shape), count[0] + est.evaluations,
                   est.status.reshape(shape), est.route.reshape(shape))
    _report_not_converged(est, model, theta, method, rtol, atol, strict, warn)
    return est


def _one_model_at_a_time(run, rtol, atol, options):
    """``run`` (a method of :data:`ALBEDO_METHODS`, one model a call) as ``run_pairs(models, theta)``:
    one call per distinct model object (the model, and at 90° its grazing limit)."""
    def run_pairs(models, theta):
        groups = indices_by_model(models)
        if len(groups) == 1:
            return run(models[0], theta, rtol, atol, **options)
        value, error = np.empty(theta.size), np.empty(theta.size)
        status, route = np.empty(theta.size, object), np.empty(theta.size, object)
        evaluations = 0
        for rows in groups:
            est = run(models[rows[0]], theta[rows], rtol, atol, **options)
            value[rows], error[rows], status[rows] = est.value, est.error, est.status
            route[rows] = None if est.route is None else np.asarray(est.route, str)
            evaluations += est.evaluations
        return Estimate(value, error, evaluations, status, None if any(r is None for r in route) else route)
    return run_pairs


def _at_the_ends(run_pairs, models, theta, rtol, atol, method, model_error=True) -> Estimate:
    """``run_pairs(models, theta)`` (albedo of ``models[i]`` at ``theta[i]``) with the meaning each model
    declares at exactly 90°: +inf (``diverged``) where it ``diverges_at_grazing``, the albedo of its
    ``grazing_limit_model()`` where that is another integrand; plus its ``evaluation_error`` (the
    error of its tables) in every error, unless ``model_error`` is False (f as evaluated).
    :func:`albedo`, :func:`albedo_table` and :func:`albedo_pairs` all answer through here; what
    depends on the model alone is decided once per distinct model object, so that one angle (or a
    curve of one model) short of 90° costs one call of ``run_pairs`` and no per-element bookkeeping."""
    groups = [(models[rows[0]], np.asarray(rows)) for rows in indices_by_model(models)]
    at_90 = theta == 90.0
    if at_90.any():
        est = _with_the_declared_ends(run_pairs, models, groups, theta, at_90, method)
    else:
        est = run_pairs(models, theta)
        route = np.full(theta.size, method) if est.route is None else np.asarray(est.route, str)
        est = Estimate(est.value, est.error, est.evaluations, np.asarray(est.status, str), route)
    if not model_error or not any(m.has_evaluation_error for m, _ in groups):
        return est
    value, error, status = np.array(est.value, float), np.array(est.error, float), np.array(est.status, object)
    finite = np.isfinite(value)
    for m, rows in groups:
        rows = rows[finite[rows]]
        if not rows.size or not m.has_evaluation_error:
            continue
        error[rows] += m.evaluation_error(theta[rows], value[rows])
        # the model is known to no better than its tables: no refinement of the integral helps
        missed = (status[rows] == CONVERGED) & (error[rows] > np.maximum(rtol * np.abs(value[rows]), atol))
        status[rows[missed]] = STALLED
    return Estimate(value, error, est.evaluations, status.astype(str), est.route)


def _with_the_declared_ends(run_pairs, models, groups, theta, at_90, method):
    """``run_pairs`` on the elements it has to answer: those at exactly 90° of a model that
    ``diverges_at_grazing`` are +inf, error 0, ``diverged`` (route ``declared``), and those of a model
    with another ``grazing_limit_model()`` integrate that limit (route suffix ``:grazing_limit``)."""
    answered, limited = np.ones(theta.size, bool), np.zeros(theta.size, bool)
    integrands = list(models)
    for m, rows in groups:
        here = rows[at_90[rows]]
        if not here.size:
            continue
        if m.diverges_at_grazing:
            answered[here] = False
        elif (limit := m.grazing_limit_model()) is not m:
            limited[here] = True
            for i in here:
                integrands[i] = limit
    value, error = np.full(theta.size, np.inf), np.zeros(theta.size)
    status, route = np.full(theta.size, DIVERGED, object), np.full(theta.size, "declared", object)
    evaluations = 0
    if answered.any():
        rows = np.flatnonzero(answered)
        est = run_pairs(integrands if rows.size == theta.size else [integrands[i] for i in rows], theta[rows])
        value[rows], error[rows], status[rows] = est.value, est.error, est.status
        route[rows] = np.full(rows.size, method) if est.route is None else np.asarray(est.route, str)
        evaluations += est.evaluations
    if limited.any():
        route[limited] = np.char.add(route[limited].astype(str), ":grazing_limit")
    return Estimate(value, error, evaluations, status.astype(str), route.astype(str))


def _report_not_converged(est, model, theta, method, rtol, atol, strict, warn):
    """Warn (or, ``strict``, raise) when a value is neither ``converged`` nor ``diverged``: how many,
    the worst reported error against the tolerance asked for, and what to try."""
    if not (strict or warn) or _all_in(est.status, CONVERGED, DIVERGED):
        return
    status = np.asarray(est.status)
    short = (status != CONVERGED) & (status != DIVERGED)
    value, error = np.asarray(est.value, float), np.asarray(est.error, float)
    target = np.fmax(rtol * np.abs(value), atol)          # atol where the value itself is NaN
    ratio = np.where(np.isfinite(error), error / np.where(target > 0, target, np.inf), np.inf)
    worst = np.flatnonzero(short)[np.argmax(np.where(short, ratio, -1.0)[short])]
    kinds = ", ".join(f"{int((status == k).sum())} {k}" for k in (BUDGET_EXHAUSTED, STALLED) if (status == k).any())
    by_model = float(np.ravel(model.evaluation_error(np.ravel(theta)[worst:worst + 1],
                                                     value.ravel()[worst:worst + 1]))[0]) if model.has_evaluation_error else 0.0
    if by_model > float(target.ravel()[worst]):
        advice = (f"a looser rtol: the model's own values (its tables) carry an error of {by_model:.3g} there, "
                  "more than the tolerance asked for; or build it with finer tables")
    else:
        advice = ("method='disk'" if method != "disk" else "method='engine'") + " or a looser rtol"
    message = (f"albedo of {model.name!r} by method {method!r}: {int(short.sum())} of {status.size} values "
               f"did not converge ({kinds}); worst at theta = {float(np.ravel(theta)[worst]):.10g} deg: "
               f"reported error {float(error.ravel()[worst]):.3g} against the {float(target.ravel()[worst]):.3g} "
               f"asked for (rtol={rtol:g}, atol={atol:g}); the errors reported are honest bounds. Try {advice}, "
               "or read Estimate.status and Estimate.error (strict=True raises; warn=False is quiet)")
    if strict:
        raise NotConvergedError(message, est)
    warnings.warn(message, NotConvergedWarning, stacklevel=3)


def albedo_table(models, theta_deg, rtol=None, atol=None) -> Estimate:
    """Albedo of several models on a common grid by the engine: arrays of shape (len(models), len(theta)).

    The engine's batch door, with :func:`albedo`'s meaning element by element (the ends at 90°, the
    models' evaluation error; no warning: read ``status``)."""
    check_table_call(models, theta_deg, rtol, atol)
    theta = _check_angles(np.atleast_1d(theta_deg)).ravel()
    est = albedo_pairs([m for m in models for _ in theta], np.tile(theta, len(models)), rtol, atol)
    shape = (len(models), theta.size)
    return Estimate(est.value.reshape(shape), est.error.reshape(shape), est.evaluations,
                    est.status.reshape(shape), est.route.reshape(shape))


def albedo_pairs(models, theta_deg, rtol=None, atol=None, as_evaluated=False) -> Estimate:
    """Albedo of ``models[i]`` at ``theta_deg[i]`` by the engine, in one adaptive run (for derived
    quantities that need many (model, angle) pairs at once: maxima, mean albedos), with
    :func:`albedo`'s meaning element by element (no warning: read ``status``).  ``as_evaluated``:
    f as evaluated, without the models' ``evaluation_error`` (a table factory that carries it itself)."""
    theta = _check_angles(theta_deg).ravel()
    rtol = DEFAULT_RTOL if rtol is None else rtol
    atol = DEFAULT_ATOL if atol is None else atol
    with counting_evaluations() as count:
        est = _at_the_ends(lambda ms, th: _albedo_pairs(ms, th, rtol, atol), list(models), theta, rtol, atol,
                           "engine", model_error=not as_evaluated)
    return Estimate(est.value, est.error, count[0] + est.evaluations, est.status, est.route)
