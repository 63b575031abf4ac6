"""Beside Figure 4.9 (the render, ``fig_4_9_sampling_efficiency``): efficiency of three sampling strategies for the metallic spheres'
patch BRDFs (the basic BRDF and a mixture, the exponential patch model), against incidence angle.

The thesis renders metallic spheres with 50 samples per pixel under (top) cosine sampling only,
51 min; (middle) the Russian roulette of section 4.2.4, 46 min; (bottom) "normal" importance
sampling of section 4.2.4, 54 min.  Here, per incidence angle θ (the viewing direction; the BRDF is
reciprocal), we estimate with one sample at a time

* the albedo a(θ) (L_in = 1), and
* the reflected radiance under the CIE overcast sky, L_in(ω) = (1 + 2 cos θ_ω)/3 (an open choice),

and measure the variance σ² of one sample's estimate and its cost c, counted deterministically:
random numbers drawn + BRDF (or albedo) evaluations + radiance look-ups (a ray cast in a renderer;
a Russian-roulette miss casts none).  Efficiency = 1/(σ² c).  The strategies:

* ``cosine``: the model's cosine strategy, V from the cosine distribution (2 numbers), weight π f
  (1 BRDF evaluation), 1 look-up.
* ``russian_roulette``: the model's strategy of that name (eqs. 4.18/4.19; section 4.4 with
  R = F⁻¹(r) for the mixture, 1 more number): a uniform point in C_min, weight W (1 here) if it lies
  in the other circle, else 0 and no look-up.
* ``normal``: R of the basic BRDF from the model (its own R, or F⁻¹(r) of the mixture), then the
  thesis's rejection loop ("repeat until found", 2 numbers per try) in C_min, then weight a_R(θ)
  (1 albedo evaluation, the lens area of eq. 4.9) and 1 look-up.

The exact albedo of the basic BRDF under ``normal`` has zero variance (its weight is a_R itself):
its efficiency is infinite and not drawn.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts._sampling_figures import SAMPLER_NAMES
from brdfs.physics import patch_geometry as patch
from brdfs.physics.geometry import light_direction
from brdfs.physics.models import model
from brdfs.physics.sampling import disk_to_direction, lens_point_by_rejection
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

NAME = "extra_sampling_efficiency"
SECTION = "sampling"
#: The metallic spheres' BRDFs (open choices): the basic BRDF of Figure 4.3 and the exponential
#: patch model of the "golden tank" of Figure 4.16.
MODELS = (("patch_basic", {"R": 0.2}), ("patch_exponential", {"s": 10.0}))
STRATEGIES = ("cosine", "russian_roulette", "normal")
QUANTITIES = ("albedo", "radiance")
#: Relative spread of weights that are equal up to rounding (a_R from the closed form of eq. 4.9).
ROUNDING = 1e-12


def overcast_sky(V):
    """CIE overcast sky, L(ω) = (1 + 2 cos θ_ω)/3 (Moon & Spencer 1942); 0 below the horizon."""
    return np.where(V[..., 2] > 0, (1.0 + 2.0 * V[..., 2]) / 3.0, 0.0)


def draw(brdf, strategy, theta_deg, n, rng):
    """(albedo weights, radiance weights, cost counters) of ``n`` one-sample estimates.

    ``cosine`` and ``russian_roulette`` are the model's own strategies (``brdf.sample``); ``normal``
    draws R of the basic BRDF from the model (``brdf.basic_radius``), a point of the lens by the
    thesis's rejection loop (:func:`~brdfs.physics.sampling.lens_point_by_rejection`) and weighs it
    a_R(θ) (eq. 4.8)."""
    L = light_direction(theta_deg)
    if strategy in ("cosine", "russian_roulette"):
        k = brdf.sample_dimension(strategy)
        V, w, _ = brdf.sample(L, rng.random((n, k)), strategy)
        if strategy == "cosine":
            counts = {"random_numbers": k * n, "brdf_evaluations": n, "radiance_lookups": n}
        else:                                             # weight W without evaluating f; a miss casts no ray
            counts = {"random_numbers": k * n, "brdf_evaluations": 0, "radiance_lookups": int((w > 0).sum())}
        return w, w * overcast_sky(V), counts
    R = brdf.basic_radius(rng.random((n, brdf.basic_radius_dimension)))
    x, y, drawn = lens_point_by_rejection(-L[0], -L[1], R, rng)
    V = disk_to_direction(x, y)
    w = patch.basic_albedo(theta_deg, R).value
    return w, w * overcast_sky(V), {"random_numbers": brdf.basic_radius_dimension * n + drawn,
                                    "brdf_evaluations": n, "radiance_lookups": n}


@figure(NAME, config=(SECTION,), resources={"runtime": 3}, chapter=4)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``model, parameters, quantity, strategy, theta_deg, n_samples, estimate, estimate_err, variance,
    random_numbers_per_sample, brdf_evaluations_per_sample, radiance_lookups_per_sample, cost_per_sample,
    efficiency, efficiency_vs_cosine``."""
    sec = cfg[SECTION]
    n = sec["efficiency_samples"]
    rows = []
    for i, (name, params) in enumerate(MODELS):
        brdf = model(name, **params)
        for j, theta in enumerate(sec["efficiency_thetas_deg"]):
            for k, strategy in enumerate(STRATEGIES):
                rng = np.random.default_rng([cfg["seed"], 49, i, j, k])
                w_albedo, w_radiance, counts = draw(brdf, strategy, float(theta), n, rng)
                cost = sum(counts.values()) / n
                for quantity, w in zip(QUANTITIES, (w_albedo, w_radiance)):
                    var = float(np.var(w, ddof=1))
                    if var <= (ROUNDING * np.mean(w)) ** 2:   # a constant weight up to rounding: exact
                        var = 0.0
                    rows.append({
                        "model": name, "parameters": " ".join(f"{a}={b:g}" for a, b in params.items()),
                        "quantity": quantity, "strategy": strategy, "theta_deg": float(theta), "n_samples": n,
                        "estimate": float(np.mean(w)), "estimate_err": float(np.sqrt(var / n)), "variance": var,
                        "random_numbers_per_sample": counts["random_numbers"] / n,
                        "brdf_evaluations_per_sample": counts["brdf_evaluations"] / n,
                        "radiance_lookups_per_sample": counts["radiance_lookups"] / n,
                        "cost_per_sample": cost,
                        "efficiency": 1.0 / (var * cost) if var > 0 else np.inf})
    df = pd.DataFrame(rows)
    key = ["model", "quantity", "theta_deg"]
    cosine = df[df["strategy"] == "cosine"].set_index(key)["efficiency"]
    df["efficiency_vs_cosine"] = df["efficiency"].to_numpy() / cosine.loc[list(map(tuple, df[key].to_numpy()))].to_numpy()
    return df


def plot(df: pd.DataFrame, path) -> None:
    fig, ax = plotting.new_axes("incidence angle θ [deg]", "efficiency / efficiency of cosine sampling",
                                "Beside Fig. 4.9: sampling efficiency 1/(variance x cost)")
    colors = {"russian_roulette": "C2", "normal": "C0", "cosine": "k"}
    styles = {"albedo": "-", "radiance": "--"}
    markers = {"patch_basic": "o", "patch_exponential": "s"}
    for (name, quantity, strategy), g in df.groupby(["model", "quantity", "strategy"], sort=False):
        if strategy == "cosine":
            continue
        finite = np.isfinite(g["efficiency_vs_cosine"])
        if finite.any():
            ax.plot(g["theta_deg"][finite], g["efficiency_vs_cosine"][finite], styles[quantity],
                    marker=markers[name], color=colors[strategy], markersize=3,
                    label=f"{SAMPLER_NAMES.get(strategy, strategy)}, {quantity}, {name.replace('patch_', '')}")
    ax.axhline(1.0, color="k", linewidth=0.8)
    ax.set_yscale("log")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7)
    plotting.savefig(fig, path)
