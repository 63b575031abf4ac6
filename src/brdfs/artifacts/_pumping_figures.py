"""Shared parts of the albedo tables and Figures 2.3-2.6 (section 2.3, albedo pumping-up).

The tables (``extra_pumping_albedo_<model>``) hold, level by level, the albedo of the model
pumped 0 ... K times as a piecewise Chebyshev interpolant (:mod:`brdfs.numerics.pumping`); the figures
rebuild the pumped models from them (no integration) and draw the albedo and the radiance
L_out(V) = f(L, V) cos θ_L of a point light of intensity 4π at distance 1 (eq. 2.3), V = R.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.numerics import pumping
from brdfs import albedo
from brdfs.physics.geometry import cos_incidence, light_direction, mirror
from brdfs.physics.models import MODELS, model, phong_constant
from brdfs.numerics.quantities import maximal_constant

#: Relative rounding bound of one BRDF evaluation (powers n ≤ 100 of a rounded dot product).
ROUNDING_RTOL = 256 * np.finfo(float).eps
LEVEL_COLUMNS = ["model", "n", "C", "pumping", "level"]


def base_model(name: str, n: float, C: float | None = None):
    """Reciprocal Phong with c = (n+2)/2π (eq. 3.6) or Blinn with C = 1/max a (computed: the model's
    :attr:`~brdfs.physics.models.base.BRDF.constant_is_computed`)."""
    if C is None and MODELS[name].constant_is_computed:
        C = float(maximal_constant([model(name, n=n)])[0].value[0])
    return model(name, n=n, C=C)


def albedo_tables(name: str, cfg: dict) -> pd.DataFrame:
    """The tidy albedo tables of ``name`` (``'phong'`` or ``'blinn'``) pumped 0 ... K times, g1 and g2."""
    p = cfg["pumping"]
    base = base_model(name, p["n"])
    df = pumping.sequence_frame(base, p["levels"], p["table_rtol"], p["engine_rtol"])
    df = df.assign(model=name, n=p["n"], C=base.C)
    return df[LEVEL_COLUMNS + [c for c in df.columns if c not in LEVEL_COLUMNS]]


def plot_tables(df: pd.DataFrame, path) -> None:
    """The table nodes: albedo against incidence angle, per pumping and level."""
    fig, ax = plotting.new_axes("incidence angle θ_L [deg]", "albedo a(θ_L) at the table nodes",
                                f"Albedo tables of {df['model'].iloc[0]} (n = {df['n'].iloc[0]:g}) pumped 0..K times")
    for (corr, level), g in df.groupby(["pumping", "level"]):
        ax.plot(np.degrees(np.arccos(g["cos_theta"])), g["albedo"], ".", ms=3, label=f"{corr} level {level}")
    plotting.savefig(fig, path)


def curves(cfg: dict, tables: pd.DataFrame, correction: str) -> pd.DataFrame:
    """Albedo (from the tables) and mirror-direction radiance of every level of one sequence.

    The albedo error is the table's error plus ε_k a (the model's own distance to the exact
    pumped model); the radiance error is ε_k L_out plus rounding.
    """
    name, n, C = tables[["model", "n", "C"]].iloc[0]
    level_tables = pumping.tables_from_frame(tables, correction)
    models = pumping.pumped_models(base_model(name, n, C), level_tables[:-1], correction)
    theta = np.arange(0.0, 90.0 + 1e-9, cfg["pumping"]["theta_step_deg"])
    lit = theta[theta < 90.0]   # at 90° the radiance is 0 · f: left out
    L = light_direction(lit)
    rows = []
    for level, (table, brdf) in enumerate(zip(level_tables, models)):
        corr = "none" if level == 0 else correction
        a = table(cos_incidence(theta))
        rows.append(pd.DataFrame({"theta_deg": theta, "albedo": a, "albedo_err": table.error + a * table.model_rtol})
                    .assign(model=name, n=n, C=C, pumping=corr, level=level))
        radiance = brdf(L, mirror(L)) * cos_incidence(lit)
        err = radiance * (pumping.model_rtol(brdf) + ROUNDING_RTOL)
        rows.append(pd.DataFrame({"theta_deg": lit, "radiance": radiance, "radiance_err": err})
                    .assign(model=name, n=n, C=C, pumping=corr, level=level, view=cfg["pumping"]["radiance_view"]))
    return pd.concat(rows, ignore_index=True)[
        LEVEL_COLUMNS + ["view", "theta_deg", "albedo", "albedo_err", "radiance", "radiance_err"]]


def distance_to_new_model(cfg: dict, df: pd.DataFrame) -> pd.DataFrame:
    """How far each level of controlled Phong pumping is from eq. 2.22 with a fitted c.

    The new model's albedo is the closed-form-azimuth integral (:mod:`brdfs.numerics.integrate.azimuthal`).
    For each level k, c is chosen to minimise max_θ |c a_new(θ)/c₀ / a_k(θ) − 1| (a fit to our
    own pumped model, never to a print); the minimum is the distance.  Rows: the new model's
    albedo with c₀ = (n+2)/2π and one distance row per level.
    """
    n = float(df["n"].iloc[0])
    albedo_rows = df[df["albedo"].notna()]
    theta = np.sort(albedo_rows["theta_deg"].unique())
    new = model("phong_cosmin", n=n)
    est = albedo(new, theta, "azimuthal", rtol=cfg["tolerance"]["rtol"], atol=cfg["tolerance"]["atol"])
    rows = [pd.DataFrame({"theta_deg": theta, "albedo": est.value, "albedo_err": est.error})
            .assign(model="phong_cosmin", n=n, C=new.C, pumping="none")]
    for level, g in albedo_rows.groupby("level"):
        g = g.sort_values("theta_deg")
        ratio = est.value / g["albedo"].to_numpy()
        rel = np.max(est.error / est.value) + np.max(g["albedo_err"] / g["albedo"])
        lo, hi = ratio.min(), ratio.max()
        rows.append(pd.DataFrame({"model": ["phong"], "n": [n], "pumping": [g["pumping"].iloc[0]], "level": [level],
                                  "distance_to_eq_2_22": [(hi - lo) / (hi + lo)], "distance_to_eq_2_22_err": [2 * rel],
                                  "c_fit": [2 * new.C / (hi + lo)]}))
    return pd.concat(rows, ignore_index=True)


def plot_curves(df: pd.DataFrame, path, title: str) -> None:
    """Albedo (left) and mirror-direction radiance relative to C (right) per pumping level."""
    fig, (left, right) = plotting.plt.subplots(1, 2, figsize=(10, 4.2))
    pumped = df[df["model"] != "phong_cosmin"]
    for level, g in pumped.groupby("level"):
        a = g[g["albedo"].notna()]
        r = g[g["radiance"].notna()]
        left.plot(a["theta_deg"], a["albedo"], label=f"level {int(level)}")
        right.plot(r["theta_deg"], r["radiance"] / r["C"], label=f"level {int(level)}")
    new = df[df["model"] == "phong_cosmin"]
    if not new.empty:
        left.plot(new["theta_deg"], new["albedo"], "k--", label="eq. 2.22, c = (n+2)/2π")
    theta = np.linspace(0, 90, 181)
    left.plot(theta, cos_incidence(theta), ":", color="grey", label="cos θ_L")
    right.axhline(1.0, color="grey", ls=":", label="L/C = 1 (unpumped, θ_L = 0)")
    left.set(xlabel="incidence angle θ_L [deg]", ylabel="albedo a(θ_L)")
    left.legend(fontsize=7, loc="lower left")
    right.legend(fontsize=7, loc="upper left")
    right.set(xlabel="incidence angle θ_L [deg]", ylabel="L_out(R) / C,  L_out = f(L,R) cos θ_L")
    fig.suptitle(f"{title} (n = {df['n'].iloc[0]:g})", fontsize=10)
    plotting.savefig(fig, path)


def phong_constant_of(n: float) -> float:
    """c₀ = (n+2)/2π of eq. 3.6."""
    return float(phong_constant(n))
