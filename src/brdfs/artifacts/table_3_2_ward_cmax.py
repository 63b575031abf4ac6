"""Table 3.2: C_max = 1 / max_θ a(θ) of the corrected Ward model (eq. 3.36), computed with C = 1."""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.models import model
from brdfs.numerics.quantities import maximal_constant

NAME = "table_3_2_ward_cmax"


@table(NAME, config=("ward_cmax",))
def compute(cfg: dict, deps: dict) -> pd.DataFrame:
    ms = [float(m) for m in cfg["ward_cmax"]["m"]]
    models = [model("ward_cosmin", m=m) for m in ms]
    C, theta = maximal_constant(models, cfg["tolerance"]["rtol"])
    a0 = np.array([float(brdf.exact_albedo(0.0)) for brdf in models])    # the model's a(0), C = 1
    return pd.DataFrame({"model": "ward_cosmin", "m": ms, "C": C.value, "C_err": C.error,
                         "theta_max_deg": theta, "C_normal_incidence_closed_form": 1 / a0,
                         "C_series_1_plus_4m2": 1 + 4 * np.asarray(ms) ** 2})


def plot(df: pd.DataFrame, path) -> None:
    printed = published.printed_lookup("ward_cmax")
    shown = df.assign(printed=[printed(m, "C_max") for m in df["m"]])
    plotting.save_table_png(shown[["m", "printed", "C", "C_err", "theta_max_deg", "C_normal_incidence_closed_form"]],
                            path, "Table 3.2: C_max of the corrected Ward model, printed and computed")


#: The searches of how chapter 3's tables were computed (:mod:`brdfs.artifacts.extra_readings_chapter_3`).
READINGS = "extra_readings_chapter_3"


@comparison("ward_cmax", tables=(NAME, READINGS))
def rows(cfg: dict, tables: dict) -> pd.DataFrame:
    """Comparison rows of Table 3.2, completed by its search (maxima over θ grids, a(0) as sums)."""
    from brdfs.artifacts.extra_readings_chapter_3 import GROUPS

    df = tables[NAME]
    printed_of = published.printed_lookup("ward_cmax")
    records = []
    for r in df.itertuples():
        printed = printed_of(r.m, "C_max")
        records.append({"model": "ward_cosmin", "param_value": f"{r.m:g}", "quantity": "C_max", "computed": r.C,
                        "computed_err": r.C_err, "evidence": get_artifact(NAME).csv,
                        "as_printed": published.verdict(printed, r.C, r.C_err) if printed else ""})
    done = readings.with_search(pd.DataFrame.from_records(records), tables[READINGS], get_artifact(READINGS).csv,
                                group=GROUPS["ward_cmax"])
    return done.drop(columns="as_printed")
