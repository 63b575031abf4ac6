"""Table 4.2: the mirror limits (n → ∞, s → ∞) of Phong, of the new patch BRDF and of a metal mirror.

Rows of kind ``limit`` hold the derived limits (Phong and Blinn from :mod:`brdfs.numerics.quantities`,
the patch BRDF from :func:`brdfs.physics.patch_geometry.limit_small_patch_albedo`, the metal mirror from the
ideal mirror with Fresnel = 1: f = δ/cos θ, a ≡ 1). Rows of kind ``numerical`` confirm them
at growing n or s (config ``patch.limit_n``, ``patch.limit_s``, ``patch.limit_theta_near_deg``).

"a(θ → 90°)" is read as the thesis argues it ("arbitrarily close to the horizontal"):
lim_{θ→90°} lim_{s→∞} a(θ). At exactly 90° the order of the limits matters for the patch BRDF:
lim_{s→∞} a(90°) = 1/2 (rows with ``theta_deg`` = 90). L_out and f_r at grazing are ratios to
their values at normal incidence for a source small against the lobe: L_out ∝ f_max cos θ.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.numerics import quantities
from brdfs.numerics.albedo import albedo_table
from brdfs.pipeline.registry import comparison, get_artifact, table
from brdfs.artifacts._patch_common import SECTION, tolerances
from brdfs.physics.models import model

NAME = "table_4_2_limit_comparison"
ARTIFACT = "limit_comparison"
INF = float("inf")


def _record(model_name, quantity, param, param_value, theta_deg, value, err, kind, note=""):
    return {"model": model_name, "quantity": quantity, "param": param, "param_value": param_value,
            "theta_deg": theta_deg, "value": float(value), "value_err": float(err), "kind": kind, "note": note}


def _limits() -> list[dict]:
    """The derived limits of the table, θ → 90° after n, s → ∞."""
    small = float(patch.limit_small_patch_albedo(90.0))
    return [
        _record("phong", "mean_albedo", "n", INF, np.nan, quantities.limit_mean_albedo("phong"), 0, "limit",
                "a(theta) -> cos theta, mean 2/3"),
        _record("blinn", "mean_albedo", "n", INF, np.nan, quantities.limit_mean_albedo("blinn"), 0, "limit",
                "a(theta) -> cos^2 theta, mean 1/2: the Phong-Blinn (N.H)^n mirror of section 4.2.2"),
        _record("phong", "albedo_at_90deg", "n", INF, 90.0, quantities.limit_albedo_90("phong"), 0, "limit"),
        _record("patch_exponential", "mean_albedo", "s", INF, np.nan, 1.0, 0, "limit"),
        _record("patch_exponential", "albedo_at_90deg", "s", INF, 90.0, float(patch.limit_small_patch_albedo(89.999)),
                0, "limit", f"lim theta->90 of lim s->inf; at exactly 90 deg lim s->inf a = {small}"),
        _record("patch_exponential", "albedo_exactly_90deg", "s", INF, 90.0, small, 0, "limit", "lim s->inf a(90 deg)"),
        _record("metal_mirror", "mean_albedo", "", INF, np.nan, 1.0, 0, "limit", "ideal mirror, Fresnel = 1"),
        _record("metal_mirror", "albedo_at_90deg", "", INF, 90.0, 1.0, 0, "limit", "ideal mirror, Fresnel = 1"),
        _record("phong", "radiance_out_at_90deg", "n", INF, 90.0, 0.0, 0, "limit", "L_out/L_in ~ f_max cos theta -> 0"),
        _record("patch_exponential", "radiance_out_at_90deg", "s", INF, 90.0, 0.0, 0, "limit",
                "L_out/L_in ~ C_max cos theta -> 0"),
        _record("metal_mirror", "radiance_out_at_90deg", "", INF, 90.0, 1.0, 0, "limit", "L_out = L_in"),
        _record("phong", "brdf_at_90deg", "n", INF, 90.0, 1.0, 0, "limit", "max_V f / its value at 0 deg: constant c"),
        _record("patch_exponential", "brdf_at_90deg", "s", INF, 90.0, 1.0, 0, "limit",
                "max_V f / its value at 0 deg: constant C_max"),
        _record("metal_mirror", "brdf_at_90deg", "", INF, 90.0, INF, 0, "limit", "delta/cos theta -> infinity"),
    ]


def _phong_blinn_numerics(n_values, theta_near, tol) -> list[dict]:
    phong = [model("phong", n=n) for n in n_values]
    blinn_c, _ = quantities.maximal_constant([model("blinn", n=n, C=1.0) for n in n_values], tol["rtol"])
    blinn = [model("blinn", n=n, C=c) for n, c in zip(n_values, blinn_c.value)]
    mean_phong, mean_blinn = quantities.mean_albedo(phong, tol["rtol"]), quantities.mean_albedo(blinn, tol["rtol"])
    grazing = albedo_table(phong, [theta_near, 90.0], tol["rtol"], tol["atol"])
    records = []
    for i, n in enumerate(n_values):
        blinn_err = mean_blinn.error[i] + mean_blinn.value[i] * blinn_c.error[i] / blinn_c.value[i]
        records += [
            _record("phong", "mean_albedo", "n", n, np.nan, mean_phong.value[i], mean_phong.error[i], "numerical"),
            _record("blinn", "mean_albedo", "n", n, np.nan, mean_blinn.value[i], blinn_err, "numerical",
                    "C = maximal constant (max albedo 1)"),
            _record("phong", "albedo_near_90deg", "n", n, theta_near, grazing.value[i, 0], grazing.error[i, 0],
                    "numerical", f"limit cos theta = {np.cos(np.radians(theta_near)):.6f}"),
            _record("phong", "albedo_exactly_90deg", "n", n, 90.0, grazing.value[i, 1], grazing.error[i, 1], "numerical"),
        ]
    return records


def _patch_numerics(s_values, theta_near, tol) -> list[dict]:
    records = []
    for s in s_values:
        profile = patch.ExponentialProfile(s)
        mean = patch.mixture_mean_albedo(profile, **tol)
        grazing = patch.mixture_albedo(profile, np.array([theta_near, 90.0]), **tol)
        records += [
            _record("patch_exponential", "mean_albedo", "s", s, np.nan, mean.value, mean.error, "numerical"),
            _record("patch_exponential", "albedo_near_90deg", "s", s, theta_near, grazing.value[0], grazing.error[0],
                    "numerical", "limit 1"),
            _record("patch_exponential", "albedo_exactly_90deg", "s", s, 90.0, grazing.value[1], grazing.error[1],
                    "numerical", "limit 1/2"),
        ]
    return records


@table(NAME, config=(SECTION,))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Table 4.2: derived limits and their numerical confirmation (columns in the module docstring)."""
    section, tol = cfg[SECTION], tolerances(cfg)
    theta_near = section["limit_theta_near_deg"]
    return pd.DataFrame(
        _limits()
        + _phong_blinn_numerics([float(n) for n in section["limit_n"]], theta_near, tol)
        + _patch_numerics([float(s) for s in section["limit_s"]], theta_near, tol)
    )


def plot(df: pd.DataFrame, path) -> None:
    """Table 4.2 as printed beside the derived limits."""
    limits = df[df["kind"] == "limit"]
    printed = published.published_rows(ARTIFACT)
    lookup = {(r.model, r.quantity): r.published for r in printed.itertuples()}
    shown = pd.DataFrame(
        {
            "model": limits["model"],
            "quantity": limits["quantity"],
            "printed": [lookup.get((m, q), "") for m, q in zip(limits["model"], limits["quantity"])],
            "derived limit": [f"{v:.6g}" for v in limits["value"]],
            "note": limits["note"],
        }
    )
    plotting.save_table_png(shown, path, "Table 4.2: mirror limits at grazing incidence (theta -> 90 after n, s -> inf)")


@comparison(ARTIFACT, tables=(NAME,))
def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Comparison rows of Table 4.2; the Phong mean albedo 1/2 is the Phong-Blinn limit."""
    df = tables[NAME]
    limits = df[df["kind"] == "limit"].set_index(["model", "quantity"])
    numeric = df[df["kind"] == "numerical"]
    evidence = get_artifact(NAME).csv
    records = []
    for printed in published.published_rows(ARTIFACT).itertuples():
        limit = limits.loc[(printed.model, printed.quantity)]
        record = {"model": printed.model, "param_value": printed.param_value, "quantity": printed.quantity,
                  "computed": limit["value"], "computed_err": limit["value_err"], "evidence": evidence}
        if published.verdict(printed.published, limit["value"], limit["value_err"]) == published.DIFFERS:
            largest = numeric[(numeric["model"] == "phong") & (numeric["quantity"] == "mean_albedo")].iloc[-1]
            context = (f"the reciprocal Phong c(R.V)^n tends to a(theta) = cos theta, mean albedo 2/3 "
                       f"(n = {largest['param_value']:g} gives {largest['value']:.6f}); 1/2 is the limit of the "
                       "Phong-Blinn C(N.H)^n model, a -> cos^2 theta, the mirror section 4.2.2 compares with")
            record |= readings.limit_law_reading(printed.published, limit["value"], context)
        records.append(record)
    return pd.DataFrame.from_records(records)
