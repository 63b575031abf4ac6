"""Figure 4.9: metal spheres of the exponential patch model rendered at equal samples per pixel with
the thesis's three samplers (section 4.2.4): cosine, the 0/1 accept/reject sampling (the thesis's
"Russian roulette") and the exact "normal" sampling.

One panel per strategy (the plugins' ``strategy``: ``cosine``, ``accept_reject``, ``normal``), the
same scene, seeds and samples per pixel in each; the CSV holds per panel the samples, BRDF
evaluations and rays per pixel (the patch plugins' and the integrator's counters; the evaluations
include next-event estimation's, one per light sample that reaches a sphere) and the measured
noise (p95 of the relative standard error, fireflies). Wall times go to ``results/benchmarks/``
only (the rule's benchmark file). The efficiency chart of the strategies (variance × cost per
sample) is the extra ``extra_sampling_efficiency``.
"""
from __future__ import annotations

import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

NAME = "fig_4_9_sampling_efficiency"
CAMERA = {"eye": (0.0, -9.0, 2.2), "target": (0.0, 0.0, 0.7), "fov_deg": 25.0}    # all three spheres in frame


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    spec = section["sampling_spheres"]
    out = []
    for strategy in spec["strategies"]:
        objects = [("floor", rf.floor(), {"diffuse": section["diffuse_reflectance"]})]
        for x, entry in zip(rf.row(len(spec["spheres"]), 2.0), spec["spheres"]):
            objects.append((f"{entry['metal']} s={entry['s']:g}", rf.sphere(x, 0.0, 0.8),
                            {"model": "patch_exponential", "metal": entry["metal"], "s": entry["s"],
                             "strategy": strategy, "mis_density": spec["mis_density"], "count": 1}))
        out.append(rf.Panel(f"{strategy.replace('_', '/')} sampling", objects, rf.TWO_LIGHTS, CAMERA,
                            aspect=1.6, extra={"strategy": strategy}))
    return out


def _costs(df: pd.DataFrame) -> pd.DataFrame:
    """Per-pixel samples, tries, BRDF evaluations of the spheres' plugins and rays of the integrator."""
    pixels = df["width"] * df["height"]
    for column in ("plugin_samples", "plugin_tries", "plugin_evaluations", "rays"):
        if column in df:
            df[f"{column}_per_pixel"] = df[column] / pixels
    return df


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 5})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return _costs(rf.compute_panels(cfg, NAME, panels(cfg), count=True))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 4.9: three samplers at equal samples per pixel", columns=1)
