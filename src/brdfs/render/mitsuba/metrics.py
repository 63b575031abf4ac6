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

Per object (issue 42; each object ID of the panel on its own object pixels, :func:`object_noise`):

* ``p95_relative_se``: the 95th percentile of the relative standard error over the object's pixels;
* **sparkles**: the passes of an object pixel whose Y exceeds 3 × the larger of the median of that
  pixel's own P passes and the median of the mean Y of its 5 × 5 neighbourhood — an outlier both in
  its own passes (not a steady highlight) and among its neighbours (not an edge);
* **fireflies**: the object's pixels with at least one sparkle.

**Validation** (issue 42, ``benchmarks/render_preview_noise.py --validate``): each object's 8-pass
p95 against the p95 of the error measured against an independent reference at 4× the samples (in
4× the passes; the prediction of |error| is the mixture of the pixels' normals with the preview's
and the reference's own standard errors). On the preview of Figs. 3.9, 3.11 (clamped) and 4.17 the
measured error is 0.97–1.11× what the estimate predicts (the bound: 1/0.85 = 1.18), so the plain
8-pass standard deviation is used, not rescaled. Where sparkles dominate an object, it understates:
Fig. 3.11 without its clamp, 1.14× on the bust and 1.50× on the copper sphere (hundreds of
``object_fireflies``): there the estimate is a lower bound, and a figure treats its caustics
(``renders.<preset>.clamp``) rather than trust it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Chebyshev radius (px) within which an object pixel's neighbours carry the same ID.
ID_RADIUS = 2
#: An object pixel's Y is at least this fraction of the panel's 99th percentile.
DARK_FRACTION = 0.01
#: A firefly's Y exceeds this multiple of its 5 × 5 median.
FIREFLY_FACTOR = 10.0
#: A sparkle's Y exceeds this multiple of both its pixel's median pass and its 5 × 5 neighbourhood's median.
SPARKLE_FACTOR = 3.0
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
    from scipy import ndimage     # in the render job, not when the workflow plans (0.6 s)

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


def neighbourhood_median(mean_luminance: np.ndarray) -> np.ndarray:
    """The median Y of each pixel's 5 × 5 neighbourhood (clipped at the border by repetition)."""
    from scipy import ndimage

    return ndimage.median_filter(np.asarray(mean_luminance, float), size=5, mode="nearest")


def fireflies(mean_luminance: np.ndarray, mask: np.ndarray, neighbours: np.ndarray | None = None) -> np.ndarray:
    """Object pixels (``mask``) whose Y exceeds 10 × the median Y of their 5 × 5 neighbourhood
    (``neighbours``, :func:`neighbourhood_median`, computed if not given)."""
    y = np.asarray(mean_luminance, float)
    neighbours = neighbourhood_median(y) if neighbours is None else neighbours
    return mask & (y > FIREFLY_FACTOR * neighbours)


def median_pass(passes: np.ndarray) -> np.ndarray:
    """Each pixel's median over its P passes (the mean of the two middle ones for even P)."""
    count = passes.shape[0]
    middle = np.partition(passes, [(count - 1) // 2, count // 2], axis=0)
    return 0.5 * (middle[(count - 1) // 2] + middle[count // 2])


def sparkles(passes: np.ndarray, mask: np.ndarray, neighbours: np.ndarray | None = None) -> np.ndarray:
    """Per pixel, how many of its passes sparkle (module docstring); 0 outside ``mask``.
    ``passes``: (P, H, W); ``neighbours``: :func:`neighbourhood_median` of their mean, if at hand."""
    passes = np.asarray(passes, float)
    neighbours = neighbourhood_median(passes.mean(axis=0)) if neighbours is None else neighbours
    # the pixels with a pass above 3 x their neighbourhood: the only ones where the own median matters
    candidates = mask & (passes.max(axis=0) > SPARKLE_FACTOR * neighbours)
    some = passes[:, candidates]
    count = np.zeros(mask.shape, int)
    count[candidates] = (some > SPARKLE_FACTOR * np.maximum(median_pass(some), neighbours[candidates])).sum(axis=0)
    return count


@dataclass(frozen=True)
class ObjectNoise:
    """The noise figures of one object of a panel, on its own object pixels (module docstring)."""

    p95_relative_se: float
    fireflies: int
    sparkles: int
    object_pixels: int


def panel_noise(passes: np.ndarray, ids: np.ndarray) -> tuple[NoiseFigures, dict[int, ObjectNoise]]:
    """The panel's :class:`NoiseFigures` and {object ID: :class:`ObjectNoise`} (every ID with object
    pixels) from its (P, H, W) luminance passes and its ID buffer, sharing the mask, the relative
    standard errors and the neighbourhood medians."""
    passes = np.asarray(passes, float)
    mean = passes.mean(axis=0)
    mask = object_pixels(ids, mean)
    rse = relative_standard_error(passes)
    neighbours = neighbourhood_median(mean)
    p95 = float(np.percentile(rse[mask], 95.0)) if mask.any() else float("nan")
    panel = NoiseFigures(p95, int(fireflies(mean, mask, neighbours).sum()), int(mask.sum()), int(passes.shape[0]))
    count = sparkles(passes, mask, neighbours)
    objects = {}
    for k in np.unique(np.asarray(ids)[mask]):
        own = mask & (ids == k)
        objects[int(k)] = ObjectNoise(float(np.percentile(rse[own], 95.0)), int((count[own] > 0).sum()),
                                      int(count[own].sum()), int(own.sum()))
    return panel, objects


def object_noise(passes: np.ndarray, ids: np.ndarray) -> dict[int, ObjectNoise]:
    """{object ID: :class:`ObjectNoise`} for every object ID with object pixels in the panel."""
    return panel_noise(passes, ids)[1]


def noise_figures(passes: np.ndarray, ids: np.ndarray) -> NoiseFigures:
    """The three figures of one panel from its (P, H, W) luminance passes and its ID buffer."""
    return panel_noise(passes, ids)[0]
