"""Rendering the thesis's images (Figures 2.8, 3.8–3.13, 4.11, 4.16–4.18) with the package's BRDFs.

:mod:`~brdfs.render.shapes` (analytic shapes), :mod:`~brdfs.render.materials`
(BRDF × spectrum), :mod:`~brdfs.render.sampling` (Monte Carlo proposals: the models' own samplers),
:mod:`~brdfs.render.tracer` (direct lighting and paths), :mod:`~brdfs.render.spectrum`
(eight wavelengths -> XYZ -> sRGB) and :mod:`~brdfs.render.scenes` (materials from config).

Mitsuba 3: :mod:`brdfs.render.mitsuba` (imports no Mitsuba until asked) gives the models as Dr.Jit BSDF
plugins a user's own scene can load: ``from brdfs.render.mitsuba import use_variant, register_plugins``;
``use_variant("llvm_ad_rgb"); register_plugins()``; then ``mi.load_dict({"type": "brdfs_phong_cosmin",
"n": 20})``.  The names are listed in :mod:`brdfs.render.mitsuba.plugins`.

Renderer decision (issue #17), by measurement (``benchmarks/render_mitsuba_vs_numpy.py``): one
scene — a new-model sphere (phong_cosmin, n = 20) on a diffuse floor, one point light, 160 × 120 —
rendered (a) direct only, 1 sample per pixel, (b) with daylight, paths of depth 3, 16 per pixel:

=================================================  ==========  ===========================
renderer                                           (a) direct  (b) paths 16 spp + daylight
=================================================  ==========  ===========================
Mitsuba 3.9.1 ``scalar_rgb``, BRDF as Python BSDF   0.12 s      5.7 s
this module (numpy, vectorised over rays)           0.035 s     1.1 s
=================================================  ==========  ===========================

(unloaded machine; under a load of ~11 on 2 cores: 0.22–0.25 s / 8.7–9.2 s against
0.07 s / 2.3 s.) Mitsuba's scalar variant calls the Python plugin once per sample, which is where
its time goes, and its plugin sampled the cosine only; the numpy tracer calls each BRDF once per
batch of rays, carries the eight wavelengths of a spectral image in the same pass (Mitsuba
``scalar_rgb`` would need eight monochrome passes or a spectral variant) and uses the models'
own samplers. It is also a dependency less. Hence the numpy tracer.
"""
