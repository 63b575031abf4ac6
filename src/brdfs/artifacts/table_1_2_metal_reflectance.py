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


def _text(value: float) -> str:
    """A decimal input as printed (the shortest repr of the double)."""
    return str(float(value))


def _explain(printed: str, computed: float, readings: pd.DataFrame) -> dict:
    """Reason, reading and value under the reading for a print eq. 1.40 does not reproduce.

    Tries, in this order: truncation instead of rounding, a transposition of two
    adjacent digits of ``n`` or ``k``, and ``n``, ``k`` at the ends of their
    printed rounding intervals; within a kind, the reading closest to the
    computed value wins.
    """
    evidence = get_artifact(READINGS).csv
    if published.truncates_to(printed, computed):
        return {"reason": f"truncated, not rounded: eq. 1.40 gives {computed:.3f}", "evidence": evidence}
    printed_inputs = readings[readings["reading"] == "printed"].iloc[0]
    for kind in ("transposed_ior_re", "transposed_ior_im", "rounding_corner"):
        candidates = readings[readings["reading"] == kind]
        candidates = candidates[[published.rounds_to(printed, v) for v in candidates["a0_percent"]]]
        if not candidates.empty:
            best = candidates.loc[(candidates["a0_percent"] - computed).abs().idxmin()]
            return _explained_by(kind, best, printed_inputs, computed) | {"evidence": evidence}
    return {
        "reason": (
            f"eq. 1.40 gives {computed:.3f}; neither truncation, nor a transposition of adjacent digits "
            "of n or k, nor n, k at the ends of their printed rounding intervals reproduces the print"
        ),
        "evidence": evidence,
    }


def _explained_by(kind: str, best: pd.Series, printed_inputs: pd.Series, computed: float) -> dict:
    """The reason and reading for the reading ``best`` of kind ``kind``."""
    if kind == "rounding_corner":
        inputs = f"n = {_text(best['ior_re'])}, k = {_text(best['ior_im'])}"
        return {
            "reason": (
                f"eq. 1.40 gives {computed:.3f} for the printed n = {_text(printed_inputs['ior_re'])}, "
                f"k = {_text(printed_inputs['ior_im'])}; no digit transposition reproduces the print, but {inputs}, "
                f"within the rounding of the printed inputs, gives {best['a0_percent']:.3f}"
            ),
            "reading": f"inputs unrounded: {inputs}",
            "value_under_reading": best["a0_percent"],
        }
    symbol, column = ("n", "ior_re") if kind == "transposed_ior_re" else ("k", "ior_im")
    misprint, printed = _text(best[column]), _text(printed_inputs[column])
    return {
        "reason": (
            f"misprinted input: {symbol} = {misprint} instead of {printed} "
            f"gives {best['a0_percent']:.2f}; eq. 1.40 with the printed inputs gives {computed:.2f}"
        ),
        "reading": f"{symbol} = {misprint} (digits of the printed {printed} transposed)",
        "value_under_reading": best["a0_percent"],
    }


@comparison(ARTIFACT, tables=("table_1_2_metal_reflectance", READINGS))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 1.2: computed a0, and a reason wherever it differs."""
    computed = tables["table_1_2_metal_reflectance"]
    readings = tables[READINGS]
    prints = published.published_rows(ARTIFACT).set_index("param_value")["published"]
    records = []
    for row in computed.itertuples(index=False):
        record = {
            "model": "fresnel_normal_incidence",
            "param_value": row.metal,
            "quantity": "a0_percent",
            "computed": row.a0_percent,
            "computed_err": row.a0_percent_err,
        }
        printed = prints.get(row.metal)  # None for a metal the thesis does not print: make_fragment refuses it
        if printed is not None and published.verdict(printed, row.a0_percent, row.a0_percent_err) == published.DIFFERS:
            record |= _explain(printed, row.a0_percent, readings[readings["metal"] == row.metal])
        records.append(record)
    return pd.DataFrame.from_records(records)
