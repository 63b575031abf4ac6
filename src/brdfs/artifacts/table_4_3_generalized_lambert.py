"""Table 4.3: C_max, f_max and a_diffuse of the clipped generalized Lambertian model (eq. 4.59).

ξ(m) = min((1 − (m/2)²)^{−d/2}, ξ(m_clip)), m_clip = 1.9 as the thesis states. ξ increases, so
the albedo is largest at grazing incidence: C_max = 1/a^ξ(90°) by eq. 4.22 (adaptive integral
over R with closed-form circle intersections); f_max = ξ_max = ξ(1.9); a_diffuse is the
albedo at normal incidence, C_max 2π ∫₀¹ ξ(r) r dr in closed form. The column
``theta_max_deg`` is where the albedo, on a 1° grid, is largest (the thesis: always at 90°).
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
from brdfs.artifacts.extra_readings_table_4_3 import NAME as READINGS

NAME = "table_4_3_generalized_lambert"
ARTIFACT = "patch_generalized_lambert"
_RTOL = patch.CLOSED_FORM_RTOL


def _row(d: float, m_clip: float, tol: dict) -> dict:
    profile = patch.GeneralizedLambertProfile(d, m_clip)
    c_max = patch.generalized_lambert_c_max(profile, **tol)
    disk = 2 * np.pi * profile.disk_integral(1.0)
    grid = np.arange(0.0, 90.5, 1.0)
    curve = patch.mixture_albedo(profile, grid, C=c_max.value, **tol)
    at_zero = curve[0]
    return {
        "model": "generalized_lambertian",
        "d": d,
        "m_clip": m_clip,
        "C_max": c_max.value,
        "C_max_err": c_max.error,
        "f_max": profile.xi_max,
        "f_max_err": _RTOL * profile.xi_max,
        "a_diffuse": c_max.value * disk,
        "a_diffuse_err": c_max.error * disk + _RTOL * c_max.value * disk,
        "a_diffuse_integrated": at_zero.value,
        "a_diffuse_integrated_err": at_zero.error + c_max.error * disk,
        "theta_max_deg": grid[np.argmax(curve.value)],
    }


@table(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Table 4.3 recomputed, one row per d (columns in the module docstring, each with ``*_err``)."""
    section = cfg[SECTION]
    return pd.DataFrame([_row(float(d), section["m_clip"], tolerances(cfg)) for d in section["table_4_3_d"]])


def plot(df: pd.DataFrame, path) -> None:
    """Table 4.3 as printed beside the recomputed values."""
    shown = published.printed_lookup(ARTIFACT)

    table_df = pd.DataFrame(
        {
            "d": [f"{v:g}" for v in df["d"]],
            "C_max printed": [shown(d, "C_max") for d in df["d"]],
            "C_max = 1/a(90)": [f"{v:.6f}" for v in df["C_max"]],
            "f_max printed": [shown(d, "f_max") for d in df["d"]],
            "xi(1.9)": [f"{v:.7f}" for v in df["f_max"]],
            "a_diffuse printed": [shown(d, "a_diffuse") for d in df["d"]],
            "a(0)": [f"{v:.6f}" for v in df["a_diffuse"]],
        }
    )
    plotting.save_table_png(table_df, path, f"Table 4.3: generalized Lambertian, xi clipped at xi({df['m_clip'].iloc[0]:g})")


@comparison(ARTIFACT, tables=(NAME, READINGS))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 4.3: each print against eq. 4.59 with C_max = 1/a(90°), and the
    C_max and a_diffuse prints against the reconstructed sum of eq. 4.22 (:mod:`extra_readings_table_4_3`)."""
    df = tables[NAME]
    evidence = get_artifact(NAME).csv
    records = []
    for printed in published.published_rows(ARTIFACT).itertuples():
        row = df[np.isclose(df["d"], float(printed.param_value), rtol=0, atol=1e-12)].iloc[0]
        value, err = row[printed.quantity], row[f"{printed.quantity}_err"]
        records.append({"model": printed.model, "param_value": printed.param_value, "quantity": printed.quantity,
                        "computed": value, "computed_err": err, "evidence": evidence,
                        "as_printed": published.verdict(printed.published, value, err)})
    done = readings.with_search(pd.DataFrame.from_records(records), tables[READINGS], get_artifact(READINGS).csv,
                                effect=_effect)
    return done.drop(columns="as_printed")


def _effect(value_under_reading: float, computed: float) -> str:
    return (f"the sum's node at the clip m = 1.9 counts xi'(1.9) for a whole step, which lowers both albedo "
            f"integrals by the same amount, so the print is {value_under_reading - computed:+.2g} off eq. 4.59")
