"""Helpers shared by the chapter-4 (patch-based BRDF) artifacts."""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pandas as pd

from brdfs.pipeline import published
from brdfs.physics.geometry import direction, light_direction

SECTION = "patch"


def tolerances(cfg: dict) -> dict:
    """``rtol``/``atol`` of the config's ``tolerance`` section, as keyword arguments."""
    return {"rtol": cfg["tolerance"]["rtol"], "atol": cfg["tolerance"]["atol"]}


def truncation_reason(printed: str, computed: float) -> dict:
    """The ``reason`` of a print that truncates, rather than rounds, the computed value; {} otherwise."""
    if published.print_kind(printed) == "numeric" and published.truncates_to(printed, computed):
        return {"reason": f"truncated, not rounded: the formula gives {computed:.{_digits(printed) + 2}f}"}
    return {}


def _digits(printed: str) -> int:
    """Decimal places of a numeric print (0 for '41721.')."""
    return max(0, -Decimal(printed).as_tuple().exponent)



def plane_of_incidence(brdf, theta_deg: float, step_deg: float) -> pd.DataFrame:
    """f(L, V) for V in the plane of incidence, θ_V signed (positive on the mirror side, φ = 180°)."""
    theta_v = np.linspace(-90.0, 90.0, int(round(180.0 / step_deg)) + 1)
    L = light_direction(np.full_like(theta_v, theta_deg))
    V = direction(np.abs(theta_v), np.where(theta_v >= 0, 180.0, 0.0))
    return pd.DataFrame({"theta_deg": theta_deg, "theta_v_deg": theta_v, "brdf": brdf(L, V)})


def grid(start: float, stop: float, step: float) -> np.ndarray:
    """``start, start + step, …, stop`` with both ends exact (``step`` rounded to divide the range)."""
    return np.linspace(start, stop, int(round((stop - start) / step)) + 1)
