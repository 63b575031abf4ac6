"""Analytic shapes of the render scenes: ray intersection, normal and tangent, vectorised over rays.

World frame: z is up. Every shape answers ``hit(o, d) -> t`` (``inf`` where the ray misses, only
``t > T_MIN``) for arrays of ray origins and unit directions (…, 3), and ``frame(p) -> (N, T)``:
the outward unit normal and a unit tangent (the direction of anisotropy, ``u`` of eq. 4.32) at
surface points ``p``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Smallest accepted ray parameter (rays start on surfaces, offset along the normal).
T_MIN = 1e-7


def normalize(v):
    """Unit vectors along the last axis."""
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def _tangent_around_z(N):
    """The azimuthal direction z × N (normalised), x where N is vertical."""
    t = np.stack([-N[..., 1], N[..., 0], np.zeros(N.shape[:-1])], axis=-1)
    length = np.linalg.norm(t, axis=-1, keepdims=True)
    return np.where(length > 1e-9, t / np.maximum(length, 1e-300), np.array([1.0, 0.0, 0.0]))


@dataclass(frozen=True)
class Sphere:
    """Sphere of ``radius`` around ``center``; the tangent runs along the parallels (z × N)."""

    center: tuple
    radius: float

    def hit(self, o, d):
        oc = o - np.asarray(self.center, float)
        b = np.einsum("...i,...i", oc, d)
        c = np.einsum("...i,...i", oc, oc) - self.radius ** 2
        disc = b * b - c
        root = np.sqrt(np.maximum(disc, 0.0))
        t_near, t_far = -b - root, -b + root
        t = np.where(t_near > T_MIN, t_near, np.where(t_far > T_MIN, t_far, np.inf))
        return np.where(disc >= 0, t, np.inf)

    def frame(self, p):
        N = (p - np.asarray(self.center, float)) / self.radius
        N = normalize(N)
        return N, _tangent_around_z(N)


@dataclass(frozen=True)
class Rectangle:
    """Horizontal rectangle z = ``height`` facing up, |x − cx| ≤ hx, |y − cy| ≤ hy; tangent x."""

    center: tuple
    half_size: tuple

    def hit(self, o, d):
        cx, cy, cz = self.center
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (cz - o[..., 2]) / d[..., 2]
        p = o + np.where(np.isfinite(t), t, 0.0)[..., None] * d
        inside = (np.abs(p[..., 0] - cx) <= self.half_size[0]) & (np.abs(p[..., 1] - cy) <= self.half_size[1])
        return np.where((t > T_MIN) & inside & np.isfinite(t), t, np.inf)

    def frame(self, p):
        shape = p.shape[:-1] + (3,)
        return np.broadcast_to([0.0, 0.0, 1.0], shape).copy(), np.broadcast_to([1.0, 0.0, 0.0], shape).copy()


@dataclass(frozen=True)
class Box:
    """Axis-aligned box around ``center`` with ``half_size``; the tangent is the next axis of each face."""

    center: tuple
    half_size: tuple

    def hit(self, o, d):
        lo = np.asarray(self.center, float) - np.asarray(self.half_size, float)
        hi = np.asarray(self.center, float) + np.asarray(self.half_size, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / d
            t1, t2 = (lo - o) * inv, (hi - o) * inv
        t1 = np.nan_to_num(t1, nan=-np.inf)
        t2 = np.nan_to_num(t2, nan=np.inf)
        t_near = np.max(np.minimum(t1, t2), axis=-1)
        t_far = np.min(np.maximum(t1, t2), axis=-1)
        t = np.where(t_near > T_MIN, t_near, t_far)
        return np.where((t_far >= t_near) & (t > T_MIN), t, np.inf)

    def frame(self, p):
        q = (p - np.asarray(self.center, float)) / np.asarray(self.half_size, float)
        axis = np.argmax(np.abs(q), axis=-1)
        N = np.zeros(p.shape)
        np.put_along_axis(N, axis[..., None], np.sign(np.take_along_axis(q, axis[..., None], -1)), -1)
        T = np.zeros(p.shape)
        np.put_along_axis(T, ((axis + 1) % 3)[..., None], 1.0, -1)
        return N, T


@dataclass(frozen=True)
class Cylinder:
    """Vertical capped cylinder: axis through ``center`` (x, y, z of the base), ``radius``, ``height``.

    The tangent runs along the parallels on the side (z × N), along x on the caps.
    """

    center: tuple
    radius: float
    height: float

    def hit(self, o, d):
        cx, cy, z0 = self.center
        ox, oy = o[..., 0] - cx, o[..., 1] - cy
        a = d[..., 0] ** 2 + d[..., 1] ** 2
        b = ox * d[..., 0] + oy * d[..., 1]
        c = ox * ox + oy * oy - self.radius ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            disc = b * b - a * c
            root = np.sqrt(np.maximum(disc, 0.0))
            candidates = [(-b - root) / a, (-b + root) / a]
            best = np.full(o.shape[:-1], np.inf)
            for t in candidates:
                z = o[..., 2] + t * d[..., 2]
                ok = (disc >= 0) & (a > 0) & (t > T_MIN) & (z >= z0) & (z <= z0 + self.height)
                best = np.where(ok & (t < best), t, best)
            for zc in (z0, z0 + self.height):
                t = (zc - o[..., 2]) / d[..., 2]
                x, y = ox + t * d[..., 0], oy + t * d[..., 1]
                ok = np.isfinite(t) & (t > T_MIN) & (x * x + y * y <= self.radius ** 2)
                best = np.where(ok & (t < best), t, best)
        return best

    def frame(self, p):
        cx, cy, z0 = self.center
        rel = p - np.array([cx, cy, z0])
        eps = 1e-6 * max(self.radius, self.height)
        top, bottom = rel[..., 2] >= self.height - eps, rel[..., 2] <= eps
        radial = np.stack([rel[..., 0], rel[..., 1], np.zeros(p.shape[:-1])], axis=-1)
        side_N = normalize(np.where(np.linalg.norm(radial, axis=-1, keepdims=True) > 0, radial, [1.0, 0.0, 0.0]))
        N = np.where(top[..., None], [0.0, 0.0, 1.0], np.where(bottom[..., None], [0.0, 0.0, -1.0], side_N))
        T = np.where((top | bottom)[..., None], [1.0, 0.0, 0.0], _tangent_around_z(side_N))
        return N, T


SHAPES = {"sphere": Sphere, "rectangle": Rectangle, "box": Box, "cylinder": Cylinder}


def make_shape(spec: dict):
    """A shape from a config entry ``{shape: sphere, center: [...], radius: ...}``."""
    spec = dict(spec)
    kind = spec.pop("shape")
    try:
        cls = SHAPES[kind]
    except KeyError:
        raise ValueError(f"unknown shape {kind!r}; known shapes: {sorted(SHAPES)}") from None
    return cls(**{k: (tuple(v) if isinstance(v, list) else v) for k, v in spec.items()})
