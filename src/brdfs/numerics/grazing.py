"""The albedo at grazing incidence: asymptotic laws (Sec. 2.2.1) and discretised readings (Secs. 3.7.2–3.7.3).

Asymptotic laws, μ = cos θ_L → 0 (derivations in the docstrings):

* Ward (eq. 2.8): a(μ) √μ → K_Ward, a one-dimensional integral (a confluent hypergeometric U);
  the albedo diverges like μ^(−1/2).
* Cook–Torrance (eq. 2.9) with G = 1: a(μ) μ → m / (2√π) exactly; diverges like 1/μ.
* Cook–Torrance with G as printed (eq. 2.10): G ≤ 2 N·H N·L / L·H bounds the albedo by 2 at
  every incidence, and a(90°) = 1: no divergence.
* Phong (eq. 2.6), the new model (eq. 3.10), corrected Ward (eq. 3.36): finite limits in closed
  form; Blinn, corrected Blinn and Cook–Torrance with Smith's G (eq. 1.38): finite limits
  evaluated as albedo integrals at θ = 90°.

Readings — the albedo as a program of 2001 could have computed it, a midpoint rule on a
(θ_V, φ_V) grid or Monte Carlo — are methods of the albedo front door (:mod:`brdfs.numerics.albedo`).
"""
from __future__ import annotations

import numpy as np

from brdfs.numerics.albedo import albedo
from brdfs.core.gauss_kronrod import Estimate
from brdfs.physics.models.base import GrazingLaw

_EPS = np.finfo(float).eps
#: D·G/(N·L N·V) constants relative to eq. 2.9's 1/(4π m² cos⁴δ): the original Cook–Torrance
#: paper (D = 1/(π m² cos⁴δ), f = D G/(π N·L N·V)) and eqs. 1.35–1.36 as printed (D = π/(4 m² cos⁴δ)).
NORMALISATION_FACTORS = {"eq_2_9": 1.0, "cook_torrance_original": 4.0 / np.pi, "eq_1_36": np.pi ** 2}


def approach_angles(exponent_from, exponent_to, per_decade):
    """Incidence angles 90° − 10^(−x) for x from ``exponent_from`` to ``exponent_to``, ``per_decade`` a decade."""
    count = int(round((exponent_to - exponent_from) * per_decade)) + 1
    return 90.0 - 10.0 ** -np.linspace(exponent_from, exponent_to, count)


def incidence_grid(step_deg, exponent_from, exponent_to, per_decade):
    """A uniform grid on [0°, 90°) joined with :func:`approach_angles` (sorted, unique)."""
    uniform = np.arange(0.0, 90.0, step_deg)
    return np.unique(np.concatenate([uniform, approach_angles(exponent_from, exponent_to, per_decade)]))


def asymptotic_law(model, rtol=None):
    """The law of a(θ_L) as cos θ_L → 0 for ``model``: its own closed form (``model.grazing_law()``)
    where it has one, else its finite limit a(90°) integrated by the engine (of the limit integrand
    ``model.grazing_limit_model()``, where the BRDF itself is singular at N·L = 0), or None."""
    law = model.grazing_law()
    if law is not None:
        return law
    limit = albedo(model.grazing_limit_model(), 90.0, rtol=rtol)
    if np.isfinite(limit.value):
        return GrazingLaw(0.0, Estimate(float(limit.value), float(limit.error)), "a(90) by the engine at 90 deg")
    return None


