"""The Phong family as Mitsuba plugins, twins of :mod:`brdfs.physics.models.phong` and
:mod:`brdfs.physics.models.pumped`:

* ``brdfs_phong``: reciprocal Phong f = C (R·V)ⁿ (eq. 2.6 / 3.5), C = (n+2)/2π by default; with
  ``pumping = "g1"`` (or ``"g2"``) the pumped model f / g, g = max(a(L), a(V)) (eq. 2.20; g2 of
  eq. 2.21 also takes N·L, N·V), a the albedo of the reciprocal Phong model as the package tabulates it
  (:func:`brdfs.numerics.tables.pump`, a piecewise Chebyshev interpolant,
  :class:`brdfs.physics.tables.AlbedoTable`) carried as a Dr.Jit texture (:class:`DrJitAlbedoTable`:
  its values at cos θ = u², u uniform, linearly interpolated by the texture's filter);
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
    extra_parameters = {"pumping": ("string", "none", "``g1`` or ``g2``: divided by its albedo, eq. 2.20 / 2.21 "
                                                      "(a table of the package's pumped model)")}

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
    """An :class:`brdfs.physics.tables.AlbedoTable` in Dr.Jit as a texture: its values at
    x = cos θ = u², u on :data:`TEXELS` uniform points of [0, 1] (denser toward grazing, where a narrow
    lobe's albedo turns), interpolated linearly in u by the texture's own filter.  ``interpolation_rtol``
    bounds the relative difference from the package's table (measured at build time at every
    interval's midpoint, where linear interpolation of a smooth function errs most; 1.0e-7 for Phong
    n = 5000, below float32's 6e-8 ulp for n ≤ 1000), which :data:`INTERPOLATION_RTOL` caps."""

    def __init__(self, values, interpolation_rtol):
        values = np.asarray(values, np.float64)
        self.texels = values.size
        self.interpolation_rtol = float(interpolation_rtol)
        self.texture = mi.Texture1f(mi.TensorXf(values.astype(np.float32)[:, None]),
                                    filter_mode=dr.FilterMode.Linear, wrap_mode=dr.WrapMode.Clamp)

    @classmethod
    def of(cls, table, texels=None):
        texels = TEXELS if texels is None else texels
        u = np.linspace(0.0, 1.0, texels)
        values = np.asarray(table(u * u), float)
        middle = 0.5 * (u[1:] + u[:-1])
        exact = np.asarray(table(middle * middle), float)
        rtol = float(np.max(np.abs(0.5 * (values[1:] + values[:-1]) - exact) / np.abs(exact)))
        if not rtol <= INTERPOLATION_RTOL:                 # NaN too (a table value of 0 or NaN)
            raise ValueError(f"albedo table texture: {texels} texels interpolate the table to {rtol:.2g}, "
                             f"more than {INTERPOLATION_RTOL:g}; build it with more texels")
        return cls(values, rtol)

    def __call__(self, x):
        u = dr.sqrt(dr.clip(x, 0.0, 1.0))
        # texel i's centre, (i + ½)/texels, holds the value at u = i/(texels − 1)
        return self.texture.eval(mi.Point1f((u * (self.texels - 1) + 0.5) / self.texels))[0]


#: Texels of a pumped plugin's albedo table (:class:`DrJitAlbedoTable`): 64 KiB of float32.
TEXELS = 16384
#: The largest relative interpolation error a table texture may carry (Phong n = 1e4: 1.4e-7).
INTERPOLATION_RTOL = 1e-6


PLUGINS = {cls.name: cls for cls in (PhongBSDF, PhongCosminBSDF, BlinnBSDF, BlinnCosminBSDF)}
