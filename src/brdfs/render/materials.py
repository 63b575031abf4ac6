"""Materials of the renders: the package's BRDFs times spectra, with their Monte Carlo proposals.

A material is a sum of lobes; each lobe is a scalar BRDF of the package (``brdfs.model(name,
**params)``, evaluated as ``model(L, V)`` on local unit vectors, N = (0, 0, 1)) times a factor
per colour channel: a constant (diffuse colours, a_s of eq. 3.31) or a Fresnel reflectance
from a complex index per wavelength, read at the angle the model declares
(:meth:`~brdfs.physics.models.base.BRDF.fresnel_cosine`: Θ_min of eq. 3.29 by default, L·H for the
microfacet models, θ' of eq. 4.53 for the patch models, eq. 4.54). Each lobe proposes directions with its model's own
sampler (:mod:`brdfs.render.sampling`). Channels are wavelengths (spectral scenes) or r, g, b
(eq. 3.31). Values have shape (…, C).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.models.base import BRDF
from brdfs.render.sampling import COSINE, Proposal


@dataclass(frozen=True)
class Lambert(BRDF):
    """f = 1/π (ρ per channel is the lobe's factor; ρ = 1 is the white-furnace material).

    A model like the package's: it samples with the cosine strategy every model has, which is
    exact for it (weight ρ)."""

    reflectance: np.ndarray | None = None
    name = "lambert"
    lobe = None

    def _eval(self, L, V, nl, nv):
        return np.where(nl > 0, 1.0 / np.pi, 0.0)


@dataclass(frozen=True)
class Lobe:
    """One term ``brdf(L, V) · factor`` of a material.

    ``factor`` is a constant per channel (C,), or, if ``ior`` (complex n + ik per channel) is
    given, the unpolarised Fresnel reflectance (eqs. 1.41–1.43) at the model's Fresnel angle
    (``brdf.fresnel_cosine``) times ``scale``.
    """

    brdf: object
    scale: np.ndarray
    ior: np.ndarray | None = None
    share: float | None = None

    def __call__(self, L, V):
        f = np.asarray(self.brdf.unchecked(L, V), float)[..., None] * self.scale
        if self.ior is None:
            return f
        cos_t = self.brdf.fresnel_cosine(L, V)[..., None]
        return f * unpolarised_reflectance(cos_t, self.ior.real, np.abs(self.ior.imag))

    @property
    def proposal(self):
        """The model's own sampler (its default strategy)."""
        return Proposal.of(self.brdf)

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
        if not all(p.is_cosine for p in proposals):
            proposals.append(Proposal(Lambert(), COSINE))
            weights = np.append((1.0 - self.defensive) * weights, self.defensive)
        object.__setattr__(self, "proposals", tuple(proposals))
        object.__setattr__(self, "probabilities", weights)

    @property
    def channels(self):
        return int(np.size(self.lobes[0].scale))

    @property
    def sample_dimension(self) -> int:
        """Uniform numbers one sample of :meth:`sample` consumes (besides the pick of the proposal)."""
        return max(p.dimension for p in self.proposals)

    def f(self, L, V):
        """BRDF per channel (…, C)."""
        return sum(lobe(L, V) for lobe in self.lobes)

    def pdf(self, V, L):
        """Mixture density of proposing L given V."""
        return sum(p * q.pdf(V, L) for p, q in zip(self.probabilities, self.proposals))

    def sample(self, V, u, u_pick):
        """L drawn from the mixture (``u`` (…, :attr:`sample_dimension`), ``u_pick`` chooses the
        proposal) and the weight f(L, V) cos θ_L / pdf(L) (…, C); 0 below the horizon."""
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


def specular(brdf, channels: int, ior=None, scale=1.0, label="") -> Material:
    """A specular material ``brdf · scale · F(ior)`` (metals: eq. 3.29 / 4.54, F at the model's angle)."""
    factor = np.broadcast_to(np.asarray(scale, float), (channels,)).copy()
    ior = None if ior is None else np.asarray(ior, complex)
    return Material((Lobe(brdf, factor, ior),), label=label or brdf.name)


def plastic(diffuse, a_s, brdf, label="plastic") -> Material:
    """Eq. 3.31: (r, g, b)/π + a_s · f_new · (1, 1, 1)."""
    rho = np.asarray(diffuse, float)
    if a_s + rho.max() > 1.0 + 1e-12:
        raise ValueError(f"plastic: a_s + max(r, g, b) must not exceed 1, got a_s={a_s}, rgb={rho.tolist()}")
    spec = np.full(rho.shape, float(a_s))
    return Material((Lobe(Lambert(rho), rho), Lobe(brdf, spec)), label=label)
