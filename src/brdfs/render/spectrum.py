"""Colour as section 3.8 computes it: eight wavelengths -> XYZ (colour-matching functions) -> RGB.

The visible range 380–780 nm is cut into eight 50 nm bins; a spectral render carries one channel
per bin (its centre, 405 … 755 nm, is where the complex indices are read). The CIE 1931 2°
colour-matching functions averaged over each bin give XYZ (normalised so that a flat spectrum 1
has Y = 1); XYZ goes to linear sRGB with the white of the equal-energy illuminant E adapted to
D65 (Bradford), so a flat spectrum is neutral gray. The conversion data come from
``colour-science`` (the thesis took them from its reference [22]).

Display mapping follows the material editor of section 3.6: one scale factor per image, set so
that the median of max(r, g, b) over a reference object (the diffuse gray sphere, or the
diffuse floor) is 0.5 on the display; then clipping and the sRGB transfer function.
"""
from __future__ import annotations

import functools

import numpy as np

from brdfs.physics.spectral_colour import colour_module

#: Centres of the eight 50 nm bins of 380–780 nm.
WAVELENGTHS_NM = np.arange(405.0, 760.0, 50.0)
BIN_WIDTH_NM = 50.0
#: Luminance weights of linear sRGB channels (for r, g, b scenes, eq. 3.31).
RGB_LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


@functools.lru_cache(maxsize=1)
def _spectral_matrices():
    colour = colour_module()

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    fine = np.arange(380.0, 780.0, 1.0) + 0.5
    values = np.stack([np.interp(fine, cmfs.wavelengths, cmfs.values[:, i]) for i in range(3)])
    bins = values.reshape(3, len(WAVELENGTHS_NM), -1).mean(axis=2)       # (3, 8): bin averages
    to_xyz = bins / bins[1].sum()                                        # flat spectrum 1 -> Y = 1
    white_e = np.array([1.0 / 3.0, 1.0 / 3.0])
    srgb = colour.RGB_COLOURSPACES["sRGB"]
    to_rgb = colour.XYZ_to_RGB(np.eye(3), srgb, illuminant=white_e,
                               chromatic_adaptation_transform="Bradford").T   # columns: images of X, Y, Z
    return to_xyz, to_rgb @ to_xyz


def spectral_to_xyz_matrix():
    """(3, 8): XYZ of a spectrum sampled at :data:`WAVELENGTHS_NM`."""
    return _spectral_matrices()[0]


def spectral_to_rgb_matrix():
    """(3, 8): linear sRGB of a spectrum sampled at :data:`WAVELENGTHS_NM`."""
    return _spectral_matrices()[1]


def luminance_weights(channels: int):
    """Weights giving Y from the channels: the Y row of the CMF matrix (8 channels) or sRGB's (3)."""
    if channels == len(WAVELENGTHS_NM):
        return spectral_to_xyz_matrix()[1]
    if channels == 3:
        return RGB_LUMINANCE
    raise ValueError(f"colour channels must be 8 (spectral) or 3 (rgb), got {channels}")


def linear_rgb(radiance):
    """Linear sRGB of an image (H, W, C): C = 8 wavelengths (converted) or 3 (already r, g, b)."""
    if radiance.shape[-1] == 3:
        return radiance
    return radiance @ spectral_to_rgb_matrix().T


def display_scale(rgb, reference_mask):
    """Scale so that the median of max(r, g, b) over the reference pixels shows as 0.5 (section 3.6)."""
    colour = colour_module()

    target_linear = float(colour.models.eotf_sRGB(0.5))
    level = np.median(np.max(rgb[reference_mask], axis=-1))
    if not np.isfinite(level) or level <= 0:
        raise ValueError("display_scale: the reference object is black or not in view")
    return target_linear / level


def to_display(rgb, scale):
    """8-bit sRGB image: scaled, clipped to [0, 1], sRGB-encoded, rounded."""
    colour = colour_module()

    encoded = colour.models.eotf_inverse_sRGB(np.clip(rgb * scale, 0.0, 1.0))
    return np.round(255.0 * encoded).astype(np.uint8)
