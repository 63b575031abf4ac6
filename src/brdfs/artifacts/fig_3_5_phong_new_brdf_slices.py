"""Figure 3.5: normalised BRDFs of Phong (eq. 3.5) and the new model (eq. 3.10), n = 100, at
0°, 40° and 80° incidence; normalisation divides by f(N, N) = c, the value at 0° incidence."""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _new_model_figures as shared
from brdfs.pipeline.registry import figure


@figure("fig_3_5_phong_new_brdf_slices", config=("new_model_lobes",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """f(L, V)/f(N, N) for V in the plane of incidence."""
    s = cfg["new_model_lobes"]
    return shared.plane_slices(("phong", "phong_cosmin"), s["n"], s["slice_theta_deg"], s["theta_v_step_deg"],
                               "brdf_normalised")


def plot(df: pd.DataFrame, path) -> None:
    """One panel per model."""
    shared.plot_slices(df, path, "brdf_normalised", "f(L,V) / f(N,N)",
                       f"Figure 3.5: BRDFs of Phong and the new model (n = {df['n'].iloc[0]:g})")
