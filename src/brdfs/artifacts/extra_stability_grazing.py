"""Stability of the albedo engine toward 90°: every model at the thesis's range of n and m at
90° − 10^(−x), checked for NaN, negative values and errors that lie — the hard points against the
independent projected-disk integration (:func:`brdfs.numerics.integrate.disk.disk_albedo_many`)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _albedo_curves as albedo_curves
from brdfs.pipeline import plotting
from brdfs.numerics.albedo import albedo_table
from brdfs.pipeline.registry import figure
from brdfs.numerics.integrate.disk import disk_albedo_many
from brdfs.physics.models import MODELS, model

#: Models parameterised by a roughness m (the others by an exponent n).
ROUGH = ("ward", "ward_cosmin", "cook_torrance")


def sweep_models(stability: dict) -> list:
    """Every listed (and registered) model at every n or m of the sweep."""
    out = []
    for name in stability["models"]:
        if name not in MODELS:
            raise ValueError(f"grazing.stability.models: unknown model {name!r}; known: {sorted(MODELS)}")
        key, values = ("m", stability["m_values"]) if name in ROUGH else ("n", stability["n_values"])
        out += [model(name, **{key: v}) for v in values]
    return out


def sweep(stability: dict, tol: dict) -> pd.DataFrame:
    """The albedo of every sweep model at 90° − 10^(−x); flags for finiteness and sign."""
    theta = 90.0 - 10.0 ** -np.asarray(stability["exponents"], float)
    models = sweep_models(stability)
    est = albedo_table(models, theta, rtol=tol["rtol"], atol=tol["atol"])
    frames = [pd.DataFrame({"check": "sweep", "model": m.name, **albedo_curves.param_columns(m), "theta_deg": theta,
                            "albedo": est.value[i], "albedo_err": est.error[i]}) for i, m in enumerate(models)]
    df = pd.concat(frames, ignore_index=True)
    return df.assign(finite=np.isfinite(df["albedo"]) & np.isfinite(df["albedo_err"]), nonnegative=df["albedo"] >= 0)


def disk_points(stability: dict, tol: dict) -> pd.DataFrame:
    """The hard points: engine and disk integration side by side; ``consistent`` when they agree
    within the sum of their reported errors.  The disk integrals of all points in one vectorised run."""
    specs = stability["disk_points"]
    models = [albedo_curves.build(spec) for spec in specs]
    theta = np.array([spec["theta_deg"] for spec in specs], float)
    ref = disk_albedo_many(models, theta)
    records = []
    for i, (spec, m) in enumerate(zip(specs, models)):
        (a, a_err) = albedo_table([m], [spec["theta_deg"]], tol["rtol"], tol["atol"])[0, 0]
        d, d_err = float(ref.value[i]), float(ref.error[i])
        records.append({"check": "disk", "model": m.name, **albedo_curves.param_columns(m),
                        "theta_deg": spec["theta_deg"], "albedo": a, "albedo_err": a_err, "disk_albedo": d,
                        "disk_albedo_err": d_err, "difference": abs(a - d)})
    df = pd.DataFrame.from_records(records)
    return df.assign(consistent=df["difference"] <= df["albedo_err"] + df["disk_albedo_err"],
                     finite=np.isfinite(df["albedo"]), nonnegative=df["albedo"] >= 0)


@figure("extra_stability_grazing", config=("grazing",), chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Sweep rows and disk cross-check rows (``check`` = ``sweep`` or ``disk``)."""
    s = cfg["grazing"]["stability"]
    return pd.concat([sweep(s, cfg["tolerance"]), disk_points(s, cfg["tolerance"])], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Reported relative error against 90° − θ for every swept model, cross-checks marked."""
    fig, ax = plotting.new_axes("90° − θ_L [deg]", "reported error / albedo")
    fig.set_size_inches(8.5, 5.5)
    sweep_rows = df[df["check"] == "sweep"]
    for name, g in sweep_rows.groupby("model", sort=False):
        ax.loglog(90.0 - g["theta_deg"], g["albedo_err"] / g["albedo"].abs(), ".", label=name)
    disk = df[df["check"] == "disk"]
    ax.loglog(90.0 - disk["theta_deg"], disk["difference"] / disk["albedo"].abs(), "kx", ms=8,
              label="|engine − disk integration| / albedo at the hard points")
    ax.invert_xaxis()
    bad = int((~sweep_rows["finite"] | ~sweep_rows["nonnegative"]).sum())
    inconsistent = int((~disk["consistent"].astype(bool)).sum())
    ax.set_title(f"Engine toward 90°: {bad} bad of {len(sweep_rows)} values, "
                 f"{inconsistent} of {len(disk)} disk checks outside the errors", fontsize=9)
    ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    plotting.savefig(fig, path)
