"""Figure 4.5: albedo of the basic BRDF (eq. 4.8, closed form) for several R, and its bound.

Section 4.2.2: 2/3 − √3/(2π) ≤ a_R(L) ≤ 1, the minimum at horizontal illumination and R = 1.
a_R decreases with θ (the lens shrinks as L'_P moves out), so the minimum over L is a_R(90°);
the series ``grazing_scan`` scans it over R (step ``patch.R_step``). The R of the curves are an
open choice (``patch.fig_4_5_R``).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import comparison, figure, get_artifact
from brdfs.artifacts._patch_common import SECTION, grid

NAME = "fig_4_5_basic_albedo"
ARTIFACT = "basic_brdf"
BOUND = 2.0 / 3.0 - np.sqrt(3.0) / (2.0 * np.pi)


@figure(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``series, R, theta_deg, albedo, albedo_err``: curves a_R(θ) and the scan of a_R(90°) over R."""
    section = cfg[SECTION]
    theta = grid(0.0, 90.0, section["theta_step_deg"])
    R_curves = np.asarray(section["fig_4_5_R"], float)
    R_scan = grid(0.0, 2.0, section["R_step"])[1:]
    T, Rc = np.meshgrid(theta, R_curves)
    curves = patch.basic_albedo(T.ravel(), Rc.ravel())
    scan = patch.basic_albedo(np.full_like(R_scan, 90.0), R_scan)
    return pd.DataFrame(
        {
            "model": "patch_basic",
            "series": ["curve"] * T.size + ["grazing_scan"] * R_scan.size,
            "R": np.concatenate([Rc.ravel(), R_scan]),
            "theta_deg": np.concatenate([T.ravel(), np.full_like(R_scan, 90.0)]),
            "albedo": np.concatenate([curves.value, scan.value]),
            "albedo_err": np.concatenate([curves.error, scan.error]),
        }
    )


def plot(df: pd.DataFrame, path) -> None:
    """Left: a_R(θ) per R with the bound; right: a_R(90°) against R. The legends stand outside the
    axes (below them), where no curve or bound line crosses them."""
    fig = plotting.plt.figure(figsize=(9.6, 4.6))
    left, right = fig.subplots(1, 2)
    for R, group in df[df["series"] == "curve"].groupby("R"):
        left.plot(group["theta_deg"], group["albedo"], label=f"R = {R:g}")
    left.axhline(BOUND, color="k", ls=":", label="bound 2/3 - sqrt(3)/(2 pi)")
    left.set(xlabel="theta [deg]", ylabel="albedo a_R", title="a_R(theta) per R (R: open choice)", ylim=(0, 1.05))
    scan = df[df["series"] == "grazing_scan"]
    right.plot(scan["R"], scan["albedo"], label="a_R(90 deg)")
    right.axhline(BOUND, color="k", ls=":", label="bound")
    right.set(xlabel="R", ylabel="albedo at 90 deg", title="minimum over R at horizontal illumination")
    for ax, columns in ((left, 4), (right, 2)):
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=columns, fontsize=7)
    fig.suptitle("Fig. 4.5: basic BRDF albedo")
    plotting.savefig(fig, path)


@comparison(ARTIFACT, tables=(NAME,))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The bound of section 4.2.2: a_1(90°) by eq. 4.9, the minimum of the scan over R and θ."""
    scan = tables[NAME][tables[NAME]["series"] == "grazing_scan"]
    at_one = patch.basic_albedo(90.0, 1.0)
    lowest = scan.loc[scan["albedo"].idxmin()]
    if lowest["R"] != 1.0:
        raise ValueError(f"{NAME}: the scan's minimum is at R = {lowest['R']}, not at R = 1 as section 4.2.2 states")
    return pd.DataFrame(
        [{"model": "patch_basic", "param_value": "1", "quantity": "min_albedo", "computed": float(at_one.value),
          "computed_err": float(at_one.error), "evidence": get_artifact(NAME).csv}]
    )
