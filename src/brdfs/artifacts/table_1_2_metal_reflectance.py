"""Table 1.2: normal-incidence reflectance a0 = rho of seven metals (eq. 1.40).

The metals' wavelengths and optical constants ``n``, ``k`` are the thesis's
inputs (config section ``metal_reflectance``); ``a0`` is the printed output,
compared with eq. 1.40 in the comparison ``metal_a0``. Where eq. 1.40 does not
reproduce a print, the readings of ``extra_metal_a0_readings`` (misprinted or
rounded inputs) are searched for one that does.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import fresnel
from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.fresnel import UNIT_ROUNDOFF

ARTIFACT = "metal_a0"
READINGS = "extra_metal_a0_readings"


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


@comparison(ARTIFACT, tables=("table_1_2_metal_reflectance", READINGS))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 1.2: computed a0, completed by the searches of
    :mod:`extra_metal_a0_readings` (inputs in their box for the group, misprinted inputs per entry)."""
    from brdfs.artifacts.extra_metal_a0_readings import GROUP, MISPRINTS

    computed = tables["table_1_2_metal_reflectance"]
    prints = published.published_rows(ARTIFACT).set_index("param_value")["published"]
    records = []
    for row in computed.itertuples(index=False):
        printed = prints.get(row.metal)  # None for a metal the thesis does not print: make_fragment refuses it
        records.append({"model": "fresnel_normal_incidence", "param_value": row.metal, "quantity": "a0_percent",
                        "computed": row.a0_percent, "computed_err": row.a0_percent_err,
                        "as_printed": published.verdict(printed, row.a0_percent, row.a0_percent_err) if printed else ""})
    records = pd.DataFrame.from_records(records)
    where = get_artifact(READINGS).csv
    records = readings.with_search(records.assign(kept=records["as_printed"]), tables[READINGS], where,
                                   effect=_box_effect, group=GROUP)
    records = readings.with_misprints(records.assign(as_printed=records.pop("kept")), tables[READINGS], MISPRINTS, where)
    return records.drop(columns="as_printed")


def _box_effect(value_under_reading: float, computed: float) -> str:
    return f"inputs rounded to the printed digits move a0 by {value_under_reading - computed:+.3f} percentage points"
