"""Albedo curves a(θ_L) of several models (Figures 2.1 and 3.4): tidy data and their plot."""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.numerics.albedo import albedo_table
from brdfs.physics.geometry import cos_incidence
from brdfs.physics.models import model

def param_names(models) -> list[str]:
    """The wide parameter columns of a curve table: every parameter of ``models``, in order of
    first appearance (contract: one column per parameter)."""
    return list(dict.fromkeys(c for m in models for c in m.param_columns()))


def build(spec: dict):
    """The model of a config entry ``{model: name, <parameter>: value, ...}`` (``theta_deg`` ignored)."""
    params = {k: v for k, v in spec.items() if k not in ("model", "theta_deg")}
    return model(spec["model"], **params)


def label(brdf) -> str:
    """A legend label naming the model and its parameters, e.g. ``cook_torrance (m=0.1, G=none)``."""
    shown = ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                      for k, v in brdf.params.items() if k != "C" and v is not None)
    return f"{brdf.name} ({shown})"


def param_columns(brdf, names=None) -> dict:
    """The parameter columns ``names`` (default: the model's own) of ``brdf``, empty where a
    parameter does not apply."""
    names = brdf.param_columns() if names is None else names
    return {c: "" if brdf.params.get(c) is None else brdf.params[c] for c in names}


def curves(specs, theta_deg, tol, known: pd.DataFrame | None = None) -> pd.DataFrame:
    """a(θ) with its error for every model of ``specs`` on ``theta_deg``, one row per value.

    A curve already in ``known`` (another figure's table: the same model and label, at every one
    of these angles, to the bit) is taken from there instead of being integrated again.
    """
    models = [build(s) for s in specs]
    theta_deg = np.asarray(theta_deg, float)
    reused = {}
    for m_label, rows in (known.groupby("label", sort=False) if known is not None else []):
        by_angle = rows.set_index("theta_deg")
        if by_angle.index.is_unique and np.isin(theta_deg, by_angle.index).all():
            reused[m_label] = by_angle.loc[theta_deg]
    todo = [m for m in models if label(m) not in reused]
    est = albedo_table(todo, theta_deg, rtol=tol["rtol"], atol=tol["atol"]) if todo else None
    names = param_names(models)
    frames = []
    for m in models:
        if label(m) in reused:
            value, error = reused[label(m)]["albedo"].to_numpy(), reused[label(m)]["albedo_err"].to_numpy()
        else:
            k = todo.index(m)
            value, error = est.value[k], est.error[k]
        frames.append(pd.DataFrame({"model": m.name, **param_columns(m, names), "label": label(m),
                                    "theta_deg": theta_deg, "cos_theta": cos_incidence(theta_deg),
                                    "albedo": value, "albedo_err": error}))
    return pd.concat(frames, ignore_index=True)


def plot_curves(df: pd.DataFrame, path, title: str, ymax: float = 3.0) -> None:
    """Two panels: a(θ) over 0°–90° (clipped at ``ymax``, as the thesis's axes), and against 90° − θ on log axes.

    The legend sits below the panels, so that it covers no curve.
    """
    fig, (ax, ax_log) = plotting.plt.subplots(1, 2, figsize=(11, 4.2))
    handles, labels = [], []
    for name, g in df.groupby("label", sort=False):
        line, = ax.plot(g["theta_deg"], g["albedo"])
        ax_log.loglog(90.0 - g["theta_deg"], g["albedo"], color=line.get_color())
        ax.fill_between(g["theta_deg"], g["albedo"] - g["albedo_err"], g["albedo"] + g["albedo_err"],
                        color=line.get_color(), alpha=0.3, lw=0)
        handles.append(line)
        labels.append(name)
    ax.set(xlabel="incidence angle θ_L [deg]", ylabel="albedo a(θ_L)", xlim=(0, 90), ylim=(0, ymax))
    ax.set_title("0°–90° (clipped at a = %g)" % ymax, fontsize=8)
    ax.axhline(1.0, color="k", lw=0.6, ls=":")
    ax_log.axhline(1.0, color="k", lw=0.6, ls=":")
    ax_log.invert_xaxis()
    ax_log.set(xlabel="90° − θ_L [deg] (log)", ylabel="albedo a(θ_L) (log)")
    ax_log.set_title("toward grazing incidence", fontsize=8)
    fig.suptitle(title, fontsize=10, y=1.0)
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=7)
    fig.tight_layout()
    plotting.savefig(fig, path)


def figure_title(number: str, df: pd.DataFrame) -> str:
    """The short title: the thesis number, the quantity and F = 1 (models, grid and choices: the caption)."""
    return f"Figure {number}: albedo of {df['label'].nunique()} models, F = 1"
