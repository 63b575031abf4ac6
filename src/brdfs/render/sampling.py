"""Direction proposals of the Monte Carlo renderer, in the local frame N = (0, 0, 1).

A proposal draws the unknown direction ``w`` of a BRDF given the known one ``k`` (the renderer
walks from the eye, so ``k`` is the viewing direction and ``w`` the light direction; every model
rendered is reciprocal, so a sampler of V given L serves for L given V) and states its
solid-angle density ``pdf(k, w)``. A material mixes proposals (one-sample mixture, i.e.
defensive importance sampling): weight = f(w, k) cos θ_w / Σ_j p_j pdf_j(k, w), which is an
unbiased estimator whatever the proposals, as long as their mixture covers the BRDF's support.

Proposals:

* :class:`ModelSampler` — the model's own ``sample(L, u) -> (V, weight, pdf)`` and ``pdf(L, V)``
  (the project's samplers, used whenever a model has them: duck typing);
* :class:`CosineSampler` — cos θ / π, the fallback of every model;
* :class:`PowerLobeSampler` — (n+1)/(2π) cos^n β around the mirror direction (eqs. 3.19/3.20),
  the density of the Phong-type lobes, used for them until the models carry samplers;
* :class:`PatchExponentialSampler`, :class:`PatchEllipseSampler` — densities on the base plane of
  the patch models (section 4.2: V_P = L'_P + z with z drawn from the model's own profile, so that
  the density in solid angle is p_A(z) cos θ_V).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import lambertw

from brdfs.physics.lobes import PowerCosine
from brdfs.physics.models.base import BRDF


def _frame_around(axis):
    """Two unit vectors completing ``axis`` (…, 3) to a right-handed orthonormal frame."""
    helper = np.where(np.abs(axis[..., :1]) < 0.9, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    t = np.cross(helper, axis)
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    return t, np.cross(axis, t)


def _lift(xy):
    """Unit vectors with horizontal part ``xy`` (…, 2), z = √(1 − |xy|²) (NaN-free; z = 0 outside)."""
    z = np.sqrt(np.maximum(1.0 - xy[..., 0] ** 2 - xy[..., 1] ** 2, 0.0))
    return np.concatenate([xy, z[..., None]], axis=-1)


@dataclass(frozen=True)
class CosineSampler:
    """Cosine-weighted hemisphere: pdf = cos θ / π."""

    def sample(self, k, u):
        r, phi = np.sqrt(u[..., 0]), 2.0 * np.pi * u[..., 1]
        return _lift(np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1))

    def pdf(self, k, w):
        return np.maximum(w[..., 2], 0.0) / np.pi


@dataclass(frozen=True)
class PowerLobeSampler:
    """cos^n β around the mirror direction R of ``k``: pdf = (n+1)/(2π) cos^n β (over the sphere)."""

    n: float

    def sample(self, k, u):
        R = k * np.array([-1.0, -1.0, 1.0])
        cos_b, sin_b = PowerCosine(self.n, "mirror").angle(u[..., 0])
        phi = 2.0 * np.pi * u[..., 1]
        t, b = _frame_around(R)
        return (cos_b[..., None] * R + (sin_b * np.cos(phi))[..., None] * t
                + (sin_b * np.sin(phi))[..., None] * b)

    def pdf(self, k, w):
        R = k * np.array([-1.0, -1.0, 1.0])
        c = np.clip(np.einsum("...i,...i", R, w), 0.0, 1.0)
        return (self.n + 1.0) / (2.0 * np.pi) * c ** self.n


@dataclass(frozen=True)
class PatchExponentialSampler:
    """p_A(z) = s² e^{−s|z|} / (2π) on the base plane, z = (w + k)_P (eq. 4.44's own profile)."""

    s: float

    def sample(self, k, u):
        # radius ~ Gamma(2, 1/s): invert its CDF 1 − (1 + x) e^{−x} = u with the W_{−1} branch
        u1 = np.clip(u[..., 0], 0.0, 1.0 - 1e-16)
        r = (-1.0 - lambertw((u1 - 1.0) / np.e, k=-1).real) / self.s
        phi = 2.0 * np.pi * u[..., 1]
        wp = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1) - k[..., :2]
        inside = np.sum(wp * wp, axis=-1) < 1.0
        return np.where(inside[..., None], _lift(wp), np.array([0.0, 0.0, -1.0]))

    def pdf(self, k, w):
        z = np.hypot(w[..., 0] + k[..., 0], w[..., 1] + k[..., 1])
        return self.s ** 2 * np.exp(-self.s * z) / (2.0 * np.pi) * np.maximum(w[..., 2], 0.0)


@dataclass(frozen=True)
class PatchEllipseSampler:
    """Uniform on the ellipse of :class:`~brdfs.physics.models.patch.PatchElliptical` (eq. 4.32)."""

    b: float
    ratio: float
    u_angle_deg: float = 0.0

    def sample(self, k, u):
        r, phi = np.sqrt(u[..., 0]), 2.0 * np.pi * u[..., 1]
        along_u, along_v = r * np.cos(phi) * self.b / self.ratio, r * np.sin(phi) * self.b
        a = np.radians(self.u_angle_deg)
        z = np.stack([np.cos(a) * along_u - np.sin(a) * along_v, np.sin(a) * along_u + np.cos(a) * along_v], -1)
        wp = z - k[..., :2]
        inside = np.sum(wp * wp, axis=-1) < 1.0
        return np.where(inside[..., None], _lift(wp), np.array([0.0, 0.0, -1.0]))

    def pdf(self, k, w):
        a = np.radians(self.u_angle_deg)
        zx, zy = w[..., 0] + k[..., 0], w[..., 1] + k[..., 1]
        along_u = np.cos(a) * zx + np.sin(a) * zy
        along_v = -np.sin(a) * zx + np.cos(a) * zy
        inside = (self.ratio * along_u) ** 2 + along_v ** 2 <= self.b ** 2
        area = np.pi * self.b ** 2 / self.ratio
        return np.where(inside, np.maximum(w[..., 2], 0.0) / area, 0.0)


@dataclass(frozen=True)
class ModelSampler:
    """The model's own sampler: ``model.sample(L, u) -> (V, weight, pdf)`` and ``model.pdf(L, V)``."""

    model: object

    def sample(self, k, u):
        w, _weight, _pdf = self.model.sample(k, u)
        return np.asarray(w, float)

    def pdf(self, k, w):
        return np.asarray(self.model.pdf(k, w), float)


def proposal_for(model):
    """The best available proposal for ``model``: its own sampler (where it overrides the protocol's
    cosine default), else one fitted to its shape."""
    own = getattr(type(model), "sample", None)
    if callable(own) and callable(getattr(model, "pdf", None)) and own is not BRDF.sample:
        return ModelSampler(model)
    name = getattr(model, "name", "")
    if name == "patch_exponential":
        return PatchExponentialSampler(model.s)
    if name == "patch_elliptical":
        return PatchEllipseSampler(model.b, model.ratio, model.u_angle_deg)
    try:
        lobe = model.lobe
    except (NotImplementedError, AttributeError):
        lobe = None
    if isinstance(lobe, PowerCosine) and lobe.frame == "mirror":
        return PowerLobeSampler(lobe.n)
    return CosineSampler()
