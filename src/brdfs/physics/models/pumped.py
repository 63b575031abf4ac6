"""Pumped models (section 2.3, albedo pumping-up): f* = f / g with g ≥ max(a(L), a(V)) (eqs. 2.16–2.21).

Two correction terms (section 2.3.1/2.3.2)::

    g1(L, V) = max(a(L), a(V))                      (eq. 2.20, "plain")
    g2(L, V) = max(a(L), a(V), N·V, N·L)            (eq. 2.21, "controlled")

A pumped model is again a symmetric BRDF, so it can be pumped with its own albedo, level after level.
It receives the albedo a of the model it pumps as a table (:class:`brdfs.physics.tables.AlbedoTable`)
when it is built: this module evaluates the table and computes none.  The tables, the pumped models'
error budget and their fast albedo integral are :mod:`brdfs.numerics.pumping`'s; build a pumped model
with its table by :func:`brdfs.numerics.tables.pump`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from brdfs.physics.models.base import BRDF
from brdfs.physics.tables import AlbedoTable

CORRECTIONS = ("g1", "g2")


@dataclass(frozen=True)
class Pumped(BRDF):
    """f* = f / g (eq. 2.16), g = g1 (eq. 2.20) or g2 (eq. 2.21) from the tabulated albedo of f.

    Attributes
    ----------
    base : BRDF
        The symmetric model pumped (itself possibly a :class:`Pumped`).
    table : AlbedoTable
        The albedo of ``base``.
    correction : str
        ``'g1'`` (plain) or ``'g2'`` (controlled).
    """

    base: BRDF
    table: AlbedoTable
    correction: str = "g1"
    #: Section 2.3: the thesis's remedy for the energy a model loses; chapter 2.
    chapter: ClassVar[int | None] = 2

    def __post_init__(self):
        if self.correction not in CORRECTIONS:
            raise ValueError(f"correction must be one of {CORRECTIONS}, got {self.correction!r}")
        if not self.base.reciprocal:
            raise ValueError(f"pumping needs a symmetric BRDF, got the non-reciprocal {self.base.name!r}")

    @property
    def name(self):
        return self.base.name

    @property
    def level(self):
        """How many times the original model has been pumped."""
        return self.base.level + 1 if isinstance(self.base, Pumped) else 1

    @property
    def root(self):
        """The original (unpumped) model of the chain."""
        return self.base.root if isinstance(self.base, Pumped) else self.base

    @property
    def conserves_energy(self):
        """g ≥ a(L) makes a*(L) = ∫ f/g cos θ_V dω_V ≤ ∫ f/a(L) cos θ_V dω_V = 1 (eq. 2.17), within the
        table's error."""
        return True

    @property
    def evaluation_rtol(self):
        """ε of this level: |f̃ / f − 1| ≤ ε = (1 + ε_base) / (1 − δ) − 1, with ε_base the tabulated
        model's own (``table.model_rtol``) and δ the table's relative error (``table.rtol``;
        :mod:`brdfs.numerics.pumping`, "Error budget")."""
        return (1.0 + self.table.model_rtol) / (1.0 - self.table.rtol) - 1.0

    @property
    def lobe(self):
        return self.base.lobe

    @property
    def sqrt_at_horizon(self):
        return self.base.sqrt_at_horizon

    def lh_levels(self, nl, cos_delta):
        """The base model's L·H kinks (g depends on N·L and N·V only)."""
        return self.base.lh_levels(nl, cos_delta)

    # the base model's other kinks, unchanged by g (a function of N·L and N·V only)
    def azimuth_levels(self, nl):
        return self.base.azimuth_levels(nl)

    def scattering_radius_levels(self):
        return self.base.scattering_radius_levels()

    def scattering_radius_kinks(self, cos_psi, sin_psi):
        return self.base.scattering_radius_kinks(cos_psi, sin_psi)

    def scattering_radius_steep_layer(self):
        return self.base.scattering_radius_steep_layer()

    @property
    def torrance_sparrow_switches(self):
        return self.base.torrance_sparrow_switches

    @property
    def kink_at_normal(self):
        return self.base.kink_at_normal

    @property
    def zero_beyond_lobe(self):
        return self.base.zero_beyond_lobe

    @property
    def symmetric_about_incidence_plane(self):
        return self.base.symmetric_about_incidence_plane

    @property
    def params(self):
        return self.base.params

    def correction_term(self, nl, nv):
        """g(L, V) of eq. 2.20 or 2.21 from N·L and N·V."""
        g = np.maximum(self.table(nl), self.table(nv))
        if self.correction == "g2":
            g = np.maximum(g, np.maximum(nl, nv))
        return g

    def _eval(self, L, V, nl, nv):
        return self.base._eval(L, V, nl, nv) / self.correction_term(nl, nv)

    def nv_levels(self, nl):
        """N·V where g switches argument: N·V = N·L, a(V) = a(L), and for g2 also N·V = a(L),
        a(V) = N·L and a(V) = N·V; plus the table's piece edges and the base model's kinks."""
        segments = self.table.segments
        bounds = list(zip(segments[:-1], segments[1:]))
        a_l = self.table(nl)
        levels = [*self.base.nv_levels(nl), nl]
        if len(bounds) > 1:            # a monotone table has the single root a(V) = a(L) at N·V = N·L
            levels += [self.table.solve(a_l, lo, hi) for lo, hi in bounds]
        levels += list(self.table.edges[1:-1])
        if self.correction == "g2":
            levels += [a_l, *(self.table.solve(nl, lo, hi) for lo, hi in bounds)]
            levels += list(self.table.cosine_crossings)
        return tuple(levels)

    # --- sampling: the base model's (f* = f/g has the base's lobe; g varies slowly) -------------
    @property
    def strategies(self):
        """The base model's strategies: its pdf follows f, and f* = f/g with g ≥ max(a(L), a(V))."""
        return self.base.strategies

    @property
    def sample_dimensions(self):
        return self.base.sample_dimensions

    @property
    def sampling_domain(self):
        return self.base.sampling_domain

    def disk_boundaries(self):
        return self.base.disk_boundaries()

    def fresnel_cosine(self, L, V):
        """The base model's Fresnel angle (g changes the lobe's height, not the metal's angle)."""
        return self.base.fresnel_cosine(L, V)

    def _sample_direction(self, L, u, strategy):
        return self.base._sample_direction(L, u, strategy)

    def _pdf(self, L, V, strategy):
        return self.base._pdf(L, V, strategy)
