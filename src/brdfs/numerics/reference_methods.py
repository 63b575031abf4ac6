"""The albedo methods besides the engine and the disk, each a function of one model and its angles
(:data:`brdfs.numerics.albedo.ALBEDO_METHODS` names them): a product Gauss–Legendre grid, the midpoint
rule of a program of 2001, ``scipy.integrate.dblquad`` and Monte Carlo with a model's own strategies;
and the judgement of a value against the tolerance asked for (:func:`status_against`), which the
front door shares.  A method's options are its keyword parameters, whose annotations give their
types and bounds (:mod:`brdfs.numerics.arguments` checks a call against them)."""
from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Annotated

import numpy as np

from brdfs.core.gauss_kronrod import BUDGET_EXHAUSTED, CONVERGED, Estimate
from brdfs.numerics.arguments import DEFAULT_ATOL, DEFAULT_RTOL, Above, AtLeast, OneOf, Tolerance
from brdfs.physics.geometry import light_direction

_EPS = np.finfo(float).eps
#: The dtype of a status array (room for the longest status, as ``np.where`` of the two gives).
_STATUS_DTYPE = f"<U{len(BUDGET_EXHAUSTED)}"


def status_against(value, error, tol):
    """``converged`` where the error is within max(rtol |value|, atol), else ``budget_exhausted``."""
    error = np.asarray(error)
    if error.size == 1:             # one value compared as floats: numpy's string where costs more
        met = float(error.item()) <= max(tol.rtol * abs(float(np.asarray(value).item())), tol.atol)
        return np.full(error.shape, CONVERGED if met else BUDGET_EXHAUSTED, _STATUS_DTYPE)
    return np.where(error <= tol.target(value), CONVERGED, BUDGET_EXHAUSTED)


def _per_angle(one):
    """A method for one angle at a time, lifted to an array of angles."""
    def method(model, theta, rtol, atol, **options):
        pairs = [one(model, float(t), rtol, atol, **options) for t in theta]
        value = np.array([p[0] for p in pairs], float)
        error = np.array([p[1] for p in pairs], float)
        return Estimate(value, error, 0, status_against(value, error, Tolerance(rtol, atol)))
    method.__doc__ = one.__doc__
    method.__wrapped__ = one             # its options are one's (brdfs.numerics.arguments reads them)
    return method


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
def product_grid(model, theta, rtol, atol, n: Annotated[int, AtLeast(2)] = 64):
    """N × N Gauss–Legendre in (u = cos θ_V, φ_V ∈ [0, π]), doubled by symmetry; error |Q_N − Q_{N/2}|."""
    value = _grid_sum(model, theta, n)
    return value, abs(value - _grid_sum(model, theta, n // 2)) if n >= 2 else np.inf


@_per_angle
def midpoint_grid(model, theta, rtol, atol, n_theta: Annotated[int, AtLeast(1)] = 90,
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
def scipy_dblquad(model, theta, rtol, atol, epsrel: Annotated[float | None, Above(0.0)] = None):
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
    return MonteCarloEstimate(mean, stderr, int(w.size), status_against(mean, stderr, Tolerance(rtol, atol)),
                              rounding=4 * _EPS * (np.log2(w.size) + 2) * np.abs(w).mean())


def _chunks(n, size=250_000):
    return [size] * (n // size) + ([n % size] if n % size else [])


def monte_carlo(model, theta, rtol, atol, n_samples: Annotated[int, AtLeast(2)] = 100_000,
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

