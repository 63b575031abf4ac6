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
#: Display names of the samplers (legend entries), in Fig. 4.9's wording: the 0/1 sampling of
#: section 4.2.4 that the thesis calls "Russian roulette" (not path termination) is accept/reject.
SAMPLER_NAMES = {"russian_roulette": "accept/reject"}
#: Panel titles where the name alone would not say which of the thesis's samplers it is.
SAMPLER_TITLES = {"russian_roulette": "accept/reject ('Russian roulette', sec. 4.2.4)"}


def sample_points(theta_deg: float, R: float, strategies, n_points: int, seed) -> pd.DataFrame:
    """Points V_P of ``n_points`` samples of ``patch_basic`` (radius ``R``) for light at ``theta_deg``,
    per strategy; an accept/reject (the thesis's "Russian roulette") miss keeps its point (drawn in
    C_min) with ``accepted`` False."""
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
    """One panel per strategy (so the samplers do not overprint): its points under the circles, the
    common chord, the centre V'_P of C(V'_P, R) and the base circle's centre O; one legend beside
    the panels."""
    import matplotlib.pyplot as plt

    strategies = list(dict.fromkeys(df["strategy"]))
    fig, axes = plt.subplots(1, len(strategies), figsize=(3.6 * len(strategies) + 1.6, 3.9), squeeze=False,
                             sharey=True)
    first = df.iloc[0]
    cx, cy, R = float(first["centre_x"]), float(first["centre_y"]), float(first["R"])
    reach = max(1.15, np.hypot(cx, cy) + R + 0.05)
    for ax, strategy in zip(axes.ravel(), strategies):
        _panel(ax, df[df["strategy"] == strategy], strategy, cx, cy, R, float(first["lens_alpha_rad"]), reach)
    axes[0, 0].set_ylabel("y on the base plane")
    handles = {label: h for ax in axes.ravel() for h, label in zip(*ax.get_legend_handles_labels())}
    for line in (line for ax in axes.ravel() for line in ax.get_lines()):
        line.set_label("_" + line.get_label())  # one legend for all panels: no panel gets its own
    axes[0, -1].legend(list(handles.values()), list(handles), loc="upper left", bbox_to_anchor=(1.02, 1.0),
                       fontsize=7, markerscale=1.5)
    fig.suptitle(title, fontsize=10)
    plotting.savefig(fig, path)


def _panel(ax, group, strategy, cx, cy, R, alpha, reach) -> None:
    t = np.linspace(0.0, 2.0 * np.pi, 721)
    markers = {"exact": ("C0", "."), "russian_roulette": ("C2", "+")}
    color, marker = markers.get(strategy, ("C1", "."))
    acc = group["accepted"].to_numpy(bool)
    name = SAMPLER_NAMES.get(strategy, strategy.replace("_", " "))
    ax.plot(group["x"][acc], group["y"][acc], marker, color=color, markersize=2, linestyle="none", alpha=0.6,
            zorder=1, label=f"{name}: accepted")
    if (~acc).any():
        ax.plot(group["x"][~acc], group["y"][~acc], "x", color="C1", markersize=2, linestyle="none", alpha=0.6,
                zorder=1, label=f"{name}: rejected")
    # The circles, the chord and the centres are drawn above the points, so no point hides them.
    ax.plot(np.cos(t), np.sin(t), color="k", zorder=3, label="unit circle C(O, 1)")
    ax.plot(cx + R * np.cos(t), cy + R * np.sin(t), color="C3", zorder=3, label=f"C(V'_P, R = {R:g})")
    if 0.0 < alpha < np.pi:                  # the common chord, from the lens geometry (eq. 4.10)
        phi0 = np.arctan2(cy, cx)
        ends = np.array([[np.cos(phi0 - alpha), np.cos(phi0 + alpha)], [np.sin(phi0 - alpha), np.sin(phi0 + alpha)]])
        ax.plot(ends[0], ends[1], color="k", linestyle=(0, (2, 1.5)), lw=1.6, zorder=4, label="common chord")
    ax.plot([0.0], [0.0], "o", color="k", ms=4, zorder=5, label="O (centre of the base circle)")
    ax.plot([cx], [cy], "P", color="C3", mec="w", mew=0.5, ms=7, zorder=5, label="V'_P (centre of C(V'_P, R))")
    ax.text(0.05, -0.05, "O", ha="left", va="top", zorder=5)
    ax.set_aspect("equal")
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_xlabel("x on the base plane")
    ax.set_title(SAMPLER_TITLES.get(strategy, f"{name} sampler"), fontsize=9)
