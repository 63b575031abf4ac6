"""He–Torrance's truths: the BRDF written again (:func:`sweep.independent.he_torrance_disk`, from the
specification /work/shared/he_torrance.md, F = 1), integrated on the projected disk by the vectorised
nested quadrature :func:`sweep.third_route.disk_albedo_vectorised`, plus the specular delta's albedo in
closed form (:func:`sweep.independent.he_specular_albedo`), as the package's ``albedo()`` defines the
albedo of ``term='total'`` (the density's integral plus ρ_s; ``term='dd'``: the integral alone).

Why the disk: D depends on V only through ρ = |L_xy + V_xy| (h = (πτ/λ)² ρ², eq. 78), a sum of Gaussians
in ρ of widths w √m, w = λ/(πτ) (the m-th term of the Kirchhoff series), so the inner radial integral is cut
at w 2^(k/2) and at √max(g, 1) w multiples; the shadowing's horizon layer N·V ~ 2σ0/τ gives the level
circles N·V = (2σ0/τ) 4^k as further cuts, and the √ end at the rim is taken out by the quadrature's
clustered last piece.  The series is summed to a stated bound (:data:`sweep.independent.HE_SERIES_RTOL`,
its tail integrated into the error).  Each cell costs ~0.03–1.2 CPU-s (≈ 10⁴–1.2·10⁶ evaluations).

Nothing here imports :mod:`brdfs`.
"""
from __future__ import annotations

import numpy as np

from sweep import independent as ind
from sweep.third_route import Truth, disk_albedo_vectorised

#: Relative tolerance of the outer and inner quadratures (the third route's usual 1e-13).
EPSREL = 1e-13
#: Relative accuracy of one evaluation of f_dd beyond the integrator's rounding allowance: exp(−h/m)
#: amplifies the rounding of h/m by h/m (≤ ~10 on the lobe), the Newton σ and erfc a few ulps.
F_RTOL = 1e-14


def radial_points(sigma0_um, tau_um, lambda_um):
    """The lobe's scales in ρ: w 2^(k/2), k = −4 … 15, and w √max(g₀, 1) × (1/2, 1, 2, 4), g₀ = (4πσ0/λ)²."""
    w = lambda_um / (np.pi * tau_um)
    g0 = (4.0 * np.pi * sigma0_um / lambda_um) ** 2
    pts = {w * 2.0 ** (k / 2) for k in range(-4, 16)} | {w * np.sqrt(max(g0, 1.0)) * k for k in (0.5, 1, 2, 4)}
    return sorted(p for p in pts if p < 2.0)


def layer_levels(sigma0_um, tau_um):
    """Levels N·V = (2σ0/τ) 4^k, k = −5 … 1, below 1: the shadowing's horizon layer."""
    c = 2.0 * sigma0_um / tau_um
    return [c * 4.0 ** k for k in range(-5, 2) if c * 4.0 ** k < 1.0]


def he_torrance_truth(sigma0_um, tau_um, theta_deg, lambda_um=0.55, term="total", epsrel=EPSREL) -> Truth:
    """a(θ) of He–Torrance (F = 1): ∫ f_dd cos θ_V dω_V (+ ρ_s(θ) for ``term='total'``), with its error."""
    xi = ind.he_torrance_disk(sigma0_um, tau_um, lambda_um, theta_deg)
    t = disk_albedo_vectorised(xi, theta_deg, radial_points(sigma0_um, tau_um, lambda_um),
                               layer_levels(sigma0_um, tau_um), epsrel=epsrel, f_rtol=F_RTOL)
    if term == "total":
        rho_s = ind.he_specular_albedo(sigma0_um, tau_um, lambda_um, theta_deg)
        t.value += rho_s
        t.error += 8 * np.finfo(float).eps * rho_s
        t.notes.append(f"rho_s {rho_s:.17g}")
    t.route = "quad/disk_vectorised+independent"
    return t
