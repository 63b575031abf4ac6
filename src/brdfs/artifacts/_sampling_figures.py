"""Helpers of Figures 4.7 and 4.8: sample points of the basic BRDF's samplers on the base plane,
with the circles and the lens from :func:`brdfs.physics.patch_geometry.circle_intersection`."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.physics.geometry import light_direction
from brdfs.physics.models import model
from brdfs.physics.sampling import russian_roulette_point
from brdfs.pipeline import plotting

SECTION = "sampling"


def sample_points(theta_deg: float, R: float, strategies, n_points: int, seed) -> pd.DataFrame:
    """Points V_P of ``n_points`` samples of ``patch_basic`` (radius ``R``) for light at ``theta_deg``,
    per strategy; a Russian-roulette miss keeps its point (drawn in C_min) with ``accepted`` False."""
    brdf = model("patch_basic", R=R)
    L = light_direction(theta_deg)
    d = float(np.hypot(L[0], L[1]))
    lens = patch.circle_intersection(d, R)
    frames = []
    for k, strategy in enumerate(strategies):
        u = np.random.default_rng([*seed, k]).random((n_points, 2))
        V, weight, _ = brdf.sample(L, u, strategy)
        accepted = V[:, 2] > 0
        if strategy == "russian_roulette":     # where the misses fell: the same point, drawn in C_min
            x, y, _, _ = russian_roulette_point(-L[0], -L[1], R, u[:, 0], u[:, 1])
        else:
            x, y = V[:, 0], V[:, 1]
        frames.append(pd.DataFrame({
            "model": "patch_basic", "R": R, "theta_deg": theta_deg, "strategy": strategy,
            "x": x, "y": y, "accepted": accepted, "weight": weight,
            "centre_x": -L[0], "centre_y": -L[1], "lens_alpha_rad": float(lens.alpha),
            "lens_area": float(lens.area), "albedo": float(patch.basic_albedo(theta_deg, R).value)}))
    return pd.concat(frames, ignore_index=True)


def plot_points(df: pd.DataFrame, path, title: str) -> None:
    fig, ax = plotting.new_axes("x on the base plane", "y on the base plane", title)
    t = np.linspace(0.0, 2.0 * np.pi, 721)
    ax.plot(np.cos(t), np.sin(t), color="k", label="unit circle C(O, 1)")
    first = df.iloc[0]
    cx, cy, R = float(first["centre_x"]), float(first["centre_y"]), float(first["R"])
    ax.plot(cx + R * np.cos(t), cy + R * np.sin(t), color="C3", label=f"C(V'_P, R = {R:g})")
    alpha = float(first["lens_alpha_rad"])
    if 0.0 < alpha < np.pi:                  # the common chord, from the lens geometry (eq. 4.10)
        phi0 = np.arctan2(cy, cx)
        ends = np.array([[np.cos(phi0 - alpha), np.cos(phi0 + alpha)], [np.sin(phi0 - alpha), np.sin(phi0 + alpha)]])
        ax.plot(ends[0], ends[1], color="C3", linestyle=":", label="common chord")
    markers = {"exact": ("C0", "."), "russian_roulette": ("C2", "+")}
    for strategy, group in df.groupby("strategy", sort=False):
        color, marker = markers.get(strategy, ("C1", "."))
        acc = group["accepted"].to_numpy(bool)
        ax.plot(group["x"][acc], group["y"][acc], marker, color=color, markersize=3, linestyle="none",
                label=f"{strategy.replace('_', ' ')}: accepted")
        if (~acc).any():
            ax.plot(group["x"][~acc], group["y"][~acc], "x", color="C1", markersize=3, linestyle="none",
                    label=f"{strategy.replace('_', ' ')}: rejected")
    ax.set_aspect("equal")
    reach = max(1.15, np.hypot(cx, cy) + R + 0.05)
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7)
    plotting.savefig(fig, path)
