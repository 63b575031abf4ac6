"""Figure 2.7: the albedo of the new model (eq. 2.22 = 3.10) for different n, and its output
radiance for n = 100 at the mirror direction (a constant c: the 1/max(N·L, N·V) cancels cos θ_L)."""
from __future__ import annotations

import pandas as pd

from brdfs.pipeline import plotting
from brdfs.artifacts import _new_model_figures as shared
from brdfs.pipeline.registry import figure


@figure("fig_2_7_new_model_albedo_radiance", config=("new_model_albedo",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Albedo rows (one curve per n) and radiance rows (n = ``radiance_n``, V = R)."""
    section = cfg["new_model_albedo"]
    albedo = shared.albedo_curves(section["fig_2_7_n"], section["theta_step_deg"], cfg["tolerance"]["rtol"])
    radiance = shared.mirror_radiance("phong_cosmin", section["radiance_n"], section["theta_step_deg"])
    return pd.concat([albedo, radiance], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Albedo per n (left), mirror radiance / c (right)."""
    fig, (left, right) = plotting.plt.subplots(1, 2, figsize=(10, 4.2))
    shared.plot_albedo(left, df[df["albedo"].notna()])
    rad = df[df["radiance"].notna()]
    right.plot(rad["theta_deg"], rad["radiance"] / rad["C"], label=f"new model, n = {rad['n'].iloc[0]:g}")
    right.set(xlabel="incidence angle θ_L [deg]", ylabel="L_out(R) / c,  L_out = f(L,R) cos θ_L", ylim=(0, 1.2))
    left.legend(fontsize=7, loc="lower left")
    fig.suptitle(f"Figure 2.7: albedo of the new model, and its output radiance (n = {rad['n'].iloc[0]:g})", fontsize=10)
    plotting.savefig(fig, path)
