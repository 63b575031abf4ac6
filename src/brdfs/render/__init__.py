"""Rendering the thesis's images (Figures 2.8, 3.8–3.13, 4.9, 4.11, 4.16–4.18) with the package's BRDFs.

:mod:`~brdfs.render.shapes` (analytic shapes), :mod:`~brdfs.render.materials`
(BRDF × spectrum), :mod:`~brdfs.render.sampling` (Monte Carlo proposals: the models' own samplers),
:mod:`~brdfs.render.tracer` (direct lighting and paths), :mod:`~brdfs.render.spectrum`
(eight wavelengths -> XYZ -> sRGB) and :mod:`~brdfs.render.scenes` (materials from config).

Mitsuba 3: :mod:`brdfs.render.mitsuba` (imports no Mitsuba until asked) gives the models as Dr.Jit BSDF
plugins a user's own scene can load: ``from brdfs.render.mitsuba import use_variant, register_plugins``;
``use_variant("llvm_ad_rgb"); register_plugins()``; then ``mi.load_dict({"type": "brdfs_phong_cosmin",
"n": 20})``.  The names are listed in :mod:`brdfs.render.mitsuba.plugins`.

Renderer (issue 23): Mitsuba 3 renders the figures (:mod:`brdfs.render.mitsuba`: the plugins, the
path tracer ``brdfs_path`` of :mod:`~brdfs.render.mitsuba.integrator`, scenes, noise metrics and
spectral colour; ``brdfs.artifacts._render_figures`` drives it). Issue 17 had chosen this numpy
tracer over Mitsuba's ``scalar_rgb`` variant with a Python per-sample plugin; in the JIT variant
``llvm_ad_rgb`` with plugins written in Dr.Jit the same paths run 14-100x faster, and
``benchmarks/render_old_vs_new.py`` measures both on one scene in one run.

The numpy tracer (:mod:`~brdfs.render.tracer` and its ``shapes``, ``materials``, ``sampling``,
``scenes``) is kept only as an independent oracle: it shares no code with Mitsuba (its own
intersections, its own sampling from the numpy models), so a user's model registered with
:func:`brdfs.physics.models.register` can be rendered by it without any plugin
(``tests/physics/test_models_protocol.py``), and the benchmark compares the two renderers' object
luminances within their errors. :mod:`~brdfs.render.spectrum` (eight wavelengths -> XYZ -> sRGB,
display scale) is shared by both.
"""
