"""Blinn-type models: functions of N·H (sections 1.2.4 and 3.7.1)."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from brdfs.physics.geometry import n_dot_h
from brdfs.physics.lobes import HALF, PowerCosine
from brdfs.physics.models.base import BRDF, N_MAX, PUMP_N_MAX, check_positive, log_range, non_negative, positive, positive_power, register
from brdfs.physics import sampling


@dataclass(frozen=True)
class _BlinnFamily(BRDF):
    n: float
    C: float = 1.0
    #: the generic tests draw n from 0 and 1e-2 … 1e4 (the thesis's narrowest lobe), C from 1e-3 … 1e3
    test_ranges = {"n": log_range(1e-2, 1e4, zero=True), "C": log_range(1e-3, 1e3)}
    pumping_ranges = {"n": non_negative(PUMP_N_MAX)}

    def __post_init__(self):
        check_positive("n", self.n, allow_zero=True)
        check_positive("C", self.C)

    @cached_property                 # a frozen model's lobe: built once, not on every look-up
    def lobe(self):
        return PowerCosine(self.n, HALF)

    # --- sampling: half vectors from the cosine power about N -----------------------------------
    #: ``"half_vector"``: H with density (n + 1)/(2π) (N·H)^n, V = 2 (L·H) H − L, so
    #: pdf(V) = (n + 1)/(2π) (N·H)^n / (4 V·H) (the half-vector Jacobian).  H with L·H ≤ 0 or a V
    #: below the horizon is rejected: the pdf's mass is P(V above the horizon) < 1.
    strategies = ("half_vector", "cosine")
    chi2_cases = ({"n": 512}, {"n": 20}, {"n": 1})

    def _sample_direction(self, L, u, strategy):
        return sampling.half_vector_sample(L, u, self.n)

    def _pdf(self, L, V, strategy):
        return sampling.half_vector_pdf(L, V, self.n)


@register
@dataclass(frozen=True)
class Blinn(_BlinnFamily):
    """Reciprocal Blinn, f = C (N·H)^n (eq. 1.34 / 2.6 / 3.33)."""

    name = "blinn"
    # --- what the model says about itself
    chapter = 1                  # eq. 1.34 (Table 1.1), again eqs. 2.6 and 3.33
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    # conserves_energy = False: the default C = 1 gives a(0) > 1 for small n (C must be scaled to
    # 1/max a, Table 3.1)
    conserves_energy = False
    half_angle_exponent_factor = 1.0     # (N·H)^n = cos^n δ
    corrected_by = "blinn_cosmin"        # eq. 3.34
    constant_is_computed = True          # C_n = 1/max a (Table 3.1)
    pumping_reducible = True     # a cosine power of N·H without kinks: numerics.pumping.pumped_albedo
    accuracy_families = {"blinn": ("n", {})}
    closed_form_azimuth = (HALF, "nv")
    limit_cos_power = 2          # dω_V = 4 (L·H) dω_H at H = N, C_n scaling the maximum to 1: a → cos²θ

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n)


@register
@dataclass(frozen=True)
class BlinnOriginal(_BlinnFamily):
    """Original Blinn, f = C (N·H)^n / cos θ_L (eq. 2.5) — not reciprocal."""

    name = "blinn_original"
    # reciprocal = False: f divides by cos θ_L alone (eq. 2.5)
    chapter = 2                  # eq. 2.5
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    # conserves_energy = False: divided by cos θ_L, its albedo diverges at grazing incidence (sec. 2.2.1)
    conserves_energy = False
    reciprocal = False
    diverges_at_grazing = True   # a(θ) cos θ → the reciprocal Blinn's a(90°) > 0

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n) / nl


@register
@dataclass(frozen=True)
class BlinnCosmin(_BlinnFamily):
    """Corrected Blinn, f = C (N·H)^n / max(N·L, N·V) (eq. 3.34)."""

    name = "blinn_cosmin"
    chapter = 3                  # eq. 3.34
    param_ranges = {"n": non_negative(N_MAX), "C": positive()}
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1.0e4}}
    # conserves_energy = False: with the default C = 1 the albedo exceeds 1 for small n (Table 3.1's
    # C_n = 1/max a is below 1 there)
    conserves_energy = False
    constant_is_computed = True          # C_n = 1/max a (Table 3.1)
    accuracy_families = {"blinn_cosmin": ("n", {})}
    closed_form_azimuth = (HALF, "nv/max")
    limit_cos_power = 1          # as Blinn, divided by max(N·L, N·V) = cos θ: a → cos θ

    def _eval(self, L, V, nl, nv):
        return self.C * positive_power(n_dot_h(L, V), self.n) / np.maximum(nl, nv)

    def nv_levels(self, nl):
        return (nl,)
