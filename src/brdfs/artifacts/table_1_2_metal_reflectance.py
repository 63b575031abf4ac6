"""Table 1.2: normal-incidence reflectance a0 = rho of seven metals (eq. 1.40).

The metals' wavelengths and optical constants ``n``, ``k`` are the thesis's
inputs (config section ``metal_reflectance``); ``a0`` is the printed output,
compared with eq. 1.40 in the comparison ``metal_a0``
(:mod:`brdfs.artifacts.extra_metal_a0_readings`, beside the searches that explain
the prints eq. 1.40 does not reproduce).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import fresnel
from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline.registry import table
from brdfs.physics.fresnel import UNIT_ROUNDOFF

ARTIFACT = "metal_a0"


def a0_percent(ior_re: np.ndarray, ior_im: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``100 a0`` (eq. 1.40) and its floating-point error bound (one more rounding for the scaling)."""
    a0 = fresnel.normal_incidence_reflectance(ior_re, ior_im)
    err = fresnel.normal_incidence_reflectance_err(ior_re, ior_im)
    return 100 * a0, 100 * (err + UNIT_ROUNDOFF * a0)


@table("table_1_2_metal_reflectance", config=("metal_reflectance",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Table 1.2 recomputed: one row per metal.

    Returns
    -------
    pandas.DataFrame
        Columns ``metal, lambda_nm, ior_re, ior_im, a0_percent, a0_percent_err``.
    """
    metals = pd.DataFrame(cfg["metal_reflectance"]["metals"]).rename(columns={"name": "metal"})
    duplicated = metals["metal"][metals["metal"].duplicated()]
    if not duplicated.empty:
        raise ValueError(f"metal_reflectance: duplicated metals {sorted(duplicated)}")
    value, err = a0_percent(metals["ior_re"].to_numpy(float), metals["ior_im"].to_numpy(float))
    return metals[["metal", "lambda_nm", "ior_re", "ior_im"]].assign(a0_percent=value, a0_percent_err=err)


def plot(df: pd.DataFrame, path) -> None:
    """Table 1.2 as printed beside the recomputed a0."""
    printed = published.published_rows(ARTIFACT).set_index("param_value")["published"]
    shown = pd.DataFrame(
        {
            "metal": df["metal"],
            "lambda [nm]": df["lambda_nm"].astype(str),
            "n": df["ior_re"].astype(str),
            "k": df["ior_im"].astype(str),
            "a0 printed [%]": df["metal"].map(printed).fillna(""),
            "a0 eq. 1.40 [%]": [f"{v:.3f}" for v in df["a0_percent"]],
        }
    )
    plotting.save_table_png(shown, path, "Table 1.2: reflectance a0 = rho at normal incidence, printed and by eq. 1.40")
