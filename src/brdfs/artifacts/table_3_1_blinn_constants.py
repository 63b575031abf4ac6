"""Table 3.1 (and its Blinn half, Table 1.1): maximal constants C_n = 1 / max_θ a(θ) of the
reciprocal Blinn model (eq. 1.34) and the corrected Blinn model (eq. 3.34), computed with C = 1.

The true maximum is located by :func:`brdfs.numerics.quantities.max_albedo`; how the thesis may
have computed its prints (maxima over θ grids, a(0) as sums) is searched in
:mod:`brdfs.artifacts.extra_readings_chapter_3`.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.numerics.albedo import albedo_table
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.models import model
from brdfs.numerics.quantities import maximal_constant

NAME = "table_3_1_blinn_constants"
MODELS = ("blinn", "blinn_cosmin")
GRID_RTOL = 1e-7         # the 1° grid only brackets the maximum


def blinn_normal_incidence_albedo(n):
    """a(0) of C (N·H)^n with C = 1 in closed form: with L = N, N·H = cos(θ_V/2), and x = cos(θ_V/2),
    a(0) = 2π ∫ x^n (2x² − 1) 4x dx over [1/√2, 1]
         = 8π [2 (1 − 2^(−(n+4)/2)) / (n+4) − (1 − 2^(−(n+2)/2)) / (n+2)]."""
    n = np.asarray(n, float)
    return 8 * np.pi * (2 * (1 - 2 ** (-(n + 4) / 2)) / (n + 4) - (1 - 2 ** (-(n + 2) / 2)) / (n + 2))


@table(NAME, config=("blinn_cn",))
def compute(cfg: dict, deps: dict) -> pd.DataFrame:
    ns = [float(n) for n in cfg["blinn_cn"]["n"]]
    models = [model(name, n=n) for name in MODELS for n in ns]
    grid = np.arange(0.0, 90.0 + 1e-9, 1.0)
    on_grid = albedo_table(models, grid, rtol=GRID_RTOL).value
    C, theta = maximal_constant(models, cfg["tolerance"]["rtol"], grid_deg=1.0, grid_values=on_grid)
    return pd.DataFrame({"model": np.repeat(MODELS, len(ns)), "n": np.tile(ns, len(MODELS)),
                         "C": C.value, "C_err": C.error, "theta_max_deg": theta})


def plot(df: pd.DataFrame, path) -> None:
    printed = published.printed_lookup("blinn_cn")
    shown = df.assign(printed=[printed(r.n, "C_max", r.model) for r in df.itertuples()])
    plotting.save_table_png(shown[["model", "n", "printed", "C", "C_err", "theta_max_deg"]], path,
                            "Table 3.1: maximal C_n of Blinn and Blinn/cos(theta_min), printed and computed")


#: The searches of how chapter 3's tables were computed (:mod:`brdfs.artifacts.extra_readings_chapter_3`).
READINGS = "extra_readings_chapter_3"


@comparison("blinn_cn", tables=(NAME, READINGS))
def rows(cfg: dict, tables: dict) -> pd.DataFrame:
    """Comparison rows of Table 3.1, completed by its search (maxima over θ grids, a(0) as sums)."""
    from brdfs.artifacts.extra_readings_chapter_3 import GROUPS

    df = tables[NAME]
    printed_of = published.printed_lookup("blinn_cn")
    records = []
    for r in df.itertuples():
        printed = printed_of(r.n, "C_max", r.model)
        records.append({"model": r.model, "param_value": f"{r.n:g}", "quantity": "C_max", "computed": r.C,
                        "computed_err": r.C_err, "evidence": get_artifact(NAME).csv,
                        "as_printed": published.verdict(printed, r.C, r.C_err) if printed else ""})
    done = readings.with_search(pd.DataFrame.from_records(records), tables[READINGS], get_artifact(READINGS).csv,
                                group=GROUPS["blinn_cn"])
    return done.drop(columns="as_printed")
