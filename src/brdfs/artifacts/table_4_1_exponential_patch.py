"""Table 4.1: C_max, I_1,2 and a_Diffuse of the exponential patch BRDF f = C_max e^{−s m}.

Closed forms (eqs. 4.45, 4.47, 4.50), each beside an independent adaptive integration:
C_max = 1/(2π ∫₀¹ ξ(r) r dr) (the albedo at normal incidence is 1), ∫_1² p(R) dR, and
p_Diffuse = 1 − ∫₀² p(R) dR (the weight p is a probability density with a Dirac part at R = 2).

Eq. 4.50 prints I_1,2 = π ∫_1² p(R) dR (carrying eq. 4.40's c(R) = π min(1, R²), the inverse of
eq. 4.7's c(R)); that is the ``I_12`` column. The column ``I_12_weight`` = ∫_1² p(R) dR, the
weight of the basic BRDFs with R ≥ 1 (their albedo at normal incidence), is the reading that
reproduces the print.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.artifacts._patch_common import SECTION, tolerances

NAME = "table_4_1_exponential_patch"
ARTIFACT = "patch_exponential"
_RTOL = patch.CLOSED_FORM_RTOL


def _closed_forms(s: np.ndarray) -> dict[str, np.ndarray]:
    """C_max (eq. 4.45), π∫_1²p and ∫_1²p = C_max π (e^{−s} − e^{−2s}) (eqs. 4.47, 4.50), p_Diffuse."""
    c_max = np.array([patch.ExponentialProfile(v).c_max for v in s])
    weight_12 = c_max * np.pi * np.exp(-s) * -np.expm1(-s)
    a_diffuse = c_max * np.pi * np.exp(-2 * s)
    return {"C_max": c_max, "I_12": np.pi * weight_12, "I_12_weight": weight_12, "a_diffuse": a_diffuse}


def _integrated(s: np.ndarray, tol: dict) -> dict[str, np.ndarray]:
    """The same three numbers by adaptive integration of ξ and of p(R) (eq. 4.47)."""
    profiles = [patch.ExponentialProfile(v) for v in s]
    disk = patch.exponential_disk_integral(s, **tol)
    upper = patch.weight_integral(profiles, 1.0, 2.0, **tol)
    whole = patch.weight_integral(profiles, 0.0, 2.0, **tol)
    return {
        "C_max_integrated": (1 / (2 * np.pi * disk.value), disk.error / (2 * np.pi * disk.value**2)),
        "I_12_integrated": (np.pi * upper.value, np.pi * upper.error),
        "a_diffuse_integrated": (1 - whole.value, whole.error + _RTOL),
    }


@table(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Table 4.1 recomputed, one row per s.

    Returns
    -------
    pandas.DataFrame
        ``s``; ``C_max, I_12, I_12_weight, a_diffuse`` by closed form and ``*_integrated`` by
        quadrature, each with ``*_err``.
    """
    s = np.asarray(cfg[SECTION]["table_4_1_s"], float)
    columns = {"model": "patch_exponential", "s": s}
    for name, value in _closed_forms(s).items():
        columns |= {name: value, f"{name}_err": _RTOL * np.abs(value)}
    for name, (value, err) in _integrated(s, tolerances(cfg)).items():
        columns |= {name: value, f"{name}_err": err}
    return pd.DataFrame(columns)


def plot(df: pd.DataFrame, path) -> None:
    """Table 4.1 as printed beside the recomputed values."""
    shown = published.printed_lookup(ARTIFACT)

    table_df = pd.DataFrame(
        {
            "s": [f"{v:g}" for v in df["s"]],
            "C_max printed": [shown(s, "C_max") for s in df["s"]],
            "C_max eq. 4.45": [f"{v:.6g}" for v in df["C_max"]],
            "I_12 printed": [shown(s, "I_12") for s in df["s"]],
            "pi*int_1^2 p (eq. 4.50)": [f"{v:.5f}" for v in df["I_12"]],
            "int_1^2 p": [f"{v:.5f}" for v in df["I_12_weight"]],
            "a_Diffuse printed": [shown(s, "a_diffuse") for s in df["s"]],
            "C_max pi e^-2s": [f"{v:.5f}" for v in df["a_diffuse"]],
        }
    )
    plotting.save_table_png(table_df, path, "Table 4.1: parameters of f = C_max exp(-s m), printed and recomputed")


#: The searches of how the table was printed (:mod:`brdfs.artifacts.extra_readings_table_4_1`).
READINGS = "extra_readings_table_4_1"


@comparison(ARTIFACT, tables=(NAME, READINGS))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 4.1, completed by the searches of :mod:`extra_readings_table_4_1`
    (a printing rule for C_max, a constant for I_1,2)."""
    df = tables[NAME]
    evidence = get_artifact(NAME).csv
    records = []
    for printed in published.published_rows(ARTIFACT).itertuples():
        row = df[df["s"] == float(printed.param_value)].iloc[0]
        value, err = row[printed.quantity], row[f"{printed.quantity}_err"]
        records.append({"model": printed.model, "param_value": printed.param_value, "quantity": printed.quantity,
                        "computed": value, "computed_err": err, "evidence": evidence,
                        "as_printed": published.verdict(printed.published, value, err)})
    from brdfs.artifacts.extra_readings_table_4_1 import GROUPS

    records = pd.DataFrame.from_records(records)
    searches = tables[READINGS]
    where = get_artifact(READINGS).csv
    for group, effect in ((GROUPS["C_max"], _printing_effect), (GROUPS["I_12"], _constant_effect)):
        done = readings.with_search(records, searches, where, effect=effect, group=group)
        done["as_printed"] = records["as_printed"]
        records = done
    return records.drop(columns="as_printed")


def _printing_effect(value_under_reading: float, computed: float) -> str:
    return "the column's printing rule cuts the fifth significant digit instead of rounding it"


def _constant_effect(value_under_reading: float, computed: float) -> str:
    return (f"eq. 4.50's factor pi is missing from the print (eq. 4.40's c(R) = pi min(1, R^2) is the inverse of "
            f"eq. 4.7's), so the print is int_1^2 p(R) dR, {value_under_reading / computed:.4f} times eq. 4.50")
