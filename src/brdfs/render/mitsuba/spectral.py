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

Choice (against Mitsuba's ``llvm_ad_spectral``, which samples four wavelengths per path from the
continuous spectrum and converts with its own CIE tables): the thesis's colour is eight bins through
colour-science, which three RGB passes reproduce exactly; the spectral variant would add wavelength
noise to every pixel's colour and would not use colour-science. The cost is three RGB passes per
seed instead of eight monochrome ones (each pass costs what one r, g, b render of the scene costs;
the ``llvm_ad_spectral`` variant, one pass, was not measured against it).
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
