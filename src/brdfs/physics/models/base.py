"""What every BRDF of the package offers the integration engine.

A model is a small frozen value type.  Calling it, ``f(L, V)``, evaluates the BRDF on arrays of
unit vectors (…, 3) with N = (0, 0, 1); directions below the horizon give 0.  Besides the value,
a model tells the engine how its integrand is shaped, so that the albedo integral can follow it:

* ``lobe``: the change of variables that follows the lobe (:mod:`brdfs.numerics.integrate.lobes`): which
  frame (around the mirror direction R or around the normal for the half vector H) and which
  radial distribution (cosine power or Beckmann).
* ``nv_levels(nl)``: values of N·V where the integrand has a kink (e.g. N·V = N·L for the
  max(N·L, N·V) of the new model).  The horizon N·V = 0 is always added by the engine.
* ``lh_levels(nl, cos_delta)``: kinks given as levels of L·H (half-vector frame only).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class BRDF:
    """Base class: subclasses implement ``_eval(L, V, nl, nv)`` and ``lobe``."""

    reciprocal = True
    name = "brdf"
    sqrt_at_horizon = False   # integrand ~ sqrt(N·V) at the horizon (Ward): the engine clusters nodes there

    def __call__(self, L, V):
        L = np.asarray(L, float)
        V = np.asarray(V, float)
        nl, nv = L[..., 2], V[..., 2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            f = self._eval(L, V, nl, nv)
        return np.where((nl >= 0) & (nv > 0), f, 0.0)

    def _eval(self, L, V, nl, nv):
        raise NotImplementedError

    @property
    def lobe(self):
        raise NotImplementedError

    def nv_levels(self, nl):
        return ()

    def lh_levels(self, nl, cos_delta):
        return ()

    @property
    def params(self) -> dict:
        """Parameters as the published-values file names them (n, m, C, ...)."""
        return {k: v for k, v in self.__dict__.items()}


def positive_power(x, n):
    """((x)^+)^n with 0^0 = 1 only for x > 0."""
    return np.where(x > 0, np.maximum(x, 0.0) ** n, 0.0)


def check_positive(name, value, allow_zero=False):
    """Reject bad parameters with a message that names them."""
    value = float(value)
    if not np.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        raise ValueError(f"{name} must be {'non-negative' if allow_zero else 'positive'}, got {value!r}")
    return value
