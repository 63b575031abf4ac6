"""Helpers shared by the chapter-4 (patch-based BRDF) artifacts."""

from __future__ import annotations

from decimal import Decimal

import numpy as np

from brdfs import published
from brdfs.integrate.gauss_kronrod import Estimate, integrate

SECTION = "patch"


def tolerances(cfg: dict) -> dict:
    """``rtol``/``atol`` of the config's ``tolerance`` section, as keyword arguments."""
    return {"rtol": cfg["tolerance"]["rtol"], "atol": cfg["tolerance"]["atol"]}


def integrate_per_element(fn, limits, tol: dict) -> Estimate:
    """∫ fn(x, element) dx over one [lo, hi, (kinks)] row of ``limits`` per element."""
    return integrate(fn, np.asarray(limits, float), **tol)


def per_profile(fn, profiles):
    """An integrand ``(x, element) -> values`` applying ``fn(profile, x_rows)`` profile by profile."""

    def integrand(x, elem):
        out = np.empty_like(x)
        for i in np.unique(elem):
            rows = elem == i
            out[rows] = fn(profiles[i], x[rows])
        return out

    return integrand


def truncation_reason(printed: str, computed: float) -> dict:
    """The ``reason`` of a print that truncates, rather than rounds, the computed value; {} otherwise."""
    if published.print_kind(printed) == "numeric" and published.truncates_to(printed, computed):
        return {"reason": f"truncated, not rounded: the formula gives {computed:.{_digits(printed) + 2}f}"}
    return {}


def _digits(printed: str) -> int:
    """Decimal places of a numeric print (0 for '41721.')."""
    return max(0, -Decimal(printed).as_tuple().exponent)

