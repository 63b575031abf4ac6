"""The spectral route of the renders, measured on one metal scene (Fig. 3.9's panel, preview size):
eight 50 nm bins as three colour groups along each path of ``llvm_ad_rgb`` (the pipeline's route,
:mod:`brdfs.render.mitsuba.spectral`) against Mitsuba's ``llvm_ad_spectral`` (one pass, four
wavelengths sampled per path from the continuous spectrum, Mitsuba's own CIE tables).

Both render the same geometry, camera, seeds, passes and samples per pixel with ``brdfs_path``; in
the spectral variant the metals' n, k are irregular spectra of the measured data on a 5 nm grid
(380-830 nm), the lights and sky Mitsuba's white (D65 radiance of an sRGB white), the floor's
reflectance flat. Printed per route: CPU seconds (``time.process_time``, all threads, JIT
included), the p95 of the relative standard error of Y on object pixels and the fireflies, and per
object its mean linear sRGB and Y relative to the gray floor's (white-balanced: the routes' whites differ).

    .venv/bin/python benchmarks/render_spectral_route.py
"""
from __future__ import annotations

import copy
import time

import numpy as np

from brdfs.artifacts import _render_figures as rf
from brdfs.artifacts import fig_3_9_metals_new_model as fig
from brdfs.pipeline.config import load_config
from brdfs.render import spectrum
from brdfs.render.mitsuba import metrics
from brdfs.render.mitsuba import scenes as msc

FINE_NM = np.arange(380.0, 831.0, 5.0)
REC709_Y = np.array([0.2126, 0.7152, 0.0722])


def _object_means(rgb, ids, labels):
    return {label: rgb[ids == k].mean(axis=0) for k, label in labels.items() if label != "light" and (ids == k).any()}


def rgb_route(cfg, panel, setup):
    start = time.process_time()
    width, height = rf.panel_size(setup, panel.aspect)
    rendered = rf.render_panel(panel, cfg, setup, width, height)
    cpu = time.process_time() - start
    noise = metrics.noise_figures(rendered.luminance_passes(rf.SPECTRAL), rendered.ids)
    rgb = spectrum.linear_rgb(rendered.radiance)
    return cpu, noise, _object_means(rgb, rendered.ids, rendered.labels)


def _irregular(values):
    return {"type": "irregular", "wavelengths": ", ".join(f"{w:g}" for w in FINE_NM),
            "values": ", ".join(f"{v:.6g}" for v in values)}


def _spectral_metal(entry: dict, metal: str) -> dict:
    from brdfs.physics import optical_constants

    ior = np.asarray(optical_constants.complex_index(metal, FINE_NM), complex)
    return {**entry, "eta": _irregular(ior.real), "k": _irregular(np.abs(ior.imag))}


def spectral_route(cfg, panel, setup):
    mi = rf._mitsuba("llvm_ad_spectral")
    start = time.process_time()
    width, height = rf.panel_size(setup, panel.aspect)
    cam = panel.camera
    camera = msc.Camera(tuple(cam["eye"]), tuple(cam["target"]), width, height, cam.get("fov_deg", 30.0))
    scene_spec = rf._scene(panel, cfg, rf.WAVELENGTH_PASSES[:1])
    objects = tuple(msc.SceneObject(o.label, o.parts, _spectral_metal(o.bsdf, spec["metal"]) if "metal" in spec else o.bsdf)
                    for o, (_, _, spec) in zip(scene_spec.objects, panel.objects))
    scene = msc.load(msc.Scene(objects, scene_spec.lights, sky=scene_spec.sky), camera,
                     rf._integrator(panel, caustics=setup["caustics"]),
                     setup["sampler"])
    spp = setup["spp"] // setup["passes"]
    images = [np.asarray(mi.render(scene, spp=spp, seed=rf.pass_seed(cfg["seed"], p))) for p in range(setup["passes"])]
    cpu = time.process_time() - start
    rgb_passes = np.stack([im[..., :3] for im in images])
    ids = np.mean([im[..., 3] for im in images], axis=0)
    ids = np.where(np.abs(ids - np.round(ids)) < 1e-5, np.round(ids), ids)
    noise = metrics.noise_figures(rgb_passes @ REC709_Y, ids)
    return cpu, noise, _object_means(rgb_passes.mean(axis=0), ids, msc.object_labels(scene))


def main() -> None:
    cfg = copy.deepcopy(load_config())
    setup = rf.settings(cfg)
    panel = fig.panels(cfg)[0]
    results = {"8 bins, 3 colour groups": rgb_route(cfg, panel, setup),
               "llvm_ad_spectral": spectral_route(cfg, panel, setup)}
    for route, (cpu, noise, means) in results.items():
        print(f"{route:22s} cpu {cpu:5.1f} s  p95 {noise.p95_relative_se:.4f}  fireflies {noise.fireflies}")
    # the routes' white differs (equal-energy bins adapted to D65 by colour-science vs Mitsuba's
    # D65 emitters), so colours are compared white-balanced on the gray floor
    ref = results["8 bins, 3 colour groups"][2]
    spectral = results["llvm_ad_spectral"][2]
    for label, rgb in spectral.items():
        r = ref[label] / ref["floor"]
        s_ = rgb / spectral["floor"]
        print(f"  {label:20s} rgb/floor: 8 bins {np.round(r, 4)}  spectral {np.round(s_, 4)}  "
              f"Y/floor {r @ REC709_Y:.4f} vs {s_ @ REC709_Y:.4f}  max channel diff {np.abs(s_ - r).max():.4f}")

if __name__ == "__main__":
    main()
