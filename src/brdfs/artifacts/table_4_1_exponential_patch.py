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
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.artifacts._patch_common import SECTION, tolerances, truncation_reason

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


def _i12_reading(computed: float, weight: float, weight_err: float, printed: str) -> dict:
    """Reason and reading of an I_1,2 print that eq. 4.50 as printed does not give."""
    return {
        "reason": (
            f"eq. 4.50 as printed, pi*int_1^2 p(R) dR, gives {computed:.5f}; the print is "
            f"int_1^2 p(R) dR = {weight:.5f}, the weight (normal-incidence albedo) of the basic BRDFs "
            "with R >= 1 (eq. 4.50 inherits eq. 4.40's c(R) = pi min(1,R^2), the inverse of eq. 4.7)"
        ),
        "reading": "I_12 = int_1^2 p(R) dR (no factor pi)",
        "value_under_reading": weight if published.verdict(printed, weight, weight_err) == published.REPRODUCES else np.nan,
    }


@comparison(ARTIFACT, tables=(NAME,))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 4.1 with a reason for every print that differs."""
    df = tables[NAME]
    prints = published.published_rows(ARTIFACT)
    evidence = get_artifact(NAME).csv
    records = []
    for printed in prints.itertuples():
        row = df[df["s"] == float(printed.param_value)].iloc[0]
        value, err = row[printed.quantity], row[f"{printed.quantity}_err"]
        record = {"model": printed.model, "param_value": printed.param_value, "quantity": printed.quantity,
                  "computed": value, "computed_err": err, "evidence": evidence}
        if published.verdict(printed.published, value, err) == published.DIFFERS:
            if printed.quantity == "I_12":
                record |= _i12_reading(value, row["I_12_weight"], row["I_12_weight_err"], printed.published)
            else:
                record |= truncation_reason(printed.published, value)
        records.append(record)
    return pd.DataFrame.from_records(records)
