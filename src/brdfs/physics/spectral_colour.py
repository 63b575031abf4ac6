"""Colour of a reflectance spectrum: CIE XYZ under D65 with the CIE 1931 2° observer, then sRGB.

All colorimetric data (colour-matching functions, the D65 spectrum, the sRGB primaries) come from
the pinned PyPI package ``colour-science``; this module only resamples a reflectance spectrum onto
the observer's wavelengths (linear interpolation in wavelength, like the optical constants) and
calls ``colour.sd_to_XYZ`` (``method="Integration"``, normalised so that a perfect white
reflector has Y = 1) and ``colour.XYZ_to_RGB`` (sRGB, whose white point is D65: no adaptation).
"""
from __future__ import annotations

import numpy as np

#: The observer and illuminant of every colour of this project.
OBSERVER = "CIE 1931 2 Degree Standard Observer"
ILLUMINANT = "D65"
#: Wavelengths (nm) on which spectra are integrated: the visible range, 5 nm steps.
VISIBLE_NM = np.arange(380.0, 780.0 + 2.5, 5.0)


def colour_module():
    """The colour-science package, imported on first use (only the artifacts that need it pay for
    the import) without its side effect on numpy: it sets ``legacy='1.13'`` print options, under
    which ``str(float64)`` keeps 12 digits, and pandas writes CSV floats through ``str``."""
    options = np.get_printoptions()
    import colour

    np.set_printoptions(**options)
    return colour


def reflectance_to_xyz(wavelength_nm, reflectance) -> np.ndarray:
    """CIE XYZ (Y of a perfect white = 1) of reflectance spectra under D65, 2° observer.

    ``reflectance`` has shape (..., len(wavelength_nm)); the spectra are interpolated linearly
    onto :data:`VISIBLE_NM` (``wavelength_nm`` must cover 380–780 nm). Returns shape (..., 3).
    """
    colour = colour_module()
    wl = np.asarray(wavelength_nm, float)
    refl = np.asarray(reflectance, float)
    if wl[0] > VISIBLE_NM[0] or wl[-1] < VISIBLE_NM[-1]:
        raise ValueError(f"wavelength_nm must cover [{VISIBLE_NM[0]:g}, {VISIBLE_NM[-1]:g}] nm, "
                         f"got [{wl[0]:g}, {wl[-1]:g}]")
    flat = refl.reshape(-1, wl.size)
    resampled = np.stack([np.interp(VISIBLE_NM, wl, r) for r in flat])
    shape = colour.SpectralShape(VISIBLE_NM[0], VISIBLE_NM[-1], 5.0)
    cmfs = colour.MSDS_CMFS[OBSERVER].copy().align(shape)
    illuminant = colour.SDS_ILLUMINANTS[ILLUMINANT].copy().align(shape)
    xyz = [colour.sd_to_XYZ(colour.SpectralDistribution(r, VISIBLE_NM), cmfs, illuminant,
                            method="Integration") / 100.0 for r in resampled]
    return np.asarray(xyz).reshape(refl.shape[:-1] + (3,))


def xyz_to_linear_srgb(xyz) -> np.ndarray:
    """Linear sRGB (no transfer function) of CIE XYZ with the D65 white point."""
    return np.asarray(colour_module().XYZ_to_RGB(np.asarray(xyz, float), "sRGB", apply_cctf_encoding=False))


def reflectance_to_linear_srgb(wavelength_nm, reflectance) -> np.ndarray:
    """Linear sRGB of reflectance spectra (see :func:`reflectance_to_xyz`); a white reflector gives (1, 1, 1)."""
    return xyz_to_linear_srgb(reflectance_to_xyz(wavelength_nm, reflectance))


def encode_srgb(linear_rgb) -> np.ndarray:
    """Display sRGB in [0, 1]: clip to [0, 1], then the sRGB transfer function (IEC 61966-2-1)."""
    return np.asarray(colour_module().cctf_encoding(np.clip(np.asarray(linear_rgb, float), 0.0, 1.0), function="sRGB"))
