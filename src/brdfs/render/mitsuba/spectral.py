"""Spectral colour of the renders as section 3.8 does it: eight wavelengths, three colour groups along one path.

A spectral panel carries the eight wavelengths of :data:`brdfs.render.spectrum.WAVELENGTHS_NM` (centres
of 50 nm bins, 405 … 755 nm), where the metals' complex indices n + ik are read from the measured
data (:func:`brdfs.physics.optical_constants.complex_index`). Mitsuba's RGB variants treat the three
channels of a spectrum as independent numbers, so an RGB spectrum holds three *monochrome* images at
once; the eight monochrome passes of the issue become three **colour groups** (405/455/505,
555/605/655, 705/755 nm, :data:`WAVELENGTH_PASSES`) carried by *one* path: the samplers do not read the
colour, so the integrator (``brdfs_path`` with ``colour_groups = 3``) keeps one throughput per group and
turns group 0's into group g's by f_g / f_0 at every vertex (``ModelBSDF.colour_ratios``: for a metal
F_g / F_0, the lobe is not evaluated again). Group 0 is the image, groups 1 and 2 its AOVs; with the
same seed and no Russian roulette each group equals the render of that group alone to float
rounding (``test_each_colour_group_of_a_spectral_path_is_the_render_of_that_group_alone``), and
the colour carries no extra noise. Three RGB passes, one per group, traced every path three times
(2.125 times with the dim third at an eighth of the samples): on the preview's spectral figures the
groups take 1.9x less CPU at the same noise (``benchmarks/render_preview_noise.py``, one machine:
Figs. 2.8, 3.9, 4.16 at 55, 30, 143 CPU-s before, 28, 13, 76 after; every panel's p95 the same to three decimals).
The eight channels then go to XYZ and linear sRGB through the CIE 1931 colour-matching functions of
colour-science (:func:`brdfs.render.spectrum.linear_rgb`).

Choice, by measurement (``benchmarks/render_spectral_route.py``: Fig. 3.9's panel, 640 × 400,
64 spp in 8 passes, multijitter, caustics off; CPU seconds of ``time.process_time``, JIT included):

==========================================  ========  ======================  =========
route                                       CPU-s     p95 relative SE of Y    fireflies
==========================================  ========  ======================  =========
8 bins, three colour groups along one path  15.7      0.0488                  0
``llvm_ad_spectral`` (one pass, 4 λ/path)    23.0      0.0540                  0
==========================================  ========  ======================  =========

(The machine of this run is about 2.5x slower than that of the first measurement, where three RGB
passes took 11.4 CPU-s and the spectral variant 9.5.) At equal noise the colour groups cost 0.56x
the spectral variant (p95² × CPU-s: 0.0374 and 0.0671): the spectral variant's sampled wavelengths
add noise to Y, the groups add none. The eight bins are kept: they are the thesis's colour,
converted by colour-science. The colours of the two routes differ, white-balanced on the gray floor,
by 3-7 % on the spheres (copper 3 %, silver 6 %, gold 6 %, aluminium 7 % in the largest sRGB channel)
and by 17 % on the tank (silver, n = 20); that difference (5 nm optical constants and Mitsuba's D65 emitters and
CIE tables against 50 nm bins, an equal-energy white and colour-science) was not resolved further.
"""
from __future__ import annotations

import numpy as np

from brdfs.render.spectrum import WAVELENGTHS_NM

#: The wavelengths (indices into WAVELENGTHS_NM) of the three colour groups of a spectral panel; the
#: last group repeats 755 nm in its third channel (discarded).
WAVELENGTH_PASSES = ((0, 1, 2), (3, 4, 5), (6, 7, 7))


def pass_channels(group) -> tuple:
    """The distinct wavelength indices of a pass, in channel order (the duplicate dropped)."""
    return tuple(dict.fromkeys(group))


def metal_constants(metal: str, channels) -> tuple[np.ndarray, np.ndarray]:
    """(n, k) of ``metal`` at the wavelengths ``channels`` (indices into WAVELENGTHS_NM)."""
    from brdfs.physics import optical_constants

    ior = np.asarray(optical_constants.complex_index(metal, WAVELENGTHS_NM[list(channels)]), complex)
    return ior.real, np.abs(ior.imag)
