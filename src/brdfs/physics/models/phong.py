"""Phong-type models: functions of R·V (chapter 2 and 3)."""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property

import numpy as np

from brdfs.physics.geometry import r_dot_v
from brdfs.physics.lobes import MIRROR, PowerCosine
from scipy.special import beta, gammaln

from brdfs.core.estimate import Estimate

from brdfs.physics.models.base import (N_MAX, PUMP_N_MAX, BRDF, GrazingLaw, Interval,
                                       check_positive, exact, log_range, non_negative, positive, positive_power,
                                       register)
from brdfs.physics import sampling


def phong_constant(n):
    """c_n = (n+2)/(2π), the largest energy-conserving constant of the reciprocal Phong (eq. 3.6)."""
    return (np.asarray(n, float) + 2.0) / (2.0 * np.pi)


def new_model_grazing_albedo(n):
    """a(90°) = (n+2) / (2(n+1)) for the new model with c = (n+2)/2π  (eq. 3.27); 1/2 for n = ∞."""
    n = np.asarray(n, float)
    return np.where(np.isinf(n), 0.5, (n + 2.0) / (2.0 * (n + 1.0)))


def phong_mean_albedo(n):
    """Mean albedo of the reciprocal Phong model with c = (n+2)/2π in closed form:

    A(n) = (2/3) (1 + W_n / (π (n+2))),  W_n = ∫₀^{π/2} cos^n α dα (Wallis),

    from A = (c/π) ∫∫ (R·V)^n (N·R)⁺ (N·V)⁺ dω_R dω_V and ∫_{S²} (N·R)⁺ (N·V)⁺ dN
    = (2/3)((π − α) cos α + sin α) for R·V = cos α.  For even n, W_n/π = (n−1)!!/(2 n!!) is
    rational and the value is returned exactly (A(4) = 11/16); A → 2/3 as n → ∞.

    Returns (value, absolute error bound).
    """
    if float(n).is_integer() and int(n) % 2 == 0:
        k = int(n)
        ratio = Fraction(1, 2)
        for j in range(2, k + 1, 2):
            ratio *= Fraction(j - 1, j)
        exact = Fraction(2, 3) * (1 + ratio / (k + 2))
        return float(exact), float(abs(Fraction(float(exact)) - exact))
    w = 0.5 * np.sqrt(np.pi) * np.exp(gammaln((n + 1) / 2) - gammaln(n / 2 + 1))
    value = 2.0 / 3.0 * (1 + w / (np.pi * (n + 2)))
    return float(value), 8 * np.finfo(float).eps * value


@dataclass(frozen=True)
class _PhongFamily(BRDF):
    n: float
    C: float | None = None
    #: the generic tests draw n from 0 and 1e-2 … 1e4 (the thesis's narrowest lobe), C from 1e-3 … 1e3
    test_ranges = {"n": log_range(1e-2, 1e4, zero=True), "C": log_range(1e-3, 1e3)}
    pumping_ranges = {"n": non_negative(PUMP_N_MAX)}

    def __post_init__(self):
        check_positive("n", self.n, allow_zero=True)
        if self.C is None:
            object.__setattr__(self, "C", float(phong_constant(self.n)))
        check_positive("C", self.C)

    #: (R·V)⁺ⁿ: nothing where R·V < 0, beyond the reach of its lobe about R.
    zero_beyond_lobe = True

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return PowerCosine(self.n, MIRROR)

    def _lobe_value(self, L, V):
        return self.C * positive_power(r_dot_v(L, V), self.n)

    # --- sampling: the cosine lobe about R (eqs. 3.19–3.22; Lafortune & Willems 1994) ---------
    #: ``"lobe"``: V with density (n + 1)/(2π) (R·V)^n about the mirror direction R (eq. 3.20);
    #: directions below the horizon are rejected (sec. 3.4.1), so the pdf integrates to the lobe's
    #: mass above the horizon (1 at normal incidence, about 1/2 at grazing).  It covers the whole
    #: support of f (R·V > 0), so Σ weight / M is unbiased for every member of the family.
    strategies = ("lobe", "cosine")
    chi2_cases = ({"n": 512}, {"n": 20}, {"n": 1})

    def _sample_direction(self, L, u, strategy):
        return sampling.mirror_lobe_sample(L, u, self.n)

    def _pdf(self, L, V, strategy):
        return sampling.mirror_lobe_pdf(L, V, self.n)


@register
@dataclass(frozen=True)
class Phong(_PhongFamily):
    """Reciprocal Phong, f = c (R·V)^n (eq. 2.6 / 3.5), c = (n+2)/2π by default."""

    name = "phong"
    # --- what the model says about itself
    chapter = 2                  # eq. 2.6 (and eq. 3.5)
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    half_angle_exponent_factor = 4.0     # (R·V)^n = cos^n 2δ ≈ cos^{4n} δ at normal incidence
    corrected_by = "phong_cosmin"        # eq. 3.10
    conserves_energy = True      # c = (n+2)/2π is the largest energy-conserving constant (eq. 3.6): a ≤ a(0) = 1
    pumping_reducible = True     # a cosine power of R·V without kinks: numerics.pumping.pumped_albedo
    accuracy_families = {"phong": ("n", {}), "pumped_phong_g1": ("n", {"pumping": "g1"}),
                         "pumped_phong_g2": ("n", {"pumping": "g2"})}
    closed_form_azimuth = (MIRROR, "nv")
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

    def exact_mean_albedo(self):
        """A(n) of :func:`phong_mean_albedo` (c = (n+2)/2π), scaled by C/c_n for another constant."""
        value, error = phong_mean_albedo(self.n)
        scale = self.C / float(phong_constant(self.n))
        if scale == 1.0:
            return Estimate(value, error)
        return Estimate(scale * value, scale * error + 2 * np.finfo(float).eps * abs(scale * value))


@register
@dataclass(frozen=True)
class PhongOriginal(_PhongFamily):
    """Original Phong, f = c (R·V)^n / cos θ_L (eq. 2.5) — not reciprocal."""

    name = "phong_original"
    # reciprocal = False: f divides by cos θ_L alone, f(L, V) ≠ f(V, L) (eq. 2.5)
    chapter = 2                  # eq. 2.5
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    # conserves_energy = False: divided by cos θ_L, its albedo grows without bound toward grazing
    # incidence (sec. 2.2, Figure 2.1; a(89.9°) ≈ 51 for n = 20)
    conserves_energy = False
    reciprocal = False
    diverges_at_grazing = True   # a(θ) cos θ → the reciprocal Phong's a(90°) = c B(3/2, (n+1)/2) > 0

    def _eval(self, L, V, nl, nv):
        lobe = self._lobe_value(L, V)
        return np.where(lobe > 0, lobe / nl, 0.0)          # 0, not 0/0, beyond the lobe on the horizon


@register
@dataclass(frozen=True)
class PhongCosmin(_PhongFamily):
    """The new model, f = c (R·V)^n / max(N·L, N·V) (eq. 3.10)."""

    name = "phong_cosmin"
    chapter = 3                  # eq. 3.10
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    # conserves_energy = False: with c = (n+2)/2π the albedo overshoots 1 slightly at intermediate
    # angles (sec. 3.2.2; Figure 3.1)
    conserves_energy = False
    accuracy_families = {"phong_cosmin": ("n", {})}
    closed_form_azimuth = (MIRROR, "nv/max")
    limit_cos_power = 0          # g = 1/max(cos θ_L, cos θ_V) at V = R: a → 1 for θ < 90°
    limit_albedo_90 = 0.5        # eq. 3.27: (n+2)/(2(n+1)) → 1/2

    def _eval(self, L, V, nl, nv):
        lobe = self._lobe_value(L, V)
        return np.where(lobe > 0, lobe / np.maximum(nl, nv), 0.0)

    def nv_levels(self, nl):
        return (nl,)

    def grazing_law(self):
        """Finite: a(90°) = c π/(n+1) (eq. 3.27)."""
        return GrazingLaw(0.0, exact(self.C * np.pi / (self.n + 1)), "a(90) = c pi/(n+1)")

    def exact_albedo(self, theta_deg):
        """a(90°) = c π/(n+1), i.e. (n+2)/(2(n+1)) for c = (n+2)/2π (eq. 3.27)."""
        theta = np.asarray(theta_deg, float)
        return np.where(theta == 90.0, self.C * np.pi / (self.n + 1), np.nan)


@register
@dataclass(frozen=True)
class PModel(_PhongFamily):
    """p-model, f = c (R·V)^n / max(N·L, N·V)^p, 0 ≤ p ≤ 1 (eq. 3.12)."""

    p: float = 1.0
    name = "p_model"
    chapter = 3                  # eq. 3.12
    param_ranges = {"n": non_negative(N_MAX), "C": positive(), "p": Interval(0.0, 1.0)}
    examples = {"typical": {"n": 20.0, "p": 0.5}, "narrowest": {"n": 1.0e4, "p": 0.5}}
    # conserves_energy = False: p = 1 is the new model (eq. 3.10), which overshoots (sec. 3.2.2)
    conserves_energy = False
    chi2_cases = ({"n": 512, "p": 0.5}, {"n": 20, "p": 0.5})

    def __post_init__(self):
        super().__post_init__()
        if not 0.0 <= float(self.p) <= 1.0:
            raise ValueError(f"p must lie in [0, 1], got {self.p!r}")

    def _eval(self, L, V, nl, nv):
        lobe = self._lobe_value(L, V)
        return np.where(lobe > 0, lobe / np.maximum(nl, nv) ** self.p, 0.0)

    def nv_levels(self, nl):
        return (nl,)
