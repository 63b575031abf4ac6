"""The in-text numbers of chapter 3: eq. 3.27 (albedo of the new model at 90°), the overshoot of
the new model above 1 for n = 1 and 0.5 (section 3.2.2), and the Blinn and corrected-Blinn albedo
at 90° for n = 128 with the C_n of Table 3.1 (section 3.7.4)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.numerics.albedo import albedo
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.models import model
from brdfs.numerics.quantities import limit_albedo_90, max_albedo
from brdfs.physics.models.phong import new_model_grazing_albedo as grazing_albedo_new_model

NAME = "extra_chapter3_claims"
CONSTANTS = "table_3_1_blinn_constants"


def _grazing_rows(ns, check_ns, tol):
    rows = []
    finite = [float(n) for n in ns] + [float(n) for n in check_ns]
    for n in finite:
        est = albedo(model("phong_cosmin", n=n), [90.0], rtol=tol)
        rows.append({"claim": "grazing_limit", "model": "phong_cosmin", "n": n, "quantity": "albedo_at_90deg",
                     "value": est.value[0], "value_err": est.error[0], "theta_deg": 90.0,
                     "closed_form": float(grazing_albedo_new_model(n)),
                     "role": "claim" if n in ns else "limit_check"})
    rows.append({"claim": "grazing_limit", "model": "phong_cosmin", "n": np.inf, "quantity": "albedo_at_90deg",
                 "value": limit_albedo_90("phong_cosmin"), "value_err": 0.0, "theta_deg": 90.0,
                 "closed_form": 0.5, "role": "claim"})
    return rows


def _overshoot_rows(ns, tol):
    amax, theta = max_albedo([model("phong_cosmin", n=float(n)) for n in ns], tol)
    return [{"claim": "overshoot", "model": "phong_cosmin", "n": float(n), "quantity": "max_albedo_minus_1",
             "value": amax.value[i] - 1, "value_err": amax.error[i], "theta_deg": theta[i], "closed_form": np.nan,
             "role": "claim"} for i, n in enumerate(ns)]


def _blinn_rows(n, constants, tol):
    rows = []
    for name in ("blinn", "blinn_cosmin"):
        c_row = constants[(constants["model"] == name) & (constants["n"] == n)].iloc[0]
        est = albedo(model(name, n=float(n), C=float(c_row["C"])), [90.0], rtol=tol)
        rows.append({"claim": "blinn_90deg", "model": name, "n": float(n), "quantity": "albedo_at_90deg",
                     "value": est.value[0], "value_err": est.error[0] + c_row["C_err"] / c_row["C"] * est.value[0],
                     "theta_deg": 90.0, "closed_form": np.nan, "role": "claim"})
    return rows


@table(NAME, deps=(CONSTANTS,), config=("chapter3_claims",), chapter=3)
def compute(cfg: dict, deps: dict) -> pd.DataFrame:
    sec, tol = cfg["chapter3_claims"], cfg["tolerance"]["rtol"]
    rows = (_grazing_rows(sec["grazing_limit_n"], sec["limit_check_n"], tol)
            + _overshoot_rows(sec["overshoot_n"], tol)
            + _blinn_rows(sec["blinn_90deg_n"], deps[CONSTANTS], tol))
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path) -> None:
    shown = df.assign(n=[f"{n:g}" for n in df["n"]])[["claim", "model", "n", "quantity", "value", "value_err", "theta_deg", "closed_form"]]
    plotting.save_table_png(shown, path, "Chapter 3 in-text numbers: eq. 3.27, overshoot (sec. 3.2.2), Blinn at 90 deg (sec. 3.7.4)")


def _claim_rows(artifact: str, df: pd.DataFrame) -> pd.DataFrame:
    prints = published.published_rows(artifact)
    records = []
    for r in df[(df["claim"] == artifact) & (df["role"] == "claim")].itertuples():
        rec = {"model": r.model, "param_value": f"{r.n:g}", "quantity": r.quantity,
               "computed": r.value, "computed_err": r.value_err}
        hit = prints[(prints["model"] == r.model) & (prints["param_value"] == f"{r.n:g}")]
        if hit.empty:           # the n of the figures: in the table, not in the print
            continue
        printed = hit["published"].iloc[0]
        if published.verdict(printed, r.value, r.value_err) == published.DIFFERS:
            rec |= published.explain_with_readings(printed, r.value, {}, f"computed {r.value:.6g} at {r.theta_deg:.4g} deg",
                                                   get_artifact(NAME).csv)
        records.append(rec)
    return pd.DataFrame.from_records(records)


@comparison("grazing_limit", tables=(NAME,))
def grazing_limit_rows(cfg: dict, tables: dict) -> pd.DataFrame:
    return _claim_rows("grazing_limit", tables[NAME])


@comparison("overshoot", tables=(NAME,))
def overshoot_rows(cfg: dict, tables: dict) -> pd.DataFrame:
    return _claim_rows("overshoot", tables[NAME])


@comparison("blinn_90deg", tables=(NAME, "extra_readings_chapter_3"))
def blinn_90deg_rows(cfg: dict, tables: dict) -> pd.DataFrame:
    """Sec. 3.7.4's two prints, completed by their search (the angle read as 90°, C_n computed or printed)."""
    from brdfs.artifacts.extra_readings_chapter_3 import GROUPS, NAME as READINGS

    df = tables[NAME]
    prints = published.published_rows("blinn_90deg")
    records = []
    for r in df[(df["claim"] == "blinn_90deg") & (df["role"] == "claim")].itertuples():
        hit = prints[(prints["model"] == r.model) & (prints["param_value"] == f"{r.n:g}")]
        if hit.empty:
            continue
        records.append({"model": r.model, "param_value": f"{r.n:g}", "quantity": r.quantity, "computed": r.value,
                        "computed_err": r.value_err, "evidence": get_artifact(NAME).csv,
                        "as_printed": published.verdict(hit["published"].iloc[0], r.value, r.value_err)})
    done = readings.with_search(pd.DataFrame.from_records(records), tables[READINGS], get_artifact(READINGS).csv,
                                group=GROUPS["blinn_90deg"])
    return done.drop(columns="as_printed")
