"""Shared parts of Figures 2.7, 3.1, 3.5 and 3.6: the new model (eq. 3.10) against Phong (eq. 3.5).

Radiance: a point light of intensity 4π at distance 1 gives the irradiance cos θ_L, so
L_out(V) = f(L, V) cos θ_L (eq. 2.3).  BRDF and radiance values are closed forms evaluated in
floating point; their error is a rounding bound (:data:`ROUNDING_RTOL`).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.numerics.albedo import albedo
from brdfs.artifacts._pumping_figures import ROUNDING_RTOL
from brdfs.physics.geometry import cos_incidence, direction, light_direction, mirror
from brdfs.physics.models import model


def albedo_curves(ns, theta_step_deg: float, rtol: float) -> pd.DataFrame:
    """Albedo of the new model, c = (n+2)/2π, for every n on a θ grid (engine, eq. 1.18)."""
    theta = np.arange(0.0, 90.0 + 1e-9, theta_step_deg)
    rows = []
    for n in ns:
        brdf = model("phong_cosmin", n=n)
        est = albedo(brdf, theta, rtol=rtol)
        rows.append(pd.DataFrame({"model": "phong_cosmin", "n": float(n), "C": brdf.C, "theta_deg": theta,
                                  "albedo": est.value, "albedo_err": est.error}))
    return pd.concat(rows, ignore_index=True)


def mirror_radiance(name: str, n: float, theta_step_deg: float) -> pd.DataFrame:
    """L_out(R) = f(L, R) cos θ_L against θ_L ∈ [0°, 90°) (at 90° it is 0 · f)."""
    theta = np.arange(0.0, 90.0 - 1e-9, theta_step_deg)
    L = light_direction(theta)
    brdf = model(name, n=n)
    radiance = brdf(L, mirror(L)) * cos_incidence(theta)
    return pd.DataFrame({"model": name, "n": float(n), "C": brdf.C, "view": "mirror", "theta_deg": theta,
                         "radiance": radiance, "radiance_err": ROUNDING_RTOL * radiance})


def plane_slices(names, n: float, theta_l_deg, step_deg: float, quantity: str) -> pd.DataFrame:
    """f(L, V)/f(N, N) (``'brdf_normalised'``) or f(L, V) cos θ_L / f(N, N) (``'radiance_normalised'``)
    for V in the plane of incidence; θ_V < 0 on the side of L, > 0 on the side of R."""
    theta_v = np.arange(-90.0 + step_deg, 90.0 - 1e-9, step_deg)
    V = direction(np.abs(theta_v), np.where(theta_v < 0, 0.0, 180.0))
    N = light_direction(np.zeros(1))
    rows = []
    for name in names:
        brdf = model(name, n=n)
        for theta in theta_l_deg:
            L = np.broadcast_to(light_direction(np.array(theta)), V.shape)
            value = brdf(L, V) / brdf(N, N)[0]
            if quantity == "radiance_normalised":
                value = value * cos_incidence(theta)
            rows.append(pd.DataFrame({"model": name, "n": float(n), "C": brdf.C, "theta_deg": float(theta),
                                      "theta_v_deg": theta_v, quantity: value,
                                      f"{quantity}_err": ROUNDING_RTOL * value}))
    return pd.concat(rows, ignore_index=True)


def plot_albedo(ax, df: pd.DataFrame) -> None:
    """One albedo curve per n."""
    for n, g in df.groupby("n"):
        ax.plot(g["theta_deg"], g["albedo"], label=f"n = {n:g}")
    ax.set(xlabel="incidence angle θ_L [deg]", ylabel="albedo a(θ_L)")


def plot_slices(df: pd.DataFrame, path, quantity: str, ylabel: str, title: str) -> None:
    """One panel per model, one curve per incidence angle."""
    names = list(dict.fromkeys(df["model"]))
    fig, axes = plotting.plt.subplots(1, len(names), figsize=(5 * len(names), 4.2), sharey=True)
    for ax, name in zip(np.atleast_1d(axes), names):
        for theta, g in df[df["model"] == name].groupby("theta_deg"):
            ax.plot(g["theta_v_deg"], g[quantity], label=f"θ_L = {theta:g}°")
        ax.set(xlabel="viewing angle θ_V [deg] (< 0: side of L)", ylabel=ylabel, title=name)
    fig.suptitle(title, fontsize=10)
    plotting.savefig(fig, path)
