"""Renderer decision (issue #17): time per image of Mitsuba 3 (scalar_rgb, the package's BRDF as a
Python BSDF plugin) and of brdfs.render on the same scene.

Scene: a sphere of the new model (phong_cosmin, n = 20, F = 1) on a diffuse floor (rho = 0.5),
one point light, 160 x 120 pixels; (a) direct lighting, 1 sample per pixel; (b) daylight (constant
environment) + point light, paths of depth 3, 16 samples per pixel, both with cosine-weighted
BSDF sampling in Mitsuba (the plugin) and, in numpy, the mixture of the model's own sampler with a
defensive cosine share (brdfs.render.sampling).

Run (Mitsuba is NOT a project dependency; use a throw-away venv):
    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 numpy scipy pandas
    PYTHONPATH=src /tmp/mi/bin/python benchmarks/render_mitsuba_vs_numpy.py
"""
import sys
import time

import numpy as np

import brdfs
from brdfs.render import materials, shapes, tracer

W, H, N = 160, 120, 20
MODEL = brdfs.model("phong_cosmin", n=N)


def numpy_times():
    mat = materials.specular(MODEL, 3)
    floor = materials.lambert(np.full(3, 0.5))
    scene = tracer.Scene([tracer.SceneObject(shapes.Sphere((0, 0, 1), 1), mat, "sphere"),
                          tracer.SceneObject(shapes.Rectangle((0, 0, 0), (5, 5)), floor, "floor")],
                         [tracer.PointLight((3, -4, 5), np.full(3, 40.0))])
    cam = tracer.Camera((0, -6, 2.5), (0, 0, 0.8), W, H, fov_deg=35)
    t = time.perf_counter()
    tracer.render(scene, cam, spp=1, depth=1)
    direct = time.perf_counter() - t
    scene.sky = np.ones(3)
    t = time.perf_counter()
    tracer.render(scene, cam, spp=16, depth=3, seed=1)
    return direct, time.perf_counter() - t


def mitsuba_times():
    import mitsuba as mi
    mi.set_variant("scalar_rgb")

    class PackageBSDF(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.m_flags = mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
            self.m_components = [self.m_flags]

        def _f(self, wi, wo):
            return float(MODEL(np.array([wo[0], wo[1], wo[2]]), np.array([wi[0], wi[1], wi[2]])))

        def sample(self, ctx, si, sample1, sample2, active=True):
            wo = mi.warp.square_to_cosine_hemisphere(sample2)
            bs = mi.BSDFSample3f()
            bs.wo, bs.pdf, bs.eta = wo, mi.warp.square_to_cosine_hemisphere_pdf(wo), 1.0
            bs.sampled_type, bs.sampled_component = int(mi.BSDFFlags.GlossyReflection), 0
            if si.wi[2] <= 0 or bs.pdf <= 0:
                return bs, mi.Color3f(0.0)
            return bs, mi.Color3f(self._f(si.wi, wo) * wo[2] / bs.pdf)

        def eval(self, ctx, si, wo, active=True):
            if si.wi[2] <= 0 or wo[2] <= 0:
                return mi.Color3f(0.0)
            return mi.Color3f(self._f(si.wi, wo) * wo[2])

        def pdf(self, ctx, si, wo, active=True):
            return mi.warp.square_to_cosine_hemisphere_pdf(wo)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

        def to_string(self):
            return "PackageBSDF"

    mi.register_bsdf("package_bsdf", lambda props: PackageBSDF(props))

    def scene(integrator, spp, sky):
        d = {
            "type": "scene",
            "integrator": integrator,
            "sensor": {"type": "perspective", "fov": 35, "fov_axis": "y",
                       "to_world": mi.ScalarTransform4f().look_at(origin=[0, -6, 2.5], target=[0, 0, 0.8], up=[0, 0, 1]),
                       "film": {"type": "hdrfilm", "width": W, "height": H, "rfilter": {"type": "box"}},
                       "sampler": {"type": "independent", "sample_count": spp}},
            "sphere": {"type": "sphere", "center": [0, 0, 1], "radius": 1.0, "bsdf": {"type": "package_bsdf"}},
            "floor": {"type": "rectangle", "to_world": mi.ScalarTransform4f().scale([5, 5, 1]),
                      "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5, 0.5, 0.5]}}},
            "light": {"type": "point", "position": [3, -4, 5], "intensity": {"type": "rgb", "value": [40, 40, 40]}},
        }
        if sky:
            d["sky"] = {"type": "constant", "radiance": {"type": "rgb", "value": [1, 1, 1]}}
        return mi.load_dict(d)

    times = []
    for integrator, spp, sky in (({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0}, 1, False),
                                 ({"type": "path", "max_depth": 3}, 16, True)):
        s = scene(integrator, spp, sky)
        t = time.perf_counter()
        mi.render(s, spp=spp)
        times.append(time.perf_counter() - t)
    return tuple(times)


if __name__ == "__main__":
    d, m = numpy_times()
    print(f"numpy   direct 1 spp: {d:.3f} s   path 16 spp depth 3 + sky: {m:.3f} s")
    if "--numpy-only" not in sys.argv:
        d, m = mitsuba_times()
        print(f"mitsuba direct 1 spp: {d:.3f} s   path 16 spp depth 3 + sky: {m:.3f} s")
