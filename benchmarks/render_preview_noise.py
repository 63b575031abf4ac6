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

#: The figures the noise estimator is validated on (``--validate``): two path-traced metal scenes and a
#: patch figure.
VALIDATED = ("fig_3_9_metals_new_model", "fig_3_11_silver_mirror", "fig_4_17_patch_shapes")

#: The figures whose caustics (sparkles) are treated (``--caustics``).
CAUSTIC = ("fig_3_11_silver_mirror", "fig_3_10_metal_teapots")


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
    """Wrap metrics.panel_noise so that each panel's luminance passes and IDs are kept (in ``store``)."""
    original = metrics.panel_noise

    def panel_noise(passes, ids):
        store.append((np.asarray(passes, float), np.asarray(ids, float)))
        return original(passes, ids)
    return panel_noise


def _scaled_spp(setup_spp, factor: int):
    return [int(v) * factor for v in setup_spp] if isinstance(setup_spp, (list, tuple)) else int(setup_spp) * factor


def reference_config(cfg: dict, name: str, factor: int) -> dict:
    """``cfg`` with figure ``name`` (and every other) at ``factor`` x its samples per pixel in ``factor`` x its passes (the
    same samples per pass, so each reference pass is distributed as a preview pass) and another seed
    (the reference's passes are independent of the preview's: pass_seed differs by 7919 * 1009)."""
    import copy

    out = copy.deepcopy(cfg)
    preset = out["renders"][out["renders"]["preset"]]
    preset["figure_spp"] = {key: _scaled_spp(spp, factor) for key, spp in preset["figure_spp"].items()}
    preset["crop_spp"] = {key: int(spp) * factor for key, spp in (preset.get("crop_spp") or {}).items()}
    preset["object_spp"] = {key: {label: int(spp) * factor for label, spp in objects.items()}
                            for key, objects in (preset.get("object_spp") or {}).items()}
    preset["passes"] = preset["passes"] * factor
    preset["spp"] = preset["spp"] * factor
    # an adaptive figure: the same samples per pixel and pass (its pilot's and its map's), factor x the passes
    preset["adaptive"] = {key: float(t) / np.sqrt(factor) for key, t in (preset.get("adaptive") or {}).items()}
    for key in ("adaptive_pilot", "adaptive_max"):
        if key in preset:
            preset[key] = int(preset[key]) * factor
    out["seed"] = int(cfg["seed"]) + 7919
    return out


def predicted_quantile(tau: np.ndarray, level: float = 0.95) -> float:
    """The ``level`` quantile of |e| over pixels when pixel i's error e_i ~ N(0, tau_i^2): the q with
    mean_i P(|e_i| > q) = 1 - level (bisection; the pixels' half-normals mixed)."""
    from scipy.special import erfc

    tau = np.asarray(tau, float)
    lo, hi = 0.0, 10.0 * float(tau.max())
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.mean(erfc(mid / (np.sqrt(2.0) * tau))) > 1.0 - level else (lo, mid)
    return hi


def validate_object(preview: np.ndarray, reference: np.ndarray, own: np.ndarray, factor: int) -> dict:
    """The estimator's p95 against the error measured on a reference, on one object's pixels ``own``.

    ``preview`` (P, H, W) and ``reference`` (factor P, H, W) are independent luminance passes. With the
    relative error e_i = (mean_preview - mean_reference) / mean_reference, the estimate s_i (the 8-pass
    relative SE) and the reference's own s_ref_i, an honest estimator gives e_i ~ N(0, s_i^2 + s_ref_i^2):

    * ``predicted_p95_error``: the p95 of |e| that this predicts (:func:`predicted_quantile`);
      ``measured_p95_error``: the p95 of |e| measured; ``ratio`` = measured / predicted. The
      reference's own noise is in both (through s_ref_i). ``measured_p95_rse`` = ratio x the estimate's
      p95: the p95 relative SE the measured errors imply (pass: estimate >= 0.85 x it).
    * ``rms_ratio``: sqrt(mean(e^2 - s_ref^2) / mean(s^2)), the same check on variances, free of the
      normal shape.
    * ``ref_p95_rse``: the p95 of sqrt(factor) x the reference's relative SE (the preview's relative SE as
      a factor P-pass standard deviation sees it).
    """
    mp, mr = preview[:, own].mean(axis=0), reference[:, own].mean(axis=0)
    keep = mr > 0
    mp, mr = mp[keep], mr[keep]
    s = metrics.relative_standard_error(preview[:, own][:, keep]) * mp / mr
    s_ref = metrics.relative_standard_error(reference[:, own][:, keep])
    e = (mp - mr) / mr
    estimate = float(np.percentile(metrics.relative_standard_error(preview[:, own][:, keep]), 95.0))
    predicted = predicted_quantile(np.sqrt(s ** 2 + s_ref ** 2))
    measured = float(np.percentile(np.abs(e), 95.0))
    ratio = measured / predicted
    return {"pixels": int(keep.sum()), "est_p95_rse": estimate,
            "ref_p95_rse": float(np.percentile(np.sqrt(factor) * s_ref, 95.0)),
            "measured_p95_error": measured, "predicted_p95_error": predicted, "ratio": ratio,
            "measured_p95_rse": ratio * estimate,
            "rms_ratio": float(np.sqrt(max(np.mean(e ** 2 - s_ref ** 2), 0.0) / np.mean(s ** 2))),
            "within_15pct": bool(estimate >= 0.85 * ratio * estimate)}


def object_means(df, panel: int) -> dict:
    """{object: (mean Y, its standard error)} of one panel of a figure's rows."""
    rows = df[df["panel"] == panel]
    return {r.object: (r.luminance, r.luminance_err) for r in rows.itertuples()}


def caustic_choice(figures, cfg: dict, clamps, factor: int, out_csv: str) -> None:
    """Per figure and object, the caustic treatments at equal samples (so at equal time: the clamp costs
    nothing measurable; the CPU seconds are in the table): no clamp and each of ``clamps``, their p95
    relative SE, fireflies, and their bias measured against an unbiased reference (no clamp, ``factor``
    x the samples, independent seeds) beside the bias the render measures itself (``clamp_bias``)."""
    import copy

    import pandas as pd

    rows = []
    for name in figures:
        module = importlib.import_module(f"brdfs.artifacts.{name}")
        base = copy.deepcopy(cfg)
        base["renders"][base["renders"]["preset"]]["clamp"] = {}
        reference, _, cpu_ref = _render(module, reference_config(base, name, factor), [])
        print(f"{name}: reference ({factor}x, no clamp) {cpu_ref:.1f} CPU-s", flush=True)
        for clamp in (0.0, *clamps):
            trial = copy.deepcopy(base)
            trial["renders"][trial["renders"]["preset"]]["clamp"] = {name: float(clamp)} if clamp else {}
            df, _, cpu = _render(module, trial, [])
            for r in df.itertuples():
                ref, ref_err = object_means(reference, r.panel)[r.object]
                bias = r.luminance / ref - 1.0
                err = np.hypot(r.luminance_err / ref, r.luminance * ref_err / ref ** 2)
                rows.append({"figure": name, "panel": r.panel, "object": r.object, "clamp": clamp, "spp": r.spp,
                             "cpu_s": cpu, "p95_relative_se": r.object_p95_relative_se,
                             "fireflies": r.object_fireflies, "sparkles": r.object_sparkles,
                             "bias_vs_reference": bias, "bias_vs_reference_err": err,
                             "clamp_bias": getattr(r, "clamp_bias", 0.0), "ref_spp": r.spp * factor})
                print(f"    clamp {clamp:6g} panel {r.panel} {r.object:14s} p95 {r.object_p95_relative_se:.4f} "
                      f"fireflies {r.object_fireflies:4.0f} bias {bias:+.4f} +- {err:.4f} "
                      f"(in-render {rows[-1]['clamp_bias']:+.4f}) cpu {cpu:.1f}", flush=True)
    pd.DataFrame(rows).to_csv(out_csv, index=False)
    print(f"wrote {out_csv}")


#: Panels whose noise is their figure's point (Fig. 4.9's cosine and accept/reject samplers): no target.
EXCEPTED = {("fig_4_9_sampling_efficiency", 0), ("fig_4_9_sampling_efficiency", 1)}


def exact_spp(spp: float, passes: int, sampler: str = "multijitter") -> int:
    """The fewest samples per pixel >= ``spp`` whose per-pass count the sampler takes exactly."""
    from brdfs.artifacts._render_figures import sampler_takes

    per_pass = max(int(np.ceil(spp / passes)), 1)
    while not sampler_takes(sampler, per_pass):
        per_pass += 1
    return per_pass * passes


def plan(preview_csv: str, target: float, budget_cpu_s: float, passes: int = 8) -> "pd.DataFrame":
    """Per figure, the samples per pixel that bring its worst object (of the panels not in
    :data:`EXCEPTED`) from its measured p95 to ``target`` (noise as 1/sqrt(spp), validated by
    --validate), or, if all of them together would take more than ``budget_cpu_s``, to the common p95
    t that the budget reaches (sum_i cpu_i (p_i / t)^2 = budget); with the predicted p95 of every object
    and the predicted CPU seconds (the preview's scaled by the samples: an upper bound, the figure's
    fixed costs scale too). A preview with crop windows (``crop_spp``) is scaled from its objects' own
    samples (``object_spp``): the final then renders the whole film at that count, no crop (an upper bound)."""
    import pandas as pd

    rows = pd.read_csv(preview_csv)
    rows = rows[[(f, p) not in EXCEPTED for f, p in zip(rows["figure"], rows["panel"])]]
    own = "object_spp" if "object_spp" in rows.columns else "spp"
    figures = rows.groupby("figure").agg(p95=("p95_relative_se", "max"), spp=(own, "max"), cpu_s=("cpu_s", "first"))
    reach = float(np.sqrt((figures["cpu_s"] * figures["p95"] ** 2).sum() / budget_cpu_s))
    goal = max(target, reach)
    figures["final_spp"] = [exact_spp(max(spp, spp * (p / goal) ** 2), passes) for p, spp in zip(figures["p95"], figures["spp"])]
    figures["predicted_p95"] = figures["p95"] * np.sqrt(figures["spp"] / figures["final_spp"])
    figures["predicted_cpu_s"] = figures["cpu_s"] * figures["final_spp"] / figures["spp"]
    figures.attrs["goal"] = goal
    return figures


def _render(module, cfg: dict, store: list):
    store.clear()
    start = time.process_time()
    df = module.compute(cfg, {})
    return df, list(store), time.process_time() - start


def validate(figures, cfg: dict, factor: int, out_csv: str) -> None:
    """Render each figure as configured and at ``factor`` x its samples (independent seeds) and write,
    per (panel, object), :func:`validate_object`'s table to ``out_csv``."""
    import pandas as pd

    store: list = []
    metrics.panel_noise = _capture_maps(store)
    rows = []
    for name in figures:
        module = importlib.import_module(f"brdfs.artifacts.{name}")
        df, previews, cpu = _render(module, cfg, store)
        _, references, cpu_ref = _render(module, reference_config(cfg, name, factor), store)
        print(f"{name}: preview {cpu:.1f} CPU-s, reference ({factor}x) {cpu_ref:.1f} CPU-s", flush=True)
        for (panel, group), (preview, ids), (reference, _) in zip(df.groupby("panel"), previews, references):
            mask = metrics.object_pixels(ids, preview.mean(axis=0))
            labels = df.attrs["ids"][panel][1]
            for k in np.unique(ids[mask]):
                label = labels[int(k)]
                row = {"figure": name, "panel": panel, "object": label, "spp": int(group["spp"].iloc[0]),
                       "passes": preview.shape[0], "ref_spp": int(group["spp"].iloc[0]) * factor,
                       "ref_passes": reference.shape[0],
                       **validate_object(preview, reference, mask & (ids == k), factor),
                       "cpu_s": cpu, "ref_cpu_s": cpu_ref}
                rows.append(row)
                print(f"    panel {panel} {label:14s} est {row['est_p95_rse']:.4f} measured {row['measured_p95_rse']:.4f} "
                      f"(ratio {row['ratio']:.3f}, rms {row['rms_ratio']:.3f}) ref-32 {row['ref_p95_rse']:.4f}", flush=True)
    pd.DataFrame(rows).to_csv(out_csv, index=False)
    print(f"wrote {out_csv}")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("figures", nargs="*", default=FIGURES)
    parser.add_argument("--maps", default=None, help="directory for per-panel relative-SE maps (npz)")
    parser.add_argument("--set", action="append", default=[], help="config override a.b=value")
    parser.add_argument("--validate", default=None, metavar="CSV",
                        help="validate the noise estimator against references at --factor x the samples")
    parser.add_argument("--factor", type=int, default=4)
    parser.add_argument("--caustics", default=None, metavar="CSV",
                        help="compare caustic treatments (clamps, --clamps) with an unbiased reference")
    parser.add_argument("--clamps", default="4,16,64", help="the clamps --caustics tries (comma separated)")
    parser.add_argument("--csv", default=None, help="per (figure, panel, object): p95, fireflies, spp, CPU-s")
    parser.add_argument("--plan", default=None, metavar="PREVIEW_CSV",
                        help="plan the final preset's spp from a --csv of the preview (to 1 %% within 30 min on 2 cores)")
    args = parser.parse_args(argv)
    cfg = load_config()
    for assignment in args.set:
        _set(cfg, assignment)
    if args.plan:
        figures = plan(args.plan, 0.0095, 2 * 30 * 60.0)
        print(figures.to_string(float_format=lambda v: f"{v:.4g}"))
        print(f"worst-object goal {figures.attrs['goal']:.4f}; predicted {figures['predicted_cpu_s'].sum():.0f} CPU-s")
        return None
    if args.caustics:
        return caustic_choice(args.figures if args.figures != FIGURES else CAUSTIC, cfg,
                              [float(c) for c in args.clamps.split(",")], args.factor, args.caustics)
    if args.validate:
        return validate(args.figures if args.figures != FIGURES else VALIDATED, cfg, args.factor, args.validate)
    store: list = []
    metrics.panel_noise = _capture_maps(store)
    total, table = 0.0, []
    for name in args.figures:
        module = importlib.import_module(f"brdfs.artifacts.{name}")
        store.clear()
        start = time.process_time()
        df = module.compute(cfg, {})
        cpu = time.process_time() - start
        total += cpu
        print(f"{name:32s} cpu {cpu:6.1f} s", flush=True)
        table += [{"figure": name, "panel": r.panel, "object": r.object, "spp": r.spp,
                   "crop_spp": getattr(r, "crop_spp", 0), "object_spp": getattr(r, "object_spp", r.spp), "cpu_s": cpu,
                   "p95_relative_se": r.object_p95_relative_se, "fireflies": r.object_fireflies,
                   "sparkles": r.object_sparkles, "clamp": getattr(r, "clamp", 0.0),
                   "clamp_bias": getattr(r, "clamp_bias", 0.0)} for r in df.itertuples()]
        for r in df.itertuples():
            print(f"    panel {r.panel} {r.object:14s} p95 {r.object_p95_relative_se:.4f} fireflies "
                  f"{r.object_fireflies:4.0f} sparkles {r.object_sparkles:4.0f} @ {r.spp:.0f} spp"
                  f" (object {getattr(r, 'object_spp', r.spp):.0f})", flush=True)
        if args.maps:
            os.makedirs(args.maps, exist_ok=True)
            for k, (passes, ids) in enumerate(store):
                np.savez_compressed(f"{args.maps}/{name}_{k}.npz", rse=metrics.relative_standard_error(passes),
                                    mean=passes.mean(axis=0), ids=ids,
                                    mask=metrics.object_pixels(ids, passes.mean(axis=0)))
            df.to_csv(f"{args.maps}/{name}.csv", index=False)
    print(f"{'total':32s} cpu {total:6.1f} s")
    if args.csv:
        import pandas as pd

        pd.DataFrame(table).to_csv(args.csv, index=False)


if __name__ == "__main__":
    main()
