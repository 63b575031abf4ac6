"""Table 1.1: the maximal constant of the reciprocal Blinn model — the Blinn half of Table 3.1."""
from __future__ import annotations

import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline.registry import table

SOURCE = "table_3_1_blinn_constants"


@table("table_1_1_blinn_constants", deps=(SOURCE,))
def compute(cfg: dict, deps: dict) -> pd.DataFrame:
    df = deps[SOURCE]
    return df[df["model"] == "blinn"][["model", "n", "C", "C_err", "theta_max_deg"]].reset_index(drop=True)


def plot(df: pd.DataFrame, path) -> None:
    plotting.save_table_png(df, path, "Table 1.1: maximal constant C(n) of the reciprocal Blinn model (computed)")
