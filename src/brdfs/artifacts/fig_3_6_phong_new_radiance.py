"""Figure 3.6: output radiance of Phong (eq. 3.5) and the new model (eq. 3.10), n = 100, for a
point light of intensity 4π at distance 1 (irradiance cos θ_L), relative to f(N, N) = c."""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _new_model_figures as shared
from brdfs.pipeline.registry import figure


@figure("fig_3_6_phong_new_radiance", config=("new_model_lobes",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """f(L, V) cos θ_L / f(N, N) for V in the plane of incidence."""
    s = cfg["new_model_lobes"]
    return shared.plane_slices(("phong", "phong_cosmin"), s["n"], s["radiance_theta_deg"], s["theta_v_step_deg"],
                               "radiance_normalised")


def plot(df: pd.DataFrame, path) -> None:
    """One panel per model, one curve per incidence angle."""
    shared.plot_slices(df, path, "radiance_normalised", "L_out(V) / c,  L_out = f(L,V) cos θ_L",
                       f"Figure 3.6: output radiance of Phong and the new model (n = {df['n'].iloc[0]:g})")
