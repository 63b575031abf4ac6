"""Benchmark: the clamp of Figs. 3.9, 4.11 and 4.16 per render preset, by the rule config.yaml declares.

The rule (session 7, ``renders.<preset>.clamp``): among the clamps 1, 2, 4 and none, measured at equal
samples, take the least worst-object error sqrt(bias^2 + p95^2) among the clamps that bias no object
by more than 1 % (the final preset's noise goal); errors within 5 % of the least are a tie (an 8-pass
p95 is itself good to about that: 0.97-1.11x, :mod:`brdfs.render.mitsuba.metrics`), which the smaller
bias breaks. The bias does not depend on the samples; the p95 of the relative standard error scales
as 1/sqrt(spp), so each measured p95 is scaled from the samples it was measured at to the object's
samples in the preset (its ``object_spp`` entry, else the figure's ``figure_spp``, else the preset's
``spp``, as the pipeline's own :func:`figure_setup` gives them). The bias of an object is the larger of
the render's own (``clamp_bias``) and, where measured, the one against an unclamped reference at 4x the samples.

The measurements are the table "Clamped interreflections" of ``benchmarks/render_noise_validation.md``
(``render_preview_noise.py --caustics CSV --clamps 1,2,4``, session 7). Prints, per preset and figure,
each clamp's worst-object error and largest bias, the rule's choice and the clamp config.yaml gives;
exits 1 where they differ.

    PYTHONPATH=src python benchmarks/render_clamp_rule.py
"""
import math
import re
import sys
from collections import defaultdict
from pathlib import Path

import yaml

from brdfs.artifacts._render_figures import PRESETS, figure_setup, settings

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "benchmarks" / "render_noise_validation.md"
FIGURES = {"3.9": "fig_3_9_metals_new_model", "4.11": "fig_4_11_anisotropic_metals", "4.16": "fig_4_16_patch_metals"}
BIAS_CAP = 0.01
TIE = 0.05


def measurements(text: str) -> list[dict]:
    """The rows of the table "Clamped interreflections" (one per figure, object and clamp)."""
    section = text.split("## Clamped interreflections", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 10 and re.fullmatch(r"\d+\.\d+", cells[0]):
            reference = abs(float(cells[7])) if cells[7] else 0.0
            rows.append({"figure": cells[0], "object": cells[1], "clamp": float(cells[2]), "spp": float(cells[3]),
                         "p95": float(cells[4]), "bias": max(abs(float(cells[6])), reference)})
    return rows


def object_spp(setup: dict, label: str) -> int:
    """An object's samples per pixel in a figure's setup (:func:`figure_setup`): its object_spp, else the
    film's (the fewest panel's, where figure_spp lists one per panel)."""
    film = setup["spp"]
    return setup["object_spp"].get(label, min(film) if isinstance(film, list) else film)


def choose(rows: list[dict], setup: dict) -> tuple[float, dict]:
    """The rule's clamp for figure ``name`` in a preset, and each clamp's (worst error, largest bias)."""
    by_clamp = defaultdict(list)
    for row in rows:
        by_clamp[row["clamp"]].append(row)
    scores = {}
    for clamp, group in sorted(by_clamp.items()):
        errors = [math.hypot(r["bias"], r["p95"] * math.sqrt(r["spp"] / object_spp(setup, r["object"])))
                  for r in group]
        scores[clamp] = (max(errors), max(r["bias"] for r in group))
    allowed = {c: s for c, s in scores.items() if s[1] <= BIAS_CAP}
    least = min(error for error, _ in allowed.values())
    tied = [c for c, (error, _) in allowed.items() if error <= least * (1 + TIE)]
    return min(tied, key=lambda c: allowed[c][1]), scores


def main() -> int:
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    rows = measurements(TABLE.read_text(encoding="utf-8"))
    differ = 0
    for preset in PRESETS:
        config["renders"]["preset"] = preset
        for figure, name in FIGURES.items():
            setup = figure_setup(settings(config), name)
            chosen, scores = choose([r for r in rows if r["figure"] == figure], setup)
            given = setup["clamp"]
            table = "; ".join(f"{c:g}: {e * 100:.3f} % (bias {b * 100:.2f} %)" for c, (e, b) in scores.items())
            print(f"{preset:8s} {figure:5s} rule {chosen:g}  config {given:g}  [{table}]")
            differ += chosen != given
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
