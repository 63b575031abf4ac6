"""What the explorer shows, computed by the package: numpy only, no web code.

Every view is a function of a model and a few bounded numbers, returning plain JSON-ready data:

* :func:`model_catalogue`: for every registered model, its declared parameters (ranges, the slider's
  span and scale, defaults) and categorical choices, read from the class (``param_ranges``,
  ``param_choices``, ``examples``, the dataclass defaults); nothing here is keyed by a model's name;
* :func:`build_model`: a model from the names and text values a page sends, refused with one line
  (:class:`BadRequest`) unless every name is a declared parameter and every value parses;
* :func:`albedo_curve`: a(θ_L) at ``n`` angles from 0° to 90° by :func:`brdfs.albedo` (rtol 1e-6),
  with the error bound and status of every value;
* :func:`lobe`: f and f cos θ_V in the plane of incidence at θ_L; :func:`lobe_3d`: f cos θ_V over
  the hemisphere;
* :func:`sphere`: a sphere under one directional light plus a uniform sky, as a PNG;
* :func:`half_diff_slice`: f over (θ_h, θ_d) at φ_d = 90° (Rusinkiewicz's coordinates, as Disney's
  BRDF Explorer draws its image slice), as a PNG.
"""
from __future__ import annotations

import dataclasses
import math
import re
import struct
import warnings
import zlib

import numpy as np

#: Caps on what one request may ask for (the server refuses more, naming the cap).
MAX_ANGLES = 181
MAX_IMAGE = 512
MAX_LOBE_POINTS = 721
MAX_LOBE_GRID = 91
ALBEDO_RTOL = 1e-6

#: The sphere's lighting: one directional light of irradiance E at normal incidence, plus a uniform
#: sky of radiance S over the hemisphere of every point (a Lambertian white of albedo 1 reads
#: E/π + S = 0.85 where the light falls on it head-on).
LIGHT_IRRADIANCE = 0.7 * math.pi
SKY_RADIANCE = 0.15


class BadRequest(ValueError):
    """A request the explorer refuses: one line naming the bad key and value."""


# --- the catalogue of models ---------------------------------------------------------------------

def _defaults(cls) -> dict:
    """Dataclass defaults of the model's fields (MISSING fields left out)."""
    return {f.name: f.default for f in dataclasses.fields(cls) if f.default is not dataclasses.MISSING}


def _example_values(cls, key) -> list[float]:
    return [float(ex[key]) for ex in cls.examples.values()
            if isinstance(ex.get(key), (int, float)) and not isinstance(ex.get(key), bool)]


def slider_span(interval, start, examples=()) -> tuple[float, float, bool]:
    """(lo, hi, log) of a parameter's slider: the declared range where it is finite, otherwise a span
    from a hundredth of the smallest of the start value and the examples to ten times the largest;
    logarithmic where the span covers two decades or more of positive values.  The number box beside
    the slider takes any value of the declared range.

    >>> slider_span((0.0, 1.0, False, False), 0.5)
    (0.0, 1.0, False)
    >>> slider_span((0.0, math.inf, False, False), 20.0, [10000.0])
    (0.2, 100000.0, True)
    """
    lo, hi = float(interval[0]), float(interval[1])
    known = [abs(v) for v in (start, *examples) if v is not None and v != 0] or [1.0]
    if math.isinf(lo) and math.isinf(hi):           # a free number (an angle): ± twice its size, at least 180
        half = max(180.0, 2 * max(known))
        return -half, half, False
    if math.isinf(hi):
        hi = max(10 * max(known), lo + 1)
    if lo <= 0 < hi and hi / min(known) >= 100:
        lo = min(known) / 100
    log = lo > 0 and hi / lo >= 100
    return lo, hi, log


def model_catalogue(models) -> list[dict]:
    """For every model class of ``models`` (name -> class): its controls, as the page draws them."""
    out = []
    for name, cls in models.items():
        defaults = {**_defaults(cls), **{k: v for k, v in cls.examples.get("typical", {}).items()
                                           if k in cls.param_ranges or k in cls.param_choices}}
        params = []
        for key, interval in cls.param_ranges.items():
            start = defaults.get(key)
            lo, hi, log = slider_span(interval, start, _example_values(cls, key))
            params.append({"name": key, "range": [_json_number(interval[0]), _json_number(interval[1])],
                           "open": [bool(interval[2]), bool(interval[3])],
                           "slider": [lo, hi], "log": log,
                           "default": None if start is None else float(start)})
        choices = [{"name": key, "values": [str(v) for v in values],
                    "default": str(defaults.get(key, values[0]))}
                   for key, values in getattr(cls, "param_choices", {}).items()]
        out.append({"name": name, "chapter": cls.chapter, "params": params, "choices": choices,
                    "isotropic": bool(cls.symmetric_about_incidence_plane),
                    "doc": _first_line(cls.__doc__)})
    return out


def _first_line(doc) -> str:
    """A docstring's first line without reST roles (``:class:`X``` -> X)."""
    line = (doc or "").strip().splitlines()[0] if (doc or "").strip() else ""
    return re.sub(r":\w+:`~?([^`]*)`", r"\1", line).replace("``", "")


def _json_number(x):
    x = float(x)
    return x if math.isfinite(x) else ("inf" if x > 0 else "-inf")


# --- building a model from what a page sends -----------------------------------------------------

def parse_number(key: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise BadRequest(f"{key}={text!r}: not a number") from None
    if not math.isfinite(value):
        raise BadRequest(f"{key}={text!r}: must be finite")
    return value


def model_arguments(models, name: str, values: dict[str, str]) -> dict:
    """The keyword arguments of model ``name`` from the page's text ``values``: only declared
    parameters (numeric ones parsed as numbers, categorical ones among their choices); the rest of the
    model's fields keep the typical example's values (e.g. a patch mixture's weight function)."""
    cls = models.get(name)
    if cls is None:
        raise BadRequest(f"model={name!r}: not a registered model")
    choices = getattr(cls, "param_choices", {})
    args = dict(cls.examples.get("typical", {}))
    for key, text in values.items():
        if key in cls.param_ranges:
            value = parse_number(key, text)
            interval = cls.param_ranges[key]
            if not interval.contains(value):
                raise BadRequest(f"{name}: {key}={value:g} is outside its range {interval.text()}")
            args[key] = value
        elif key in choices:
            match = [v for v in choices[key] if str(v) == text]
            if not match:
                raise BadRequest(f"{name}: {key}={text!r}: choose one of {', '.join(map(str, choices[key]))}")
            args[key] = match[0]
        else:
            raise BadRequest(f"{name}: {key!r} is not a parameter of this model "
                             f"(its parameters: {', '.join([*cls.param_ranges, *choices]) or 'none'})")
    return args


# --- the views ----------------------------------------------------------------------------------

def albedo_curve(model, n: int = 91) -> dict:
    """a(θ_L) at ``n`` angles 0°..90° (rtol 1e-6) by :func:`brdfs.albedo`: values, error bounds, status.

    Infinite values (a model that diverges at grazing) are sent as null with status ``diverged``."""
    import brdfs
    theta = np.linspace(0.0, 90.0, n)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")             # the statuses say it: the page reports them
        est = brdfs.albedo(model, theta, rtol=ALBEDO_RTOL)
    value = np.asarray(est.value, float)
    error = np.asarray(est.error, float)
    status = [str(s) for s in np.broadcast_to(np.asarray(est.status), theta.shape)]
    counts: dict[str, int] = {}
    for s in status:
        counts[s] = counts.get(s, 0) + 1
    return {"theta": theta.tolist(), "value": _finite_or_none(value), "error": _finite_or_none(error),
            "status": status, "counts": counts, "rtol": ALBEDO_RTOL,
            "evaluations": int(np.sum(est.evaluations))}


def _finite_or_none(a) -> list:
    return [float(x) if math.isfinite(x) else None for x in np.asarray(a, float).ravel()]


def lobe(model, theta_l: float, n: int = 361) -> dict:
    """f(L, V) and f cos θ_V for V in the plane of incidence, θ_V from −90° (the light's side) to 90°."""
    from brdfs.physics.geometry import light_direction
    theta_v = np.linspace(-90.0, 90.0, n)
    V = light_direction(theta_v)                    # θ_V > 0: the mirror side (x > 0), the light at x < 0
    L = light_direction(-theta_l)
    f = np.asarray(model(L, V), float)
    fcos = f * V[..., 2]
    return {"theta_v": theta_v.tolist(), "f": _finite_or_none(f), "fcos": _finite_or_none(fcos)}


def lobe_3d(model, theta_l: float, n_theta: int = 24, n_phi: int = 48) -> dict:
    """f cos θ_V over the hemisphere at θ_L: rows θ_V from 0° to 90°, columns φ_V from 0° (the
    mirror side of the plane of incidence) to 360°, for the page's 3-D lobe."""
    from brdfs.physics.geometry import direction, light_direction
    theta_v = np.linspace(0.0, 90.0, n_theta)
    phi_v = np.linspace(0.0, 360.0, n_phi + 1)
    V = direction(theta_v[:, None], phi_v[None, :])
    f = np.asarray(model(light_direction(-theta_l), V), float)
    return {"theta_v": theta_v.tolist(), "phi_v": phi_v.tolist(),
            "fcos": [_finite_or_none(row) for row in f * V[..., 2]]}


def _sky_albedo(curve: dict, cos_v):
    """a(θ_V) read off the albedo curve (linear in θ), the last finite value where it diverges."""
    theta = np.asarray(curve["theta"], float)
    value = np.array([np.nan if v is None else v for v in curve["value"]])
    finite = np.isfinite(value)
    theta_v = np.degrees(np.arccos(np.clip(cos_v, 0.0, 1.0)))
    return np.interp(theta_v, theta[finite], value[finite])


def sphere(model, curve: dict, theta_l: float, size: int = 256) -> bytes:
    """:func:`sphere_rgb` as a PNG."""
    return png(sphere_rgb(model, curve, theta_l, size))


def sphere_rgb(model, curve: dict, theta_l: float, size: int = 256) -> np.ndarray:
    """A sphere seen along −z, lit by a directional light at θ_L from the view direction (from the
    left) of irradiance :data:`LIGHT_IRRADIANCE`, by evaluation (E f cos θ_L), plus a uniform sky of
    radiance :data:`SKY_RADIANCE` through the albedo (S a(θ_V): the reflected radiance under a uniform
    sky is a(θ_V) for a reciprocal BRDF).  Clipped to [0, 1], sRGB-encoded grey: (size, size, 3) uint8."""
    c = (np.arange(size) + 0.5) / size * 2 - 1
    x, y = np.meshgrid(c, -c)
    inside = x * x + y * y < 1.0
    n = np.stack([x[inside], y[inside], np.sqrt(1.0 - x[inside] ** 2 - y[inside] ** 2)], -1)
    # a tangent frame per point: t along the world's x projected on the tangent plane
    t = np.array([1.0, 0.0, 0.0]) - n[:, :1] * n
    t_len = np.linalg.norm(t, axis=-1, keepdims=True)
    t = np.where(t_len > 1e-9, t / np.maximum(t_len, 1e-300), np.array([0.0, 1.0, 0.0]))
    b = np.cross(n, t)
    light = np.array([-math.sin(math.radians(theta_l)), 0.0, math.cos(math.radians(theta_l))])
    view = np.array([0.0, 0.0, 1.0])
    local = lambda w: np.stack([t @ w, b @ w, n @ w], -1)        # noqa: E731
    L, V = local(light), local(view)
    f = np.nan_to_num(np.asarray(model(L, V), float), nan=0.0, posinf=0.0)
    radiance = LIGHT_IRRADIANCE * f * np.maximum(L[:, 2], 0.0) + SKY_RADIANCE * _sky_albedo(curve, V[:, 2])
    image = np.zeros((size, size))
    image[inside] = radiance
    background = np.zeros((size, size), bool)
    background[~inside] = True
    grey = _srgb(np.clip(image, 0.0, 1.0))
    rgb = np.repeat(grey[..., None], 3, -1)
    rgb[background] = (40, 44, 52)
    return rgb


def half_diff_directions(size: int):
    """(θ_h, θ_d, L, V) on a size × size grid: θ_h along x (0°..90°), θ_d along y (90° at the top row
    .. 0°), φ_h = 0 and φ_d = 90°: the difference vector (0, sin θ_d, cos θ_d) about H, rotated by θ_h
    about y so that H = (sin θ_h, 0, cos θ_h), and V = 2 (L·H) H − L (Rusinkiewicz 1998)."""
    th = np.radians((np.arange(size) + 0.5) / size * 90.0)
    td = np.radians((np.arange(size)[::-1] + 0.5) / size * 90.0)
    theta_h, theta_d = np.meshgrid(th, td)
    ch, sh = np.cos(theta_h), np.sin(theta_h)
    dy, dz = np.sin(theta_d), np.cos(theta_d)
    L = np.stack([sh * dz, dy, ch * dz], -1)
    H = np.stack([sh, np.zeros_like(sh), ch], -1)
    V = 2 * np.sum(L * H, -1, keepdims=True) * H - L
    return theta_h, theta_d, L, V


def half_diff_slice(model, size: int = 128) -> bytes:
    """f over (θ_h, θ_d) at φ_d = 90° (:func:`half_diff_directions`), as BRDF Explorer's image slice:
    log-scaled over four decades below the image's maximum, in a viridis-like map; black where L or V
    is below the horizon or f vanishes."""
    _, _, L, V = half_diff_directions(size)
    f = np.nan_to_num(np.asarray(model(L, V), float), nan=0.0, posinf=0.0)
    valid = (L[..., 2] > 0) & (V[..., 2] > 0) & (f > 0)
    rgb = np.zeros((size, size, 3), np.uint8)
    if valid.any():
        top = np.log10(f[valid].max())
        level = np.clip((np.log10(np.where(valid, f, 1e-300)) - (top - 4)) / 4, 0, 1)
        rgb[valid] = _viridis(level[valid])
    return png(rgb)


_VIRIDIS = np.array([[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]], float)


def _viridis(level):
    x = np.asarray(level) * (len(_VIRIDIS) - 1)
    i = np.clip(np.floor(x).astype(int), 0, len(_VIRIDIS) - 2)
    w = (x - i)[..., None]
    return ((1 - w) * _VIRIDIS[i] + w * _VIRIDIS[i + 1]).round().astype(np.uint8)


def _srgb(linear):
    s = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)
    return (s * 255 + 0.5).astype(np.uint8)


def png(rgb) -> bytes:
    """An 8-bit RGB PNG of an (h, w, 3) uint8 array (zlib, no filter)."""
    rgb = np.ascontiguousarray(rgb, np.uint8)
    h, w, _ = rgb.shape
    raw = np.concatenate([np.zeros((h, 1), np.uint8), rgb.reshape(h, 3 * w)], 1).tobytes()

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
