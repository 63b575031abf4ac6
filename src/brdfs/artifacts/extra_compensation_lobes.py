"""Lobes at 60° incidence in the plane of incidence (in the style of Figure 3.3), F = 1: where Kulla–Conty
compensation and the thesis's pumping put the energy they restore, against the random walk.

Per family (Phong-matched α = 0.156, Blinn-matched α = 0.302, :mod:`brdfs.artifacts._microfacet_energy`):
GGX and Beckmann single scattering and with Kulla–Conty (its f_ms part also alone, variant ``ms_term``),
the thesis's model unpumped and pumped once and twice (g1, eq. 2.20), the new model, and the random walk
binned in θ_V within a wedge |φ − φ_plane| < ``lobe_walk_phi_halfwidth_deg`` (all bounces: ``walk``;
two or more: ``walk_multiple``, the part Kulla–Conty's f_ms stands for).
Plotted quantity: f(L, V) cos θ_V ("intensity", energy per unit solid angle of V); φ = 180° is the
mirror side.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _microfacet_energy as mf
from brdfs.numerics.random_walk import random_walk
from brdfs.physics.geometry import direction, light_direction
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

DEPS = (*mf.PUMPING_TABLES.values(), mf.ENERGY_TABLE)
#: Marker colours of the walks per distribution.
WALK_COLOURS = {"ggx": "k", "beckmann": "0.5"}
#: Relative rounding of a closed-form BRDF value (powers ≤ 100 of rounded dot products, tables' polynomials).
EVAL_RTOL = 256 * np.finfo(float).eps
COLUMNS = ["family", "model", "variant", "pumping", "level", "n", "alpha", "theta_deg", "theta_v_deg", "phi_deg",
           "intensity", "intensity_err"]


def _curve(family, name, variant, brdf, theta, theta_v, ms_error=None, **columns):
    """f cos θ_V at φ = 0° and 180°; ``ms_error``: the compensated model whose f_ms error bound is added."""
    L = light_direction(theta)
    frames = []
    for phi in (0.0, 180.0):
        V = direction(theta_v, phi)
        value = brdf(L, V) * V[..., 2]
        err = EVAL_RTOL * np.abs(value)
        if ms_error is not None:
            err = err + ms_error.multiple_scattering_error(L[2], V[..., 2]) * V[..., 2]
        frames.append(pd.DataFrame({"family": family, "model": name, "variant": variant, "theta_deg": theta,
                                    "theta_v_deg": theta_v, "phi_deg": phi, "intensity": value,
                                    "intensity_err": err, **columns}))
    return frames


class _MultipleScatteringOnly:
    """f_ms of a compensated model alone (a callable of (L, V))."""

    def __init__(self, brdf):
        self.brdf = brdf

    def __call__(self, L, V):
        nl, nv = np.broadcast_arrays(np.asarray(L, float)[..., 2], np.asarray(V, float)[..., 2])
        return np.where((nl >= 0) & (nv > 0), self.brdf.multiple_scattering(nl, nv), 0.0)


@figure("extra_compensation_lobes", deps=DEPS, config=("microfacet",), chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Rows ``family, model, variant, pumping, level, n, alpha, theta_deg, theta_v_deg, phi_deg, intensity, intensity_err``."""
    c = cfg["microfacet"]
    mf.seed_energy_tables(deps[mf.ENERGY_TABLE])
    theta = float(c["lobe_theta_deg"])
    step = float(c["lobe_step_deg"])
    theta_v = np.arange(0.0, 90.0, step)
    frames = []
    for f_index, family in enumerate(("phong", "blinn")):
        levels, n = mf.pumped_family(family, deps[mf.PUMPING_TABLES[family]], "g1", c["pumping_levels"])
        alpha = float(mf.alpha_of_n(family, n))
        for level, brdf, _ in levels:
            frames += _curve(family, family, "pumped" if level else "original", brdf, theta, theta_v,
                             pumping="g1" if level else "none", level=level, n=n, alpha=alpha)
        new = mf.new_model(family, n)
        frames += _curve(family, new.name, "new_model", new, theta, theta_v, n=n, alpha=alpha)
        for k, name in enumerate(("ggx", "beckmann")):
            single = mf.microfacet(name, alpha)
            compensated = mf.microfacet(name, alpha, "kulla_conty")
            frames += _curve(family, name, "single_scattering", single, theta, theta_v, alpha=alpha)
            frames += _curve(family, name, "kulla_conty", compensated, theta, theta_v, ms_error=compensated,
                             alpha=alpha)
            frames += _curve(family, name, "ms_term", _MultipleScatteringOnly(compensated), theta, theta_v,
                             ms_error=compensated, alpha=alpha)
            paths = int(c["lobe_walk_paths"]) * (10 if c["walk_full"] else 1)
            rng = np.random.default_rng([int(cfg["seed"]), 3, f_index, k])
            walk = random_walk(mf.distribution(name, alpha), theta, paths, rng, max_order=int(c["walk_max_order"]))
            edges = np.arange(0.0, 90.0 + 1e-9, float(c["lobe_walk_bin_deg"]))
            for variant, orders in (("walk", None), ("walk_multiple", tuple(range(2, int(c["walk_max_order"]) + 1)))):
                centre, phi, value, err = walk.plane_lobe(edges, float(c["lobe_walk_phi_halfwidth_deg"]), orders)
                frames.append(pd.DataFrame({"family": family, "model": name, "variant": variant, "alpha": alpha,
                                            "theta_deg": theta, "theta_v_deg": centre, "phi_deg": phi,
                                            "intensity": value, "intensity_err": err}))
    df = pd.concat(frames, ignore_index=True)
    for col in ("pumping",):
        df[col] = df[col].fillna("")
    return df[COLUMNS]


def plot(df: pd.DataFrame, path) -> None:
    """Two polar half-planes (Phong-matched, Blinn-matched): normal up, mirror side right."""
    fig = plotting.plt.figure(figsize=(13, 6))
    for i, family in enumerate(("phong", "blinn")):
        ax = fig.add_subplot(1, 2, i + 1, projection="polar")
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_thetamin(-90)
        ax.set_thetamax(90)
        fam = df[df["family"] == family]
        for keys, g in fam.groupby(["model", "variant", "level"], sort=False, dropna=False):
            name, variant, level = keys
            signed = np.where(g["phi_deg"] == 180.0, 1.0, -1.0) * g["theta_v_deg"]
            order = np.argsort(signed.to_numpy())
            x, y = np.radians(signed.to_numpy()[order]), g["intensity"].to_numpy()[order]
            label = f"{name} {variant}" + (f" ×{int(level)}" if variant == "pumped" else "")
            if variant.startswith("walk"):
                ax.plot(x, y, "o" if variant == "walk" else "^", ms=3, color=WALK_COLOURS.get(name, "0.5"),
                        mfc="none" if variant == "walk_multiple" else None, label=label)
            else:
                ax.plot(x, y, {"kulla_conty": "--", "ms_term": ":", "new_model": "-."}.get(variant, "-"), lw=1.0,
                        label=label)
        theta = fam["theta_deg"].iloc[0]
        ax.set_title(f"{family}-matched: n = {fam['n'].dropna().iloc[0]:g}, α = {fam['alpha'].iloc[0]:.3f}; "
                     f"θ_L = {theta:g}°, f·cos θ_V in the plane of incidence", fontsize=8)
        ax.legend(fontsize=5.5, loc="lower left", bbox_to_anchor=(-0.15, -0.3), ncol=3)
    fig.suptitle("Where the restored energy goes: Kulla–Conty (diffuse-like f_ms) vs pumping (scaled lobe) "
                 "vs the Smith random walk", fontsize=10)
    plotting.savefig(fig, path)
