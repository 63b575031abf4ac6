"""Independent albedo integration over the projected unit disk — the cross-check of the engine.

With V = (x, y, √(1 − x² − y²)) the projected solid angle is cos θ_V dω_V = dx dy, so
a(L) = ∬_{x²+y²<1} f(L, V(x, y)) dx dy: no cos θ_V factor and no pole at the horizon.

Coordinates (none shared with :mod:`.hemisphere`, which follows the lobe around R or N in its
cumulative weight t).  Polar coordinates (r, ψ) are centred on the projected mirror direction
c = (−sin θ, 0), where every model here has its peak; ψ = 0 points from c toward the centre of
the disk, and the ray at ψ leaves the disk at r = ρ(ψ).  Along a ray r = ρ (1 − (1 − x)⁴), x ∈ [0, 1]:
near the rim ρ − r ∝ (1 − x)⁴ and N·V ∝ (1 − x)², so even Ward's 1/√(N·V) becomes a smooth
integrand.  r is also the distance |L_xy + V_xy| of the patch models (chapter 4) and the horizontal
scattering vector of He–Torrance: their kinks are radii.

Breakpoints, all in closed form from the disk geometry (the "no narrow feature can hide" rule):

* radial: decades r = ρ·10^(−k) down to the scale of the narrowest lobe at this incidence;
  every N·V level the model declares (circles |p|² = 1 − c²; N·V = N·L of max(N·L, N·V));
  the masking and shadowing switches of Torrance–Sparrow's G (eq. 2.10), a quadratic and a cubic
  in r along the ray; R·V = 0 for the mirror-frame lobes, where (R·V)⁺ is cut; the radii
  r = |L_xy + V_xy| the model declares (the patch models', He–Torrance's radial scales); where the
  ray crosses a half-plane φ_V = const through N that the model declares (``azimuth_levels``).
* azimuthal: pieces of equal width, the tangent ray ψ = π/2 and points mu·10^k around it (the
  ray length ρ(ψ) changes from ~cos²θ to ~2 over |ψ − π/2| ~ cos θ near grazing), the rays
  tangent to the kink circles, and the rays through the points where a declared half-plane
  φ_V = const meets the rim.

Every kink is declared by the model (:class:`brdfs.physics.models.base.BRDF`); nothing here knows a
model by its name.

Both directions are integrated by the vectorised adaptive Gauss–Kronrod driver
(:func:`.gauss_kronrod.integrate`): the inner radial integrals of all rays of all elements at once,
their error carried into the outer ψ integral as a known error.  The driver is the engine's; the
coordinates, breakpoints and initial partition are not.
"""
from __future__ import annotations

import numpy as np

from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.physics.lobes import MIRROR, SCATTERING
from brdfs.core.gauss_kronrod import Estimate, NodeValues, integrate
from brdfs.numerics.integrate.grouping import first_of_model

INNER_SHARE = 0.1             # the inner integrals get this share of the tolerance
_PIECES = 8                   # equal ψ pieces on [0, π]
_EPS = np.finfo(float).eps


def disk_albedo(model, theta_deg, rtol=1e-12, atol=1e-16):
    """a(θ) of one model at one angle over the projected disk; a scalar :class:`Estimate`."""
    est = disk_albedo_many([model], [float(theta_deg)], rtol=rtol, atol=atol)
    return Estimate(np.array(est.value[0]), np.array(est.error[0]))


def disk_albedo_many(models, theta_deg, rtol=1e-12, atol=1e-16):
    """Albedo (the density part) of ``models[i]`` at ``theta_deg[i]`` for every i, in one run.

    A model with a Dirac part (He–Torrance's specular term) gets its closed-form ``delta_albedo``
    added, as :func:`brdfs.numerics.albedo.albedo` does.
    """
    theta_deg = np.asarray(theta_deg, float).ravel()
    models = list(models)
    if len(models) != theta_deg.size:
        raise ValueError("disk_albedo_many needs one model per angle")
    # Pass 1, coarse: the albedo's size, which sets the absolute tolerance of every ray in pass 2
    # (a ray far out in the lobe's flank needs no 1e-13 of its own tiny value, and rounding noise
    # of f — 1e-10 relative near grazing, where L + V cancels — would keep refining it).
    rough = _disk(models, theta_deg, ROUGH_RTOL, atol, None)
    est = _disk(models, theta_deg, rtol, atol, np.abs(rough.value) + rough.error)
    value, error = np.array(est.value), np.array(est.error)
    for i, m in enumerate(models):
        delta = m.delta_albedo(theta_deg[i])          # zero unless the model has a Dirac part
        value[i] += float(delta.value)
        error[i] += float(delta.error)
    return Estimate(value, error, status=est.status)


ROUGH_RTOL = 1e-5


def _disk(models, theta_deg, rtol, atol, scale):
    """The disk integral of every element; rays to ``INNER_SHARE`` of the target relative to their own
    value, or (``scale`` given: the element's albedo) at least that share of rtol · scale spread over ψ."""
    mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    full = np.array([not m.symmetric_about_incidence_plane for m in models])
    bp = _pad([_psi_breakpoints(m, mu[i], st[i], full[i]) for i, m in enumerate(models)])
    index = first_of_model(models)      # the same model object at many angles is evaluated together
    weight_el = np.where(full, 1.0, 2.0)             # [0, π] doubled by symmetry
    span = np.where(full, 2 * np.pi, np.pi)

    def outer(psi, elem):
        shape = psi.shape
        e = np.repeat(elem, shape[1])
        if scale is None:
            inner_rtol, inner_atol = INNER_SHARE * rtol, atol
        else:
            inner_rtol = INNER_SHARE * rtol
            inner_atol = INNER_SHARE * np.maximum(rtol * scale[e], atol) / (weight_el[e] * span[e])
        inner = _rays(models, index, e, psi.ravel(), mu[e], st[e], inner_rtol, inner_atol)
        w = weight_el[e]
        value = (w * inner.value).reshape(shape)
        return NodeValues(value, value, (w * inner.error).reshape(shape))

    return integrate(outer, bp, rtol=rtol, atol=atol, chunk=16)


def _pad(rows):
    out = np.full((len(rows), max(r.size for r in rows)), np.nan)
    for i, r in enumerate(rows):
        out[i, : r.size] = r
    return out


def ray_length(mu, st, cos_psi):
    """ρ(ψ): distance from c = (−sin θ, 0) to the unit circle along u = (cos ψ, sin ψ),
    the positive root of r² − 2 r sin θ cos ψ − cos²θ = 0, without cancellation."""
    a = st * cos_psi
    root = np.sqrt(a * a + mu * mu)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a >= 0, a + root, mu * mu / (root - a))


def _psi_breakpoints(model, mu, st, full):
    """ψ breakpoints of one element: equal pieces, the tangent ray and points around it, and the
    rays tangent to the model's N·V level circles (and to the circle |p| = sin θ)."""
    top = 2 * np.pi if full else np.pi
    pts = [np.linspace(0.0, top, (2 if full else 1) * _PIECES + 1)]
    offsets = mu * 10.0 ** np.arange(-3, 4)
    offsets = offsets[(offsets > 0) & (offsets < 0.5)]
    for centre in ((np.pi / 2, 3 * np.pi / 2) if full else (np.pi / 2,)):
        pts.append(centre - offsets)
        pts.append(centre + offsets)
    for radius in _level_radii(model, mu):
        if 0 < radius < st:                     # c outside the circle: tangent rays exist
            a = np.arcsin(radius / st)
            pts.append([a, top - a] if full else [a])
    if _frame(model) is MIRROR:
        # the cut R·V = 0 of (R·V)⁺ projects to the half ellipse x²/cos²θ + y² = 1, x ≥ 0, which meets
        # the rim at (0, ±1): the rays through those points switch between crossing the cut inside
        # the disk and not (Phong, n = 1, at 86.84°: the ray at 45.04° beside the piece edge at 45°
        # hid the kink, 5.5e-11 off at a reported 1.3e-13 against the closed form)
        a = np.arctan2(1.0, st)
        pts.append([a, top - a] if full else [a])
    for radius in _constant_radii(model):       # the ray that ends where the circle r = R meets the rim
        with np.errstate(divide="ignore", invalid="ignore"):
            x = (radius * radius - mu * mu) / (2 * radius * st)
        if -1 < x < 1:
            a = np.arccos(x)
            pts.append([a, top - a] if full else [a])
    for phi in _half_plane_azimuths(model, mu, full):   # the ray from c to where φ_V = φ₀ meets the rim
        pts.append([np.mod(np.arctan2(np.sin(phi), np.cos(phi) + st), 2 * np.pi)])
    out = np.unique(np.concatenate([np.atleast_1d(np.asarray(p, float)) for p in pts]))
    return out[(out >= 0) & (out <= top)]


def _constant_radii(model):
    """Kinks at a fixed r = |L_xy + V_xy| the model declares (patch radii, He–Torrance's radial scales)."""
    return [float(r) for r in model.scattering_radius_levels()]


def _frame(model):
    """The frame of the model's lobe, or None for a model without one (``lobe = None``)."""
    return None if model.lobe is None else model.lobe.frame


def _half_plane_azimuths(model, mu, full):
    """The declared azimuths φ_V of half-planes with a kink, in [0, 2π) (``full``) or folded into [0, π]."""
    out = []
    for c in model.azimuth_levels(np.float64(mu)):
        phi = float(np.mod(float(np.broadcast_to(c, ())), 2 * np.pi))
        out += [phi] if full else [min(phi, 2 * np.pi - phi)]
    return out


def _level_radii(model, mu):
    """Radii |p| = √(1 − c²) of the model's N·V level circles (and of N·V = N·L)."""
    levels = [float(np.broadcast_to(c, ())) for c in model.nv_levels(np.float64(mu))] + [float(mu)]
    if _frame(model) is SCATTERING:
        levels += list(model.lobe.nv_levels())
    return [float(np.sqrt(max(1.0 - c * c, 0.0))) for c in levels if 0.0 < c < 1.0]


def _rays(models, index, elem, psi, mu, st, rtol, atol):
    """∫₀^ρ f(L, V(c + r u)) r dr along every ray (one per entry of ``psi``)."""
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)
    rho = ray_length(mu, st, cos_psi)
    cols = [np.zeros_like(psi), np.ones_like(psi)]
    depth = _decades(mu)
    cols += [_x_of(10.0 ** -k * np.ones_like(psi)) for k in range(1, depth + 1)]
    for k in np.unique(index[elem]):
        rows = index[elem] == k
        for r in _radial_kinks(models[k], mu[rows], st[rows], cos_psi[rows], sin_psi[rows], rho[rows]):
            col = np.full(psi.shape, np.nan)
            with np.errstate(invalid="ignore", divide="ignore"):
                col[rows] = np.where((r > 0) & (r < rho[rows]), _x_of(r / rho[rows]), np.nan)
            cols.append(col)
    bp = np.sort(np.stack(cols, -1), axis=-1)

    def integrand(x, ray):
        e = index[elem[ray]]
        high, rounding = np.empty_like(x), np.empty_like(x)
        w = 1.0 - x
        w2 = w * w
        frac = x * (4.0 + x * (-6.0 + x * (4.0 - x)))     # r / ρ = 1 − (1 − x)⁴ without cancellation
        for k in np.unique(e):
            rows = e == k
            rr = ray[rows]
            s, c, u, v, p = (a[rr, None] for a in (st, mu, cos_psi, sin_psi, rho))
            r = p * frac[rows]
            px, py = r * u - s, r * v
            # N·V = √(1 − |p|²) = √((ρ − r)(r + ρ − 2 sin θ cos ψ)) = (1 − x)² √(ρ r + cos²θ)
            # (ρ − 2 sin θ cos ψ = cos²θ/ρ: no cancellation near the centre of the rays)
            nv = w2[rows] * np.sqrt(p * r + c * c)
            L = np.stack(np.broadcast_arrays(s, 0 * s, c), -1)
            V = np.stack([px, py, nv], -1)
            f = models[k](L, V)
            # rounding noise of f: a quarter of its change when V_x moves by 2 ulp (V_x carries ½ ulp;
            # near grazing L + V cancels in x), summed without cancellation: a bound, not a guess
            V[..., 0] += 2 * np.spacing(V[..., 0])
            noise = 0.25 * np.abs(models[k](L, V) - f) + 4 * _EPS * np.abs(f)
            jac = r * 4 * p * w2[rows] * w[rows]          # r dr/dx
            high[rows] = np.where(f == 0, 0.0, f * jac)
            rounding[rows] = np.where(np.isfinite(noise), noise * jac, 0.0)
        return NodeValues(high, high, rounding)

    return integrate(integrand, bp, rtol=rtol, atol=atol, chunk=256)


def _x_of(frac):
    """x with r/ρ = 1 − (1 − x)⁴ = ``frac``."""
    return -np.expm1(0.25 * np.log1p(-frac))


def _decades(mu):
    """How many decades below ρ the radial partition goes: the narrowest lobe of the package
    (n = 10⁴, m = 0.005: ~0.005 rad) projects to ~0.005·cos θ along the ray toward the centre."""
    smallest = 1e-3 * np.max(np.maximum(mu, 1e-9))
    return int(np.clip(np.ceil(-np.log10(smallest)), 3, 12))


def _radial_kinks(model, mu, st, cos_psi, sin_psi, rho):
    """Radii along the rays where the model's integrand has a kink or a jump (arrays, NaN = none)."""
    a = st * cos_psi                    # c·u = −a: |p|² = sin²θ − 2 a r + r²
    out = []
    levels = [np.broadcast_to(c, mu.shape) for c in model.nv_levels(mu)] + [mu]
    frame = _frame(model)
    if frame is SCATTERING:
        levels += [np.full(mu.shape, c) for c in model.lobe.nv_levels()]
    for c in levels:                    # |p|² = 1 − c²: r² − 2 a r + sin²θ − 1 + c² = 0
        disc = a * a + (1 - st) * (1 + st) - c * c
        with np.errstate(invalid="ignore"):
            root = np.sqrt(disc)
        out += [a - root, a + root]
    if frame is MIRROR:                 # R·V = 0: (a² + μ²) r² − 2 a r + sin²θ − μ² = 0, μ ν = a r − sin²θ ≥ 0
        q2, q1, q0 = a * a + mu * mu, -2 * a, st * st - mu * mu
        with np.errstate(invalid="ignore", divide="ignore"):
            root = np.sqrt(q1 * q1 - 4 * q2 * q0)
            out += [(-q1 - root) / (2 * q2), (-q1 + root) / (2 * q2)]
    if model.torrance_sparrow_switches:
        out += _torrance_sparrow_kinks(mu, a)
    out += list(model.scattering_radius_kinks(cos_psi, sin_psi))
    out += _half_plane_kinks(model, mu, st, cos_psi, sin_psi)
    return out


def _half_plane_kinks(model, mu, st, cos_psi, sin_psi):
    """Radii where the ray c + r u crosses a declared half-plane φ_V = φ₀ through N (the half-line
    s e, e = (cos φ₀, sin φ₀), s ≥ 0, on the disk): (c + r u) × e = 0 gives r = sin θ sin φ₀ / sin(φ₀ − ψ),
    kept where r > 0 and s = (c + r u)·e ≥ 0.  For a model symmetric about the plane of incidence the
    half-plane's mirror image φ_V = −φ₀ is a kink as well."""
    out = []
    for c in model.azimuth_levels(mu):
        phi0 = np.broadcast_to(np.asarray(c, float), mu.shape)
        for phi in ((phi0, -phi0) if model.symmetric_about_incidence_plane else (phi0,)):
            ce, se = np.cos(phi), np.sin(phi)
            with np.errstate(invalid="ignore", divide="ignore"):
                r = st * se / (se * cos_psi - ce * sin_psi)
            s = (r * cos_psi - st) * ce + r * sin_psi * se
            out.append(np.where((r > 0) & (s >= 0), r, np.nan))
    return out


def _torrance_sparrow_kinks(mu, a):
    """Radii where eq. 2.10's shadowing or masking term reaches 1 along the ray (N·V = z):

    shadowing 2 N·H N·L / L·H = 1  ⟺  μ z = a r − μ²  ⟹  r = 4 a μ² / (μ² + a²);
    masking   2 N·H N·V / V·H = 1  ⟺  μ z = 2 r² − 3 a r − μ²  ⟹
    4 r³ − 12 a r² + (9 a² − 3 μ²) r + 4 a μ² = 0 (with z² = μ² + 2 a r − r²).
    Roots of the squared equations are kept only where the unsquared sign holds."""
    out = []
    with np.errstate(invalid="ignore", divide="ignore"):
        r_s = 4 * a * mu * mu / (mu * mu + a * a)
        out.append(np.where(a * r_s - mu * mu >= 0, r_s, np.nan))
        coef = np.stack([np.full_like(a, 4.0), -12 * a, 9 * a * a - 3 * mu * mu, 4 * a * mu * mu], -1)
        roots = _cubic_roots(coef)
        for r in roots:
            r = _newton(coef, r)
            ok = 2 * r * r - 3 * a * r - mu * mu >= -1e-12
            out.append(np.where(ok, r, np.nan))
    return out


def _cubic_roots(coef):
    """Real roots (NaN where complex) of c0 r³ + c1 r² + c2 r + c3, vectorised via companion matrices."""
    c = coef / coef[:, :1]
    comp = np.zeros((c.shape[0], 3, 3))
    comp[:, 0, :] = -c[:, 1:]
    comp[:, 1, 0] = comp[:, 2, 1] = 1.0
    good = np.all(np.isfinite(comp), axis=(1, 2))
    ev = np.full((c.shape[0], 3), np.nan + 0j)
    if good.any():
        ev[good] = np.linalg.eigvals(comp[good])
    real = np.abs(ev.imag) <= 1e-7 * np.maximum(np.abs(ev.real), 1e-300)
    return list(np.where(real, ev.real, np.nan).T)


def _newton(coef, r, steps=3):
    for _ in range(steps):
        p = ((coef[:, 0] * r + coef[:, 1]) * r + coef[:, 2]) * r + coef[:, 3]
        dp = (3 * coef[:, 0] * r + 2 * coef[:, 1]) * r + coef[:, 2]
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(dp != 0, p / dp, 0.0)
        r = r - np.where(np.isfinite(step), step, 0.0)
    return r
