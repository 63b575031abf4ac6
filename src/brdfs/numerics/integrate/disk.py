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

* radial: decades r = ρ·10^(−k) down to a tenth of the distance from c to the edge of the
  element's own lobe along the ray (:func:`_decades`); every N·V level the model declares (circles
  |p|² = 1 − c²; N·V = N·L of max(N·L, N·V)); the masking and shadowing switches of
  Torrance–Sparrow's G (eq. 2.10), a quadratic and a cubic in r along the ray; R·V = 0 for the
  mirror-frame lobes, where (R·V)⁺ is cut; the radii r = |L_xy + V_xy| the model declares (the
  patch models', He–Torrance's radial scales); where the ray crosses a half-plane φ_V = const
  through N that the model declares (``azimuth_levels``).
* azimuthal: four pieces of equal width, the tangent ray ψ = π/2 and points μ·10^(k/2) around
  it, every half decade from μ up to 1/2 (the ray length ρ(ψ) changes from ~cos²θ to ~2 over
  |ψ − π/2| ~ cos θ near grazing, and beyond the tangent ray the ray integrals fall like
  (ψ − π/2)⁻²), the rays tangent to the kink circles, the rays through the points where a
  declared half-plane φ_V = const meets the rim, and — by a scan and bisection, for every radial
  kink above (a scattering lobe's scales, smooth, excepted) — the rays where a kink enters or
  leaves the rays or two kinks change order (a kink curve meets the rim, touches a ray, or
  crosses another: the ray integral has a kink or a jump of its curvature there).

A kink next to the rim is placed by its distance to the rim, ρ − r, in closed form where it has one
(N·V levels: at 90° − 1e-9, N·V = N·L lies 1e-22 inside the rim, where r/ρ rounds to 1 but
1 − x ≈ 4e-6 does not).  The rounding bound of f is a quarter of its change when V_x moves by 2 ulp
plus the lobe's declared rounding in ulps (cos^n β carries n of them).

Every kink is declared by the model (:class:`brdfs.physics.models.base.BRDF`); nothing here knows a
model by its name.

Both directions are integrated by the vectorised adaptive Gauss–Kronrod driver
(:func:`.gauss_kronrod.integrate`): the inner radial integrals of all rays of all elements at once,
their error carried into the outer ψ integral as a known error, in one pass: each ray to
``INNER_SHARE`` of rtol of its own value.  An element's partition is its own, whatever else runs
with it.  The driver is the engine's; the coordinates, breakpoints and initial partition are not.

What each of these choices costs or saves (the full accuracy map at rtol 1e-12,
``benchmarks/bench_engine_speed.py --accuracy-grid``) is said in the comment where it is made.
"""
from __future__ import annotations

import numpy as np

from brdfs.physics.geometry import cos_incidence, sin_incidence
from brdfs.physics.lobes import HALF, MIRROR, SCATTERING
from brdfs.physics.patch_geometry import weight_layer_cuts
from brdfs.core.gauss_kronrod import Estimate, NodeValues, integrate
from brdfs.numerics.integrate.grouping import first_of_model, indices_by_model

INNER_SHARE = 0.1             # the inner integrals get this share of the tolerance
_PIECES = 4                   # equal ψ pieces on [0, π]
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
    # One pass: each ray to a share of rtol of its own value.  (A coarse first pass that set the rays'
    # absolute tolerances from the albedo's size cost 35–50 % of the time and moved no reported error
    # by more than 2 % (Cook–Torrance m = 0.1 at 69 angles, Ward m = 0.005, He–Torrance and the
    # exponential patch at grazing): the rounding bound of f, not the tolerance, stops the flank rays.)
    est = _disk(models, theta_deg, rtol, atol, psi_breakpoints_many(models, theta_deg))
    value, error = np.array(est.value), np.array(est.error)
    for i, m in enumerate(models):
        delta = m.delta_albedo(theta_deg[i])          # zero unless the model has a Dirac part
        value[i] += float(delta.value)
        error[i] += float(delta.error)
    return Estimate(value, error, est.evaluations, est.status)


def psi_breakpoints_many(models, theta_deg):
    """The ψ breakpoints of every element (:func:`_psi_breakpoints`), one NaN-padded row each; the
    kink events (:func:`_kink_events`) of the elements of one model are found together."""
    mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    events = [None] * len(models)
    for members in indices_by_model(models):
        m = models[members[0]]
        top = np.pi if m.symmetric_about_incidence_plane else 2 * np.pi
        for i, ev in zip(members, _kink_events(m, mu[members], st[members], top)):
            events[i] = ev
    return _pad([_psi_breakpoints(m, mu[i], st[i], not m.symmetric_about_incidence_plane, events[i])
                 for i, m in enumerate(models)])


def _disk(models, theta_deg, rtol, atol, bp):
    """The disk integral of every element over its ψ breakpoints ``bp``; rays to ``INNER_SHARE`` of the
    target relative to their own value."""
    mu, st = cos_incidence(theta_deg), sin_incidence(theta_deg)
    full = np.array([not m.symmetric_about_incidence_plane for m in models])
    index = first_of_model(models)      # the same model object at many angles is evaluated together
    weight_el = np.where(full, 1.0, 2.0)             # [0, π] doubled by symmetry
    width = np.array([_lobe_width(models[k]) for k in index])
    isotropic = np.array([_frame(models[k]) is SCATTERING for k in index])
    nodes = []

    def outer(psi, elem):
        shape = psi.shape
        e = np.repeat(elem, shape[1])
        psi = psi.ravel()
        depth = _decades(mu[e], width[e], np.cos(psi), isotropic[e])
        inner = _rays(models, index, e, psi, mu[e], st[e], depth, INNER_SHARE * rtol, atol)
        nodes.append(inner.evaluations)
        w = weight_el[e]
        value = (w * inner.value).reshape(shape)
        return NodeValues(value, value, (w * inner.error).reshape(shape))

    est = integrate(outer, bp, rtol=rtol, atol=atol, chunk=16)
    # two BRDF values a node: f and its rounding probe
    return Estimate(est.value, est.error, 2 * int(sum(nodes)), est.status)


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


def _psi_breakpoints(model, mu, st, full, events=None):
    """ψ breakpoints of one element: equal pieces, the tangent ray and points around it, the rays
    tangent to the model's N·V level circles (and to the circle |p| = sin θ), and the kink events
    (:func:`_kink_events`, computed here unless given)."""
    top = 2 * np.pi if full else np.pi
    pts = [np.linspace(0.0, top, (2 if full else 1) * _PIECES + 1)]
    # every half decade from μ up to 1/2: beyond the tangent ray the rays shorten like μ²/(ψ − π/2)
    # and their integrals fall like (ψ − π/2)⁻² from μ on, which one piece [π/2 + 10³μ, 3π/8] missed
    # at 90° − 1e-9 (Cook–Torrance, m = 0.005: 2.9e-11 of the albedo in its first 1e-7).  Half
    # decades, because the driver split nearly every whole decade once near grazing (Cook–Torrance,
    # m = 0.1, 89.999°: 798 rays on decades, 504 on half decades).  Below μ there is no scale:
    # ρ = a + √(a² + μ²), a = sin θ cos ψ, is analytic in ψ on |ψ − π/2| ≲ μ/sin θ (the decades
    # μ·10⁻³ … μ/10 cost 40 % of the rays at 30° and moved no reported error by 5 %).
    offsets = mu * 10.0 ** (0.5 * np.arange(0, 2 * (4 + max(0, int(np.ceil(-np.log10(max(mu, 1e-300))))))))
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
    for a in _steep_layer_rays(model, mu, st):     # graded toward the ray whose end comes nearest a pole
        pts.append([a, top - a] if full else [a])
    for phi in _half_plane_azimuths(model, mu, full):   # the ray from c to where φ_V = φ₀ meets the rim
        pts.append([np.mod(np.arctan2(np.sin(phi), np.cos(phi) + st), 2 * np.pi)])
    pts.append(_kink_events(model, np.array([mu]), np.array([st]), top)[0] if events is None else events)
    out = np.unique(np.concatenate([np.atleast_1d(np.asarray(p, float)) for p in pts]))
    return out[(out >= 0) & (out <= top)]


def _steep_layer_rays(model, mu, st):
    """The rays ψ whose end lies at r_k = R_e − g (4^k − 1) (:data:`~brdfs.physics.patch_geometry.WEIGHT_LAYER_GRADING`,
    k ≥ 1, r_k > 1) when the model's f grows toward a pole at r = P up to r = end
    (``scattering_radius_steep_layer``): R_e = min(1 + sin θ, end) is the largest radius any ray's
    integrand reaches, g = P − R_e its distance to the pole.  The ray integral carries a layer in ψ
    about ψ_e, the ray that reaches R_e (ψ = 0, or the ray ending at r = end), where P − min(ρ, end)
    grows from g (like ψ² about ψ = 0): the cuts lie where it is g 4^k, 2^k g^½ apart in ψ about ψ = 0.
    Made only where R_e − 1 > :data:`~brdfs.physics.patch_geometry.WEIGHT_LAYER_TRIGGER` g (as the engine's,
    whose lens kink is R = 1; never for end ≤ 1.9).  Without them the piece [0, π/4] held a layer of width
    ~g^½ that neither Gauss nor Kronrod saw: generalized Lambertian d = 1, m_clip = 2 − 1e-9 at 89.99°
    (g = 1.5e-8), rtol 1e-6: 5.3e-8 off at a reported 5.2e-8; m_clip = 2 − 1e-12 at 89.999°, rtol 1e-9:
    9.3e-10 off at a reported 5.4e-10."""
    layer = model.scattering_radius_steep_layer()
    if layer is None or st <= 0:
        return []
    end, pole = (float(v) for v in layer)
    if end < 1.0 + st:
        r_end, g = end, pole - end
    else:                       # P − (1 + sin θ) with 1 − sin θ = cos²θ/(1 + sin θ): no cancellation
        r_end, g = 1.0 + st, (pole - 2.0) + mu * mu / (1.0 + st)
    radii = np.array(weight_layer_cuts(1.0, r_end, g))                # the engine's cuts above its lens kink R = 1
    if radii.size == 0:
        return []
    x = (radii * radii - mu * mu) / (2 * radii * st)          # the ray that ends at r (_constant_radii)
    return list(np.arccos(x[(x > -1) & (x < 1)]))


#: ψ-scan of :func:`_kink_events`: uniform points on [0, top], and points graded toward the
#: tangent ray ψ = π/2 (3π/2) from μ·10⁻³ to 1/2 on either side.
_PSI_SCAN = 512
_PSI_GRADED = 96


def _kink_events(model, mu, st, top):
    """The rays ψ where the declared radial kinks change how they cut the rays: a kink enters or
    leaves the ray (its curve meets the rim, touches a ray, or passes through c) or two kinks
    cross (curves that meet: eq. 2.10's two switches and N·V = N·L meet where its three terms are
    equal).  The ray integral, smooth in ψ elsewhere, has a kink, a square-root point or a jump in
    its curvature there.  Found by a scan and bisection, for every kink the model declares (the
    closed-form tangent rays above cover the N·V circles only), for all angles (arrays ``mu``,
    ``st``) at once: a list of arrays, one per angle.  Cook–Torrance with eq. 2.10, m = 1, 85°: the
    ray through that triple point (ψ = 1.4832) and the ray where the shadowing switch leaves the
    disk (ψ = 1.5203) were missing, 1.2e-9 off at a reported 3.4e-11."""
    mu, st = np.asarray(mu, float), np.asarray(st, float)
    offsets = np.geomspace(np.maximum(mu, 1e-300) * 1e-3, 0.5, _PSI_GRADED, axis=-1)       # (n, G)
    centres = (np.pi / 2, 3 * np.pi / 2) if top > np.pi else (np.pi / 2,)
    uniform = np.broadcast_to(np.linspace(0.0, top, _PSI_SCAN + 1), (mu.size, _PSI_SCAN + 1))
    scan = np.sort(np.clip(np.concatenate([uniform] + [c + sign * offsets for c in centres for sign in (-1, 1)], 1),
                           0.0, top), 1)                                                    # (n, S)
    mu_s, st_s = (np.broadcast_to(x[:, None], scan.shape) for x in (mu, st))
    radii = _kinks_inside(model, mu_s, st_s, scan)                # (k, n, S), NaN outside the ray
    inside = np.isfinite(radii)
    rho = ray_length(mu_s, st_s, np.cos(scan))
    # an event is (first kink, second kink or −1, element, scan interval): a kink entering or
    # leaving the rays, or two kinks changing order
    found = []
    for a in range(radii.shape[0]):
        el, w = np.nonzero(inside[a, :, :-1] != inside[a, :, 1:])
        found.append((np.full(el.size, a), np.full(el.size, -1), el, w))
        for b in range(a + 1, radii.shape[0]):
            gap = radii[a] - radii[b]
            apart = np.abs(gap) > 64 * _EPS * rho                # duplicates and rounding ties are no crossing
            el, w = np.nonzero(apart[:, :-1] & apart[:, 1:] & (np.sign(gap[:, :-1]) != np.sign(gap[:, 1:])))
            found.append((np.full(el.size, a), np.full(el.size, b), el, w))
    first, second, el, w = (np.concatenate(x) for x in zip(*found))
    if el.size == 0:
        return [np.empty(0)] * mu.size
    lo, hi = scan[el, w], scan[el, w + 1]
    mu_e, st_e = mu[el][:, None], st[el][:, None]

    def state(psi):                                                 # psi: (events, points)
        r = _kinks_inside(model, np.broadcast_to(mu_e, psi.shape), np.broadcast_to(st_e, psi.shape), psi)
        mine = np.take_along_axis(r, first[None, :, None], 0)[0]
        other = np.take_along_axis(r, np.maximum(second, 0)[None, :, None], 0)[0]
        return np.where(second[:, None] < 0, np.isfinite(mine), mine > other)

    # 16-way bisection: 13 rounds of 15 points per event narrow the bracket by 2^-52
    left = state(lo[:, None])
    fractions = np.arange(1, _SPLIT) / _SPLIT
    rows = np.arange(lo.size)
    for _ in range(13):
        pts = lo[:, None] + (hi - lo)[:, None] * fractions
        flipped = state(pts) != left
        k = np.where(flipped.any(1), np.argmax(flipped, 1), _SPLIT - 1)
        new_lo = np.where(k > 0, pts[rows, np.maximum(k - 1, 0)], lo)
        hi = np.where(k < _SPLIT - 1, pts[rows, np.minimum(k, _SPLIT - 2)], hi)
        lo = new_lo
    roots = 0.5 * (lo + hi)
    return [roots[el == i] for i in range(mu.size)]


_SPLIT = 16


def _kinks_inside(model, mu, st, psi):
    """The declared radial kinks along the rays at ``psi`` (any shape, with ``mu``, ``st`` of the same
    shape), shape (kinks,) + psi.shape, NaN where a kink does not lie inside its ray (0 < r, inside
    the rim)."""
    shape = psi.shape
    psi, mu, st = (np.ravel(x) for x in (psi, mu, st))
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)
    rho = ray_length(mu, st, cos_psi)
    with np.errstate(invalid="ignore"):
        kinks = [np.where((r > 0) & (gap > 0), r, np.nan)
                 for r, gap in _radial_kinks(model, mu, st, cos_psi, sin_psi, rho, scales=False)]
    return np.stack(kinks).reshape((-1,) + shape)


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


def _rays(models, index, elem, psi, mu, st, depth, rtol, atol):
    """∫₀^ρ f(L, V(c + r u)) r dr along every ray (one per entry of ``psi``), split at the decades
    r/ρ = 10⁻¹ … 10^(−depth) (:func:`_decades`) and at the model's radial kinks."""
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)
    rho = ray_length(mu, st, cos_psi)
    cols = [np.zeros_like(psi), np.ones_like(psi)]
    cols += [np.where(k <= depth, _x_of(10.0 ** -k), np.nan) for k in range(1, int(depth.max(initial=0)) + 1)]
    for k in np.unique(index[elem]):
        rows = index[elem] == k
        for r, gap in _radial_kinks(models[k], mu[rows], st[rows], cos_psi[rows], sin_psi[rows], rho[rows]):
            col = np.full(psi.shape, np.nan)
            with np.errstate(invalid="ignore", divide="ignore"):
                col[rows] = np.where((r > 0) & (gap > 0), _x_of_gap(gap / rho[rows]), np.nan)
            cols.append(col)
    bp = np.sort(np.stack(cols, -1), axis=-1)

    ulps = {k: _rounding_ulps(models[k]) for k in np.unique(index[elem])}

    def integrand(x, ray):
        e = index[elem[ray]]
        high, rounding = np.empty_like(x), np.empty_like(x)
        w = 1.0 - x
        w2 = w * w
        frac = x * (4.0 + x * (-6.0 + x * (4.0 - x)))     # r / ρ = 1 − (1 − x)⁴ without cancellation
        for k, rows in _groups(e):
            rr = ray[rows]
            s, c, u, v, p = (a[rr, None] for a in (st, mu, cos_psi, sin_psi, rho))
            r = p * frac[rows]
            px, py = r * u - s, r * v
            # N·V = √(1 − |p|²) = √((ρ − r)(r + ρ − 2 sin θ cos ψ)) = (1 − x)² √(ρ r + cos²θ)
            # (ρ − 2 sin θ cos ψ = cos²θ/ρ: no cancellation near the centre of the rays)
            nv = w2[rows] * np.sqrt(p * r + c * c)
            L = np.stack(np.broadcast_arrays(s, 0 * s, c), -1)
            V = np.stack([px, py, nv], -1)
            f = models[k].unchecked(L, V)
            # rounding noise of f: a quarter of its change when V_x moves by 2 ulp (V_x carries ½ ulp;
            # near grazing L + V cancels in x), summed without cancellation: a bound, not a guess
            V[..., 0] += 2 * np.spacing(V[..., 0])
            noise = 0.25 * np.abs(models[k].unchecked(L, V) - f) + ulps[k] * _EPS * np.abs(f)
            jac = r * 4 * p * w2[rows] * w[rows]          # r dr/dx
            high[rows] = np.where(f == 0, 0.0, f * jac)
            rounding[rows] = np.where(np.isfinite(noise), noise * jac, 0.0)
        return NodeValues(high, high, rounding)

    return integrate(integrand, bp, rtol=rtol, atol=atol, chunk=256)


def _groups(e):
    """(model index, rows) for each distinct model index in ``e``; rows is a plain slice where all
    share one (no copies of the node arrays in the common case)."""
    if e.size and np.all(e == e[0]):
        return [(e[0], slice(None))]
    return [(k, e == k) for k in np.unique(e)]


def _rounding_ulps(model):
    """Relative rounding of f in ulps beyond what a move of V_x shows: the lobe's declared rounding
    (cos^n β carries n ulps of cos β, which here is R·V from the rounded V: Phong-type lobes of
    n = 1e4 at normal incidence were 1.1e-12 off, a bias, at a reported 7.7e-13), at least 4.  Only
    the lobes around R or the half vector declare one; the scattering-frame lobes carry none."""
    return max(4.0, float(model.lobe.rounding)) if _frame(model) in (MIRROR, HALF) else 4.0


def _x_of(frac):
    """x with r/ρ = 1 − (1 − x)⁴ = ``frac``."""
    return -np.expm1(0.25 * np.log1p(-frac))


def _x_of_gap(gap):
    """x with (ρ − r)/ρ = (1 − x)⁴ = ``gap``: a kink next to the rim keeps its place in x, where
    r/ρ rounds to 1 (N·V = N·L at 90° − 1e-9 lies 1e-22 inside the rim, at 1 − x ≈ 4e-6)."""
    return -np.expm1(0.25 * np.log(gap))


def _decades(mu, width, cos_psi, isotropic):
    """How many decades below ρ the radial partition of each ray goes: down to a tenth of the
    distance from c to the edge of its element's lobe (:func:`_lobe_width`) along the ray, at least
    one decade, at most 12.  Around c a lobe of angular width w is an ellipse of semi-axes w cos θ
    (along x, the plane of incidence) and w (along y), which the ray at ψ leaves at
    w cos θ / √(cos²ψ + cos²θ sin²ψ); a scattering-frame lobe (``isotropic``), a width in
    r = |L_xy + V_xy| itself, is a circle of radius w.  (n = 10⁴ along ψ = 0: 1.2e-3 cos θ, as the
    package's narrowest lobe set for every model and ray before.)  Per ray, so that an element's
    partition does not depend on the others of its run, and the rays across the plane of incidence
    near grazing do not get the decades of the compressed direction."""
    mu = np.maximum(mu, 1e-9)
    along = mu / np.sqrt(cos_psi * cos_psi + mu * mu * (1.0 - cos_psi * cos_psi))
    smallest = 0.1 * width * np.where(isotropic, 1.0, along)
    return np.clip(np.ceil(-np.log10(smallest)), 1, 12).astype(int)


#: The lobe width assumed for a model without a lobe (the patch models; their kinks are declared radii):
#: the narrowest lobe of the package, n = 10⁴ or m = 0.005 (~0.01 rad).
_NARROWEST_WIDTH = 0.01


def _lobe_width(model):
    """The angular width of the model's lobe around its peak, in V: the angle β within which half its
    radial weight lies (the lobe's own :meth:`angle` at t = ½; twice that for a lobe in the half
    vector, which V turns at twice the rate), the radial scale of a scattering-frame lobe, or
    :data:`_NARROWEST_WIDTH` for a model without a lobe."""
    frame = _frame(model)
    if frame is SCATTERING:
        return float(model.lobe.width)
    if frame not in (MIRROR, HALF):
        return _NARROWEST_WIDTH
    cos_b, sin_b = model.lobe.angle(np.float64(0.5))
    return float(np.arctan2(sin_b, cos_b)) * (2.0 if frame is HALF else 1.0)


def _radial_kinks(model, mu, st, cos_psi, sin_psi, rho, scales=True):
    """Where the model's integrand has a kink or a jump along the rays: a list of pairs (r, ρ − r)
    of arrays (NaN = none), the distance to the rim free of cancellation where it is known.  With
    ``scales`` also the scales of a scattering-frame lobe (:class:`~brdfs.physics.lobes.ScatteringLobe`:
    its boundary layer in N·V and its radial scales), where the integrand changes fast but smoothly:
    breakpoints of the rays, not kinks whose crossings the ψ-scan (:func:`_kink_events`) must find."""
    a = st * cos_psi                    # c·u = −a: |p|² = sin²θ − 2 a r + r²
    levels = [np.broadcast_to(c, mu.shape) for c in model.nv_levels(mu)] + [mu]
    frame = _frame(model)
    if frame is SCATTERING and scales:
        levels += [np.full(mu.shape, c) for c in model.lobe.nv_levels()]
    # ρ = a + √(a² + μ²); the level circle |p|² = 1 − c² is crossed at r = a ± √(a² + μ² − c²), the
    # smaller root from the product of the two, (c − μ)(c + μ) (exactly 0 for N·V = N·L, whose circle
    # passes through c), and ρ − r = c² / (√(a² + μ²) + √(a² + μ² − c²)) at the outer crossing: no
    # cancellation near c nor near the rim
    out = []
    reach = np.sqrt(a * a + mu * mu)
    for c in levels:
        with np.errstate(invalid="ignore", divide="ignore"):
            root = np.sqrt(a * a + mu * mu - c * c)
            product = (c - mu) * (c + mu)
            outer = np.where(a >= 0, a + root, product / (a - root))
            inner = np.where(a >= 0, product / (a + root), a - root)
        out += [(inner, reach + root), (outer, c * c / (reach + root))]
    # elsewhere ρ − r by subtraction: a kink within rounding of the rim (the cut R·V = 0 at normal
    # incidence is the rim itself) is not a kink of the ray integral
    for r in _other_kinks(model, mu, st, cos_psi, sin_psi, a, frame, scales):
        gap = rho - r
        out.append((r, np.where(gap > 4 * _EPS * rho, gap, 0.0)))
    return out


def _other_kinks(model, mu, st, cos_psi, sin_psi, a, frame, scales=True):
    """Radii of the kinks other than N·V levels (:func:`_radial_kinks`; ``scales`` as there)."""
    out = []
    if frame is MIRROR:                 # R·V = 0: (a² + μ²) r² − 2 a r + sin²θ − μ² = 0, μ ν = a r − sin²θ ≥ 0
        # the discriminant a² − (a² + μ²)(sin²θ − μ²) = μ² (sin²θ cos 2ψ + μ²) in closed form: by
        # subtraction it cancelled to rounding near grazing (at 90° − 1e-7 the cut, the edge of the
        # sliver of width μ that Phong n = 0 reflects beyond x = 0, was lost: (1 + cos θ)/2 came back 1/2)
        q2 = a * a + mu * mu
        with np.errstate(invalid="ignore", divide="ignore"):
            half_root = mu * np.sqrt(st * st * (2 * cos_psi * cos_psi - 1) + mu * mu)
            far = np.where(a >= 0, a + half_root, a - half_root) / q2     # the root without cancellation
            near = (st * st - mu * mu) / (q2 * far)                       # the other, from their product
            out += [np.minimum(near, far), np.maximum(near, far)]
    if model.torrance_sparrow_switches:
        out += _torrance_sparrow_kinks(mu, a)
    lobe_scales = set() if scales or frame is not SCATTERING else {float(r) for r in model.lobe.radial_levels()}
    out += [r for r in model.scattering_radius_kinks(cos_psi, sin_psi) if not _constant_in(r, lobe_scales)]
    out += _half_plane_kinks(model, mu, st, cos_psi, sin_psi)
    return out


def _constant_in(r, values):
    """Whether the radii ``r`` are one constant that is among ``values``."""
    flat = np.ravel(r)
    return bool(values) and flat.size > 0 and np.all(flat == flat[0]) and float(flat[0]) in values


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
    Roots of the squared equations are kept only where the unsquared sign holds.

    The cubic has three real roots for μ > 0 (in s = 2r − 3a it is s³ + 3a s² − 3μ² s − a μ² = 0,
    depressed by s = y − a to y³ − 3(a² + μ²) y + 2a(a² + μ²) = 0, discriminant 108 μ² (a² + μ²)²),
    in closed form r_k = √(a² + μ²) cos((φ₀ − 2πk)/3) + a, φ₀ = atan2(μ, −a).  Near grazing two of
    them are 1e-11 apart at r ≈ 3a/2 (a near-double root, which companion-matrix eigenvalues resolved
    only to √ε, so that they came and went between neighbouring rays); the angle form keeps them.
    The root near r = 0 is taken from the product of the roots, −a μ².  Each k keeps its root from
    one ray to the next (:func:`_kink_events` follows the roots by their slots)."""
    out = []
    with np.errstate(invalid="ignore", divide="ignore"):
        r_s = 4 * a * mu * mu / (mu * mu + a * a)
        out.append(np.where(a * r_s - mu * mu >= 0, r_s, np.nan))
        reach = np.sqrt(a * a + mu * mu)
        phi0 = np.arctan2(mu, -a)
        r_roots = reach[:, None] * np.cos((phi0[:, None] - 2 * np.pi * np.arange(3)) / 3) + a[:, None]
        near_zero = np.argmin(np.abs(r_roots), -1)
        others = np.prod(np.where(np.arange(3) == near_zero[:, None], 1.0, r_roots), -1)
        np.put_along_axis(r_roots, near_zero[:, None], (-a * mu * mu / others)[:, None], -1)
        for k in range(3):
            r = r_roots[:, k]
            sv = 2 * r - 3 * a
            rhs = r * sv - mu * mu
            ok = rhs >= -8 * _EPS * (np.abs(r * sv) + mu * mu)
            out.append(np.where(ok, r, np.nan))
    return out
