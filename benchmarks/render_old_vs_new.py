"""One scene, one run: time and noise of the old numpy tracer (brdfs.render.tracer) and of the new
Mitsuba path (``brdfs_path`` with the package's Dr.Jit plugins, ``llvm_ad_rgb``).

The scene: a sphere of the new model (``phong_cosmin``, n = 20, Fresnel 1) on a gray Lambert floor
(ρ = 0.5), one point light of intensity 60 at (−4, −5, 6) (the new path: a sphere of radius 0.12
radiating the same intensity) and a constant daylight S = 1, r, g, b channels; 320 × 200 pixels,
``SPP`` samples per pixel split into 8 independently seeded passes; the old tracer's paths stop at
``OLD_DEPTH`` vertices (its draft setting), the new path ends by Russian roulette.

Printed per renderer: wall time of the 8 passes (the new path's first pass includes its JIT
compilation; a second line without it), the p95 of the per-pixel relative standard error on object
pixels, fireflies, and each object's mean luminance with its standard error.

    .venv/bin/python benchmarks/render_old_vs_new.py
"""
from __future__ import annotations

import os
import time

import numpy as np

import brdfs
from brdfs.render import materials, shapes, spectrum, tracer
from brdfs.render.mitsuba import metrics

WIDTH, HEIGHT, SPP, PASSES, OLD_DEPTH = 320, 200, 64, 8, 3
EYE, TARGET, FOV = (0.0, -7.0, 2.5), (0.0, 0.0, 0.8), 34.0
LIGHT, INTENSITY, SKY = (-4.0, -5.0, 6.0), 60.0, 1.0


def old_passes():
    model = brdfs.model("phong_cosmin", n=20.0)
    floor = tracer.SceneObject(shapes.Rectangle((0.0, 0.0, 0.0), (4.0, 4.0)), materials.lambert(np.full(3, 0.5)), "floor")
    ball = tracer.SceneObject(shapes.Sphere((0.0, 0.0, 1.0), 1.0), materials.specular(model, 3), "ball")
    scene = tracer.Scene([floor, ball], [tracer.PointLight(LIGHT, np.full(3, INTENSITY))], sky=np.full(3, SKY))
    camera = tracer.Camera(EYE, TARGET, WIDTH, HEIGHT, FOV)
    images = []
    for p in range(PASSES):
        image = tracer.render(scene, camera, spp=SPP // PASSES, depth=OLD_DEPTH, seed=100 + p,
                              stat_weights=spectrum.RGB_LUMINANCE)
        images.append(image.radiance)
    return np.stack(images), image.index + 1.0


def new_passes():
    from brdfs.render.mitsuba import integrator, register_plugins, scenes, use_variant

    mi = use_variant(os.environ.get("VARIANT", "llvm_ad_rgb"))
    register_plugins()
    integrator.register()
    objects = (scenes.SceneObject("floor", scenes.floor(4.0), {"type": "brdfs_lambert",
                                                              "reflectance": {"type": "rgb", "value": [0.5] * 3}}),
               scenes.SceneObject("ball", scenes.sphere((0.0, 0.0, 1.0), 1.0), {"type": "brdfs_phong_cosmin", "n": 20.0}))
    scene = scenes.load(scenes.Scene(objects, (scenes.Light(LIGHT, INTENSITY),), sky=SKY),
                        scenes.Camera(EYE, TARGET, WIDTH, HEIGHT, FOV), {"type": "brdfs_path"})
    images, times = [], []
    for p in range(PASSES):
        start = time.perf_counter()
        images.append(np.asarray(mi.render(scene, spp=SPP // PASSES, seed=100 + p)))
        times.append(time.perf_counter() - start)
    stack = np.stack(images)
    labels = scenes.object_labels(scene)
    ids = stack[0, ..., 3]
    return stack[..., :3], ids, times, labels


def report(name, passes, ids, seconds, labels):
    y = passes @ spectrum.RGB_LUMINANCE
    figures = metrics.noise_figures(y, ids)
    print(f"{name}: {seconds:.2f} s for {PASSES} passes, {WIDTH}x{HEIGHT}, {SPP} spp; "
          f"p95 relative SE {figures.p95_relative_se:.4f} on {figures.object_pixels} object pixels; "
          f"fireflies {figures.fireflies}")
    for k, label in labels.items():
        sel = ids == k
        if sel.any() and label != "light":
            per_pass = y[:, sel].mean(axis=1)
            print(f"  {label}: Y = {per_pass.mean():.5f} +- {per_pass.std(ddof=1) / np.sqrt(PASSES):.5f}")


def main():
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    start = time.perf_counter()
    passes, ids = old_passes()
    report(f"old numpy tracer (depth {OLD_DEPTH})", passes, ids, time.perf_counter() - start, {1: "floor", 2: "ball"})
    passes, ids, times, labels = new_passes()
    report("new Mitsuba path (Russian roulette)", passes, ids, sum(times), labels)
    print(f"  without the first pass (JIT compilation): {sum(times[1:]) * PASSES / (PASSES - 1):.2f} s")


if __name__ == "__main__":
    main()
