"""The masking factor S(N·L, N·V) of a microfacet model f = D(H) S(N·L, N·V), declared as a value.

A model that factors so declares ``half_vector_factors() = (distribution, S)``
(:meth:`brdfs.physics.models.base.BRDF.half_vector_factors`).  Where S is one of the forms below, it is
an instance of one of these frozen classes: the form, its roughness and its scale are fields, and the
instance evaluates itself.  The numpy route calls it; the compiled polar route
(:mod:`brdfs.numerics.integrate.polar_compiled`) reads its fields, by the form's exact type (a subclass
may change the formula: the numpy route answers for it).  One fact in one place: what S is, the model
says once, and both routes read it.  Any other callable S (a user's) is evaluated as it is.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from brdfs.physics.distributions import Beckmann

#: The forms of Smith's G2 (Walter et al. 2007; Heitz 2014): G1(L) G1(V), or 1/(1 + Λ(L) + Λ(V)).
G2_FORMS = ("separable", "height_correlated")


@dataclass(frozen=True)
class SmithG2:
    """S = G2/(4 N·L N·V) of Smith's masking-shadowing with Λ of ``distribution`` (GGX or Beckmann:
    its ``smith_lambda_cos``, λ(μ) = Λ μ), ``form`` one of :data:`G2_FORMS`.  Written with λ, finite at
    the horizon: 1/(4 (μ_L μ_V + μ_V λ(μ_L) + μ_L λ(μ_V))) (height-correlated) or
    1/(4 (μ_L + λ(μ_L)) (μ_V + λ(μ_V))) (separable)."""

    distribution: object
    form: str = "height_correlated"

    def __post_init__(self):
        if self.form not in G2_FORMS:
            raise ValueError(f"SmithG2: form must be one of {G2_FORMS}, got {self.form!r}")

    def __call__(self, nl, nv):
        lam = self.distribution.smith_lambda_cos
        if self.form == "height_correlated":
            return 1.0 / (4.0 * (nl * nv + nv * lam(nl) + nl * lam(nv)))
        return 1.0 / (4.0 * (nl + lam(nl)) * (nv + lam(nv)))


def g_smith_beckmann(nl, nv, m):
    """G = G*(N·L) G*(N·V) with Smith's G* as eq. 1.38 prints it (:meth:`Beckmann.smith_g1_thesis`)."""
    d = Beckmann(m)
    return d.smith_g1_thesis(nl) * d.smith_g1_thesis(nv)


@dataclass(frozen=True)
class ThesisSmith:
    """S = C G*(N·L) G*(N·V)/(4 N·L N·V) with the thesis's G* of roughness ``m`` (eq. 1.38,
    :meth:`Beckmann.smith_g1_thesis`): Cook–Torrance's with ``G='smith'`` (eq. 2.9), scale ``C``."""

    m: float
    C: float = 1.0

    def __call__(self, nl, nv):
        return self.C * g_smith_beckmann(nl, nv, self.m) / (4 * nl * nv)

