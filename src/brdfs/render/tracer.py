"""A small vectorised ray tracer of analytic shapes: direct lighting and Monte Carlo paths.

The renderer models no more than a scene needs:

* **direct** (:func:`render` with ``sky = None`` and ``depth = 1``): point lights only; each pixel
  is L = Σ_lights f(L, V) I cos θ_L / r² with a shadow ray (eq. 2.3 per light), a deterministic
  BRDF evaluation at the pixel centre (``spp = 1``) or at jittered positions;
* **Monte Carlo** (``sky`` given or ``depth > 1``): paths from the eye; at every vertex the point
  lights are added by explicit connection (next-event estimation, exact for point lights), the
  path continues by importance sampling the material with its models' own samplers
  (:mod:`brdfs.render.sampling`; each bounce draws the numbers the most demanding one needs, plus one
  to pick the proposal),
  and a path leaving the scene collects the homogeneous daylight S (section 3.6, eq. 3.32).
  Because the sky is only reached by sampling and the point lights only by connection, no
  contribution is counted twice and the estimator is unbiased up to the path-depth truncation.

All arrays are (…, 3) world vectors with z up; spectra have C channels (wavelengths or r, g, b).
The random stream is ``numpy.random.default_rng(seed)`` consumed in a fixed order, so the
same scene and seed give the same pixels bit for bit.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from brdfs.render.shapes import normalize

#: Rays traced at once (bounds memory: ~ CHUNK × C × 8 bytes per array).
CHUNK = 1 << 15
#: Offset of secondary ray origins along the normal, relative to the scene size 1.
RAY_OFFSET = 1e-6


@dataclass(frozen=True)
class PointLight:
    """Isotropic point light: radiant intensity ``intensity`` (per channel) at ``position``."""

    position: tuple
    intensity: np.ndarray


@dataclass(frozen=True)
class Camera:
    """Pinhole camera at ``eye`` looking at ``target``; ``fov_deg`` is the vertical field of view."""

    eye: tuple
    target: tuple
    width: int
    height: int
    fov_deg: float = 30.0
    up: tuple = (0.0, 0.0, 1.0)

    def rays(self, jitter):
        """Origins and unit directions of the rays through the pixels + ``jitter`` (H, W, 2) in [0, 1)."""
        eye = np.asarray(self.eye, float)
        forward = normalize(np.asarray(self.target, float) - eye)
        right = normalize(np.cross(forward, np.asarray(self.up, float)))
        up = np.cross(right, forward)
        half_h = np.tan(np.radians(self.fov_deg) / 2.0)
        half_w = half_h * self.width / self.height
        j, i = np.meshgrid(np.arange(self.width), np.arange(self.height))
        x = (2.0 * (j + jitter[..., 0]) / self.width - 1.0) * half_w
        y = (1.0 - 2.0 * (i + jitter[..., 1]) / self.height) * half_h
        d = normalize(forward + x[..., None] * right + y[..., None] * up)
        return np.broadcast_to(eye, d.shape), d


@dataclass(frozen=True)
class SceneObject:
    shape: object
    material: object
    label: str


@dataclass
class Scene:
    """Objects, point lights and an optional homogeneous sky S (radiance per channel, all directions)."""

    objects: list
    lights: list = field(default_factory=list)
    sky: np.ndarray | None = None
    background: np.ndarray | None = None

    @property
    def channels(self):
        return self.objects[0].material.channels

    @property
    def sample_dimension(self) -> int:
        """Uniform numbers a bounce draws per path for the materials' samplers (the most any needs)."""
        return max(obj.material.sample_dimension for obj in self.objects)

    def intersect(self, o, d):
        """Nearest hit: (t, object index; −1 where nothing is hit)."""
        t_best = np.full(o.shape[:-1], np.inf)
        index = np.full(o.shape[:-1], -1)
        for k, obj in enumerate(self.objects):
            t = obj.shape.hit(o, d)
            closer = t < t_best
            t_best = np.where(closer, t, t_best)
            index = np.where(closer, k, index)
        return t_best, index

    def occluded(self, o, d, distance):
        """True where something lies on the segment of length ``distance`` from ``o`` along ``d``."""
        blocked = np.zeros(o.shape[:-1], bool)
        for obj in self.objects:
            blocked |= obj.shape.hit(o, d) < distance * (1.0 - 1e-9)
        return blocked


def _local(v, N, T, B):
    """World vectors in the shading frame (T, B, N)."""
    return np.stack([np.einsum("...i,...i", v, T), np.einsum("...i,...i", v, B), np.einsum("...i,...i", v, N)], -1)


def _world(v, N, T, B):
    return v[..., :1] * T + v[..., 1:2] * B + v[..., 2:3] * N


def _shading_frame(scene, p, index, d):
    """Unit normal N (facing the incoming ray), tangent T and bitangent B at the hits."""
    N = np.zeros(p.shape)
    T = np.zeros(p.shape)
    for k, obj in enumerate(scene.objects):
        sel = index == k
        if np.any(sel):
            N[sel], T[sel] = obj.shape.frame(p[sel])
    flip = np.einsum("...i,...i", N, d) > 0
    N = np.where(flip[..., None], -N, N)
    T = normalize(T - np.einsum("...i,...i", T, N)[..., None] * N)
    return N, T, np.cross(N, T)


def _evaluate(scene, index, L, V):
    """BRDF per channel at each hit, by object."""
    f = np.zeros(L.shape[:-1] + (scene.channels,))
    for k, obj in enumerate(scene.objects):
        sel = index == k
        if np.any(sel):
            f[sel] = obj.material.f(L[sel], V[sel])
    return f


def _direct(scene, p, index, N, T, B, Vloc):
    """Σ_lights f(L, V) I cos θ_L / r², with shadow rays (eq. 2.3); 0 where nothing is hit."""
    out = np.zeros(p.shape[:-1] + (scene.channels,))
    hit = index >= 0
    if not np.all(hit):
        out[hit] = _direct(scene, p[hit], index[hit], N[hit], T[hit], B[hit], Vloc[hit])
        return out
    origin = p + RAY_OFFSET * N           # shadow rays only; the shading geometry is at p
    for light in scene.lights:
        to_light = np.asarray(light.position, float) - p
        r2 = np.einsum("...i,...i", to_light, to_light)
        Lw = to_light / np.sqrt(r2)[..., None]
        Lloc = _local(Lw, N, T, B)
        from_origin = np.asarray(light.position, float) - origin
        distance = np.sqrt(np.einsum("...i,...i", from_origin, from_origin))
        lit = (Lloc[..., 2] > 0) & ~scene.occluded(origin, from_origin / distance[..., None], distance)
        f = _evaluate(scene, index, Lloc, Vloc)
        out += np.where(lit[..., None], f * (Lloc[..., 2] / r2)[..., None] * np.asarray(light.intensity, float), 0.0)
    return out


def _sample_materials(scene, index, Vloc, u, u_pick):
    L = np.zeros(Vloc.shape)
    w = np.zeros(Vloc.shape[:-1] + (scene.channels,))
    for k, obj in enumerate(scene.objects):
        sel = index == k
        if np.any(sel):
            L[sel], w[sel] = obj.material.sample(Vloc[sel], u[sel], u_pick[sel])
    return L, w


def trace(scene, o, d, rng, depth):
    """Radiance (…, C) along rays ``o, d`` and the object index of the first hit."""
    C = scene.channels
    radiance = np.zeros(o.shape[:-1] + (C,))
    throughput = np.ones(o.shape[:-1] + (C,))
    alive = np.ones(o.shape[:-1], bool)
    first_index = None
    for bounce in range(depth):
        t, index = scene.intersect(o, d)
        if first_index is None:
            first_index = index.copy()
        escaped = alive & (index < 0)
        sky = scene.sky if (bounce > 0 or scene.background is None) else scene.background
        if sky is not None:
            radiance += np.where(escaped[..., None], throughput * np.asarray(sky, float), 0.0)
        alive &= index >= 0
        if not np.any(alive):
            break
        p = o + np.where(alive, t, 0.0)[..., None] * d
        N, T, B = _shading_frame(scene, p, np.where(alive, index, -1), d)
        Vloc = _local(-d, N, T, B)
        idx = np.where(alive, index, -1)
        radiance += np.where(alive[..., None], throughput * _direct(scene, p, idx, N, T, B, Vloc), 0.0)
        if bounce == depth - 1 or scene.sky is None and depth == 1:
            break
        k = scene.sample_dimension           # 2 for most materials: u then has 3 numbers, as always
        u = rng.random(o.shape[:-1] + (k + 1,))
        Lloc, weight = _sample_materials(scene, idx, Vloc, u[..., :k], u[..., k])
        throughput = throughput * weight
        alive &= np.any(weight > 0, axis=-1)
        o = p + RAY_OFFSET * N
        d = _world(Lloc, N, T, B)
    return radiance, first_index


@dataclass(frozen=True)
class Image:
    """A rendered image: per-pixel mean radiance (H, W, C), the per-pixel variance of the mean of
    the scalar statistic ``radiance @ stat_weights`` (H, W), and the object index of the pixel centre."""

    radiance: np.ndarray
    variance_of_mean: np.ndarray
    index: np.ndarray
    spp: int
    stat_weights: np.ndarray


def render(scene, camera, spp=1, depth=1, seed=0, stat_weights=None, jitter=True):
    """Render ``scene`` with ``spp`` jittered paths per pixel (``spp = 1``: the pixel centre, no noise
    when the scene is direct-only) and at most ``depth`` path vertices.

    ``stat_weights`` (C,) define the scalar per-pixel statistic whose variance is kept (default:
    the channel mean), e.g. the luminance weights of the channels. ``jitter = False`` sends every
    path through the pixel centre (the tests compare pixels with values at one direction).
    """
    rng = np.random.default_rng(seed)
    H, W, C = camera.height, camera.width, scene.channels
    total = np.zeros((H * W, C))
    w = np.full(C, 1.0 / C) if stat_weights is None else np.asarray(stat_weights, float)
    total_sq = np.zeros(H * W)
    for s in range(spp):
        offsets = rng.random((H, W, 2)) if (jitter and spp > 1) else np.full((H, W, 2), 0.5)
        o, d = camera.rays(offsets)
        o, d = o.reshape(-1, 3), d.reshape(-1, 3)
        for start in range(0, H * W, CHUNK):
            part = slice(start, start + CHUNK)
            value, _ = trace(scene, o[part], d[part], rng, depth)
            total[part] += value
            total_sq[part] += (value @ w) ** 2
    mean = total / spp
    y = mean @ w
    var_mean = np.maximum(total_sq / spp - y * y, 0.0) / (spp - 1) if spp > 1 else np.zeros_like(y)
    o, d = camera.rays(np.full((H, W, 2), 0.5))
    _, index = scene.intersect(o.reshape(-1, 3), d.reshape(-1, 3))
    return Image(mean.reshape(H, W, C), var_mean.reshape(H, W), index.reshape(H, W), spp, w)


def object_statistics(image, scene):
    """Per object (and the background): pixel count, the mean over its pixels of the statistic
    ``radiance @ stat_weights`` and the Monte Carlo standard error of that mean, sqrt(Σ var_p) / n."""
    value = image.radiance @ image.stat_weights
    rows = []
    labels = [obj.label for obj in scene.objects] + ["background"]
    for k, label in enumerate(labels):
        sel = image.index == (k if k < len(scene.objects) else -1)
        n = int(sel.sum())
        if n == 0:
            continue
        rows.append({"object": label, "pixels": n, "radiance": float(value[sel].mean()),
                     "radiance_err": float(np.sqrt(image.variance_of_mean[sel].sum()) / n)})
    return rows
