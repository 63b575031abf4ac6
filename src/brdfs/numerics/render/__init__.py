"""Rendering the thesis's images (Figures 2.8, 3.8–3.13, 4.11, 4.16–4.18) with the package's BRDFs.

:mod:`~brdfs.numerics.render.shapes` (analytic shapes), :mod:`~brdfs.numerics.render.materials`
(BRDF × spectrum), :mod:`~brdfs.numerics.render.sampling` (Monte Carlo proposals),
:mod:`~brdfs.numerics.render.tracer` (direct lighting and paths), :mod:`~brdfs.numerics.render.spectrum`
(eight wavelengths -> XYZ -> sRGB) and :mod:`~brdfs.numerics.render.scenes` (scenes from config).
"""
