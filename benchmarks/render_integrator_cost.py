"""Cost per sample of brdfs_path and the package's GGX plugin against Mitsuba's own path integrator and
roughconductor on one scene (four GGX spheres alpha = 0.2 on a GGX plate, Fig. 4.16's three lights, the sky;
640 x 400, 16 spp, multijitter, one Dr.Jit thread), two rounds (issue 42 (e) of speed_notes.md)::

    PYTHONPATH=src .venv/bin/python benchmarks/render_integrator_cost.py
"""
from __future__ import annotations

import time

import numpy as np

from brdfs.artifacts import _render_figures as rf
from brdfs.render.mitsuba import scenes as msc

ROUGH = {"type": "roughconductor", "distribution": "ggx", "alpha": 0.2, "sample_visible": False, "material": "none"}
GGX = {"type": "brdfs_ggx", "alpha": 0.2, "G2": "separable"}
CASES = {"path + roughconductor": (ROUGH, {"type": "path"}),
         "brdfs_path + roughconductor": (ROUGH, {"type": "brdfs_path", "caustics": False}),
         "brdfs_path + brdfs_ggx": (GGX, {"type": "brdfs_path", "caustics": False})}


def scene(bsdf: dict, integrator: dict):
    objects = [msc.SceneObject("floor", msc.floor(4.0), bsdf)] + [
        msc.SceneObject(f"s{k}", msc.sphere((x, 0.0, 0.6), 0.6), bsdf) for k, x in enumerate((-2.1, -0.7, 0.7, 2.1))]
    lights = tuple(msc.Light(tuple(p), 60.0 * s) for p, s in rf.THREE_LIGHTS)
    cam = rf.STREET_CAMERA
    camera = msc.Camera(cam["eye"], cam["target"], 640, 400, cam["fov_deg"])
    return msc.load(msc.Scene(tuple(objects), lights, sky=1.0), camera, integrator, "multijitter")


def main() -> None:
    mi = rf._mitsuba("llvm_ad_rgb")
    with rf.one_thread():
        for _ in range(2):
            for name, (bsdf, integrator) in CASES.items():
                loaded = scene(bsdf, integrator)
                np.asarray(mi.render(loaded, spp=1, seed=1))          # trace and compile
                start = time.process_time()
                image = np.asarray(mi.render(loaded, spp=16, seed=2))
                print(f"{name:30s} 16 spp {time.process_time() - start:.2f} CPU-s  mean {image[..., :3].mean():.4f}",
                      flush=True)


if __name__ == "__main__":
    main()
