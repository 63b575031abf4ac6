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

The last four live in :mod:`brdfs.numerics.reference_methods`.

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
(:func:`_answer`: its plan, run and merge), but no warnings: read their ``status``.  ``albedo_pairs(as_evaluated=True)``
leaves the model error out (a table factory that carries it itself, :mod:`brdfs.numerics.pumping`).

A model whose lobe's coordinates stop short of the hemisphere (a lobe about R reaches R·V ≥ 0 only)
is integrated by the engine only if it declares ``zero_beyond_lobe`` (f vanishes beyond); otherwise
the engine refuses it and ``auto`` takes the disk.

How a call is answered: :func:`_plan` groups its (model, θ) pairs by model once and gives each group
one route (a :class:`Group`: a declared end at 90°, the model's own route, azimuthal, polar,
hemisphere, scattering, or the disk); :func:`_run` runs each route once on all of its groups'
elements, in chunks of at most :data:`ENGINE_CHUNK`; every answer is written into the call's arrays
by one helper (:meth:`_Answer.put`).  The tolerance travels as one checked value
(:class:`~brdfs.numerics.arguments.Tolerance`).  Within :func:`reporting_progress` the chunk loop
reports its progress (the command line's progress bar).
"""
from __future__ import annotations

import contextlib
import contextvars
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from brdfs.core.estimate import DIVERGED, STALLED
from brdfs.core.gauss_kronrod import BUDGET_EXHAUSTED, CONVERGED, Estimate
from brdfs.numerics.arguments import (DEFAULT_ATOL, DEFAULT_RTOL, PER_MODEL, Tolerance, check_albedo_call,
                                      check_angles, check_table_call)
from brdfs.numerics.integrate import azimuthal, polar
from brdfs.numerics.integrate.disk import disk_albedo_many
from brdfs.numerics.integrate.grouping import indices_by_model
from brdfs.numerics.integrate.hemisphere import albedo_many
from brdfs.numerics.integrate.scattering import albedo_scattering
from brdfs.numerics.lens_mixture import own_albedo_estimate
from brdfs.numerics.reference_methods import (MonteCarloEstimate, midpoint_grid, monte_carlo, monte_carlo_albedo,
                                              product_grid, scipy_dblquad, status_against)
from brdfs.physics.lobes import SCATTERING
from brdfs.physics.models.base import BRDF, counting_evaluations

__all__ = ["albedo", "albedo_table", "albedo_pairs", "ALBEDO_METHODS", "DEFAULT_RTOL", "DEFAULT_ATOL",
           "Estimate", "NotConvergedWarning", "NotConvergedError", "EngineCannotIntegrate", "reporting_progress",
           "monte_carlo_albedo", "MonteCarloEstimate"]


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


# --- the plan: each group of elements on one route ----------------------------------------------

#: The engine's integral routes: ``route(models, theta, rtol=, atol=)`` integrates (model, angle)
#: pairs.  The 1-D ones (a closed-form inner integral) count their own nodes as evaluations, and
#: integrate again in two dimensions the elements they leave short of the tolerance.
ENGINE_ROUTES: dict[str, Callable[..., Estimate]] = {
    "azimuthal": azimuthal.albedo_many, "polar": polar.albedo_many,
    "hemisphere": albedo_many, "scattering": albedo_scattering}
_ONE_DIMENSIONAL = ("azimuthal", "polar")
#: The methods that take the engine's routes (``auto`` with the disk for what they leave short).
_ENGINE_METHODS = ("auto", "engine", "engine_2d", "azimuthal")


@dataclass(frozen=True)
class Group:
    """The elements ``rows`` of a call that share one integrand and one route.

    ``model`` is the integrand (the model asked for, or at exactly 90° its ``grazing_limit_model()``,
    then ``limit``), ``owner`` the model asked for (its ``evaluation_error``).  ``route``: ``declared``
    (a value the model declares), ``own`` (its ``albedo_estimate``), a key of :data:`ENGINE_ROUTES`,
    ``disk``, or another method's name; ``then_disk``: ``auto`` takes the disk where the route
    falls short."""

    model: BRDF
    owner: BRDF
    rows: np.ndarray
    route: str
    then_disk: bool = False
    limit: bool = False


def _plan(models, theta, method, own=True) -> list[Group]:
    """The groups of a call: its elements grouped by model object once, each model's elements at
    exactly 90° apart where the model declares its end (+inf, or its grazing limit integrated)."""
    groups = []
    at_90 = theta == 90.0
    any_90 = bool(at_90.any())
    for rows in indices_by_model(models):
        m, rows = models[rows[0]], np.asarray(rows)
        ends = rows[at_90[rows]] if any_90 else rows[:0]
        if ends.size and m.diverges_at_grazing:
            groups.append(Group(m, m, ends, "declared"))
        elif ends.size and (limit := m.grazing_limit_model()) is not m:
            groups.append(_routed(limit, m, ends, method, limit=True, own=own))
        else:
            ends = rows[:0]
        rest = rows[~at_90[rows]] if ends.size else rows
        if rest.size:
            groups.append(_routed(m, m, rest, method, own=own))
    return groups


def _routed(model, owner, rows, method, limit=False, own=True) -> Group:
    """The group of ``model``'s ``rows`` on the route ``method`` takes for it: another method's own;
    for the engine's methods the model's own route (``own``), else the engine's route for its lobe,
    or for ``auto`` the disk where the engine cannot integrate it."""
    if method not in _ENGINE_METHODS:
        return Group(model, owner, rows, method, limit=limit)
    if method == "azimuthal" and not azimuthal.supports(model):
        raise ValueError(f"the azimuthal method needs a closed-form azimuth, which {model.name!r} lacks")
    auto = method == "auto"
    if own and type(model).albedo_estimate is not BRDF.albedo_estimate:
        return Group(model, owner, rows, "own", auto, limit)
    refusal = _refusal(model)
    if refusal is not None:
        if auto:
            return Group(model, owner, rows, "disk", limit=limit)
        raise EngineCannotIntegrate(refusal)
    return Group(model, owner, rows, _engine_route(model, method != "engine_2d"), auto, limit)


def _refusal(model) -> str | None:
    """Why the engine cannot integrate ``model`` (without a route of its own), or None: no lobe, not
    symmetric about the plane of incidence (the engine integrates φ over [0, π] and doubles it), or a
    lobe whose coordinates reach only part of the hemisphere while f may not vanish beyond it."""
    if model.lobe is None:
        return f"{model.name!r} declares neither a lobe nor its own albedo route; use method='disk' (or 'auto')"
    if not model.symmetric_about_incidence_plane:
        return (f"{model.name!r} is not symmetric about the plane of incidence, which the engine assumes; "
                "use method='disk' (or 'auto')")
    if not model.lobe.reaches_hemisphere and not model.zero_beyond_lobe:
        return (f"{model.name!r} has a lobe whose coordinates reach only part of the hemisphere (about R: "
                "R·V ≥ 0) and does not declare zero_beyond_lobe; use method='disk' (or 'auto')")
    return None


def _engine_route(model, closed_form_azimuth=True) -> str:
    """The engine's route for a model without one of its own: Kirchhoff lobes in the scattering-vector
    frame, a closed-form azimuth in one dimension (``azimuthal``), f = D(H) S(N·L, N·V) in θ_V
    (``polar``, issue 24 E3), unless ``closed_form_azimuth`` is False; the others in two dimensions
    around R or N (``hemisphere``)."""
    if model.lobe.frame is SCATTERING:
        return "scattering"
    if closed_form_azimuth and azimuthal.supports(model):
        return "azimuthal"
    if closed_form_azimuth and polar.supports(model):
        return "polar"
    return "hemisphere"


# --- the run: each route once, on all of its elements, in chunks ---------------------------------

#: The most elements one adaptive run integrates at once: the driver's budget of intervals is the run's
#: (100,000), so 7,000 angles of Phong n = 20 in one run exhausted it and every angle went to the disk
#: (35 s against 0.4 s for 5,000); in chunks the cost is linear in the angles and the memory bounded.
ENGINE_CHUNK = 2000

_PROGRESS: contextvars.ContextVar = contextvars.ContextVar("albedo_progress", default=None)


@contextlib.contextmanager
def reporting_progress(callback: Callable[[int, int], None]):
    """Within the block, every albedo call (:func:`albedo`, :func:`albedo_table`, :func:`albedo_pairs`)
    calls ``callback(done, total)`` after each chunk of its elements (a command line's progress bar)."""
    token = _PROGRESS.set(callback)
    try:
        yield
    finally:
        _PROGRESS.reset(token)


class _Chunks:
    """Runs a route on at most :data:`ENGINE_CHUNK` elements at a time and tells the progress
    callback how many of the call's ``total`` elements are done."""

    def __init__(self, total):
        self.total, self.done, self.callback = total, 0, _PROGRESS.get()

    def run(self, route, models, theta, tol, counted=True):
        if theta.size <= ENGINE_CHUNK:
            parts = [route(models, theta, rtol=tol.rtol, atol=tol.atol)]
            self.advance(theta.size, counted)
        else:
            parts = []
            for k in range(0, theta.size, ENGINE_CHUNK):
                parts.append(route(models[k:k + ENGINE_CHUNK], theta[k:k + ENGINE_CHUNK], rtol=tol.rtol, atol=tol.atol))
                self.advance(parts[-1].value.size, counted)
        return _joined(parts)

    def advance(self, n, counted=True):
        if counted:
            self.done += n
        if self.callback is not None:
            self.callback(min(self.done, self.total), self.total)


def _joined(parts) -> Estimate:
    """Estimates of consecutive elements as one (a route's ``route`` kept where every part has one)."""
    if len(parts) == 1:
        return parts[0]
    join = lambda field: np.concatenate([np.asarray(getattr(p, field)) for p in parts])   # noqa: E731
    route = None if any(p.route is None for p in parts) else join("route")
    return Estimate(join("value"), join("error"), sum(int(p.evaluations or 0) for p in parts),
                    join("status").astype(str), route)


class _Answer:
    """The elements of a call as they are answered: value, error, status and route arrays, written
    by one helper (:meth:`put`) from each route's answer, and the evaluations the routes report."""

    def __init__(self, size):
        self.value, self.error = np.zeros(size), np.zeros(size)
        self.status, self.route = np.empty(size, object), np.empty(size, object)
        self.evaluations = 0

    def put(self, rows, est, route=None, where=None):
        """``est`` (of the elements ``rows``) into the answer, only at ``where`` (a mask over ``rows``)
        if given; its route, or ``route`` where it names none."""
        if where is not None:
            rows, est = rows[where], _taken(est, where)
        self.value[rows], self.error[rows], self.status[rows] = est.value, est.error, est.status
        self.route[rows] = route if est.route is None else np.asarray(est.route, str)

    def better(self, rows, est, route):
        """``est`` put where it reports a smaller error (or converged where the first value is not
        finite) than the answer so far at ``rows``."""
        first = np.where(np.isfinite(self.error[rows]), self.error[rows], np.inf)
        self.put(rows, est, route, (est.error < first) | ((est.status == CONVERGED) & ~np.isfinite(self.value[rows])))

    def estimate(self) -> Estimate:
        return Estimate(self.value, self.error, self.evaluations, self.status.astype(str), self.route.astype(str))


def _taken(est, where):
    return Estimate(np.asarray(est.value)[where], np.asarray(est.error)[where], est.evaluations,
                    np.asarray(est.status)[where], None if est.route is None else np.asarray(est.route)[where])


def _run(groups, theta, tol, method, options, ran=None) -> _Answer:
    """Every group on its route: the models' own routes (a model's may decline: None takes it to the
    engine), then each engine route once on all of its groups' elements, in chunks (or its answer in
    ``ran``, by route, where it has run already); the 1-D routes' short elements again in two
    dimensions, the Dirac parts added, and ``auto``'s short elements on the disk; other methods one
    call per group."""
    answer, chunks = _Answer(theta.size), _Chunks(theta.size)
    groups = [_own_route(g, answer, theta, tol, method, chunks) if g.route == "own" else g for g in groups]
    by_route: dict[str, list[Group]] = {}
    for g in groups:
        if g.route != "own":
            by_route.setdefault(g.route, []).append(g)
    for route, members in by_route.items():
        rows, models = _elements(members)
        if route == "declared":
            answer.put(rows, Estimate(np.full(rows.size, np.inf), np.zeros(rows.size), 0, np.full(rows.size, DIVERGED)),
                       "declared")
            chunks.advance(rows.size, True)
        elif route in ENGINE_ROUTES:
            if ran and route in ran:
                est = ran[route]
                chunks.advance(rows.size)
            else:
                est = chunks.run(ENGINE_ROUTES[route], models, theta[rows], tol)
            answer.put(rows, est, f"engine/{route}")
            if route in _ONE_DIMENSIONAL:
                answer.evaluations += int(est.evaluations)
                _short_ones_in_two_dimensions(answer, rows, models, theta, tol, chunks)
        elif route == "disk":
            est = _disk_run(models, theta[rows], tol, chunks)
            answer.put(rows, est)
            answer.evaluations += est.evaluations
        else:
            for g in members:
                est = ALBEDO_METHODS[route](g.model, theta[g.rows], tol.rtol, tol.atol, **options)
                answer.put(g.rows, est, route)
                answer.evaluations += int(est.evaluations or 0)
                chunks.advance(g.rows.size, True)
    for g in groups:
        if (g.route == "own" or g.route in ENGINE_ROUTES) and type(g.model).delta_albedo is not BRDF.delta_albedo:
            _with_the_dirac_part(answer, g, theta)
    _short_ones_on_the_disk(answer, [g for g in groups if g.then_disk], theta, tol, chunks)
    return answer


def _elements(groups):
    """The rows of ``groups`` in the order of the call (a route's elements in one run are in the
    order the call gave them, whatever their groups) and the integrand of each."""
    if len(groups) == 1:
        return groups[0].rows, [groups[0].model] * groups[0].rows.size
    rows = np.concatenate([g.rows for g in groups])
    models = [g.model for g in groups for _ in g.rows]
    order = np.argsort(rows, kind="stable")
    return rows[order], [models[k] for k in order]


def _own_route(group, answer, theta, tol, method, chunks) -> Group:
    """``group`` answered by its model's own route (``albedo_estimate``); where that declines (None,
    as a user's subclass may), the group the engine's route takes instead, to be run."""
    own = own_albedo_estimate(group.model, theta[group.rows], tol.rtol, tol.atol)
    if own is None:
        return _routed(group.model, group.owner, group.rows, method, group.limit, own=False)
    # a route that reports no status is judged by its error, not taken as converged
    status = status_against(own.value, own.error, tol) if own.status is None else np.asarray(own.status, str)
    answer.put(group.rows, Estimate(np.asarray(own.value, float), np.asarray(own.error, float), 0, status), "engine/own")
    chunks.advance(group.rows.size, True)
    return group


def _with_the_dirac_part(answer, group, theta):
    """The albedo of ``group``'s model's Dirac part (``delta_albedo``, e.g. He–Torrance's specular
    term; a model that does not override it has none) added to its elements."""
    delta = group.model.delta_albedo(theta[group.rows])
    answer.value[group.rows] += delta.value
    answer.error[group.rows] += delta.error


def _short_ones_in_two_dimensions(answer, rows, models, theta, tol, chunks):
    """A 1-D route's elements that missed their tolerance integrated again in two dimensions, where
    that reports the smaller error: within ~1e-4 of grazing the 1-D route of max(N·L, N·V) models
    loses ε / cos θ to rounding and can stop short of the tolerance."""
    short = answer.status[rows] != CONVERGED
    if not short.any():
        return
    second = chunks.run(albedo_many, [m for m, s in zip(models, short) if s], theta[rows[short]], tol, counted=False)
    answer.better(rows[short], second, "engine/hemisphere")


def _short_ones_on_the_disk(answer, groups, theta, tol, chunks):
    """``auto``: the elements of ``groups`` the engine left short of the tolerance on the disk, each
    keeping the answer with the smaller reported error (its route says which)."""
    if not groups:
        return
    rows, models = _elements(groups)
    short = answer.status[rows] != CONVERGED
    if not short.any():
        return
    second = _disk_run([m for m, s in zip(models, short) if s], theta[rows[short]], tol, chunks, counted=False)
    answer.better(rows[short], second, "disk")
    answer.evaluations += second.evaluations


def _disk_run(models, theta, tol, chunks, counted=True) -> Estimate:
    """The independent projected-disk reference (:func:`brdfs.numerics.integrate.disk.disk_albedo_many`);
    a value short of its tolerance keeps the driver's reason (``stalled`` or ``budget_exhausted``)."""
    est = chunks.run(disk_albedo_many, models, theta, tol, counted)
    met = status_against(est.value, est.error, tol) == CONVERGED
    reason = np.where(np.asarray(est.status) == CONVERGED, STALLED, np.asarray(est.status, str))
    evaluations = 0 if est.evaluations is None else est.evaluations
    return Estimate(est.value, est.error, evaluations, np.where(met, CONVERGED, reason), np.full(theta.size, "disk"))


def _merged_model_errors(answer, groups, theta, tol):
    """Each group's owner's ``evaluation_error`` (the error of its tables) added to its finite
    values; a value it takes above the tolerance is ``stalled`` (no refinement of the integral helps)."""
    for g in groups:
        if not g.owner.has_evaluation_error:
            continue
        rows = g.rows[np.isfinite(answer.value[g.rows])]
        if not rows.size:
            continue
        answer.error[rows] += g.owner.evaluation_error(theta[rows], answer.value[rows])
        missed = (answer.status[rows] == CONVERGED) & (answer.error[rows] > tol.target(answer.value[rows]))
        answer.status[rows[missed]] = STALLED


def _answer(models, theta, tol, method, options=None, model_error=True, own=True) -> Estimate:
    """Albedo of ``models[i]`` at ``theta[i]`` (1-D) by ``method``: planned, run and merged, with the
    meaning each model declares at 90° and its ``evaluation_error`` (unless ``model_error`` is False);
    ``own`` False: the models' own routes are not asked (their answer was None)."""
    with counting_evaluations() as count:
        groups = _plan(models, theta, method, own)
        answer = _run(groups, theta, tol, method, options or {})
        if model_error:
            _merged_model_errors(answer, groups, theta, tol)
        for g in groups:
            if g.limit:
                answer.route[g.rows] = np.char.add(answer.route[g.rows].astype(str), ":grazing_limit")
    est = answer.estimate()
    return Estimate(est.value, est.error, count[0] + est.evaluations, est.status, est.route)


def _engine(model, theta, rtol, atol):
    """The engine: the model's own route, else its lobe's (an integral in one or two dimensions)."""
    return _answer([model] * theta.size, theta, Tolerance(rtol, atol), "engine")


def _engine_2d(model, theta, rtol, atol):
    """The engine always in two dimensions (no closed-form azimuth)."""
    return _answer([model] * theta.size, theta, Tolerance(rtol, atol), "engine_2d")


def _azimuthal(model, theta, rtol, atol):
    """Only the engine's 1-D route of a closed-form azimuth."""
    return _answer([model] * theta.size, theta, Tolerance(rtol, atol), "azimuthal")


def _auto(model, theta, rtol, atol):
    """The engine, then the disk for the values the engine left short of the tolerance (or for all,
    where the engine cannot integrate the model); each value keeps the answer with the smaller
    reported error, and its route says which."""
    return _answer([model] * theta.size, theta, Tolerance(rtol, atol), "auto")


def _disk(model, theta, rtol, atol):
    """The independent projected-disk reference (:func:`brdfs.numerics.integrate.disk.disk_albedo_many`)."""
    return _answer([model] * theta.size, theta, Tolerance(rtol, atol), "disk")


# --- the front door's helpers -------------------------------------------------------------------

def _all_in(status, *kinds) -> bool:
    """Whether every value's status is one of ``kinds`` (one value compared as a str: numpy's string
    comparison costs a single-angle call more than the answer it checks)."""
    status = np.asarray(status)
    if status.size == 1:
        return status.item() in kinds
    return bool(np.all(np.isin(status, kinds)))


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
    "product_grid": product_grid,
    "midpoint_grid": midpoint_grid,
    "dblquad": scipy_dblquad,
    "monte_carlo": monte_carlo,
}


# --- the front doors -------------------------------------------------------------------------

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
    tol = Tolerance.checked(rtol, atol)
    check_albedo_call(model, theta_deg, method, ALBEDO_METHODS, options, strict=strict, warn=warn)
    theta = np.asarray(theta_deg, float)
    est = _by_its_own_route(model, theta, tol) if method in ("auto", "engine") else None
    if est is None or est is _DECLINED:
        est = _by_its_engine_route(model, theta, tol, method, declined=est is _DECLINED) or \
            _answer([model] * theta.size, theta.ravel(), tol, method, options, own=est is None)
    shape = theta.shape
    est = Estimate(est.value.reshape(shape), est.error.reshape(shape), est.evaluations,
                   est.status.reshape(shape), est.route.reshape(shape))
    _report_not_converged(est, model, theta, method, tol, strict, warn)
    return est


#: :func:`_by_its_own_route`: the model's own route declined (None), the engine's route is next.
_DECLINED = Estimate(np.zeros(0), np.zeros(0))


def _by_its_own_route(model, theta, tol) -> Estimate | None:
    """The short way of a model with a route of its own (a closed form: Oren–Nayar, the patch
    models), nothing to plan: its ``albedo_estimate`` where that answers every angle within the
    tolerance, the model has no tables' error and declares nothing else at 90°; else None (the
    plan, which gives the same answer: a single call costs the closed form and little more);
    :data:`_DECLINED` where the route answered None."""
    if type(model).albedo_estimate is BRDF.albedo_estimate or model.has_evaluation_error:
        return None
    if _declares_its_end(model) and (theta == 90.0).any():
        return None
    with counting_evaluations() as count:
        own = own_albedo_estimate(model, theta.ravel(), tol.rtol, tol.atol)
        if own is None:
            return _DECLINED
        value, error = np.asarray(own.value, float), np.asarray(own.error, float)
        status = status_against(value, error, tol) if own.status is None else np.asarray(own.status, str)
        if not _all_in(status, CONVERGED):
            return None
        if type(model).delta_albedo is not BRDF.delta_albedo:
            delta = model.delta_albedo(theta.ravel())
            value, error = value + delta.value, error + delta.error
    return Estimate(value, error, count[0], status, np.full(value.shape, "engine/own"))


def _by_its_engine_route(model, theta, tol, method, declined=False) -> Estimate | None:
    """The short way of a single angle that the plan gives one of the engine's routes: the route's
    answer where it converged; else the rest of the run (:func:`_run` of that one group, on the
    route's answer: the 1-D route's second try in two dimensions, ``auto``'s disk).  None (the whole
    plan, run and merge) where more applies: tables' error, a Dirac part, or a group on another route
    (the model's own unless it ``declined``, a declared end at 90°, the disk)."""
    if (method not in ("auto", "engine") or theta.size != 1 or model.has_evaluation_error
            or type(model).delta_albedo is not BRDF.delta_albedo):
        return None
    flat = theta.ravel()
    if flat[0] == 90.0 and _declares_its_end(model):
        return None
    route = _single_route(model, method, own=not declined)
    if route not in ENGINE_ROUTES:
        return None
    with counting_evaluations() as count:
        est = ENGINE_ROUTES[route]([model], flat, rtol=tol.rtol, atol=tol.atol)
        if _all_in(est.status, CONVERGED) and _PROGRESS.get() is None:
            own = int(est.evaluations) if route in _ONE_DIMENSIONAL else 0      # as _run counts them
            return Estimate(est.value, est.error, count[0] + own, est.status, _ROUTE_OF_ONE[route].copy())
        answer = _run(_plan([model], flat, method, own=not declined), flat, tol, method, {}, ran={route: est})
    est = answer.estimate()
    return Estimate(est.value, est.error, count[0] + est.evaluations, est.status, est.route)


#: The route column of a single angle's answer on each engine route (copied, never handed out).
_ROUTE_OF_ONE = {route: np.full(1, f"engine/{route}") for route in ENGINE_ROUTES}


def _single_route(model, method, own) -> str:
    """The route :func:`_plan` gives ``model`` below 90° for ``method`` (``own``: its own route asked), kept
    while the model object lives (:data:`~brdfs.numerics.arguments.PER_MODEL`): the route depends on the
    model alone (its class's routes, its lobe, what it declares), where finding it again cost a single
    call ~4 µs."""
    return PER_MODEL.get(model, ("single route", method, own),
                         lambda: _routed(model, model, _NO_ROWS, method, own=own).route)


_NO_ROWS = np.zeros(0, np.intp)


def _declares_its_end(model) -> bool:
    """Whether ``model`` declares its albedo at exactly 90° (+inf, or its grazing limit's)."""
    return model.diverges_at_grazing or model.grazing_limit_model() is not model


def _report_not_converged(est, model, theta, method, tol, strict, warn):
    """Warn (or, ``strict``, raise) when a value is neither ``converged`` nor ``diverged``: how many,
    the worst reported error against the tolerance asked for, and what to try."""
    if not (strict or warn) or _all_in(est.status, CONVERGED, DIVERGED):
        return
    status = np.asarray(est.status)
    short = (status != CONVERGED) & (status != DIVERGED)
    value, error = np.asarray(est.value, float), np.asarray(est.error, float)
    target = np.fmax(tol.rtol * np.abs(value), tol.atol)          # atol where the value itself is NaN
    ratio = np.where(np.isfinite(error), error / np.where(target > 0, target, np.inf), np.inf)
    worst = np.flatnonzero(short)[np.argmax(np.where(short, ratio, -1.0)[short])]
    kinds = ", ".join(f"{int((status == k).sum())} {k}" for k in (BUDGET_EXHAUSTED, STALLED) if (status == k).any())
    by_model = float(np.ravel(model.evaluation_error(np.ravel(theta)[worst:worst + 1],
                                                     value.ravel()[worst:worst + 1]))[0]) if model.has_evaluation_error else 0.0
    if by_model > float(target.ravel()[worst]):
        advice = (f"a looser rtol: the model's own values ({model.evaluation_error_source}) carry an error of "
                  f"{by_model:.3g} there, more than the tolerance asked for; or {model.evaluation_error_remedy}")
    else:
        advice = ("method='disk'" if method != "disk" else "method='engine'") + " or a looser rtol"
    message = (f"albedo of {model.name!r} by method {method!r}: {int(short.sum())} of {status.size} values "
               f"did not converge ({kinds}); worst at theta = {float(np.ravel(theta)[worst]):.10g} deg: "
               f"reported error {float(error.ravel()[worst]):.3g} against the {float(target.ravel()[worst]):.3g} "
               f"asked for (rtol={tol.rtol:g}, atol={tol.atol:g}); the errors reported are honest bounds. Try {advice}, "
               "or read Estimate.status and Estimate.error (strict=True raises; warn=False is quiet)")
    if strict:
        raise NotConvergedError(message, est)
    warnings.warn(message, NotConvergedWarning, stacklevel=3)


def albedo_table(models, theta_deg, rtol=None, atol=None) -> Estimate:
    """Albedo of several models on a common grid by the engine: arrays of shape (len(models), len(theta)).

    The engine's batch door, with :func:`albedo`'s meaning element by element (the ends at 90°, the
    models' evaluation error; no warning: read ``status``)."""
    tol = Tolerance.checked(rtol, atol, "albedo_table()")
    check_table_call(models, theta_deg)
    theta = np.atleast_1d(np.asarray(theta_deg, float)).ravel()
    est = _answer([m for m in models for _ in theta], np.tile(theta, len(models)), tol, "engine")
    shape = (len(models), theta.size)
    return Estimate(est.value.reshape(shape), est.error.reshape(shape), est.evaluations,
                    est.status.reshape(shape), est.route.reshape(shape))


def albedo_pairs(models, theta_deg, rtol=None, atol=None, as_evaluated=False) -> Estimate:
    """Albedo of ``models[i]`` at ``theta_deg[i]`` by the engine, in one adaptive run (for derived
    quantities that need many (model, angle) pairs at once: maxima, mean albedos), with
    :func:`albedo`'s meaning element by element (no warning: read ``status``).  ``as_evaluated``:
    f as evaluated, without the models' ``evaluation_error`` (a table factory that carries it itself)."""
    tol = Tolerance.checked(rtol, atol, "albedo_pairs()")
    check_angles("albedo_pairs()", theta_deg)
    theta = np.asarray(theta_deg, float).ravel()
    return _answer(list(models), theta, tol, "engine", model_error=not as_evaluated)
