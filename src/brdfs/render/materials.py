"""Materials of the renders: the package's BRDFs times spectra, with their Monte Carlo proposals.

A material is a sum of lobes; each lobe is a scalar BRDF of the package (``brdfs.model(name,
**params)``, evaluated as ``model(L, V)`` on local unit vectors, N = (0, 0, 1)) times a factor
per colour channel: a constant (diffuse colours, a_s of eq. 3.31) or a Fresnel reflectance
from a complex index per wavelength (eq. 3.29 with F at Θ_min, eq. 4.54 with F at θ' of eq. 4.53).
Channels are wavelengths (spectral scenes) or r, g, b (eq. 3.31). Values have shape (…, C).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from brdfs.render.sampling import CosineSampler, proposal_for
from brdfs.physics.fresnel import unpolarised_reflectance


@dataclass(frozen=True)
class Lambert:
    """f = ρ/π, ρ per channel (ρ = 1 is the white-furnace material)."""

    reflectance: np.ndarray
    name = "lambert"

    def __call__(self, L, V):
        lit = (L[..., 2] > 0) & (V[..., 2] > 0)
        return np.where(lit, 1.0 / np.pi, 0.0)


def _cos_theta_min(L, V):
    """cos Θ_min = max(N·L, N·V) (eq. 3.29)."""
    return np.clip(np.maximum(L[..., 2], V[..., 2]), 0.0, 1.0)


def _cos_theta_prime(L, V):
    """cos θ' with sin θ' = |L_P − V_P| / 2 (eqs. 4.52/4.53): θ_L at the mirror pair."""
    half = 0.5 * np.hypot(L[..., 0] - V[..., 0], L[..., 1] - V[..., 1])
    return np.sqrt(np.clip(1.0 - half * half, 0.0, 1.0))


FRESNEL_ANGLES = {"theta_min": _cos_theta_min, "theta_prime": _cos_theta_prime}


@dataclass(frozen=True)
class Lobe:
    """One term ``brdf(L, V) · factor`` of a material.

    ``factor`` is a constant per channel (C,), or, if ``ior`` (complex n + ik per channel) is
    given, the unpolarised Fresnel reflectance (eqs. 1.41–1.43) at the angle ``fresnel_angle``
    times ``scale``.
    """

    brdf: object
    scale: np.ndarray
    ior: np.ndarray | None = None
    fresnel_angle: str = "theta_min"
    share: float | None = None

    def __call__(self, L, V):
        f = np.asarray(self.brdf(L, V), float)[..., None] * self.scale
        if self.ior is None:
            return f
        cos_t = FRESNEL_ANGLES[self.fresnel_angle](L, V)[..., None]
        return f * unpolarised_reflectance(cos_t, self.ior.real, np.abs(self.ior.imag))

    @property
    def proposal(self):
        return CosineSampler() if isinstance(self.brdf, Lambert) else proposal_for(self.brdf)

    @property
    def weight(self):
        """Share of this lobe in the proposal mixture: ``share`` if given, else its largest channel factor."""
        return float(np.max(self.scale)) if self.share is None else float(self.share)


@dataclass(frozen=True)
class Material:
    """A sum of lobes; ``defensive`` is the share of cosine sampling kept in every mixture."""

    lobes: tuple
    defensive: float = 0.1
    label: str = ""
    proposals: tuple = field(init=False)
    probabilities: np.ndarray = field(init=False)

    def __post_init__(self):
        proposals = [lobe.proposal for lobe in self.lobes]
        weights = np.array([lobe.weight for lobe in self.lobes], float)
        weights = weights / weights.sum()
        if not all(isinstance(p, CosineSampler) for p in proposals):
            proposals.append(CosineSampler())
            weights = np.append((1.0 - self.defensive) * weights, self.defensive)
        object.__setattr__(self, "proposals", tuple(proposals))
        object.__setattr__(self, "probabilities", weights)

    @property
    def channels(self):
        return int(np.size(self.lobes[0].scale))

    def f(self, L, V):
        """BRDF per channel (…, C)."""
        return sum(lobe(L, V) for lobe in self.lobes)

    def pdf(self, V, L):
        """Mixture density of proposing L given V."""
        return sum(p * q.pdf(V, L) for p, q in zip(self.probabilities, self.proposals))

    def sample(self, V, u, u_pick):
        """L drawn from the mixture and the weight f(L, V) cos θ_L / pdf(L) (…, C); 0 below the horizon."""
        cumulative = np.cumsum(self.probabilities)
        pick = np.minimum(np.searchsorted(cumulative, u_pick, side="right"), len(self.proposals) - 1)
        L = np.zeros(V.shape)
        for j, proposal in enumerate(self.proposals):
            chosen = pick == j
            if np.any(chosen):
                L[chosen] = proposal.sample(V[chosen], u[chosen])
        L = L / np.maximum(np.linalg.norm(L, axis=-1, keepdims=True), 1e-300)
        pdf = self.pdf(V, L)
        ok = (L[..., 2] > 0) & (pdf > 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            weight = self.f(L, V) * (L[..., 2] / np.where(ok, pdf, 1.0))[..., None]
        return L, np.where(ok[..., None], weight, 0.0)


def lambert(reflectance, label="diffuse") -> Material:
    """A diffuse material, ρ per channel."""
    rho = np.atleast_1d(np.asarray(reflectance, float))
    return Material((Lobe(Lambert(rho), rho),), label=label)


def specular(brdf, channels: int, ior=None, scale=1.0, fresnel_angle="theta_min", label="") -> Material:
    """A specular material ``brdf · scale · F(ior)`` (metals: eq. 3.29 / 4.54)."""
    factor = np.broadcast_to(np.asarray(scale, float), (channels,)).copy()
    ior = None if ior is None else np.asarray(ior, complex)
    return Material((Lobe(brdf, factor, ior, fresnel_angle),), label=label or getattr(brdf, "name", ""))


def plastic(diffuse, a_s, brdf, label="plastic") -> Material:
    """Eq. 3.31: (r, g, b)/π + a_s · f_new · (1, 1, 1)."""
    rho = np.asarray(diffuse, float)
    if a_s + rho.max() > 1.0 + 1e-12:
        raise ValueError(f"plastic: a_s + max(r, g, b) must not exceed 1, got a_s={a_s}, rgb={rho.tolist()}")
    spec = np.full(rho.shape, float(a_s))
    return Material((Lobe(Lambert(rho), rho), Lobe(brdf, spec)), label=label)
