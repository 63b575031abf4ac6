"""Building blocks of the models' importance samplers (``BRDF.sample`` / ``BRDF.pdf``).

Conventions (N = (0, 0, 1)):

* A sampler maps uniform numbers ``u`` (…, k) to directions V (…, 3), a weight f cos θ_V / pdf and
  the pdf per solid angle of V.  A *rejected* sample (a direction the proposal puts below the
  horizon, a point outside the unit disk, a half vector facing away from L, a Russian-roulette
  miss) is returned as V = −N with weight 0 and pdf 0.  Its probability is the mass the pdf lacks:
  ∫_Ω pdf dω = 1 − P(rejected) (a *sub-probability* density; the estimator Σ weight / M stays
  unbiased because f = 0 where the sampler never goes).
* Projected-disk samplers (chapter 4) draw a point x of the unit disk; V = (x, √(1 − |x|²)) (eq. 4.17),
  and a density q per unit area of the disk is q · cos θ_V per solid angle (cos θ_V dω = dA).

Functions here are vectorised over leading axes and allocate no random numbers of their own, but
for :func:`lens_point_by_rejection` (the thesis's "repeat ... until found"), which draws from the
generator it is given as many numbers as its tries take.
"""
from __future__ import annotations

import numpy as np

from brdfs.physics import patch_geometry as patch
from brdfs.physics.geometry import r_dot_v

#: The direction a rejected sample is reported as.
REJECTED = np.array([0.0, 0.0, -1.0])


def broadcast_directions(L, u):
    """L broadcast to the sample shape of ``u`` (…, k) → (…, 3), and u as an array."""
    u = np.asarray(u, float)
    L = np.broadcast_to(np.asarray(L, float), u.shape[:-1] + (3,))
    return L, u


def orthonormal_basis(axis):
    """Two unit vectors (e1, e2) completing ``axis`` (…, 3) to a right-handed frame
    (Duff et al. 2017, "Building an orthonormal basis, revisited")."""
    x, y, z = axis[..., 0], axis[..., 1], axis[..., 2]
    sign = np.where(z >= 0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    e1 = np.stack([1.0 + sign * x * x * a, sign * b, -sign * x], -1)
    e2 = np.stack([b, sign + y * y * a, -y], -1)
    return e1, e2


def around_axis(axis, cos_a, sin_a, phi):
    """The direction at polar angle a (cos, sin) and azimuth φ about ``axis``."""
    e1, e2 = orthonormal_basis(axis)
    return (sin_a * np.cos(phi))[..., None] * e1 + (sin_a * np.sin(phi))[..., None] * e2 + cos_a[..., None] * axis


def power_cosine(u1, n):
    """(cos a, sin a) with density (n + 1)/(2π) cos^n a per solid angle about an axis (eq. 3.20):
    cos a = u1^{1/(n+1)}; sin a from expm1 so that n = 512 keeps its digits."""
    log_u = np.log(np.maximum(u1, np.finfo(float).tiny))
    cos_a = np.exp(log_u / (n + 1.0))
    sin_a = np.sqrt(np.maximum(-np.expm1(2.0 * log_u / (n + 1.0)), 0.0))
    return cos_a, sin_a


def power_cosine_pdf(cos_a, n):
    """(n + 1)/(2π) (cos a)^n for cos a > 0 (eq. 3.19)."""
    return (n + 1.0) / (2.0 * np.pi) * np.where(cos_a > 0, np.maximum(cos_a, 0.0) ** n, 0.0)


def mirror_direction(L):
    """R = 2 (N·L) N − L."""
    return L * np.array([-1.0, -1.0, 1.0])


def reflect_about(L, H):
    """V = 2 (L·H) H − L and L·H."""
    lh = np.sum(L * H, axis=-1)
    return 2.0 * lh[..., None] * H - L, lh


def half_vector_jacobian(L, V):
    """(N·H, 1/(4 V·H)) of V's half vector: dω_H/dω_V = 1/(4 V·H) (Walter et al. 2007, eq. 14)."""
    h = L + V
    norm = np.linalg.norm(h, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        vh = np.sum(V * h, axis=-1) / norm
        return h[..., 2] / norm, np.where(vh > 0, 1.0 / (4.0 * vh), 0.0)


def reflect_half_vectors(L, H):
    """V = 2 (L·H) H − L for half vectors H drawn about N; V = −N (rejected) where L·H ≤ 0 or V lies
    below the horizon."""
    V, lh = reflect_about(L, H)
    return np.where(((lh > 0) & (V[..., 2] > 0))[..., None], V, REJECTED)


def half_vector_sample(L, u, n):
    """The half-vector sampler of a lobe (N·H)^n: H with density (n + 1)/(2π) (N·H)^n about N
    (:func:`power_cosine`), V = 2 (L·H) H − L (:func:`reflect_half_vectors`); ``u`` (…, 2).
    Its density is :func:`half_vector_pdf`; its mass is P(V above the horizon) < 1."""
    L, u = broadcast_directions(L, u)
    cos_d, sin_d = power_cosine(u[..., 0], n)
    phi = 2.0 * np.pi * u[..., 1]
    H = np.stack([sin_d * np.cos(phi), sin_d * np.sin(phi), cos_d], -1)
    return reflect_half_vectors(L, H)


def half_vector_pdf(L, V, n):
    """Density per solid angle of V of :func:`half_vector_sample`: (n + 1)/(2π) (N·H)^n / (4 V·H)."""
    nh, jacobian = half_vector_jacobian(L, V)
    return power_cosine_pdf(nh, n) * jacobian


def mirror_lobe_sample(L, u, n):
    """The mirror-frame sampler of a lobe (R·V)^n: V with density (n + 1)/(2π) (R·V)^n about the
    mirror direction R (eq. 3.20, Lafortune & Willems 1994); V below the horizon is rejected
    (V = −N).  ``u`` (…, 2); its density is :func:`mirror_lobe_pdf`."""
    L, u = broadcast_directions(L, u)
    cos_a, sin_a = power_cosine(u[..., 0], n)
    V = around_axis(mirror_direction(L), cos_a, sin_a, 2.0 * np.pi * u[..., 1])
    return np.where((V[..., 2] > 0)[..., None], V, REJECTED)


def mirror_lobe_pdf(L, V, n):
    """Density per solid angle of V of :func:`mirror_lobe_sample`: (n + 1)/(2π) (R·V)^n (eq. 3.19)."""
    return power_cosine_pdf(r_dot_v(L, V), n)


def disk_to_direction(x, y):
    """V = (x, y, √(1 − x² − y²)) (eq. 4.17); points outside the unit disk are rejected."""
    r2 = x * x + y * y
    V = np.stack([x, y, np.sqrt(np.maximum(1.0 - r2, 0.0))], -1)
    return np.where((r2 < 1.0)[..., None], V, REJECTED)


def uniform_in_circle(cx, cy, radius, u1, u2):
    """Uniform points in the circle C((cx, cy), radius): the area-preserving polar map r = R √u1."""
    r, phi = radius * np.sqrt(u1), 2.0 * np.pi * u2
    return cx + r * np.cos(phi), cy + r * np.sin(phi)


def _half_disk_primitive(x, r):
    """P_r(x) = ∫ 2√(r² − t²) dt = x √(r² − x²) + r² asin(x/r), |x| ≤ r."""
    x = np.clip(x, -r, r)
    return x * np.sqrt(np.maximum((r - x) * (r + x), 0.0)) + r * r * np.arcsin(np.clip(x / r, -1.0, 1.0))


def uniform_in_lens(cx, cy, R, u1, u2, iterations=54):
    """Uniform points in C(c, R) ∩ unit disk, c = (cx, cy) = V'_P (section 4.2.4, the general case).

    The thesis draws them by rejection ("repeat until found"); here by inverting the area: with t
    the coordinate along c/|c| and d = |c|, the chord of the lens at t has half-length
    √(R² − (t − d)²) left of the common chord t* = (1 + d² − R²)/(2d) and √(1 − t²) right of it,
    so the area left of t is P_R(min(t, t*) − d) − P_R(−R) + P_1(max(t, t*)) − P_1(t*); t solves
    area(t) = u1 · area (bisection), the point is uniform on the chord at t (u2).  The special
    cases — circle inside the disk (the area-preserving map of a circle) and disk inside the
    circle (the cosine distribution) — are taken as such.  Same distribution as rejection, from
    exactly two numbers.
    """
    cx, cy, R, u1, u2 = np.broadcast_arrays(*(np.asarray(a, float) for a in (cx, cy, R, u1, u2)))
    d = np.hypot(cx, cy)
    inside = d + R <= 1.0
    covers = R >= 1.0 + d
    x_in, y_in = uniform_in_circle(cx, cy, R, u1, u2)
    x_cos, y_cos = uniform_in_circle(0.0, 0.0, 1.0, u1, u2)
    general = ~(inside | covers)
    dg = np.where(general, d, 1.0)
    Rg = np.where(general, R, 1.0)
    t_star = (1.0 + (dg - Rg) * (dg + Rg)) / (2.0 * dg)
    lo, hi = dg - Rg, np.ones_like(dg)
    base_R, base_1 = _half_disk_primitive(-Rg, Rg), _half_disk_primitive(t_star, 1.0)

    def area_left(t):
        return (_half_disk_primitive(np.minimum(t, t_star) - dg, Rg) - base_R
                + _half_disk_primitive(np.maximum(t, t_star), 1.0) - base_1)

    target = u1 * area_left(hi)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        below = area_left(mid) < target
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    t = 0.5 * (lo + hi)
    half = np.where(t < t_star, np.sqrt(np.maximum(Rg * Rg - (t - dg) ** 2, 0.0)),
                    np.sqrt(np.maximum(1.0 - t * t, 0.0)))
    s = (2.0 * u2 - 1.0) * half
    ex, ey = np.where(general, cx / dg, 1.0), np.where(general, cy / dg, 0.0)
    x_gen, y_gen = t * ex - s * ey, t * ey + s * ex
    x = np.where(inside, x_in, np.where(covers, x_cos, x_gen))
    y = np.where(inside, y_in, np.where(covers, y_cos, y_gen))
    return x, y


def lens_area(d, R):
    """Area of C(V'_P, R) ∩ unit disk (eq. 4.9, :func:`brdfs.physics.patch_geometry.circle_intersection`)."""
    return patch.circle_intersection(d, R).area


def russian_roulette_point(cx, cy, R, u1, u2):
    """The thesis's Russian roulette (eqs. 4.18/4.19): a uniform point in C_min(V'_P, R) — the circle
    C(V'_P, R) if R < 1, else the unit disk — and whether it lies in the other one too.

    Returns (x, y, accepted, area of C_min).
    """
    cx, cy, R, u1, u2 = np.broadcast_arrays(*(np.asarray(a, float) for a in (cx, cy, R, u1, u2)))
    small = R < 1.0
    x, y = uniform_in_circle(np.where(small, cx, 0.0), np.where(small, cy, 0.0), np.where(small, R, 1.0), u1, u2)
    in_disk = x * x + y * y < 1.0
    in_circle = np.hypot(x - cx, y - cy) <= R
    return x, y, in_disk & in_circle, np.pi * np.minimum(R, 1.0) ** 2


def lens_point_by_rejection(cx, cy, R, rng):
    """Uniform points in C(V'_P, R) ∩ unit disk as section 4.2.4 draws them for "normal" importance
    sampling: uniform points of C_min (:func:`russian_roulette_point`) tried until one lies in the
    other circle too ("repeat ... until found"); one point per entry of ``R`` (n,).

    The same distribution as :func:`uniform_in_lens` (which inverts the area from two numbers); here
    a sample costs 2 numbers per try, 2 Area(C_min)/Area(lens) in the mean, drawn from ``rng`` (a
    :class:`numpy.random.Generator`) in rounds over the samples still pending.

    Returns (x, y, the count of uniform numbers drawn).
    """
    R = np.asarray(R, float)
    cx, cy = (np.broadcast_to(np.asarray(c, float), R.shape) for c in (cx, cy))
    x, y = np.zeros(R.shape), np.zeros(R.shape)
    pending = np.arange(R.size)
    numbers = 0
    while pending.size:                                   # repeat ... until found (section 4.2.4)
        u = rng.random((pending.size, 2))
        numbers += 2 * pending.size
        px, py, accepted, _ = russian_roulette_point(cx[pending], cy[pending], R[pending], u[:, 0], u[:, 1])
        x[pending[accepted]], y[pending[accepted]] = px[accepted], py[accepted]
        pending = pending[~accepted]
    return x, y, numbers
