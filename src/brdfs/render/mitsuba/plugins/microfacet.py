"""Microfacet models as Mitsuba plugins, twins of :mod:`brdfs.physics.models.microfacet` (Ward,
Cook–Torrance: the Beckmann lobe of eqs. 2.8–2.10 with the thesis's m) and
:mod:`brdfs.physics.models.smith_microfacet` (GGX and Beckmann with Smith's G2, as rendered today).

Half vector.  h = L + V, tan²δ = |h_xy|²/h_z², cos δ = h_z/|h|, L·H = V·H = |h|/2
(:func:`brdfs.physics.distributions.half_vector_parts`).

Samplers (the models' own):

* ``brdfs_ward``, ``brdfs_cook_torrance``: ``"beckmann"``, H with density D(H) N·H, tan δ = m √(−ln(1 − u₁))
  (:meth:`brdfs.physics.distributions.Beckmann.sample_normal`), V = 2 (L·H) H − L, pdf D (N·H)/(4 V·H);
  H with L·H ≤ 0 or V below the horizon rejected;
* ``brdfs_ggx``, ``brdfs_beckmann``: ``"visible_normals"``, H from the distribution of normals visible from
  L, pdf D_L(H)/(4 L·H) = D(H)/(4 (N·L + λ(N·L))) (λ = Λ cos θ).  GGX's by Heitz (2018), as the package;
  Beckmann's by Mitsuba's own ``mi.MicrofacetDistribution`` (Heitz & d'Eon 2014 with Jakob's inversion,
  the same distribution as the package's Newton inversion, checked by the chi-square tests).
"""
from __future__ import annotations

import mitsuba as mi
import drjit as dr
import numpy as np

from brdfs.render.mitsuba.plugins._common import ModelBSDF, cos_half_angle, opaque, read_float

SQRT_PI = float(np.sqrt(np.pi))


def half_vector_parts(L, V):
    """(tan²δ, cos²δ, |h|) of h = L + V, without cancellation."""
    h = L + V
    hz2 = h.z * h.z
    hxy2 = h.x * h.x + h.y * h.y
    return hxy2 / hz2, hz2 / (hz2 + hxy2), dr.sqrt(hz2 + hxy2)


def log1p(x):
    """ln(1 + x) to full relative precision for small x (Dr.Jit has none)."""
    u = 1.0 + x
    return dr.select(u == 1.0, x, dr.log(u) * x / (u - 1.0))


def reflect(L, H):
    """V = 2 (L·H) H − L."""
    return 2.0 * dr.dot(L, H) * H - L


def beckmann_normal(u, alpha):
    """H with density D(H) N·H (Beckmann, :meth:`brdfs.physics.distributions.Beckmann.sample_normal`)."""
    tan_d = alpha * dr.safe_sqrt(-log1p(-u.x))
    cos_d = dr.rsqrt(1.0 + tan_d * tan_d)
    sin_phi, cos_phi = dr.sincos(2.0 * dr.pi * u.y)
    sin_d = tan_d * cos_d
    return mi.Vector3f(sin_d * cos_phi, sin_d * sin_phi, cos_d)


class _BeckmannLobe(ModelBSDF):
    """Ward and Cook–Torrance: parameters ``m`` (roughness), ``C``; sampler ``"beckmann"``."""

    strategies = ("beckmann", "cosine")
    #: A metal (``eta``/``k``) reads F at L·H, as the numpy model declares.
    fresnel_cosine = staticmethod(cos_half_angle)

    def __init__(self, props):
        super().__init__(props)
        self.m = read_float(props, "m")
        if self.m <= 0:
            raise ValueError(f"{props.plugin_name()}: m = {self.m!r} must be > 0")
        self.C = read_float(props, "C", 1.0)
        if self.C <= 0:
            raise ValueError(f"{props.plugin_name()}: C = {self.C!r} must be > 0")
        self._m, self._C = opaque(self.m), opaque(self.C)

    def slope_weight(self, tan2):
        """exp(−tan²δ/m²) (eqs. 2.8, 2.9)."""
        return dr.exp(-tan2 / (self._m * self._m))

    def own_pdf(self, L, V, active):
        tan2, cos2, h_norm = half_vector_parts(L, V)
        m2 = self._m * self._m
        d_cos = self.slope_weight(tan2) / (dr.pi * m2 * cos2 * dr.sqrt(cos2))      # D(H) N·H
        vh = dr.dot(V, L + V) / h_norm            # V·H as the package forms it (= |h|/2 for unit L, V)
        return dr.select((vh > 0) & (cos2 > 0), d_cos / (4.0 * vh), 0.0)

    def own_sample(self, L, u, active):
        H = beckmann_normal(u, self._m)
        V = reflect(L, H)
        return dr.select(dr.dot(L, H) > 0, V, mi.Vector3f(0.0, 0.0, -1.0))

    def describe(self):
        return {"m": self.m, "C": self.C, "strategy": self.strategy, "metal": self.eta is not None}


class WardBSDF(_BeckmannLobe):
    """Isotropic Ward, f = C/(4π m²) exp(−tan²δ/m²)/√(N·L N·V) (eq. 2.8 / 3.35)."""

    name = "ward"

    def lobe_eval(self, L, V, active):
        tan2, _, _ = half_vector_parts(L, V)
        return self._C / (4.0 * dr.pi * self._m * self._m) * self.slope_weight(tan2) * dr.rsqrt(L.z * V.z)


GEOMETRY_FACTORS = ("torrance_sparrow", "smith", "none")


def g1_thesis(x, alpha):
    """Smith's G* as eq. 1.38 prints it: h = x²/(2α²(1 − x²)), g = √(πh)(2 − erfc √h), G* = g/(g + 1)
    (:meth:`brdfs.physics.distributions.Beckmann.smith_g1_thesis`)."""
    h = x * x / (2.0 * alpha * alpha * (1.0 - x) * (1.0 + x))
    root = dr.sqrt(h)
    g = SQRT_PI * root * (1.0 + dr.erf(root))
    return dr.select(x >= 1.0, 1.0, g / (g + 1.0))


class CookTorranceBSDF(_BeckmannLobe):
    """Cook–Torrance with F = 1 (eq. 2.9): f = C exp(−tan²δ/m²)/(4π m² cos⁴δ) · G/(N·L N·V); ``G``:
    ``"torrance_sparrow"`` (eq. 2.10, default), ``"smith"`` (G* of eq. 1.38) or ``"none"``."""

    name = "cook_torrance"

    def __init__(self, props):
        super().__init__(props)
        self.G = props.get("G", "torrance_sparrow")
        if self.G not in GEOMETRY_FACTORS:
            raise ValueError(f"{props.plugin_name()}: G = {self.G!r}; choose one of {GEOMETRY_FACTORS}")

    def geometry(self, nl, nv, nh, lh):
        if self.G == "torrance_sparrow":
            return dr.minimum(1.0, dr.minimum(2.0 * nh * nv / lh, 2.0 * nh * nl / lh))
        if self.G == "smith":
            return g1_thesis(nl, self._m) * g1_thesis(nv, self._m)
        return mi.Float(1.0)

    def lobe_eval(self, L, V, active):
        tan2, cos2, h_norm = half_vector_parts(L, V)
        d = self._C * self.slope_weight(tan2) / (4.0 * dr.pi * self._m * self._m * cos2 * cos2)
        return d * self.geometry(L.z, V.z, dr.sqrt(cos2), 0.5 * h_norm) / (L.z * V.z)

    def describe(self):
        return {**super().describe(), "G": self.G}


# --- Smith microfacet models (GGX, Beckmann) ---------------------------------------------------------

G2_FORMS = ("height_correlated", "separable")


class _SmithBSDF(ModelBSDF):
    """f = F(L·H) D(H) G2/(4 N·L N·V) (Walter et al. 2007, eq. 20); parameters ``alpha``, ``G2``
    (``height_correlated`` or ``separable``), ``ior_re``/``ior_im`` (the model's own Fresnel, F = 1 when
    absent) or, per channel, ``eta``/``k`` (the same F(L·H), as Mitsuba's ``roughconductor``; not both);
    Kulla–Conty's compensation renders through ``brdfs_model``."""

    strategies = ("visible_normals", "cosine")
    fresnel_cosine = staticmethod(cos_half_angle)

    def __init__(self, props):
        super().__init__(props)
        self.alpha = read_float(props, "alpha")
        if self.alpha <= 0:
            raise ValueError(f"{props.plugin_name()}: alpha = {self.alpha!r} must be > 0")
        self.G2 = props.get("G2", "height_correlated")
        if self.G2 not in G2_FORMS:
            raise ValueError(f"{props.plugin_name()}: G2 = {self.G2!r}; choose one of {G2_FORMS}")
        compensation = props.get("compensation", "none")
        if compensation != "none":
            raise ValueError(f"{props.plugin_name()}: compensation = {compensation!r} has no Dr.Jit twin; "
                             f"render it through brdfs_model (model = {self.name!r})")
        self.ior_re = read_float(props, "ior_re", 0.0) if ("ior_re" in props) else None
        self.ior_im = read_float(props, "ior_im", 0.0)
        if self.ior_re is None and "ior_im" in props:
            raise ValueError(f"{props.plugin_name()}: ior_im = {self.ior_im!r} given without ior_re")
        if self.ior_re is not None and not self.ior_re > 0:
            raise ValueError(f"{props.plugin_name()}: ior_re = {self.ior_re!r} must be > 0")
        if not self.ior_im >= 0:
            raise ValueError(f"{props.plugin_name()}: ior_im = {self.ior_im!r} must be >= 0")
        self._alpha = opaque(self.alpha)
        self._ior = None if self.ior_re is None else (opaque(self.ior_re), opaque(self.ior_im))

    def D(self, tan2, cos2):
        raise NotImplementedError

    def smith_lambda_cos(self, c):
        """λ(μ) = Λ(θ) cos θ, finite at the horizon."""
        raise NotImplementedError

    def g2_over_4_nl_nv(self, nl, nv):
        """G2/(4 N·L N·V) without 0/0 at the horizon (:meth:`_SmithMicrofacet.g2_over_4_nl_nv`)."""
        lam_l, lam_v = self.smith_lambda_cos(nl), self.smith_lambda_cos(nv)
        if self.G2 == "height_correlated":
            return 1.0 / (4.0 * (nl * nv + nv * lam_l + nl * lam_v))
        return 1.0 / (4.0 * (nl + lam_l) * (nv + lam_v))

    def own_fresnel(self, L, V):
        """The model's own F(L·H) of ``ior_re``/``ior_im`` (1 without)."""
        if self.ior_re is None:
            return mi.Float(1.0)
        return self.fresnel(L, V, *self._ior)

    def lobe_eval(self, L, V, active):
        tan2, cos2, _ = half_vector_parts(L, V)
        return self.own_fresnel(L, V) * self.D(tan2, cos2) * self.g2_over_4_nl_nv(L.z, V.z)

    def own_pdf(self, L, V, active):
        tan2, cos2, h_norm = half_vector_parts(L, V)
        lh = dr.dot(L, L + V) / h_norm
        p = self.D(tan2, cos2) / (4.0 * (L.z + self.smith_lambda_cos(L.z)))
        return dr.select((lh > 0) & (h_norm > 0) & (V.z > 0), p, 0.0)

    def own_sample(self, L, u, active):
        return reflect(L, self.visible_normal(L, u))

    def describe(self):
        return {"alpha": self.alpha, "G2": self.G2, "ior_re": self.ior_re, "ior_im": self.ior_im,
                "strategy": self.strategy, "metal": self.eta is not None}


class GGXBSDF(_SmithBSDF):
    """GGX (Trowbridge–Reitz): D = α²/(π cos⁴δ (α² + tan²δ)²), λ(μ) = α² sin²θ/(2(√(μ² + α² sin²θ) + μ))."""

    name = "ggx"

    def D(self, tan2, cos2):
        a2 = self._alpha * self._alpha
        return a2 / (dr.pi * cos2 * cos2 * (a2 + tan2) ** 2)

    def smith_lambda_cos(self, c):
        c = dr.clip(c, 0.0, 1.0)
        s2 = (1.0 - c) * (1.0 + c)
        a2 = self._alpha * self._alpha
        return 0.5 * a2 * s2 / (dr.sqrt(c * c + a2 * s2) + c)

    def visible_normal(self, w, u):
        """Heitz (2018), listing 1 (:meth:`brdfs.physics.distributions.GGX.sample_visible_normal`)."""
        a = self._alpha
        vh = dr.normalize(mi.Vector3f(a * w.x, a * w.y, w.z))
        lensq = vh.x * vh.x + vh.y * vh.y
        inv = dr.select(lensq > 0, dr.rsqrt(dr.select(lensq > 0, lensq, 1.0)), 0.0)
        t1_vec = dr.select(lensq > 0, mi.Vector3f(-vh.y * inv, vh.x * inv, 0.0), mi.Vector3f(1.0, 0.0, 0.0))
        t2_vec = dr.cross(vh, t1_vec)
        r = dr.sqrt(u.x)
        sin_phi, cos_phi = dr.sincos(2.0 * dr.pi * u.y)
        t1, t2 = r * cos_phi, r * sin_phi
        s = 0.5 * (1.0 + vh.z)
        t2 = (1.0 - s) * dr.safe_sqrt(1.0 - t1 * t1) + s * t2
        nh = t1 * t1_vec + t2 * t2_vec + dr.safe_sqrt(1.0 - t1 * t1 - t2 * t2) * vh
        return dr.normalize(mi.Vector3f(a * nh.x, a * nh.y, dr.maximum(nh.z, 0.0)))


class BeckmannBSDF(_SmithBSDF):
    """Beckmann: D = exp(−tan²δ/α²)/(π α² cos⁴δ), λ(μ) = α sin θ e^{−a²}/(2√π) − μ erfc(a)/2, a = cot θ/α."""

    name = "beckmann"

    def D(self, tan2, cos2):
        a2 = self._alpha * self._alpha
        return dr.exp(-tan2 / a2) / (dr.pi * a2 * cos2 * cos2)

    def smith_lambda_cos(self, c):
        c = dr.clip(c, 0.0, 1.0)
        s = dr.safe_sqrt((1.0 - c) * (1.0 + c))
        a = c / (self._alpha * dr.select(s > 0, s, 1.0))
        lam = self._alpha * s * dr.exp(-a * a) / (2.0 * SQRT_PI) - 0.5 * c * (1.0 - dr.erf(a))
        return dr.select(s > 0, dr.maximum(lam, 0.0), 0.0)

    def visible_normal(self, w, u):
        """Mitsuba's visible-normal sampler of the Beckmann distribution (module docstring)."""
        distribution = mi.MicrofacetDistribution(mi.MicrofacetType.Beckmann, self._alpha, True)
        H, _ = distribution.sample(w, mi.Point2f(u))
        return H


PLUGINS = {cls.name: cls for cls in (WardBSDF, CookTorranceBSDF, GGXBSDF, BeckmannBSDF)}
