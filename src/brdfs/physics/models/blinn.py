"""Blinn-type models: functions of N·H (sections 1.2.4 and 3.7.1)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from brdfs.physics.geometry import n_dot_h
from brdfs.physics.lobes import PowerCosine
from brdfs.physics.models.base import BRDF, check_positive, positive_power
from brdfs.physics import sampling


@dataclass(frozen=True)
class _BlinnFamily(BRDF):
    n: float
    C: float = 1.0

    def __post_init__(self):
        check_positive("n", self.n, allow_zero=True)
        check_positive("C", self.C)

    @property
    def lobe(self):
        return PowerCosine(self.n, "half")

    # --- sampling: half vectors from the cosine power about N -----------------------------------
    #: ``"half_vector"``: H with density (n + 1)/(2π) (N·H)^n, V = 2 (L·H) H − L, so
    #: pdf(V) = (n + 1)/(2π) (N·H)^n / (4 V·H) (the half-vector Jacobian).  H with L·H ≤ 0 or a V
    #: below the horizon is rejected: the pdf's mass is P(V above the horizon) < 1.
    strategies = ("half_vector", "cosine")

    def _sample_direction(self, L, u, strategy):
        cos_d, sin_d = sampling.power_cosine(u[..., 0], self.n)
        phi = 2.0 * np.pi * u[..., 1]
        H = np.stack([sin_d * np.cos(phi), sin_d * np.sin(phi), cos_d], -1)
        V, lh = sampling.reflect_about(L, H)
        return np.where(((lh > 0) & (V[..., 2] > 0))[..., None], V, sampling.REJECTED)

    def _pdf(self, L, V, strategy):
        nh, jacobian = sampling.half_vector_jacobian(L, V)
        return sampling.power_cosine_pdf(nh, self.n) * jacobian


@dataclass(frozen=True)
class Blinn(_BlinnFamily):
    """Reciprocal Blinn, f = C (N·H)^n (eq. 1.34 / 2.6 / 3.33)."""

    name = "blinn"
    closed_form_azimuth = ("half", "nv")
    limit_cos_power = 2          # dω_V = 4 (L·H) dω_H at H = N, C_n scaling the maximum to 1: a → cos²θ

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n)


@dataclass(frozen=True)
class BlinnOriginal(_BlinnFamily):
    """Original Blinn, f = C (N·H)^n / cos θ_L (eq. 2.5) — not reciprocal."""

    name = "blinn_original"
    reciprocal = False

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n) / nl


@dataclass(frozen=True)
class BlinnCosmin(_BlinnFamily):
    """Corrected Blinn, f = C (N·H)^n / max(N·L, N·V) (eq. 3.34)."""

    name = "blinn_cosmin"
    closed_form_azimuth = ("half", "nv/max")
    limit_cos_power = 1          # as Blinn, divided by max(N·L, N·V) = cos θ: a → cos θ

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n) / np.maximum(nl, nv)

    def nv_levels(self, nl):
        return (nl,)
