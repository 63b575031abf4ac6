"""Tables a model is built with: the albedo a(θ) of a model as a piecewise Chebyshev interpolant in
x = cos θ (:class:`AlbedoTable`), and the request that names one (:class:`TableRequest`).

A model that divides by or subtracts an albedo (the pumped models of sec. 2.3, eqs. 2.16–2.21;
Kulla–Conty's compensated microfacet models) receives its tables when it is built.  This module only
*evaluates* a table; computing one integrates the hemisphere, which is the numerics layer's work
(:func:`brdfs.numerics.pumping.tabulate_albedo`, behind the factory :func:`brdfs.numerics.tables.build`).
Nothing here imports above the physics layer, nor pandas (a table's tidy rows are written and read by
:class:`brdfs.numerics.pumping.AlbedoTable`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as cheb

from brdfs.core.estimate import Estimate

_BISECTIONS = 60            # halves a segment of [0, 1] below the spacing of doubles
#: Measured interpolation error at off-grid points × this = the reported error (also the margin by
#: which a crossing of table and cosine must exceed the table's error to count).
CHECK_SAFETY = 10.0


def lobatto_points(degree):
    """Chebyshev–Lobatto points cos(π j / D), j = 0 … D, on [−1, 1] (ascending)."""
    return np.cos(np.pi * np.arange(degree, -1, -1) / degree)


def chebyshev_coefficients(values):
    """Chebyshev coefficients of the interpolant through ``values`` at ascending Lobatto points."""
    degree = values.shape[-1] - 1
    s = lobatto_points(degree)
    return np.linalg.solve(cheb.chebvander(s, degree), values.T).T


@dataclass(frozen=True, eq=False)
class AlbedoTable:
    """a(θ) as a piecewise Chebyshev interpolant in x = cos θ, with an absolute error bound.

    Attributes
    ----------
    edges : ndarray (P + 1,)
        Piece boundaries in x, ascending from 0 to 1 (kinks of a, if any, are edges).
    values : ndarray (P, D + 1)
        Albedo at the Chebyshev–Lobatto points of each piece (ascending in x).
    error : float
        Absolute bound on |table − albedo of the model it tabulates| (interpolation + engine).
    model_rtol : float
        ε of the tabulated model: its relative distance to the exact pumped model.
    """

    edges: np.ndarray
    values: np.ndarray
    error: float
    model_rtol: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "_coef", chebyshev_coefficients(np.asarray(self.values, float)))
        object.__setattr__(self, "segments", self._monotone_segments())
        object.__setattr__(self, "cosine_crossings", self._crossings_with_cosine())

    @property
    def rtol(self):
        """δ: relative distance of the table to the exact albedo of the exact pumped model."""
        return self.model_rtol + self.error / float(np.min(self.values))

    def _local(self, x):
        x = np.clip(np.asarray(x, float), 0.0, 1.0)
        piece = np.clip(np.searchsorted(self.edges, x, side="right") - 1, 0, len(self.edges) - 2)
        lo, hi = self.edges[piece], self.edges[piece + 1]
        return piece, (2.0 * x - lo - hi) / (hi - lo)

    def __call__(self, x):
        """The tabulated albedo at x = cos θ (any shape)."""
        piece, s = self._local(x)
        out = np.empty(s.shape)
        for p in np.unique(piece):
            mask = piece == p
            out[mask] = cheb.chebval(s[mask], self._coef[p])
        return out

    def solve(self, y, lo, hi):
        """x in [lo, hi] (where the table is monotone) with table(x) = y; ``lo`` where there is none."""
        y = np.asarray(y, float)
        f_lo, f_hi = self(lo), self(hi)
        rising = f_hi >= f_lo
        inside = (np.minimum(f_lo, f_hi) <= y) & (y <= np.maximum(f_lo, f_hi))
        a, b = np.full(y.shape, lo), np.full(y.shape, hi)
        for _ in range(_BISECTIONS):
            mid = 0.5 * (a + b)
            below = (self(mid) < y) == rising
            a, b = np.where(below, mid, a), np.where(below, b, mid)
        return np.where(inside, 0.5 * (a + b), lo)

    def _monotone_segments(self):
        """Boundaries in x of the segments where the table is monotone (edges and extrema)."""
        points = list(self.edges)
        for p, coef in enumerate(self._coef):
            roots = cheb.chebroots(cheb.chebder(coef)) if coef.size > 2 else np.array([])
            real = roots[np.abs(roots.imag) < 1e-9].real
            lo, hi = self.edges[p], self.edges[p + 1]
            points += list(lo + (hi - lo) * (real[(real > -1) & (real < 1)] + 1) / 2)
        return np.unique(points)

    def _crossings_with_cosine(self):
        """x where table(x) − x changes sign by more than the table's error (kinks of max(a, cos θ))."""
        x = np.linspace(0.0, 1.0, 4097)
        d = self(x) - x
        significant = np.abs(d) > CHECK_SAFETY * self.error
        xs, ds = x[significant], d[significant]
        change = np.nonzero(np.sign(ds[:-1]) != np.sign(ds[1:]))[0]
        roots = []
        for i in change:
            a, b = xs[i], xs[i + 1]
            for _ in range(_BISECTIONS):
                mid = 0.5 * (a + b)
                a, b = (mid, b) if np.sign(self(mid) - mid) == np.sign(ds[i]) else (a, mid)
            roots.append(0.5 * (a + b))
        return np.array(roots)


def cosine_weighted_average(table) -> Estimate:
    """2 ∫₀¹ table(μ) μ dμ, exact for the piecewise polynomial (Gauss–Legendre, 2·(D+1) nodes a piece);
    its error is the table's bound (2 ∫ err μ dμ = err) plus rounding (Kulla & Conty's E_avg)."""
    degree = table.values.shape[1] - 1
    x, w = np.polynomial.legendre.leggauss(degree + 2)
    total = 0.0
    for lo, hi in zip(table.edges[:-1], table.edges[1:]):
        mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x
        total += 0.5 * (hi - lo) * np.sum(w * table(mu) * mu)
    return Estimate(2.0 * total, table.error + 64 * np.finfo(float).eps)


@dataclass(frozen=True)
class TableRequest:
    """What to tabulate for a model that needs a table: the albedo of ``model`` on the pieces
    ``edges`` of x = cos θ, each of degree ``degree`` or more (doubled until the interpolant meets
    ``target_rtol`` at the midpoints), nodes integrated to ``engine_rtol``; ``model_rtol`` is ε of
    the tabulated model (pumped models).  A value type, hashable, so the factory caches by it.

    A model names its requests in :meth:`brdfs.physics.models.base.BRDF.table_requests`; the factory
    :func:`brdfs.numerics.tables.build` computes them (:func:`brdfs.numerics.pumping.tabulate_albedo`).
    """

    model: object
    edges: tuple = (0.0, 1.0)
    degree: int = 16
    target_rtol: float = 1e-9
    engine_rtol: float = 1e-11
    model_rtol: float = 0.0


class MissingTable(ValueError):
    """A model that needs a table was built without it (in the physics layer, which computes none)."""
