"""The Phong family as Mitsuba plugins, twins of :mod:`brdfs.physics.models.phong` and
:mod:`brdfs.physics.models.pumped`:

* ``brdfs_phong``: reciprocal Phong f = C (R·V)ⁿ (eq. 2.6 / 3.5), C = (n+2)/2π by default; with
  ``pumping = "g1"`` (or ``"g2"``) the pumped model f / g, g = max(a(L), a(V)) (eq. 2.20; g2 of
  eq. 2.21 also takes N·L, N·V), a the albedo of the reciprocal Phong model as the package tabulates it
  (:func:`brdfs.numerics.tables.pump`, a piecewise Chebyshev interpolant,
  :class:`brdfs.physics.tables.AlbedoTable`) carried as Dr.Jit arrays of its pieces' coefficients
  and evaluated by Clenshaw's recurrence: the same polynomial, in float32;
* ``brdfs_phong_cosmin``: the new model f = C (R·V)ⁿ / max(N·L, N·V) (eq. 3.10); with ``eta`` and ``k``
  its metal variant f · F(Θ_min) (eq. 3.29, :class:`brdfs.physics.models.metal.PhongCosminMetal`);
* ``brdfs_blinn``, ``brdfs_blinn_cosmin``: f = C (N·H)ⁿ (eq. 1.34) and C (N·H)ⁿ / max(N·L, N·V)
  (eq. 3.34), C = 1 by default, twins of :mod:`brdfs.physics.models.blinn`, sampled by their
  ``"half_vector"`` strategy: H with density (n+1)/(2π) (N·H)ⁿ, V = 2 (L·H) H − L, pdf divided by 4 V·H.

Sampler (the models' own, ``"lobe"``; eqs. 3.19–3.22): V with density (n+1)/(2π) (R·V)ⁿ about
R = mirror(L), cos a = u^{1/(n+1)}, directions below the horizon rejected (a sub-probability,
:meth:`brdfs.physics.models.phong._PhongFamily._pdf`); ``strategy = "cosine"`` draws the cosine.
"""
from __future__ import annotations

import mitsuba as mi
import drjit as dr
import numpy as np

from brdfs.render.mitsuba.plugins._common import (INV_TWO_PI, ModelBSDF, around_axis, mirror, neg_expm1, opaque,
                                                  positive_power, r_dot_v, read_float)

PUMPINGS = ("none", "g1", "g2")
#: Accuracy of the albedo table a pumped plugin divides by (as :data:`brdfs.render.scenes.PUMPING_TABLE_RTOL`).
PUMPING_TABLE_RTOL = 1e-6
PUMPING_ENGINE_RTOL = 1e-8


def power_cosine(u1, n):
    """(cos a, sin a) with density (n+1)/(2π) cosⁿ a about an axis (eq. 3.20), as
    :func:`brdfs.physics.sampling.power_cosine`: cos a = u^{1/(n+1)}, sin a from expm1."""
    log_u = dr.log(dr.maximum(u1, 1e-38)) / (n + 1.0)
    return dr.exp(log_u), dr.safe_sqrt(neg_expm1(2.0 * log_u))


class PhongBSDF(ModelBSDF):
    """f = C (R·V)ⁿ (eq. 2.6), optionally pumped (eq. 2.20 / 2.21)."""

    name = "phong"
    strategies = ("lobe", "cosine")

    def __init__(self, props):
        super().__init__(props)
        self.n = read_float(props, "n")
        if self.n < 0:
            raise ValueError(f"{props.plugin_name()}: n = {self.n!r} must be >= 0")
        self.C = read_float(props, "C", (self.n + 2.0) / (2.0 * np.pi))
        self.pumping = props.get("pumping", "none")
        if self.pumping not in PUMPINGS:
            raise ValueError(f"{props.plugin_name()}: pumping = {self.pumping!r}; choose one of {PUMPINGS}")
        self._n, self._C = opaque(self.n), opaque(self.C)
        self.table = None
        if self.pumping != "none":
            self.table = DrJitAlbedoTable.of(self.pumped_model().table)

    def model(self):
        """The package's model this plugin is the twin of (unpumped)."""
        from brdfs.physics.models import model
        return model(self.name, n=self.n, C=self.C)

    def pumped_model(self):
        """The package's pumped model (:func:`brdfs.numerics.tables.pump`) whose table the plugin carries."""
        from brdfs.numerics.tables import pump
        return pump(self.model(), self.pumping, target_rtol=PUMPING_TABLE_RTOL, engine_rtol=PUMPING_ENGINE_RTOL)

    def lobe_value(self, L, V):
        return self._C * positive_power(r_dot_v(L, V), self._n)

    def correction(self, nl, nv):
        """g of eq. 2.20 (g1) or 2.21 (g2) from the albedo table; 1 unpumped."""
        if self.table is None:
            return mi.Float(1.0)
        g = dr.maximum(self.table(nl), self.table(nv))
        if self.pumping == "g2":
            g = dr.maximum(g, dr.maximum(nl, nv))
        return g

    def lobe_eval(self, L, V, active):
        return self.lobe_value(L, V) / self.correction(L.z, V.z)

    def own_pdf(self, L, V, active):
        cos_a = r_dot_v(L, V)
        return (self._n + 1.0) * INV_TWO_PI * positive_power(cos_a, self._n)

    def own_sample(self, L, u, active):
        cos_a, sin_a = power_cosine(u.x, self._n)
        return around_axis(mirror(L), cos_a, sin_a, 2.0 * np.pi * u.y)

    def describe(self):
        return {"n": self.n, "C": self.C, "pumping": self.pumping, "strategy": self.strategy,
                "metal": self.eta is not None}


class PhongCosminBSDF(PhongBSDF):
    """The new model f = C (R·V)ⁿ / max(N·L, N·V) (eq. 3.10); a metal with ``eta``, ``k`` (eq. 3.29)."""

    name = "phong_cosmin"

    def lobe_eval(self, L, V, active):
        return super().lobe_eval(L, V, active) / dr.maximum(L.z, V.z)


class BlinnBSDF(ModelBSDF):
    """f = C (N·H)ⁿ (eq. 1.34), N·H = (N·L + N·V)/|L + V|; sampler ``"half_vector"``."""

    name = "blinn"
    strategies = ("half_vector", "cosine")

    def __init__(self, props):
        super().__init__(props)
        self.n = read_float(props, "n")
        if self.n < 0:
            raise ValueError(f"{props.plugin_name()}: n = {self.n!r} must be >= 0")
        self.C = read_float(props, "C", 1.0)
        self._n, self._C = opaque(self.n), opaque(self.C)

    def lobe_eval(self, L, V, active):
        h = L + V
        return self._C * positive_power(h.z / dr.norm(h), self._n)

    def own_pdf(self, L, V, active):
        h = L + V
        norm = dr.norm(h)
        vh = dr.dot(V, h) / norm                     # V·H as the package forms it
        p = (self._n + 1.0) * INV_TWO_PI * positive_power(h.z / norm, self._n) / (4.0 * vh)
        return dr.select(vh > 0, p, 0.0)

    def own_sample(self, L, u, active):
        cos_d, sin_d = power_cosine(u.x, self._n)
        sin_phi, cos_phi = dr.sincos(2.0 * np.pi * u.y)
        H = mi.Vector3f(sin_d * cos_phi, sin_d * sin_phi, cos_d)
        lh = dr.dot(L, H)
        return dr.select(lh > 0, 2.0 * lh * H - L, mi.Vector3f(0.0, 0.0, -1.0))

    def describe(self):
        return {"n": self.n, "C": self.C, "strategy": self.strategy, "metal": self.eta is not None}


class BlinnCosminBSDF(BlinnBSDF):
    """Corrected Blinn, f = C (N·H)ⁿ / max(N·L, N·V) (eq. 3.34)."""

    name = "blinn_cosmin"

    def lobe_eval(self, L, V, active):
        return super().lobe_eval(L, V, active) / dr.maximum(L.z, V.z)


class DrJitAlbedoTable:
    """An :class:`brdfs.physics.tables.AlbedoTable` in Dr.Jit: the Chebyshev coefficients of its pieces
    as one flat array, evaluated at x = cos θ by Clenshaw's recurrence (the numpy table evaluates the
    same polynomial by ``chebval``)."""

    def __init__(self, edges, coefficients):
        self.edges = [float(e) for e in edges]
        self.degree = coefficients.shape[1] - 1
        self.coef = mi.Float(np.ascontiguousarray(coefficients, np.float64).ravel())

    @classmethod
    def of(cls, table):
        return cls(table.edges, np.asarray(table._coef, float))

    def __call__(self, x):
        x = dr.clip(x, 0.0, 1.0)
        piece = mi.UInt32(0)
        lo, hi = mi.Float(self.edges[0]), mi.Float(self.edges[1])
        for p in range(1, len(self.edges) - 1):          # pieces are few: a select per inner edge
            beyond = x >= self.edges[p]
            piece = dr.select(beyond, p, piece)
            lo = dr.select(beyond, self.edges[p], lo)
            hi = dr.select(beyond, self.edges[p + 1], hi)
        s = (2.0 * x - lo - hi) / (hi - lo)
        base = piece * (self.degree + 1)
        b1, b2 = mi.Float(0.0), mi.Float(0.0)
        for j in range(self.degree, 0, -1):
            b1, b2 = dr.fma(2.0 * s, b1, dr.gather(mi.Float, self.coef, base + j) - b2), b1
        return dr.fma(s, b1, dr.gather(mi.Float, self.coef, base) - b2)
PLUGINS = {cls.name: cls for cls in (PhongBSDF, PhongCosminBSDF, BlinnBSDF, BlinnCosminBSDF)}
