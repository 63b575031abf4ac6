"""Noise figures of a rendered panel, as issue 23 defines them (numpy only).

A panel is rendered as P ≥ 8 independently seeded passes; ``luminance`` is their (P, H, W) stack of
per-pixel luminance Y, ``ids`` the (H, W) object ID buffer (the AOV ``id`` of ``brdfs_path``:
1-based shape index, averaged over the pixel's samples, 0 for the background).

* **Object pixels**: the ID is that of an object (> 0) and equals the ID of every pixel within
  2 px (the 5 × 5 neighbourhood, clipped at the border), and the mean luminance Y is at least 1 %
  of the panel's 99th percentile of Y.
* **Relative standard error** of a pixel's mean: the standard deviation over the passes (ddof 1),
  divided by √P and by the mean.
* **Fireflies**: object pixels whose Y exceeds 10 × the median Y of their 5 × 5 neighbourhood.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

#: Chebyshev radius (px) within which an object pixel's neighbours carry the same ID.
ID_RADIUS = 2
#: An object pixel's Y is at least this fraction of the panel's 99th percentile.
DARK_FRACTION = 0.01
#: A firefly's Y exceeds this multiple of its 5 × 5 median.
FIREFLY_FACTOR = 10.0
#: Fewest independently seeded passes the relative standard error is taken over.
MIN_PASSES = 8


@dataclass(frozen=True)
class NoiseFigures:
    """The three figures of a panel: p95 of the relative SE on object pixels, fireflies, object pixels."""

    p95_relative_se: float
    fireflies: int
    object_pixels: int
    passes: int


def _window(radius: int) -> int:
    return 2 * radius + 1


def uniform_id(ids: np.ndarray, radius: int | None = None) -> np.ndarray:
    """True where every pixel within ``radius`` px (default :data:`ID_RADIUS`; clipped at the border)
    has the pixel's ID."""
    size = _window(ID_RADIUS if radius is None else radius)
    low = ndimage.minimum_filter(ids, size=size, mode="nearest")
    high = ndimage.maximum_filter(ids, size=size, mode="nearest")
    return (low == ids) & (high == ids)


def object_pixels(ids: np.ndarray, mean_luminance: np.ndarray) -> np.ndarray:
    """The object pixels of a panel (module docstring): (H, W) bool."""
    ids = np.asarray(ids, float)
    y = np.asarray(mean_luminance, float)
    if ids.shape != y.shape:
        raise ValueError(f"ids shape {ids.shape} != luminance shape {y.shape}")
    bright = y >= DARK_FRACTION * np.percentile(y, 99.0)
    return (ids > 0) & (ids == np.round(ids)) & uniform_id(ids) & bright


def relative_standard_error(passes: np.ndarray) -> np.ndarray:
    """std over passes (ddof 1) / √P / mean, per pixel; inf where the mean is 0. ``passes``: (P, H, W)."""
    passes = np.asarray(passes, float)
    count = passes.shape[0]
    if count < 2:
        raise ValueError(f"relative_standard_error: {count} pass(es); needs >= 2 (the issue asks for >= {MIN_PASSES})")
    mean = passes.mean(axis=0)
    se = passes.std(axis=0, ddof=1) / np.sqrt(count)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(mean > 0, se / mean, np.inf)


def fireflies(mean_luminance: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Object pixels (``mask``) whose Y exceeds 10 × the median Y of their 5 × 5 neighbourhood."""
    y = np.asarray(mean_luminance, float)
    median = ndimage.median_filter(y, size=5, mode="nearest")
    return mask & (y > FIREFLY_FACTOR * median)


def noise_figures(passes: np.ndarray, ids: np.ndarray) -> NoiseFigures:
    """The three figures of one panel from its (P, H, W) luminance passes and its ID buffer."""
    passes = np.asarray(passes, float)
    mean = passes.mean(axis=0)
    mask = object_pixels(ids, mean)
    rse = relative_standard_error(passes)[mask]
    p95 = float(np.percentile(rse, 95.0)) if rse.size else float("nan")
    return NoiseFigures(p95, int(fireflies(mean, mask).sum()), int(mask.sum()), int(passes.shape[0]))
