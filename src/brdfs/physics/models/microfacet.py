"""Beckmann-lobe models: Ward (eqs. 2.8, 3.35), corrected Ward (eq. 3.36), Cook–Torrance (eqs. 2.9, 2.10)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import erfc

from brdfs.physics.geometry import dot, half_vector
from brdfs.numerics.integrate.lobes import Beckmann
from brdfs.physics.models.base import BRDF, check_positive


def beckmann_exponential(L, V, m):
    """exp(−tan²δ / m²) with tan²δ = (1 − NH²)/NH² computed from h = L + V without cancellation."""
    h = L + V
    hz2 = h[..., 2] ** 2
    tan2 = (h[..., 0] ** 2 + h[..., 1] ** 2) / hz2
    return np.exp(-tan2 / m ** 2), np.sqrt(hz2 / (hz2 + h[..., 0] ** 2 + h[..., 1] ** 2))


@dataclass(frozen=True)
class _BeckmannFamily(BRDF):
    m: float
    C: float = 1.0

    def __post_init__(self):
        check_positive("m", self.m)
        check_positive("C", self.C)

    @property
    def lobe(self):
        return Beckmann(self.m)


@dataclass(frozen=True)
class Ward(_BeckmannFamily):
    """Isotropic Ward, f = C/(4π m²) · exp(−tan²δ/m²) / √(N·L N·V) (eq. 2.8 / 3.35)."""

    name = "ward"
    sqrt_at_horizon = True

    def _eval(self, L, V, nl, nv):
        e, _ = beckmann_exponential(L, V, self.m)
        return self.C / (4 * np.pi * self.m ** 2) * e / np.sqrt(nl * nv)


@dataclass(frozen=True)
class WardCosmin(_BeckmannFamily):
    """Corrected Ward, f = C/(4π m²) · exp(−tan²δ/m²) / max(N·L, N·V) (eq. 3.36)."""

    name = "ward_cosmin"

    def _eval(self, L, V, nl, nv):
        e, _ = beckmann_exponential(L, V, self.m)
        return self.C / (4 * np.pi * self.m ** 2) * e / np.maximum(nl, nv)

    def nv_levels(self, nl):
        return (nl,)


def g_torrance_sparrow(nh, nl, nv, lh):
    """G = min{1, 2 NH NV / VH, 2 NH NL / LH} (eq. 2.10; V·H = L·H)."""
    return np.minimum(1.0, np.minimum(2 * nh * nv / lh, 2 * nh * nl / lh))


def g_smith_beckmann(nl, nv, m):
    """G = G*(N·L) G*(N·V) with Smith's G* for a Beckmann surface (eq. 1.38)."""
    return _smith_g1(nl, m) * _smith_g1(nv, m)


def _smith_g1(x, m):
    h = x * x / (2 * m * m * (1 - x * x))
    g = np.sqrt(np.pi * h) * (2 - erfc(np.sqrt(h)))
    return np.where(x >= 1.0, 1.0, g / (g + 1))


GEOMETRY_FACTORS = ("torrance_sparrow", "smith", "none")


@dataclass(frozen=True)
class CookTorrance(_BeckmannFamily):
    """Cook–Torrance with F = 1 (eq. 2.9):
    f = exp(−tan²δ/m²) / (4π m² cos⁴δ) · G / (N·L N·V), G from eq. 2.10 by default.

    ``G`` selects the geometry factor: ``"torrance_sparrow"`` (eq. 2.10, as printed),
    ``"smith"`` (eq. 1.38) or ``"none"`` (G = 1).
    """

    G: str = "torrance_sparrow"
    name = "cook_torrance"

    def __post_init__(self):
        super().__post_init__()
        if self.G not in GEOMETRY_FACTORS:
            raise ValueError(f"unknown geometry factor G={self.G!r}; choose one of {GEOMETRY_FACTORS}")

    def _eval(self, L, V, nl, nv):
        e, nh = beckmann_exponential(L, V, self.m)
        d = self.C * e / (4 * np.pi * self.m ** 2 * nh ** 4)
        return d * self._geometry(L, V, nl, nv, nh) / (nl * nv)

    def _geometry(self, L, V, nl, nv, nh):
        if self.G == "torrance_sparrow":
            return g_torrance_sparrow(nh, nl, nv, dot(L, half_vector(L, V)))
        if self.G == "smith":
            return g_smith_beckmann(nl, nv, self.m)
        return 1.0

    def nv_levels(self, nl):
        """N·V = N·L: where eq. 2.10's minimum switches between its masking and shadowing terms."""
        return (nl,) if self.G == "torrance_sparrow" else ()

    def lh_levels(self, nl, cos_delta):
        """Where the shadowing (LH = 2 NH NL) and masking (LH (4 NH² − 1) = 2 NH NL) terms of eq. 2.10 reach 1."""
        if self.G != "torrance_sparrow":
            return ()
        with np.errstate(divide="ignore"):
            masking = 2 * cos_delta * nl / (4 * cos_delta ** 2 - 1)
        return (2 * cos_delta * nl, np.where(4 * cos_delta ** 2 > 1, masking, np.inf))
