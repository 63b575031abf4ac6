"""Ward's claim (Sec. 3.7.2): with C_max = 1 and m < 0.2 the albedo on 0°–89° stays at or below 1
(and its maximum above 0.85); comparison ``ward_in_range``."""

from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.optimize import minimize_scalar

from brdfs import plotting, published
from brdfs.albedo import albedo
from brdfs.artifacts import comparison, get_artifact, table
from brdfs.models import model

ARTIFACT = "ward_in_range"
GRID_STEP_DEG = 0.25


def max_albedo_on(brdf, theta_max, tol) -> tuple[float, float, float]:
    """max of a(θ) on [0, theta_max]: a grid bracket refined by a bounded scalar search.

    The error adds the albedo error and the variation of a across the final tolerance in θ.
    """
    grid = np.append(np.arange(0.0, theta_max, GRID_STEP_DEG), theta_max)
    coarse = albedo(brdf, grid, tol["rtol"], tol["atol"]).value
    i = int(np.argmax(coarse))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = minimize_scalar(lambda t: -float(albedo(brdf, t, tol["rtol"], tol["atol"]).value),
                          bounds=(lo, hi), method="bounded", options={"xatol": 1e-7})
    best = res.x if -res.fun > coarse[i] else grid[i]
    est = albedo(brdf, [best, max(best - 1e-7, 0.0), min(best + 1e-7, theta_max)], tol["rtol"], tol["atol"])
    spread = float(np.max(np.abs(est.value - est.value[0])))
    return float(est.value[0]), float(est.error.max()) + spread, float(best)


@table("extra_ward_in_range", config=("grazing",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Columns ``model, m, C, theta_max_deg, max_albedo, max_albedo_err, theta_at_max_deg``."""
    w = cfg["grazing"]["ward_in_range"]
    records = []
    for m in w["m_values"]:
        value, err, at = max_albedo_on(model("ward", m=m), w["theta_max_deg"], cfg["tolerance"])
        records.append({"model": "ward", "m": m, "C": 1.0, "theta_max_deg": w["theta_max_deg"],
                        "max_albedo": value, "max_albedo_err": err, "theta_at_max_deg": at})
    return pd.DataFrame.from_records(records)


def plot(df: pd.DataFrame, path) -> None:
    """The maximal albedo on 0°–89° against m, with the claimed band (0.85, 1]."""
    fig, ax = plotting.new_axes("m", f"max a(θ), 0° ≤ θ ≤ {df['theta_max_deg'].iloc[0]:g}°",
                                "Ward (C_max = 1): maximal albedo on 0°–89° (Sec. 3.7.2)")
    ax.semilogx(df["m"], df["max_albedo"], "o-", label="Ward, eq. 3.35")
    ax.axhspan(0.85, 1.0, color="g", alpha=0.1, label="claimed: ≤ 1 and > 0.85")
    plotting.savefig(fig, path)


@comparison(ARTIFACT, tables=("extra_ward_in_range",))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """computed = the maximum for m = 0.1; the claim is judged over every m < 0.2 of the table."""
    df = tables["extra_ward_in_range"]
    swept = df[df["m"] < 0.2]
    holds = bool(((swept["max_albedo"] + swept["max_albedo_err"] <= 1.0)
                  & (swept["max_albedo"] - swept["max_albedo_err"] > 0.85)).all())
    own = df[np.isclose(df["m"], 0.1)].iloc[0]
    (row,) = published.published_rows(ARTIFACT).itertuples(index=False)
    record = {"model": "ward", "param_value": row.param_value, "quantity": row.quantity,
              "computed": own["max_albedo"], "computed_err": own["max_albedo_err"], "claim_holds": holds,
              "evidence": get_artifact("extra_ward_in_range").csv}
    if not holds:
        record["reason"] = "the maximal albedo leaves (0.85, 1] for some m < 0.2 of the sweep"
    return pd.DataFrame([record])
