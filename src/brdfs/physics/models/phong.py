"""Phong-type models: functions of R·V (chapter 2 and 3)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from brdfs.physics.geometry import r_dot_v
from brdfs.physics.lobes import PowerCosine
from scipy.special import beta

from brdfs.physics.models.base import BRDF, GrazingLaw, check_positive, exact, positive_power
from brdfs.physics import sampling


def phong_constant(n):
    """c_n = (n+2)/(2π), the largest energy-conserving constant of the reciprocal Phong (eq. 3.6)."""
    return (np.asarray(n, float) + 2.0) / (2.0 * np.pi)


@dataclass(frozen=True)
class _PhongFamily(BRDF):
    n: float
    C: float | None = None

    def __post_init__(self):
        check_positive("n", self.n, allow_zero=True)
        if self.C is None:
            object.__setattr__(self, "C", float(phong_constant(self.n)))
        check_positive("C", self.C)

    @property
    def lobe(self):
        return PowerCosine(self.n, "mirror")

    def _lobe_value(self, L, V):
        return self.C * positive_power(r_dot_v(L, V), self.n)

    # --- sampling: the cosine lobe about R (eqs. 3.19–3.22; Lafortune & Willems 1994) ---------
    #: ``"lobe"``: V with density (n + 1)/(2π) (R·V)^n about the mirror direction R (eq. 3.20);
    #: directions below the horizon are rejected (sec. 3.4.1), so the pdf integrates to the lobe's
    #: mass above the horizon (1 at normal incidence, about 1/2 at grazing).  It covers the whole
    #: support of f (R·V > 0), so Σ weight / M is unbiased for every member of the family.
    strategies = ("lobe", "cosine")

    def _sample_direction(self, L, u, strategy):
        cos_a, sin_a = sampling.power_cosine(u[..., 0], self.n)
        V = sampling.around_axis(sampling.mirror_direction(L), cos_a, sin_a, 2.0 * np.pi * u[..., 1])
        return np.where((V[..., 2] > 0)[..., None], V, sampling.REJECTED)

    def _pdf(self, L, V, strategy):
        return sampling.power_cosine_pdf(r_dot_v(L, V), self.n)


@dataclass(frozen=True)
class Phong(_PhongFamily):
    """Reciprocal Phong, f = c (R·V)^n (eq. 2.6 / 3.5), c = (n+2)/2π by default."""

    name = "phong"
    closed_form_azimuth = ("mirror", "nv")
    limit_cos_power = 1          # the lobe → a delta at R of weight 1: a → cos θ
    limit_albedo_90 = 0.0        # a(90°) ≤ c·2π/(n+1) · max N·V over the lobe → 0

    def _eval(self, L, V, nl, nv):
        return self._lobe_value(L, V)

    def grazing_law(self):
        """Finite: a(90°) = c B(3/2, (n+1)/2)."""
        return GrazingLaw(0.0, exact(self.C * beta(1.5, (self.n + 1) / 2)), "a(90) = c B(3/2,(n+1)/2)")

    def exact_albedo(self, theta_deg):
        """a(0) = c 2π/(n+2) (eq. 3.6: 1 for c = (n+2)/2π)."""
        theta = np.asarray(theta_deg, float)
        return np.where(theta == 0.0, self.C * 2 * np.pi / (self.n + 2), np.nan)


@dataclass(frozen=True)
class PhongOriginal(_PhongFamily):
    """Original Phong, f = c (R·V)^n / cos θ_L (eq. 2.5) — not reciprocal."""

    name = "phong_original"
    reciprocal = False

    def _eval(self, L, V, nl, nv):
        return self._lobe_value(L, V) / nl


@dataclass(frozen=True)
class PhongCosmin(_PhongFamily):
    """The new model, f = c (R·V)^n / max(N·L, N·V) (eq. 3.10)."""

    name = "phong_cosmin"
    closed_form_azimuth = ("mirror", "nv/max")
    limit_cos_power = 0          # g = 1/max(cos θ_L, cos θ_V) at V = R: a → 1 for θ < 90°
    limit_albedo_90 = 0.5        # eq. 3.27: (n+2)/(2(n+1)) → 1/2

    def _eval(self, L, V, nl, nv):
        return self._lobe_value(L, V) / np.maximum(nl, nv)

    def nv_levels(self, nl):
        return (nl,)

    def grazing_law(self):
        """Finite: a(90°) = c π/(n+1) (eq. 3.27)."""
        return GrazingLaw(0.0, exact(self.C * np.pi / (self.n + 1)), "a(90) = c pi/(n+1)")

    def exact_albedo(self, theta_deg):
        """a(90°) = c π/(n+1), i.e. (n+2)/(2(n+1)) for c = (n+2)/2π (eq. 3.27)."""
        theta = np.asarray(theta_deg, float)
        return np.where(theta == 90.0, self.C * np.pi / (self.n + 1), np.nan)


@dataclass(frozen=True)
class PModel(_PhongFamily):
    """p-model, f = c (R·V)^n / max(N·L, N·V)^p, 0 ≤ p ≤ 1 (eq. 3.12)."""

    p: float = 1.0
    name = "p_model"

    def __post_init__(self):
        super().__post_init__()
        if not 0.0 <= float(self.p) <= 1.0:
            raise ValueError(f"p must lie in [0, 1], got {self.p!r}")

    def _eval(self, L, V, nl, nv):
        return self._lobe_value(L, V) / np.maximum(nl, nv) ** self.p

    def nv_levels(self, nl):
        return (nl,)
