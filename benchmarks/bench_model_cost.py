"""Benchmark: time per million BRDF evaluations of every model in MODELS, vectorised, in one run.

Each model is called on the same 10⁶ random direction pairs (upper hemisphere, seeded), in
interleaved rounds (model A, B, C, …, A, B, C, …) so that a load change on the shared machine
hits all models alike; the best round counts.  Beside each time: its ratio to Ward and to
Phong, and the thesis's claim where it makes one:

* §4.8 "the computational time of the new model is practically equal to the time of the
  Phong–Blinn model and half of the time of the Ward model" (measured with Heckbert's BRDF viewer);
* §2.2.3 (He–Torrance) "Its running time is 75 times that of the Ward model".

Writes results/benchmarks/model_cost.csv and .png.  Run with ``make benchmark`` (wall times never
enter an artifact).
"""
import time

import numpy as np
import pandas as pd

from brdfs.physics.geometry import direction
from brdfs.physics.models import MODELS, model
from brdfs.pipeline import plotting
from brdfs.pipeline.io import REPO_ROOT

EVALUATIONS = 1_000_000
ROUNDS = 3
SEED = 20010101

#: One parameter set per model (the thesis's usual values); the patch mixture gets a uniform weight.
PARAMETERS = {
    "phong": {"n": 20}, "phong_original": {"n": 20}, "phong_cosmin": {"n": 20}, "p_model": {"n": 20, "p": 0.5},
    "blinn": {"n": 20}, "blinn_original": {"n": 20}, "blinn_cosmin": {"n": 20},
    "ward": {"m": 0.1}, "ward_cosmin": {"m": 0.1}, "cook_torrance": {"m": 0.1},
    "he_torrance": {"sigma0_um": 0.1, "tau_um": 1.7, "term": "dd"},
    "patch_basic": {"R": 0.5}, "patch_exponential": {"s": 8.0}, "patch_elliptical": {"b": 0.5, "ratio": 0.5},
    "generalized_lambertian": {"d": 0.5},
    "ggx": {"alpha": 0.1}, "beckmann": {"alpha": 0.1},     # today's Smith microfacet models (rtr4 ch. 9)
    "patch_mixture": {"weight": lambda R: np.ones_like(R) / 2.0},
}
#: The thesis's claims: (model, reference model, claimed time ratio, where).
CLAIMS = [("phong_cosmin", "phong", 1.0, "§4.8: new model ≈ Phong–Blinn"),
          ("phong_cosmin", "ward", 0.5, "§4.8: new model ≈ half of Ward"),
          ("blinn_cosmin", "blinn", 1.0, "§4.8: new model ≈ Phong–Blinn"),
          ("he_torrance", "ward", 75.0, "§2.2.3: He–Torrance = 75 × Ward")]


def _directions(rng, count):
    theta = np.degrees(np.arccos(rng.uniform(0.0, 1.0, count)))
    return direction(theta, rng.uniform(0.0, 360.0, count))


def main():
    rng = np.random.default_rng(SEED)
    L, V = _directions(rng, EVALUATIONS), _directions(rng, EVALUATIONS)
    models = {name: model(name, **PARAMETERS[name]) for name in MODELS if name in PARAMETERS}
    skipped = sorted(set(MODELS) - set(models))
    # the patch mixture integrates per evaluation: time it on 1 % of the pairs and scale
    sizes = {name: EVALUATIONS // 100 if name == "patch_mixture" else EVALUATIONS for name in models}
    best = {name: np.inf for name in models}
    for _ in range(ROUNDS):
        for name, brdf in models.items():
            k = sizes[name]
            start = time.perf_counter()
            brdf(L[:k], V[:k])
            best[name] = min(best[name], (time.perf_counter() - start) * EVALUATIONS / k)
    df = pd.DataFrame({"model": list(best), "params": [str({k: v for k, v in PARAMETERS[n].items() if k != "weight"})
                                                       for n in best],
                       "evaluations_timed": [sizes[n] for n in best],
                       "s_per_million": list(best.values())})
    df["ratio_to_ward"] = df["s_per_million"] / best["ward"]
    df["ratio_to_phong"] = df["s_per_million"] / best["phong"]
    claims = pd.DataFrame([{"model": m, "reference": r, "claimed_ratio": c, "measured_ratio": best[m] / best[r],
                            "claim": where} for m, r, c, where in CLAIMS])
    out = REPO_ROOT / "results" / "benchmarks" / "model_cost.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(out, index=False, float_format="%.4g")
    claims.to_csv(out.with_name("model_cost_claims.csv"), index=False, float_format="%.4g")
    print(df.to_string(index=False))
    print(claims.to_string(index=False))
    if skipped:
        print("not timed (no parameter set):", skipped)
    _plot(df.sort_values("s_per_million"), claims, out.with_suffix(".png"))


def _plot(df, claims, path):
    fig, ax = plotting.new_axes("time per 10⁶ evaluations [s] (vectorised numpy, best of 3)", "",
                                "BRDF evaluation cost per model (one run, same direction pairs)")
    ax.barh(df["model"], df["s_per_million"], color="tab:blue")
    ax.set_xscale("log")
    ax.xaxis.set_minor_formatter(plotting.plt.NullFormatter())
    for y, (s, r) in enumerate(zip(df["s_per_million"], df["ratio_to_ward"])):
        ax.text(s, y, f"  {r:.2g}× Ward", va="center", fontsize=7)
    text = "\n".join(f"{c.claim}: measured {c.measured_ratio:.2g}" for c in claims.itertuples())
    ax.text(0.98, 0.02, text, transform=ax.transAxes, ha="right", va="bottom", fontsize=7,
            bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"})
    plotting.savefig(fig, path)


if __name__ == "__main__":
    main()
