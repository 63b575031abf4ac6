"""Ward's claim (Sec. 3.7.2): with C_max = 1 and m < 0.2 the albedo on 0°–89° stays at or below 1
(and its maximum above 0.85); comparison ``ward_in_range``."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.models import model
from brdfs.numerics.quantities import max_albedo

ARTIFACT = "ward_in_range"
GRID_STEP_DEG = 1.0


@table("extra_ward_in_range", config=("grazing",), chapter=3)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Columns ``model, m, C, theta_max_deg, max_albedo, max_albedo_err, theta_at_max_deg``.

    The maximum over [0°, theta_max] by :func:`brdfs.numerics.quantities.max_albedo` on a 1° bracket grid."""
    w = cfg["grazing"]["ward_in_range"]
    ms = [float(m) for m in w["m_values"]]
    amax, at = max_albedo([model("ward", m=m) for m in ms], cfg["tolerance"]["rtol"], grid_deg=GRID_STEP_DEG,
                          theta_max_deg=w["theta_max_deg"])
    return pd.DataFrame({"model": "ward", "m": ms, "C": 1.0, "theta_max_deg": w["theta_max_deg"],
                         "max_albedo": amax.value, "max_albedo_err": amax.error, "theta_at_max_deg": at})


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
