"""Spectral colour of the renders as section 3.8 does it: eight wavelengths, three to a pass of the RGB variant.

A spectral panel carries the eight wavelengths of :data:`brdfs.render.spectrum.WAVELENGTHS_NM` (centres
of 50 nm bins, 405 … 755 nm), where the metals' complex indices n + ik are read from the measured
data (:func:`brdfs.physics.optical_constants.complex_index`). Mitsuba's RGB variants treat the three
channels of a spectrum as independent numbers, so one RGB pass renders three *monochrome* images at
once: the eight monochrome passes of the issue become three RGB passes (405/455/505, 555/605/655,
705/755 nm), all with the same seeds (the samplers do not depend on the colour, so the passes trace
the same paths and the colour carries no extra noise). The eight channels then go to XYZ and linear
sRGB through the CIE 1931 colour-matching functions of colour-science
(:func:`brdfs.render.spectrum.linear_rgb`).

Choice, by measurement (``benchmarks/render_spectral_route.py``: Fig. 3.9's panel, 640 × 400,
64 spp in 8 passes, multijitter, caustics off; CPU seconds of ``time.process_time``, JIT included):

==========================================  ========  ======================  =========
route                                       CPU-s     p95 relative SE of Y    fireflies
==========================================  ========  ======================  =========
8 bins, three RGB passes (the third at 1/8)  11.4      0.0489                  0
``llvm_ad_spectral`` (one pass, 4 λ/path)    9.5       0.0540                  0
==========================================  ========  ======================  =========

At equal noise the two cost the same (p95² × CPU-s: 0.0273 and 0.0277): the spectral variant's one
pass is cheaper, but its sampled wavelengths add noise to Y. The eight bins are kept: they are the
thesis's colour, converted by colour-science, and add no colour noise (every pass traces the same
paths). The colours of the two routes differ, white-balanced on the gray floor, by 3-7 % on the
spheres (copper 3 %, silver 6 %, gold 6 %, aluminium 7 % in the largest sRGB channel) and by 17 % on
the tank (silver, n = 20); that difference (5 nm optical constants and Mitsuba's D65 emitters and
CIE tables against 50 nm bins, an equal-energy white and colour-science) was not resolved further.
The third pass (705/755 nm) is rendered at an eighth of the samples (:data:`PASS_SPP_FRACTION`):
it costs 2.125 instead of 3 passes' time.
"""
from __future__ import annotations

import numpy as np

from brdfs.render.spectrum import WAVELENGTHS_NM

#: The wavelengths (indices into WAVELENGTHS_NM) of the three RGB passes of a spectral panel; the
#: last pass repeats 755 nm in its third channel (discarded).
WAVELENGTH_PASSES = ((0, 1, 2), (3, 4, 5), (6, 7, 7))
#: Samples per pixel of each wavelength pass relative to the panel's: the third (705/755 nm) carries
#: 0.23 % of Y and at most 1.6 % of a linear-sRGB channel (the CIE 1931 weights of
#: :func:`brdfs.render.spectrum.luminance_weights` and ``spectral_to_rgb_matrix``), so an eighth of
#: the samples adds at most ~5 % of its own small share to a pixel's noise.
PASS_SPP_FRACTION = (1.0, 1.0, 0.125)


def pass_channels(group) -> tuple:
    """The distinct wavelength indices of a pass, in channel order (the duplicate dropped)."""
    return tuple(dict.fromkeys(group))


def metal_constants(metal: str, channels) -> tuple[np.ndarray, np.ndarray]:
    """(n, k) of ``metal`` at the wavelengths ``channels`` (indices into WAVELENGTHS_NM)."""
    from brdfs.physics import optical_constants

    ior = np.asarray(optical_constants.complex_index(metal, WAVELENGTHS_NM[list(channels)]), complex)
    return ior.real, np.abs(ior.imag)
