"""What every plugin of the package shares: the local frame, the cosine sampler, Fresnel, the
mutation switches, and :class:`ModelBSDF`, the base class that turns one scalar lobe f(L, V) into a
Mitsuba BSDF (eval, pdf, sample, eval_pdf, traverse), optionally beside a diffuse lobe.

Frames.  Mitsuba hands a BSDF its directions in the shading frame of the surface
(``si.sh_frame``, built by the shape from ``si.dp_du`` and the shading normal): N = (0, 0, 1) and the
tangent x = dp/du, the package's convention (L in the x–z plane of incidence has φ = 0).  An
anisotropic model (``patch_elliptical``) reads its axes in that frame; :func:`to_model` /
:func:`from_model` map between Mitsuba's frame and the model's and are the one place where the
frame can be turned (the mutation :data:`FRAME_ROTATED_90`).

Directions.  The model's L is Mitsuba's ``wo`` (the direction to the light in radiance transport) and
V is ``si.wi`` (toward the viewer) for :meth:`ModelBSDF.eval`; the sampler draws V from L by the
model's protocol (``BRDF.sample(L, u)``), here ``wo`` from ``si.wi`` — the same thing for the
reciprocal models written here.  ``eval`` returns f cos θ_o, as every Mitsuba BSDF does.

Mutation switches (module-level, default off, each on one line marked ``# MUTATION``, so that
``workflow/scripts/check_mutations.sh`` can flip it with sed in a temporary copy and assert that a
named test fails):

* :data:`FRAME_ROTATED_90`: the model frame turned 90° about N (x → y);
* :data:`UNIFORM_CLAIMS_COSINE`: the cosine sampler draws uniform directions while its pdf still
  claims cos θ / π;
* :data:`PDF_SCALE`: every pdf the plugins report is multiplied by it (1.05: off by 5 %);

and lines marked ``# MUTATION:<name> <replacement>`` (the line becomes the replacement):
``mis_weights_apart``, ``fresnel_at_theta_l`` (every metal reads F at cos θ_L, not at its
model's angle) and ``tangent_flipped`` (the model frame's y = −(N × x): anisotropy mirrored).

Fresnel.  A metal (``eta``/``k``, or a microfacet model's own ``ior_re``/``ior_im``) reads F at the
angle its model declares (:meth:`ModelBSDF.fresnel_cosine`, the twin of the numpy model's
``fresnel_cosine``): Θ_min (eq. 3.29) by default, L·H for the microfacet models
(:func:`cos_half_angle`), θ' for the patch models (eq. 4.53).  Two Fresnel factors on one lobe
(``eta`` beside ``ior_re``) have no meaning: the scene fails to load, naming the parameter.
"""
from __future__ import annotations

import mitsuba as mi
import drjit as dr
import numpy as np

FRAME_ROTATED_90 = False  # MUTATION frame_rotated_90: the model frame turned 90 degrees about N
UNIFORM_CLAIMS_COSINE = False  # MUTATION uniform_claims_cosine: uniform directions, cosine pdf claimed
PDF_SCALE = 1.0  # MUTATION pdf_scale: 1.05 reports every pdf 5 % too high

INV_PI = 1.0 / np.pi
INV_TWO_PI = 0.5 / np.pi


# --- frames ----------------------------------------------------------------------------------------

def to_model(v):
    """A direction of Mitsuba's shading frame (``si.sh_frame``: x = dp/du) in the model's frame."""
    if FRAME_ROTATED_90:
        return mi.Vector3f(v.y, -v.x, v.z)
    return mi.Vector3f(v)  # MUTATION:tangent_flipped return mi.Vector3f(v.x, -v.y, v.z)


def from_model(v):
    """A direction of the model's frame in Mitsuba's shading frame (inverse of :func:`to_model`)."""
    if FRAME_ROTATED_90:
        return mi.Vector3f(-v.y, v.x, v.z)
    return mi.Vector3f(v)  # MUTATION:tangent_flipped return mi.Vector3f(v.x, -v.y, v.z)


def around_axis(axis, cos_a, sin_a, phi):
    """The direction at polar angle a (cos, sin) and azimuth φ about ``axis``: Duff et al.'s basis
    (:func:`brdfs.physics.sampling.orthonormal_basis`, the same as ``mi.Frame3f``)."""
    sin_phi, cos_phi = dr.sincos(phi)
    return mi.Frame3f(axis).to_world(mi.Vector3f(sin_a * cos_phi, sin_a * sin_phi, cos_a))


def mirror(v):
    """R = 2 (N·v) N − v (eq. 3.8)."""
    return mi.Vector3f(-v.x, -v.y, v.z)


def r_dot_v(L, V):
    """R·V = 2 (N·L)(N·V) − L·V (eq. 3.9), as :func:`brdfs.physics.geometry.r_dot_v`."""
    return 2.0 * L.z * V.z - dr.dot(L, V)


def positive_power(x, n):
    """((x)⁺)ⁿ with 0⁰ = 1 only for x > 0 (:func:`brdfs.physics.models.base.positive_power`)."""
    return dr.select(x > 0, dr.power(dr.maximum(x, 1e-38), n), 0.0)


def neg_expm1(x):
    """−(eˣ − 1) to full relative precision for small |x| (Kahan's trick; Dr.Jit has no expm1)."""
    u = dr.exp(x)
    small = dr.abs(x) < 1e-4
    return dr.select(small, -x * (1.0 + 0.5 * x), -dr.select(u == 1.0, x, (u - 1.0) * x / dr.log(u)))


# --- the cosine sampler (every model's baseline strategy; Lambert's own) ---------------------------

def sample_cosine(u):
    """Directions with density cos θ / π from ``u`` (Vector2f) — or, under the mutation
    :data:`UNIFORM_CLAIMS_COSINE`, uniform directions whose pdf still claims the cosine."""
    if UNIFORM_CLAIMS_COSINE:
        return mi.warp.square_to_uniform_hemisphere(u)
    return mi.warp.square_to_cosine_hemisphere(u)


def cosine_pdf(v):
    """cos θ / π above the horizon, 0 below (``BRDF.pdf(…, "cosine")``)."""
    return dr.select(v.z > 0, v.z * INV_PI, 0.0)


# --- Fresnel (eqs. 1.41–1.43; twin of brdfs.physics.fresnel.unpolarised_reflectance) ---------------

def fresnel_conductor(cos_theta, eta, k):
    """Unpolarised reflectance F = (|r_⊥|² + |r_∥|²)/2 of the complex index η = n + ik (eqs. 1.41–1.43),
    per channel of ``eta``/``k`` (Spectrum), at ``cos_theta`` (Float, clipped to [0, 1]).

    The package's complex formula written out in reals: η² = (n² − k², 2nk), w = √(η² − sin²θ)
    (principal root: Re w ≥ 0, Im w ≥ 0 for k ≥ 0), r_⊥ = (c − w)/(c + w), r_∥ = (η²c − w)/(η²c + w).
    """
    c = dr.clip(cos_theta, 0.0, 1.0)
    er, ei = eta * eta - k * k, 2.0 * eta * k
    zr, zi = er - (1.0 - c * c), ei
    modulus = dr.sqrt(zr * zr + zi * zi)
    wr = dr.safe_sqrt(0.5 * (modulus + zr))
    wi = dr.safe_sqrt(0.5 * (modulus - zr))
    perp = ((c - wr) ** 2 + wi * wi) / ((c + wr) ** 2 + wi * wi)
    pr, pi_ = er * c, ei * c
    par = ((pr - wr) ** 2 + (pi_ - wi) ** 2) / ((pr + wr) ** 2 + (pi_ + wi) ** 2)
    return 0.5 * (perp + par)


def cos_half_angle(L, V):
    """L·H = L·(L + V)/|L + V|, clipped to [0, 1] (0 where L + V = 0): where a microfacet model reads F
    (:func:`brdfs.physics.fresnel.cos_theta_half`)."""
    h = L + V
    norm = dr.norm(h)
    return dr.select(norm > 0, dr.clip(dr.dot(L, h) / dr.select(norm > 0, norm, 1.0), 0.0, 1.0), 0.0)


#: The scene keys every plugin reads besides its model's parameters: name -> (type, default, meaning),
#: for the plugin reference of the documentation (``docs/_ext/model_pages.py``).  A plugin's own
#: extra keys are its class's :attr:`ModelBSDF.extra_parameters`.
COMMON_PARAMETERS = {
    "specular": ("texture", "1", "the lobe's weight w_s (Lambert: ``reflectance``)"),
    "diffuse_reflectance": ("texture", "none", "adds a Lambertian lobe ρ_d/π (eq. 3.31); one-sample MIS over the two"),
    "eta": ("texture", "none", "real part n of a metal's index: the lobe times the conductor Fresnel factor "
                               "at the model's declared angle (L·H for the microfacet models, Θ_min for the "
                               "Phong family, θ' for the patch models)"),
    "k": ("texture", "0", "imaginary part k of the metal's index (with ``eta``)"),
    "strategy": ("string", "the model's own", "the lobe's sampler: the model's own strategy or ``cosine``"),
}


def channel_mean(value):
    """The mean over the channels of a Spectrum (a Float): the share a lobe gets in one-sample MIS."""
    return dr.mean(value, axis=0) if dr.depth_v(value) > 1 else value


# --- the base plugin ---------------------------------------------------------------------------------

def opaque(value):
    """A parameter as an opaque Dr.Jit scalar: a kernel argument, not a literal, so that one compiled
    kernel serves every value of it (a scene or test with another n recompiles nothing)."""
    return dr.opaque(mi.Float, float(value))


def read_float(props, name, default=None):
    """A scalar parameter ``name`` of ``props`` as a float (``default`` when absent); a missing
    parameter without default, or a non-finite value, raises one line naming it."""
    if name in props:
        value = float(props[name])
    elif default is None:
        raise ValueError(f"{props.plugin_name()}: parameter {name!r} is required")
    else:
        value = float(default)
    if not np.isfinite(value):
        raise ValueError(f"{props.plugin_name()}: {name} = {value!r} must be finite")
    return value


def _more_colour_groups(props, has_eta) -> list:
    """The (eta_g, k_g) textures of colour groups g = 1, 2, … (``eta_1``, ``k_1``, …), for a panel
    whose wavelengths are rendered as several colour groups along the same paths."""
    out = []
    while f"eta_{len(out) + 1}" in props:
        g = len(out) + 1
        if not has_eta:
            raise ValueError(f"{props.plugin_name()}: eta_{g} given without eta")
        out.append((props.get_unbounded_texture(f"eta_{g}"), props.get_unbounded_texture(f"k_{g}", 0.0)))
    if f"k_{len(out) + 1}" in props:
        raise ValueError(f"{props.plugin_name()}: k_{len(out) + 1} given without eta_{len(out) + 1}")
    return out


def _ratio(numerator, denominator):
    """numerator / denominator per channel, 0 where the denominator is 0."""
    return dr.select(denominator != 0, numerator / dr.select(denominator != 0, denominator, 1.0), 0.0)


class ModelBSDF(mi.BSDF):
    """A Mitsuba BSDF from one scalar lobe of the package (subclasses: :meth:`lobe_eval`,
    :meth:`lobe_pdf`, :meth:`lobe_sample`, in the model frame, with N = (0, 0, 1)):

        f_material = w_s · F · f(L, V) + ρ_d / π

    ``specular`` (texture, default 1) is w_s; ``eta`` and ``k`` (unbounded textures, optional) make
    the lobe a metal with F the conductor Fresnel at :meth:`fresnel_cosine` (Θ_min of eq. 3.29 by
    default); ``eta_1``, ``k_1``, ``eta_2``, … (optional) are the metal's n, k of further colour groups
    (:meth:`colour_ratios`, the integrator's ``colour_groups``); ``diffuse_reflectance`` (texture,
    optional) adds a Lambertian lobe ρ_d/π (eq. 3.31).
    With two lobes, :meth:`sample` picks one (one-sample MIS, no defensive share): the diffuse lobe
    with probability p_d = mean ρ_d / (mean ρ_d + mean w_s), and reports the mixture's pdf
    p_d cos θ/π + (1 − p_d) pdf_lobe.  ``strategy`` chooses the lobe's sampler among the model's
    (its own, the default, or ``"cosine"``).
    """

    #: The model's sampling strategies, its own first (as ``BRDF.strategies``).
    strategies = ("cosine",)
    #: The name of the lobe's weight in the scene description.
    weight_name = "specular"
    #: Mitsuba's flag of the lobe.
    lobe_flag = mi.BSDFFlags.GlossyReflection
    #: The plugin's scene keys beyond its model's parameters and :data:`COMMON_PARAMETERS`:
    #: name -> (type, default, meaning), for the documentation's plugin reference.
    extra_parameters: dict = {}

    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.strategy = props.get("strategy", self.strategies[0])
        if self.strategy not in self.strategies:
            raise ValueError(f"{props.plugin_name()}: strategy = {self.strategy!r}; choose one of {self.strategies}")
        self.weight = props.get_texture(self.weight_name, 1.0)
        self.diffuse = props.get_texture("diffuse_reflectance") if ("diffuse_reflectance" in props) else None
        has_eta, has_k = ("eta" in props), ("k" in props)
        if has_k and not has_eta:
            raise ValueError(f"{props.plugin_name()}: k given without eta")
        if has_eta and "ior_re" in props:
            raise ValueError(f"{props.plugin_name()}: eta given beside ior_re = {props['ior_re']!r}: two Fresnel "
                             f"factors on one lobe; give eta/k (per channel) or ior_re/ior_im, not both")
        self.eta = props.get_unbounded_texture("eta") if has_eta else None
        self.k = props.get_unbounded_texture("k", 0.0) if has_eta else None
        self.colour_groups = [(self.eta, self.k)] + _more_colour_groups(props, has_eta)
        flags = self.lobe_flag | mi.BSDFFlags.FrontSide
        components = [flags]
        if self.diffuse is not None:
            components.append(mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide)
            flags = flags | mi.BSDFFlags.DiffuseReflection
        self.m_components = components
        self.m_flags = flags

    # --- the lobe: subclasses ------------------------------------------------------------------
    def lobe_eval(self, L, V, active):
        """f(L, V) of the model (Float), L, V in the model frame, both above the horizon."""
        raise NotImplementedError

    def lobe_pdf(self, L, V, active):
        """The density of :meth:`lobe_sample` of V given L, per solid angle (Float)."""
        if self.strategy == "cosine":
            return cosine_pdf(V)
        return self.own_pdf(L, V, active)

    def lobe_sample(self, L, u, active):
        """V drawn from L with :meth:`lobe_pdf` (Vector3f in the model frame; below the horizon:
        rejected)."""
        if self.strategy == "cosine":
            return sample_cosine(u)
        return self.own_sample(L, u, active)

    def own_pdf(self, L, V, active):
        raise NotImplementedError

    def own_sample(self, L, u, active):
        raise NotImplementedError

    def fresnel_cosine(self, L, V):
        """cos of the angle at which a metal reads F: Θ_min, max(N·L, N·V) (eq. 3.29), unless the
        model declares another (the twin of its numpy model's ``fresnel_cosine``)."""
        return dr.clip(dr.maximum(L.z, V.z), 0.0, 1.0)

    def fresnel(self, L, V, eta, k):
        """F of the index ``eta`` + i ``k`` at :meth:`fresnel_cosine` (the one place a plugin reads F)."""
        cos_f = self.fresnel_cosine(L, V)  # MUTATION:fresnel_at_theta_l cos_f = dr.clip(L.z, 0.0, 1.0)
        return fresnel_conductor(cos_f, eta, k)

    # --- the material ----------------------------------------------------------------------------
    def _specular_factor(self, si, L, V, active, group=0):
        w = self.weight.eval(si, active)
        if self.eta is None:
            return w
        eta, k = self.colour_groups[group]
        return w * self.fresnel(L, V, eta.eval(si, active), k.eval(si, active))

    def _diffuse_probability(self, si, active):
        if self.diffuse is None:
            return mi.Float(0.0)
        d = channel_mean(self.diffuse.eval(si, active))
        s = channel_mean(self.weight.eval(si, active))
        total = d + s
        return dr.select(total > 0, d / total, 0.5)

    def _value(self, si, L, V, active, group=0):
        """f_material(L, V) (Spectrum) of colour group ``group``, 0 unless both directions lie above the horizon."""
        active = active & (L.z > 0) & (V.z > 0)
        f = self._specular_factor(si, L, V, active, group) * self.lobe_eval(L, V, active)
        if self.diffuse is not None:
            f = f + self.diffuse.eval(si, active) * INV_PI
        return dr.select(active, f, 0.0)

    def colour_ratios(self, si, wo, active):
        """f_g / f_0 at (``si.wi``, ``wo``) for each colour group g ≥ 1 (a list of Spectrum; empty
        with one group): what turns group 0's path throughput into group g's (the samplers do not
        read the colour, so every group follows the same paths).  A metal without a diffuse lobe
        needs only the Fresnel factors F_g / F_0, not the lobe."""
        if len(self.colour_groups) == 1:
            return []
        L, V = to_model(wo), to_model(si.wi)
        part = self._specular_factor if self.diffuse is None else self._value
        base = part(si, L, V, active)
        return [_ratio(part(si, L, V, active, g), base) for g in range(1, len(self.colour_groups))]

    def mis_lobe_pdf(self, L, V, active):
        """The lobe's density in the MIS weights of :meth:`eval_pdf` (next-event estimation) and of a
        sample's ``bs.pdf``: :meth:`lobe_pdf` here.  A plugin whose ``sample`` weight does not divide by
        the density may report a cheaper one: MIS weights that sum to one for every direction keep the
        estimate unbiased whatever density they are computed from (Veach 1997, sec. 9.2)."""
        return self.lobe_pdf(L, V, active)

    def _pdf(self, si, given, drawn, active, mis=False):
        """The mixture density of ``drawn`` (``wo``) sampled from ``given`` (``si.wi``): the model's
        ``pdf(L=given, V=drawn)``; with ``mis``, the density of the MIS weights (:meth:`mis_lobe_pdf`)."""
        active = active & (given.z > 0) & (drawn.z > 0)
        p_lobe = (self.mis_lobe_pdf if mis else self.lobe_pdf)(given, drawn, active)
        if self.diffuse is not None:
            p_d = self._diffuse_probability(si, active)
            p_lobe = p_d * cosine_pdf(drawn) + (1.0 - p_d) * p_lobe
        return dr.select(active, PDF_SCALE * p_lobe, 0.0)

    # --- Mitsuba's verbs ------------------------------------------------------------------------
    def eval(self, ctx, si, wo, active=True):
        wi_m, wo_m = to_model(si.wi), to_model(wo)
        return self._value(si, wo_m, wi_m, active) * dr.maximum(wo.z, 0.0)

    def pdf(self, ctx, si, wo, active=True):
        return self._pdf(si, to_model(si.wi), to_model(wo), active)

    def eval_pdf(self, ctx, si, wo, active=True):
        wi_m, wo_m = to_model(si.wi), to_model(wo)
        mis = True  # MUTATION:mis_weights_apart mis = False
        return (self._value(si, wo_m, wi_m, active) * dr.maximum(wo.z, 0.0),
                self._pdf(si, wi_m, wo_m, active, mis=mis))

    def sample(self, ctx, si, sample1, sample2, active=True):
        wi_m = to_model(si.wi)
        active = mi.Bool(active) & (wi_m.z > 0)
        wo_m = self.lobe_sample(wi_m, sample2, active)
        sampled_type = mi.UInt32(int(self.lobe_flag))
        component = mi.UInt32(0)
        if self.diffuse is not None:
            diffuse = sample1 < self._diffuse_probability(si, active)
            wo_m = dr.select(diffuse, sample_cosine(sample2), wo_m)
            sampled_type = dr.select(diffuse, mi.UInt32(int(mi.BSDFFlags.DiffuseReflection)), sampled_type)
            component = dr.select(diffuse, mi.UInt32(1), component)
        wo_m = dr.normalize(wo_m)
        pdf = self._pdf(si, wi_m, wo_m, active)
        active = active & (wo_m.z > 0) & (pdf > 0)
        bs = dr.zeros(mi.BSDFSample3f)
        bs.wo = from_model(wo_m)
        bs.pdf = dr.select(active, pdf, 0.0)
        bs.eta = 1.0
        bs.sampled_type = sampled_type
        bs.sampled_component = component
        value = self._value(si, wo_m, wi_m, active) * wo_m.z
        weight = dr.select(active, value / dr.select(active, pdf, 1.0), 0.0)
        return bs, weight

    def traverse(self, callback):
        callback.put(self.weight_name, self.weight, mi.ParamFlags.Differentiable)
        if self.diffuse is not None:
            callback.put("diffuse_reflectance", self.diffuse, mi.ParamFlags.Differentiable)
        if self.eta is not None:
            callback.put("eta", self.eta, mi.ParamFlags.Differentiable)
            callback.put("k", self.k, mi.ParamFlags.Differentiable)
        for g, (eta, k) in enumerate(self.colour_groups[1:], start=1):
            callback.put(f"eta_{g}", eta, mi.ParamFlags.Differentiable)
            callback.put(f"k_{g}", k, mi.ParamFlags.Differentiable)

    def parameters_changed(self, keys):
        pass

    def to_string(self):
        params = ", ".join(f"{k}={v!r}" for k, v in self.describe().items())
        return f"{type(self).__name__}[{params}]"

    def describe(self) -> dict:
        """The model parameters of the plugin (for :meth:`to_string`)."""
        return {"strategy": self.strategy}
