"""Accuracy map: the engine's albedo and its reported error against the independent projected-disk
integration (:mod:`brdfs.numerics.integrate.disk`) for every model of the package, over incidence
angles up to 89.9999° and the thesis's parameter ranges.

Per cell: engine value and reported error, reference value and error, the difference, and
``ratio`` = |engine − reference| / reported engine error (meaningful where the reference is the more
accurate, ``judged``).  As measures of the engine's true error, both are known within the reference's
error: ``difference_err`` = the reference's error, ``ratio_err`` = that over the engine's error.  A cell is ``dishonest`` when the two disagree beyond their combined reported
errors, ``failed`` when either method returns a non-finite value, and ``meets_tolerance`` when the
engine's error meets the contract's target (rtol, or atol below 1e-4).

Engines: the model's own route to its albedo where it has one (the patch models whose albedo is
integrated, exponential and generalized Lambertian: the mixture integral over R of
:func:`brdfs.physics.patch_geometry.mixture_albedo`, eqs. 4.22/4.24, through
:meth:`~brdfs.physics.models.base.BRDF.albedo_estimate`), else the hemisphere/scattering front door
:func:`brdfs.numerics.albedo.albedo_table`.  Pumped models (:mod:`brdfs.numerics.pumping`): level 1 of
the reciprocal Phong, plain (g1) and controlled (g2), each from its albedo table
(:func:`brdfs.numerics.tables.pump`); engine and reference integrate the same tabulated model.

The families are the models' own (:attr:`~brdfs.physics.models.base.BRDF.accuracy_families`: which
parameter a family sweeps and which it fixes); ``config.yaml`` gives each family's values, so a model
that declares a family is mapped with no edit here.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.numerics import tables
from brdfs.numerics.albedo import albedo_table
from brdfs.numerics.grazing import approach_angles
from brdfs.numerics.integrate.disk import disk_albedo_many
from brdfs.physics.models import MODELS, model
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

NAME = "extra_accuracy_map"
SECTION = "accuracy_map"
#: The contract's switch from relative to absolute error targets.
ABSOLUTE_BELOW = 1e-4


def families() -> dict[str, tuple[str, str, dict]]:
    """Every family the registered models declare (:attr:`BRDF.accuracy_families`): family name ->
    (model name, the swept parameter, fixed parameters)."""
    return {family: (name, key, fixed) for name, cls in MODELS.items()
            for family, (key, fixed) in cls.accuracy_families.items()}


def grid(sec: dict) -> tuple[dict, np.ndarray]:
    """The families with their parameter values, and the incidence angles, of the chosen grid."""
    g = sec[sec["grid"]]
    theta = np.asarray(g["theta_deg"], float)
    if "theta_step_deg" in g:
        theta = np.concatenate([theta, np.arange(0.0, 90.0, g["theta_step_deg"]),
                                approach_angles(g["approach_from"], g["approach_to"], g["per_decade"])])
    theta = np.unique(np.round(theta, 10))
    return g["families"], theta


def build(family: str, value: float, sec: dict):
    """The model of ``family`` at the swept parameter ``value``; pumped once (:func:`tables.pump`, its
    table to ``pumping_table_rtol`` on engine values at ``pumping_engine_rtol``) if the family fixes a
    ``pumping`` correction."""
    name, key, fixed = families()[family]
    params = {k: v for k, v in fixed.items() if k != "pumping"}
    brdf = model(name, **{key: value}, **params)
    if "pumping" not in fixed:
        return brdf
    return tables.pump(brdf, fixed["pumping"], target_rtol=sec["pumping_table_rtol"],
                       engine_rtol=sec["pumping_engine_rtol"])


def _engine(brdf, theta: np.ndarray, tol: dict):
    """The model's own albedo route where it has one (the patch models' lens areas), else the engine."""
    own = brdf.albedo_estimate(theta, tol["rtol"], tol["atol"])
    if own is not None:
        return own
    return albedo_table([brdf], theta, rtol=tol["rtol"], atol=tol["atol"])[0]


def accuracy_map(sec: dict, tol: dict) -> pd.DataFrame:
    """One row per (family, parameter value, θ): engine, reference, difference, flags."""
    swept, theta = grid(sec)
    declared = families()
    frames, models, angles = [], [], []
    for family, values in swept.items():
        key = declared[family][1]
        for value in values:
            brdf = build(family, value, sec)
            with np.errstate(all="ignore"):
                eng = _engine(brdf, theta, tol)
            frames.append(pd.DataFrame({"family": family, "model": brdf.name, "parameter": key,
                                        "parameter_value": float(value), "theta_deg": theta,
                                        "albedo": np.asarray(eng.value, float), "albedo_err": np.asarray(eng.error, float)}))
            models += [brdf] * theta.size
            angles.append(theta)
    df = pd.concat(frames, ignore_index=True)
    with np.errstate(all="ignore"):
        ref = disk_albedo_many(models, np.concatenate(angles), rtol=sec["reference_rtol"], atol=tol["atol"] * 1e-2)
    df["reference_albedo"], df["reference_albedo_err"] = ref.value, ref.error
    return flag(df, tol)


def flag(df: pd.DataFrame, tol: dict) -> pd.DataFrame:
    """Difference, ratio to the reported error, their errors, and the flags of the module docstring."""
    diff = (df["albedo"] - df["reference_albedo"]).abs()
    finite = np.isfinite(df[["albedo", "albedo_err", "reference_albedo", "reference_albedo_err"]]).all(axis=1)
    target = np.maximum(tol["rtol"] * df["albedo"].abs(), np.where(df["albedo"].abs() < ABSOLUTE_BELOW, tol["atol"], 0.0))
    reported = df["albedo_err"].where(df["albedo_err"] > 0, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio, ratio_err = diff / reported, df["reference_albedo_err"] / reported
    return df.assign(
        difference=diff,
        difference_err=df["reference_albedo_err"],
        ratio=np.where(reported > 0, ratio, np.inf),
        ratio_err=np.where(reported > 0, ratio_err, np.inf),
        judged=df["reference_albedo_err"] < df["albedo_err"],
        dishonest=finite & (diff > df["albedo_err"] + df["reference_albedo_err"]),
        failed=~finite,
        meets_tolerance=finite & (df["albedo_err"] <= np.maximum(target, tol["atol"])),
    )


@figure(NAME, config=(SECTION,), resources={"runtime": 5}, chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``family, model, parameter, parameter_value, theta_deg, albedo, albedo_err, reference_albedo,
    reference_albedo_err, difference, difference_err, ratio, ratio_err, judged, dishonest, failed,
    meets_tolerance``."""
    return accuracy_map(cfg[SECTION], cfg["tolerance"])


def summary(df: pd.DataFrame) -> pd.DataFrame:
    """Counts per family: cells, dishonest, failed, missing the tolerance, largest ratio."""
    g = df.groupby("family", sort=False)
    return pd.DataFrame({"cells": g.size(), "dishonest": g["dishonest"].sum(), "failed": g["failed"].sum(),
                         "over_tolerance": (~df["meets_tolerance"]).groupby(df["family"], sort=False).sum(),
                         "max_ratio": g["ratio"].max()})


def plot(df: pd.DataFrame, path) -> None:
    """One heat map per family: log10(|engine − reference| / reported error) over (θ, parameter);
    dishonest cells ringed red, failed cells black, cells over the tolerance marked orange, cells
    where the reference is not the more accurate crossed grey."""
    families = list(dict.fromkeys(df["family"]))
    cols = 3
    rows = -(-len(families) // cols)
    fig, axes = plotting.plt.subplots(rows, cols, figsize=(5.0 * cols, 2.9 * rows + 0.8), squeeze=False)
    fig.subplots_adjust(hspace=1.0, wspace=0.25, right=0.86)
    theta = np.unique(df["theta_deg"])
    image = None
    for ax, family in zip(axes.ravel(), families):
        sub = df[df["family"] == family]
        values = np.unique(sub["parameter_value"])
        table = sub.pivot_table(index="parameter_value", columns="theta_deg", values="ratio", aggfunc="first")
        table = table.reindex(index=values, columns=theta)
        data = np.log10(np.clip(table.to_numpy(float), 1e-6, 1e6))
        image = ax.imshow(data, aspect="auto", origin="lower", cmap="RdYlGn_r", vmin=-3, vmax=1,
                          extent=(-0.5, theta.size - 0.5, -0.5, values.size - 0.5), interpolation="nearest")
        pos = {t: i for i, t in enumerate(theta)}
        rowpos = {v: i for i, v in enumerate(values)}
        for r in sub.itertuples():
            x, y = pos[r.theta_deg], rowpos[r.parameter_value]
            if r.failed:
                ax.plot(x, y, "ks", ms=6)
            elif r.dishonest:
                ax.plot(x, y, "o", mfc="none", mec="red", ms=7, mew=1.5)
            elif not r.judged:
                ax.plot(x, y, "x", color="0.4", ms=4)
            if not r.failed and not r.meets_tolerance:
                ax.plot(x, y, "^", mfc="none", mec="darkorange", ms=8, mew=1.2)
        ticks = np.linspace(0, theta.size - 1, min(theta.size, 8)).round().astype(int)
        ax.set_xticks(ticks)
        ax.set_xticklabels([f"{theta[i]:.6g}" for i in ticks], fontsize=6, rotation=45)
        ax.set_yticks(range(values.size))
        ax.set_yticklabels([f"{v:g}" for v in values], fontsize=6)
        bad, failed = int(sub["dishonest"].sum()), int(sub["failed"].sum())
        ax.set_title(f"{family}: {bad} dishonest, {failed} failed of {len(sub)}", fontsize=8,
                     color="red" if bad or failed else "black")
        ax.set_xlabel("θ_L [deg] (cells, not to scale)", fontsize=7)
        ax.set_ylabel(sub["parameter"].iloc[0], fontsize=7)
        ax.grid(False)
    for ax in axes.ravel()[len(families):]:
        ax.set_visible(False)
    if image is not None:
        bar = fig.colorbar(image, cax=fig.add_axes([0.89, 0.3, 0.015, 0.4]))
        bar.set_label("log10 |engine − reference| / engine's reported error")
    fig.suptitle("Accuracy map: engine against the projected-disk reference (red ring: outside the combined errors;\n"
                 "black square: NaN; orange triangle: engine error above the tolerance; grey x: reference not sharper)",
                 fontsize=9)
    plotting.savefig(fig, path)
