"""Per figure of the preview preset: CPU seconds, and per panel the p95 of the relative standard
error on object pixels, the fireflies and the samples per pixel (the issue-23 figures).

CPU seconds are ``time.process_time`` of this process (user + sys of all its threads: Dr.Jit's
LLVM backend runs its kernels on a thread pool), so they are honest on a shared machine where wall
time is not; JIT compilation is included (the first figure of a process also pays Mitsuba's import
and the plugins' registration). With ``--maps DIR`` each panel's per-pixel relative-SE map, mean
luminance and ID buffer are saved as ``DIR/<figure>_<panel>.npz`` (where the p95 comes from).

    .venv/bin/python benchmarks/render_preview_noise.py [fig_3_9_metals_new_model ...] [--maps /tmp/maps]
    .venv/bin/python benchmarks/render_preview_noise.py --set renders.preview.spp=128
"""
from __future__ import annotations

import argparse
import importlib
import os
import time

import numpy as np

from brdfs.pipeline.config import load_config
from brdfs.render.mitsuba import metrics

#: The rendered figures: the Snakemake batch renders_paths, then renders_patch_and_direct (the patch
#: models' Figs. 4.11, 4.16, 4.17 and the direct-lighting Figs. 3.8, 4.18; the two batches cost about
#: the same, so they balance on 2 cores).
FIGURES = ("fig_2_8_pumping_render", "fig_3_9_metals_new_model", "fig_3_10_metal_teapots", "fig_3_11_silver_mirror",
           "fig_3_12_plastics", "fig_3_13_ceramics", "fig_4_9_sampling_efficiency", "fig_4_11_anisotropic_metals",
           "fig_4_16_patch_metals", "fig_4_17_patch_shapes", "fig_3_8_material_spheres", "fig_4_18_generalized_lambert")


def _set(cfg: dict, assignment: str) -> None:
    """``a.b.c=value`` (value parsed as int, float or string) into the nested config."""
    key, value = assignment.split("=", 1)
    *path, last = key.split(".")
    node = cfg
    for part in path:
        node = node[part]
    for kind in (int, float):
        try:
            node[last] = kind(value)
            break
        except ValueError:
            continue
    else:
        node[last] = value


def _capture_maps(store: list):
    """Wrap metrics.noise_figures so that each panel's passes and IDs are kept (in ``store``)."""
    original = metrics.noise_figures

    def noise_figures(passes, ids):
        store.append((np.asarray(passes, float), np.asarray(ids, float)))
        return original(passes, ids)
    return noise_figures


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("figures", nargs="*", default=FIGURES)
    parser.add_argument("--maps", default=None, help="directory for per-panel relative-SE maps (npz)")
    parser.add_argument("--set", action="append", default=[], help="config override a.b=value")
    args = parser.parse_args(argv)
    cfg = load_config()
    for assignment in args.set:
        _set(cfg, assignment)
    store: list = []
    metrics.noise_figures = _capture_maps(store)
    total = 0.0
    for name in args.figures:
        module = importlib.import_module(f"brdfs.artifacts.{name}")
        store.clear()
        start = time.process_time()
        df = module.compute(cfg, {})
        cpu = time.process_time() - start
        total += cpu
        per_panel = df.groupby("panel").first()
        cells = " ".join(f"{r.p95_relative_se:.4f}/{int(r.fireflies)}@{int(r.spp)}" for r in per_panel.itertuples())
        print(f"{name:32s} cpu {cpu:6.1f} s  p95/fireflies@spp {cells}", flush=True)
        if args.maps:
            os.makedirs(args.maps, exist_ok=True)
            for k, (passes, ids) in enumerate(store):
                np.savez_compressed(f"{args.maps}/{name}_{k}.npz", rse=metrics.relative_standard_error(passes),
                                    mean=passes.mean(axis=0), ids=ids,
                                    mask=metrics.object_pixels(ids, passes.mean(axis=0)))
            df.to_csv(f"{args.maps}/{name}.csv", index=False)
    print(f"{'total':32s} cpu {total:6.1f} s")


if __name__ == "__main__":
    main()
