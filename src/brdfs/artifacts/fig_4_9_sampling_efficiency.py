"""Figure 4.9: metal spheres of the exponential patch model rendered at equal samples per pixel with
the thesis's three samplers (section 4.2.4): cosine, the 0/1 accept/reject sampling (the thesis's
"Russian roulette") and the exact "normal" sampling.

One panel per strategy (the plugins' ``strategy``: ``cosine``, ``accept_reject``, ``normal``), the
same scene, seeds and samples per pixel in each; the CSV holds per panel the samples, BRDF
evaluations and rays per pixel (the patch plugins' and the integrator's counters; the evaluations
include next-event estimation's, one per light sample that reaches a sphere) and the measured
noise (p95 of the relative standard error, fireflies). Measured seconds per panel go to
``results/renders/<name>/timing.json`` (beside the EXR files; the report's and the docs' page show
them, :func:`brdfs.pipeline.report.render_seconds`), never into the CSV or PNG. The efficiency chart of the strategies (variance × cost per
sample) is the extra ``extra_sampling_efficiency``.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from brdfs.artifacts import _render_figures as rf
from brdfs.pipeline.registry import figure

if TYPE_CHECKING:      # pandas loads in the job, not when planning reads the figure's objects
    import pandas as pd

NAME = "fig_4_9_sampling_efficiency"
CAMERA = {"eye": (0.0, -9.0, 2.2), "target": (0.0, 0.0, 0.7), "fov_deg": 25.0}    # all three spheres in frame
#: The thesis's render times per strategy (its caption: 50 samples per pixel, 51, 46 and 54 min).
THESIS_MINUTES = {"cosine": 51.0, "accept_reject": 46.0, "normal": 54.0}
THESIS_SPP = 50


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
                            aspect=1.6, extra={"strategy": strategy,
                                                  "thesis_minutes": THESIS_MINUTES.get(strategy, float("nan"))}))
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


def panel_costs(df: pd.DataFrame) -> list[str]:
    """Per panel, its cost line: samples per pixel, rays and the spheres' plugin evaluations per
    pixel (counts, identical run to run), beside the thesis's minutes at its 50 spp."""
    out = []
    for _, rows in df.groupby("panel", sort=True):
        first = rows.iloc[0]
        minutes = first["thesis_minutes"]
        thesis = f"thesis {THESIS_SPP} spp, {minutes:g} min" if minutes == minutes else "not in the thesis"
        spheres = [int(v) for v in rows.loc[rows["object"] != "floor", "object_spp"]]
        crop = f" (spheres {'/'.join(map(str, spheres))})" if any(v != first["spp"] for v in spheres) else ""
        out.append(f"{int(first['spp'])} spp{crop}, {first['rays_per_pixel']:.0f} rays/px, "
                   f"{rows['plugin_evaluations_per_pixel'].sum():.1f} plugin evals/px; {thesis}")
    return out


def plot(df: pd.DataFrame, path) -> None:
    """The panels, each titled with its sampler and its costs (:func:`panel_costs`)."""
    shown = df.copy()
    shown.attrs = {**df.attrs, "images": rf.SharedList((f"{title.replace(' sampling', '')}: {costs}", image)
                                                       for (title, image), costs in zip(df.attrs["images"], panel_costs(df)))}
    rf.plot_panels(shown, path, "Fig. 4.9: three samplers at equal samples per pixel", columns=1)
