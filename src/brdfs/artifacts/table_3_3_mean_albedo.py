"""Table 3.3: mean albedo (eq. 3.37) of the reciprocal Phong, the new model, Blinn and corrected
Blinn for n = 1 … 512 (Blinn columns with this project's C_n of Table 3.1), the n → ∞ row from
the derived limits (:mod:`brdfs.numerics.quantities`), and rows at growing n that confirm the limits."""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.physics.models import model
from brdfs.numerics.quantities import limit_mean_albedo, mean_albedo
from brdfs.artifacts.table_3_1_blinn_constants import blinn_normal_incidence_albedo

NAME = "table_3_3_mean_albedo"
CONSTANTS = "table_3_1_blinn_constants"
MODELS = ("phong", "phong_cosmin", "blinn", "blinn_cosmin")


def _blinn_constants(ns, constants: pd.DataFrame):
    """C_n from Table 3.1 where it was computed; beyond it (the limit check, n ≫ 512) the maximum
    is at normal incidence, where both Blinn models coincide and a(0) has a closed form."""
    out = {}
    for name in ("blinn", "blinn_cosmin"):
        table31 = constants[constants["model"] == name].set_index("n")
        for n in ns:
            if n in table31.index:
                out[name, n] = (table31.at[n, "C"], table31.at[n, "C_err"])
            else:
                out[name, n] = (1 / float(blinn_normal_incidence_albedo(n)), 0.0)
    return out


@table(NAME, deps=(CONSTANTS,), config=("mean_albedo",))
def compute(cfg: dict, deps: dict) -> pd.DataFrame:
    sec = cfg["mean_albedo"]
    ns = [float(n) for n in sec["n"]] + [float(n) for n in sec["limit_check_n"]]
    C = _blinn_constants(ns, deps[CONSTANTS])
    models = [model(name, n=n) if name.startswith("phong") else model(name, n=n, C=1.0) for name in MODELS for n in ns]
    est = mean_albedo(models, sec["rtol"])
    rows = []
    for i, (name, n) in enumerate((name, n) for name in MODELS for n in ns):
        c, c_err = C.get((name, n), ((n + 2) / (2 * np.pi), 0.0))
        scale = 1.0 if name.startswith("phong") else c
        value, err = scale * est.value[i], scale * est.error[i] + (0.0 if name.startswith("phong") else c_err * est.value[i])
        engine = value
        exact = models[i].exact_mean_albedo()
        if exact is not None:   # exact where the engine's ±4e-11 would straddle a rounding tie (A(4) = 11/16)
            value, err = exact.value, exact.error
        rows.append({"model": name, "n": n, "C": c, "C_err": c_err, "mean_albedo": value, "mean_albedo_err": err,
                     "mean_albedo_engine": engine, "role": "table" if n in sec["n"] else "limit_check"})
    for name in MODELS:
        rows.append({"model": name, "n": np.inf, "C": np.nan, "C_err": np.nan, "mean_albedo": limit_mean_albedo(name),
                     "mean_albedo_err": 0.0, "mean_albedo_engine": np.nan, "role": "limit"})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path) -> None:
    printed = published.printed_lookup("mean_albedo")
    wide = df[df["role"] != "limit_check"].pivot(index="n", columns="model", values="mean_albedo")[list(MODELS)]
    shown = pd.DataFrame({"n": [f"{n:g}" for n in wide.index]})
    for name in MODELS:
        shown[f"{name} printed"] = [printed(n, "mean_albedo", name) for n in wide.index]
        shown[f"{name} computed"] = [f"{v:.4f}" for v in wide[name]]
    plotting.save_table_png(shown, path, "Table 3.3: mean albedo, printed and computed (Blinn with this project's C_n)")


def _limit_reason(name, computed, printed, df):
    checks = df[(df["model"] == name) & (df["role"] == "limit_check")]
    trend = ", ".join(f"n={r.n:g}: {r.mean_albedo:.4f}" for r in checks.itertuples())
    context = (f"the derived limit is {computed:.6g} (a(θ) → cos^k θ as n → ∞, A = 2/(k+2)), confirmed by growing n "
               f"({trend}) and by the column's own finite-n prints")
    return readings.limit_law_reading(printed, computed, context) | {"evidence": get_artifact(NAME).csv}


#: The searches of how chapter 3's tables were computed (:mod:`brdfs.artifacts.extra_readings_chapter_3`).
READINGS = "extra_readings_chapter_3"


@comparison("mean_albedo", tables=(NAME, READINGS))
def rows(cfg: dict, tables: dict) -> pd.DataFrame:
    """Comparison rows of Table 3.3: the finite-n rows completed by their search (eq. 3.37's outer
    integral as sums), the n → ∞ row against the limit laws."""
    from brdfs.artifacts.extra_readings_chapter_3 import GROUPS

    df = tables[NAME]
    printed_of = published.printed_lookup("mean_albedo")
    records = []
    for r in df[df["role"] != "limit_check"].itertuples():
        printed = printed_of(r.n, "mean_albedo", r.model)
        rec = {"model": r.model, "param_value": f"{r.n:g}", "quantity": "mean_albedo", "computed": r.mean_albedo,
               "computed_err": r.mean_albedo_err, "evidence": get_artifact(NAME).csv,
               "as_printed": published.verdict(printed, r.mean_albedo, r.mean_albedo_err) if printed else ""}
        if np.isinf(r.n) and rec["as_printed"] == published.DIFFERS:
            rec |= _limit_reason(r.model, r.mean_albedo, printed, df)
        records.append(rec)
    done = readings.with_search(pd.DataFrame.from_records(records), tables[READINGS], get_artifact(READINGS).csv,
                                effect=_effect, group=GROUPS["mean_albedo"])
    return done.drop(columns="as_printed")


def _effect(value_under_reading: float, computed: float) -> str:
    return (f"90 midpoints in u = cos^2 theta sample the fall of a narrow lobe's albedo next to grazing "
            f"(u < 1/90) once, so the sum is {value_under_reading - computed:+.2g} off eq. 3.37")
