"""Albedo pumping-up (section 2.3): f* = f / g with g ≥ max(a(L), a(V)) (eqs. 2.16–2.21).

Two correction terms (section 2.3.1/2.3.2)::

    g1(L, V) = max(a(L), a(V))                      (eq. 2.20, "plain")
    g2(L, V) = max(a(L), a(V), N·V, N·L)            (eq. 2.21, "controlled")

A pumped model is again a symmetric BRDF (:class:`brdfs.physics.models.pumped.Pumped`, a model of
the physics layer), so it can be pumped with its own albedo, level after level.  As the thesis
suggests for rendering (end of section 2.3), the albedo a pumped model divides by is precomputed once
per level as a one-variable table (:class:`AlbedoTable`, the interpolant of
:mod:`brdfs.physics.tables` with its tidy rows): a piecewise Chebyshev interpolant in x = cos θ whose
error is measured against the engine at off-grid points and carried into the error of everything
computed from it.  This module tabulates; the pumped model receives its table when it is built
(:func:`brdfs.numerics.tables.pump`).

Error budget.  Let ``f̃_k`` be the model actually evaluated at level k (built from interpolated
albedos) and ``f_k`` the exact pumped model.  If |f̃_k / f_k − 1| ≤ ε_k and the table of level k
satisfies |ã_k / a_k − 1| ≤ δ_k, then, since g is a maximum of its arguments and the dot
products are exact, |g̃_k / g_k − 1| ≤ δ_k and

    ε_{k+1} = (1 + ε_k) / (1 − δ_k) − 1,      δ_k = ε_k + (interpolation + engine error) / min ã_k.

Every value computed from ``f̃_k`` therefore carries the relative error ε_k on top of its own.

Speed.  The table nodes are integrated by :func:`pumped_albedo`, not by the hemisphere engine: in
V's polar coordinates every correction g depends on N·V alone, so the tables (a Chebyshev sum per
evaluation) are evaluated on the 1-D outer nodes only, and the azimuthal kernel of the original
lobe is shared by all levels.  This cut the two pumping tables from 75 s (Phong) and ~170 s
(Blinn) to about 1.3 s and 2.5 s; the tests compare it with the engine at 1e-11.
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial import chebyshev as cheb

from brdfs.numerics.albedo import albedo_pairs
from brdfs.core.gauss_kronrod import NodeValues, integrate
from brdfs.physics.lobes import MIRROR, PowerCosine
from brdfs.physics import tables as physics_tables
from brdfs.physics.models.pumped import CORRECTIONS, Pumped
from brdfs.physics.tables import CHECK_SAFETY as _CHECK_SAFETY
from brdfs.physics.tables import chebyshev_coefficients as _coefficients
from brdfs.physics.tables import lobatto_points

__all__ = ["AlbedoTable", "CORRECTIONS", "Pumped", "kink_edges", "lobatto_points", "model_rtol",
           "pumped_albedo", "pumped_models", "pumping_factor", "sequence_frame", "tables_from_frame",
           "tabulate_albedo"]

_MAX_DEGREE = 256
_PEAK_GRADES = 6          # azimuth breakpoints w, 4w, 16w, ... around a lobe's peak of width w


class AlbedoTable(physics_tables.AlbedoTable):
    """:class:`brdfs.physics.tables.AlbedoTable` (the interpolant a model is built with) with its tidy
    rows: what :func:`tabulate_albedo` returns and the table artifacts write and read."""

    def to_frame(self):
        """Tidy rows: one per node (piece, x, albedo), the error bounds repeated."""
        import pandas as pd  # the pipeline's extra; albedo() and the models need only numpy and scipy
        pieces, degree = self.values.shape[0], self.values.shape[1] - 1
        s = lobatto_points(degree)
        rows = []
        for p in range(pieces):
            lo, hi = self.edges[p], self.edges[p + 1]
            x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * s
            rows.append(pd.DataFrame({"piece": p, "x_lo": lo, "x_hi": hi, "node": np.arange(degree + 1),
                                      "cos_theta": x, "albedo": self.values[p]}))
        return pd.concat(rows, ignore_index=True).assign(albedo_err=self.error, model_rtol=self.model_rtol)

    @classmethod
    def from_frame(cls, df):
        """Inverse of :meth:`to_frame`."""
        df = df.sort_values(["piece", "node"])
        pieces = df.groupby("piece")
        edges = np.append(pieces["x_lo"].first().to_numpy(), df["x_hi"].iloc[-1])
        values = np.vstack([g["albedo"].to_numpy() for _, g in pieces])
        return cls(edges, values, float(df["albedo_err"].iloc[0]), float(df["model_rtol"].iloc[0]))


def _engine(model, x, rtol):
    """Albedo at x = cos θ: the polar-azimuth reduction :func:`pumped_albedo` for a pumped
    Phong/Blinn chain (its root in the mirror or half frame), else the hemisphere engine."""
    root, _ = _chain(model)
    if root.pumping_reducible and isinstance(root.lobe, PowerCosine):
        return pumped_albedo(model, x, rtol=rtol)
    theta = np.degrees(np.arccos(np.clip(x, 0.0, 1.0)))
    # f as evaluated (its own ε is carried by model_rtol), by the engine, as it always was
    return albedo_pairs([model] * theta.size, theta, rtol=rtol, as_evaluated=True)


def _chain(model):
    """(root model, [pumped levels from the outermost in]) of a possibly pumped model."""
    levels = []
    while isinstance(model, Pumped):
        levels.append(model)
        model = model.base
    return model, levels


def pumping_factor(model, nl, nv):
    """h(N·L, N·V) = f / f_root = Π 1/g_j over the levels of a pumped model (1 for an original one)."""
    _, levels = _chain(model)
    h = np.ones(np.broadcast_shapes(np.shape(nl), np.shape(nv)))
    for level in levels:
        h = h / level.correction_term(nl, nv)
    return h


def pumped_albedo(model, x, rtol=1e-10, atol=1e-14):
    """a*(x) for a model f = f_root(L, V) · h(N·L, N·V) whose root is a Phong (R·V) or Blinn
    (N·H) lobe without kinks of its own, at x = N·L (array), as a nested 1-D × 1-D integral.

    In V's own polar coordinates (μ_V = N·V, azimuth φ from the mirror azimuth) the correction
    h of every pumping level depends on μ_V only, so

        a*(μ_L) = 2 ∫₀¹ μ_V h(μ_L, μ_V) K(μ_L, μ_V) dμ_V,   K = ∫₀^π f_root(L, V(μ_V, φ)) dφ.

    h — the expensive part (Chebyshev tables, one per level) — is evaluated only on the outer
    nodes instead of on every two-dimensional node.  Outer breakpoints: the kinks of h
    (``model.nv_levels``) and μ_V = sin θ_L, where the support R·V > 0 of a Phong lobe starts to
    cut the azimuth circle; inner breakpoints: the azimuth where R·V = 0 and a graded set w, 4w,
    16w, … at the lobe's peak φ = 0 of width w — for Blinn at grazing incidence the lobe sits in
    the corner V = −L (μ_V → 0, φ → 0) with w ∝ μ_L + μ_V, which an ungraded rule steps over
    (it lost 1e-8 at 90° before the grading; the tests hold it to the engine).  The inner integral is
    asked for rtol/10 and its error is carried into the outer one (as in :mod:`.integrate.mean`).
    """
    x = np.atleast_1d(np.asarray(x, float))
    root, _ = _chain(model)
    mu_l = np.clip(x, 0.0, 1.0)
    s_l = np.sqrt(np.maximum(1.0 - mu_l * mu_l, 0.0))
    levels = [np.broadcast_to(np.asarray(c, float), mu_l.shape) for c in model.nv_levels(mu_l)]
    cols = [np.zeros_like(mu_l), *levels, s_l, np.ones_like(mu_l)]
    bp = np.sort(np.clip(np.column_stack(cols), 0.0, 1.0), axis=1)
    mirror_frame = root.lobe.frame is MIRROR

    def kernel(mu_v, elem):
        """K(μ_L, μ_V) at outer nodes mu_v (m, 21) of elements elem: an Estimate, flattened."""
        ml, sl = (np.broadcast_to(v[elem, None], mu_v.shape).ravel() for v in (mu_l, s_l))
        mv = mu_v.ravel()
        sv = np.sqrt(np.maximum(1.0 - mv * mv, 0.0))
        a, b = ml * mv, sl * sv                                 # R·V = a + b cos φ
        # the lobe peaks at φ = 0 with width w; near V = −L (Blinn, both grazing) w → 0
        peak = np.sqrt(2.0) if mirror_frame else np.sqrt(np.maximum(2.0 + 2.0 * (a - b), 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            w = np.clip(peak / np.sqrt((root.lobe.n + 1.0) * b), 1e-12, np.pi)
        cols = [np.zeros_like(mv), *(np.minimum(w * 4.0 ** k, np.pi) for k in range(_PEAK_GRADES))]
        if mirror_frame:
            with np.errstate(divide="ignore", invalid="ignore"):
                cols.append(np.arccos(np.clip(np.where(b > 0, -a / b, -1.0), -1.0, 1.0)))
        inner_bp = np.sort(np.column_stack(cols + [np.full_like(mv, np.pi)]), axis=1)

        def f_root(phi, e):
            L = np.stack(np.broadcast_arrays(sl[e, None], 0.0, ml[e, None]), -1)
            V = np.stack([-sv[e, None] * np.cos(phi), sv[e, None] * np.sin(phi),
                          np.broadcast_to(mv[e, None], phi.shape)], -1)
            return root.unchecked(L, V)

        return integrate(f_root, inner_bp, rtol=rtol / 10, atol=atol / 10)

    def outer(mu_v, elem):
        k = kernel(mu_v, elem)
        weight = 2.0 * mu_v * pumping_factor(model, mu_l[elem, None], mu_v)
        value = weight * k.value.reshape(mu_v.shape)
        return NodeValues(value, value, weight * k.error.reshape(mu_v.shape))

    return integrate(outer, bp, rtol=rtol, atol=atol)


def tabulate_albedo(model, edges=(0.0, 1.0), target_rtol=1e-9, engine_rtol=1e-11, degree=16, model_rtol=0.0):
    """Tabulate the albedo of ``model`` on pieces ``edges`` of x = cos θ.

    The degree D of every piece is doubled until the interpolant through D + 1 Lobatto points
    matches the integrated albedo at the D midpoints (the new points of degree 2D) within
    ``target_rtol`` × min a.  The reported error is ``10 ×`` the largest mismatch there plus the
    largest integration error, so it bounds the error between the check points too.  The nodes
    are integrated to ``engine_rtol`` by :func:`pumped_albedo` for pumped Phong/Blinn chains,
    else by the hemisphere engine (:func:`_engine`).

    Raises
    ------
    RuntimeError
        If degree 256 does not reach the target (a kink not declared as an edge).
    """
    edges = np.asarray(edges, float)
    values, mismatch, engine_err = [], 0.0, 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        d = degree
        fine = _engine(model, 0.5 * (lo + hi) + 0.5 * (hi - lo) * lobatto_points(2 * d), engine_rtol)
        while True:
            nodes, check = fine.value[::2], fine.value[1::2]
            s_check = lobatto_points(2 * d)[1::2]
            miss = np.max(np.abs(cheb.chebval(s_check, _coefficients(nodes)) - check))
            if miss <= target_rtol * np.min(fine.value) or 2 * d > _MAX_DEGREE:
                break
            d *= 2
            new = _engine(model, 0.5 * (lo + hi) + 0.5 * (hi - lo) * lobatto_points(2 * d)[1::2], engine_rtol)
            merged = np.empty(2 * d + 1)
            merged[::2], merged[1::2] = fine.value, new.value
            merged_err = np.empty(2 * d + 1)
            merged_err[::2], merged_err[1::2] = fine.error, new.error
            fine = type(fine)(merged, merged_err)
        if miss > target_rtol * np.min(fine.value):
            raise RuntimeError(f"albedo table of {model!r} on [{lo}, {hi}] misses {target_rtol} at degree {d}")
        values.append(nodes)
        mismatch, engine_err = max(mismatch, miss), max(engine_err, float(np.max(fine.error)))
    width = max(v.size for v in values)
    values = np.vstack([_resample(v, width - 1) for v in values])
    return AlbedoTable(edges, values, _CHECK_SAFETY * mismatch + engine_err, model_rtol)


def _resample(values, degree):
    """Values at the Lobatto points of ``degree`` ≥ their own (the same polynomial, exact to rounding)."""
    if values.size == degree + 1:
        return values
    return cheb.chebval(lobatto_points(degree), _coefficients(values))


def kink_edges(table, correction):
    """Piece edges for the table of the next level: the kinks of max(a, cos θ) (g2) and of ``table``."""
    edges = list(table.edges)
    if correction == "g2":
        edges += list(table.cosine_crossings)
    return np.unique(edges)


def model_rtol(model):
    """ε of a model: 0 for an original model, else from the table of the level below (module doc)."""
    return model.evaluation_rtol


def pumped_models(base, tables, correction):
    """``base`` and its pumped versions built from the tables of levels 0 … K−1 (no integration)."""
    models = [base]
    for table in tables:
        models.append(Pumped(models[-1], table, correction))
    return models


def sequence_frame(base, levels, target_rtol=1e-9, engine_rtol=1e-11):
    """The albedo tables of ``base`` pumped 0 … ``levels`` times with g1 and with g2, as tidy rows.

    Level 0 (``pumping = 'none'``) is tabulated once and shared by both sequences.
    Columns: ``pumping, level`` and those of :meth:`AlbedoTable.to_frame`.
    """
    import pandas as pd  # the pipeline's extra (see AlbedoTable.to_frame)
    first = tabulate_albedo(base, target_rtol=target_rtol, engine_rtol=engine_rtol)
    frames = [first.to_frame().assign(pumping="none", level=0)]
    for correction in CORRECTIONS:
        tables = [first]
        for level in range(1, levels + 1):
            model = pumped_models(base, tables, correction)[-1]
            tables.append(tabulate_albedo(model, kink_edges(tables[-1], correction), target_rtol, engine_rtol,
                                          model_rtol=model_rtol(model)))
            frames.append(tables[-1].to_frame().assign(pumping=correction, level=level))
    return pd.concat(frames, ignore_index=True)


def tables_from_frame(df, correction):
    """The tables of levels 0, 1, … of one sequence of :func:`sequence_frame`."""
    rows = df[(df["pumping"] == correction) | (df["level"] == 0)]
    return [AlbedoTable.from_frame(rows[rows["level"] == k]) for k in sorted(rows["level"].unique())]
