"""The third route: directional albedos a(θ) = ∫ f(L, V) cos θ_V dω_V by nested quadrature that
shares no code with :mod:`brdfs.numerics` (it imports nothing from the package at all).

Coordinates (L = (sin θ, 0, cos θ), N = (0, 0, 1); every integrand here is even in V_y, so the
azimuth runs over [0, π] and the result is doubled):

* ``mirror``: V = cos α R + sin α (cos ψ e₁ + sin ψ e₂) about the mirror direction
  R = (−sin θ, 0, cos θ), e₁ = (cos θ, 0, sin θ), e₂ = (0, 1, 0); dω_V = sin α dα dψ and
  N·V = cos α cos θ + sin α sin θ cos ψ.
* ``half``: the half vector H = (sin δ cos φ, sin δ sin φ, cos δ), V = 2 (L·H) H − L,
  dω_V = 4 (L·H) sin δ dδ dφ (Walter et al. 2007, eq. 14), L·H = sin θ sin δ cos φ + cos θ cos δ,
  N·V = 2 (L·H) cos δ − cos θ.

In both, a level N·V = c or L·H = c of the integrand is a threshold cos φ = τ(r) = num/den of the
inner variable at each outer radius r (α or δ), with den ≥ 0; the horizon is the level N·V = 0.
The outer integral (``scipy.integrate.quad``, its own error estimate) is split where a threshold
enters or leaves (−1, 1) (num = ±den) or where two thresholds cross (num_j den_k = num_k den_j),
found on a dense scan and polished by ``brentq``, and at the lobe's scale points.  The inner
integral is a vectorised Gauss–Legendre pair (N and 2N nodes) on the pieces between the
thresholds, bisected until the pair agrees; the piece that ends at the horizon is integrated in
u with φ = a + (b − a)(1 − (1 − u)²), which takes a √(N·V) endpoint (Ward) out.

* ``disk`` (patch models, chapter 4): on the projected disk (cos θ_V dω_V = dx dy) in polar
  coordinates (ρ, ψ) about V'_P = −L_P = (−sin θ, 0): the unit disk ends at
  ρ_max(ψ) = s cos ψ + √(1 − s² sin² ψ) (s = sin θ), and m(L, V) = ρ.

The truth's error is the outer estimate plus the largest relative inner estimate times the value
plus a rounding allowance.

Two variants (session 5):

* ``hemisphere_albedo(..., extended=True)``: the same nested quadrature with every node, weight, value
  and sum in numpy's 80-bit long double (ε = 1.1e-19), the breakpoints still doubles, for truths sharp to
  the rounding of the double they are stored as (the engine's bounds reach ~100 ε of a double, and a row
  is judged only where the truth's error is a tenth of them);
* :func:`disk_albedo_vectorised`: the projected disk with all the nodes of a round of the outer and the
  inner quadratures in one call of the BRDF (He–Torrance, whose series is summed at every node).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
from scipy.optimize import brentq

EPS = np.finfo(float).eps
#: Relative tolerance asked of every quadrature of the third route.
EPSREL = 1e-13
#: Gauss–Kronrod 10/21 (QUADPACK's qk21; the constants as scipy.integrate.quad_vec prints them), as
#: strings, so that the extended-precision route (``extended=True``: numpy's 80-bit long double) gets them
#: to its own precision.
_XK_DIGITS = (
    "0.995657163025808080735527280689003", "0.973906528517171720077964012084452",
    "0.930157491355708226001207180059508", "0.865063366688984510732096688423493",
    "0.780817726586416897063717578345042", "0.679409568299024406234327365114874",
    "0.562757134668604683339000099272694", "0.433395394129247190799265943165784",
    "0.294392862701460198131126603103866", "0.148874338981631210884826001129720", "0.0",
)
_WG_DIGITS = (
    "0.066671344308688137593568809893332", "0.149451349150580593145776339657697",
    "0.219086362515982043995534934228163", "0.269266719309996355091226921569469",
    "0.295524224714752870173892994651338",
)
_WK_DIGITS = (
    "0.011694638867371874278064396062192", "0.032558162307964727478818972459390",
    "0.054755896574351996031381300244580", "0.075039674810919952767043140916190",
    "0.093125454583697605535065465083366", "0.109387158802297641899210590325805",
    "0.123491976262065851077958109831074", "0.134709217311473325928054001771707",
    "0.142775938577060080797094273138717", "0.147739104901338491374841515972068",
    "0.149445554002916905664936468389821",
)
LONG = np.longdouble


def _rule_arrays(dtype):
    xk, wg, wk = (np.array([dtype(x) for x in digits]) for digits in (_XK_DIGITS, _WG_DIGITS, _WK_DIGITS))
    return np.concatenate([xk, -xk[-2::-1]]), np.concatenate([wg, wg[::-1]]), np.concatenate([wk, wk[-2::-1]])


_RULES = {np.dtype(float): _rule_arrays(np.float64), np.dtype(LONG): _rule_arrays(LONG)}
_XK, _WG, _WK = _RULES[np.dtype(float)]


def _rule(dtype):
    """(nodes, Gauss weights, Kronrod weights) in ``dtype`` (float64 or long double)."""
    return _RULES[np.dtype(dtype)]


def gauss_kronrod(g, h):
    """(K21, QUADPACK's truncation estimate, rounding) of node values ``g`` (…, 21) on intervals of
    half-width h: I_dev min(1, (200 |K − G| / I_dev)^1.5), and 50 ε ∫|g| (Piessens et al. 1983, qk21).
    The adaptive loops refine on the truncation alone (rounding does not fall when an interval is
    halved) and report the sum."""
    _, wg, wk = _rule(g.dtype)
    k = h * (g @ wk)
    gauss = h * (g[..., 1::2] @ wg)
    dev = h * (np.abs(g - (k / (2 * h))[..., None]) @ wk)
    diff = np.abs(k - gauss)
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.where((dev > 0) & (diff > 0), dev * np.minimum(1.0, (200 * diff / dev) ** 1.5), diff)
    return k, err, 50 * np.finfo(g.dtype).eps * h * (np.abs(g) @ wk)
#: Rounds of bisection of the inner pieces.
_INNER_ROUNDS = 12
#: The inner acceptance (relative to the radius's integral) and rounds in long double.
_LONG_FLOOR = 5e-19
_LONG_INNER_ROUNDS = 18
#: Widest inner piece before the first comparison [rad].
_INNER_WIDTH = 0.4


@dataclass(frozen=True)
class Integrand:
    """What the third route needs of one BRDF.

    ``f(L, V, nl, nv, geo)`` evaluates the BRDF on arrays (…, 3) of directions; ``geo`` holds the
    frame's exact coordinates (``cos_axis``: R·V in the mirror frame, N·H in the half frame;
    ``lh``: L·H in the half frame) for formulas that can use them instead of a rounded dot product.
    ``nv_levels(nl)`` and ``lh_levels(nl, cos_delta)`` are the kinks (levels of N·V, of L·H);
    ``radial_points`` the lobe's scale points of the outer variable (α or δ in radians);
    ``normal_kink``: a cone-shaped kink at V = N (the outer radius of V = N is a breakpoint and the
    inner azimuth is refined geometrically toward it).
    """

    f: Callable
    frame: str
    radial_points: Sequence[float] = ()
    nv_levels: Callable = lambda nl: ()
    lh_levels: Callable = lambda nl, cos_delta: ()
    normal_kink: bool = False
    #: Relative accuracy of one evaluation of f beyond rounding (a truncated series).
    f_rtol: float = 0.0
    #: An integrable 1/√ singularity or a divergence is expected nowhere; extra outer points.
    extra_points: Sequence[float] = ()


@dataclass
class Truth:
    value: float
    error: float
    route: str
    evaluations: int = 0
    notes: list = field(default_factory=list)


def incidence(theta_deg):
    """(cos θ, sin θ), cos θ as sin(90° − θ) (exact to rounding at grazing angles)."""
    return float(np.sin(np.radians(90.0 - theta_deg))), float(np.sin(np.radians(theta_deg)))


# --- thresholds ------------------------------------------------------------------------------

def _mirror_thresholds(integrand, cl, sl, alpha):
    """(num, den) of every threshold cos ψ = τ at outer radii α; the horizon first."""
    ca, sa = np.cos(alpha), np.sin(alpha)
    den = sa * sl
    out = [(0.0 - ca * cl, den)]
    for c in integrand.nv_levels(cl):
        c = float(np.asarray(c).ravel()[0]) if np.ndim(c) else float(c)
        if 0.0 < c < 1.0:
            out.append((c - ca * cl, den))
    return out


def _half_thresholds(integrand, cl, sl, delta):
    cd, sd = np.cos(delta), np.sin(delta)
    den = sl * sd
    out = [(0.5 * cl / cd - cl * cd, den)]
    for c in integrand.nv_levels(cl):
        c = float(c)
        if 0.0 < c < 1.0:
            out.append((0.5 * (c + cl) / cd - cl * cd, den))
    for c in integrand.lh_levels(cl, cd):
        c = np.broadcast_to(np.asarray(c, float), np.shape(cd))
        out.append((np.where(np.isfinite(c), c, 10.0) - cl * cd, den))
    return out


def _thresholds(integrand, cl, sl, r):
    fn = _mirror_thresholds if integrand.frame == "mirror" else _half_thresholds
    return fn(integrand, cl, sl, np.asarray(r, float))


def _tau(num, den):
    num, den = np.broadcast_arrays(np.asarray(num, float), np.asarray(den, float))
    with np.errstate(divide="ignore", invalid="ignore"):
        t = num / den
    return np.where(den > 0, t, np.where(num > 0, np.inf, -np.inf))


# --- the outer breakpoints -----------------------------------------------------------------

def _scan_grid(lo, hi, anchors):
    """A dense grid of [lo, hi], geometric toward lo, hi and every anchor."""
    pts = [np.linspace(lo, hi, 3001)]
    width = hi - lo
    for a in (lo, hi, *anchors):
        if lo <= a <= hi:
            off = width * np.geomspace(1e-12, 1.0, 400)
            pts += [a + off, a - off]
    g = np.concatenate(pts)
    return np.unique(g[(g >= lo) & (g <= hi)])


def _roots(fun, grid):
    """Sign changes of fun on the grid, polished by brentq."""
    v = fun(grid)
    out = []
    s = np.sign(v)
    idx = np.nonzero((s[:-1] * s[1:] < 0) & np.isfinite(v[:-1]) & np.isfinite(v[1:]))[0]
    for i in idx:
        try:
            out.append(brentq(lambda x: float(fun(np.array([x]))[0]), grid[i], grid[i + 1], xtol=1e-15, rtol=4 * EPS))
        except ValueError:
            out.append(0.5 * (grid[i] + grid[i + 1]))
    out += list(grid[np.nonzero(v == 0)[0]])
    return out


def outer_breakpoints(integrand, cl, sl, lo, hi):
    """Outer radii where a threshold enters or leaves (−1, 1), two thresholds cross, plus the lobe's
    scale points, V = N (``normal_kink``) and the frame's own points, inside (lo, hi)."""
    anchors = [p for p in (*integrand.radial_points, *integrand.extra_points) if lo < p < hi]
    theta = float(np.arctan2(sl, cl))
    if integrand.normal_kink:
        anchors.append(theta if integrand.frame == "mirror" else 0.5 * theta)
    grid = _scan_grid(lo, hi, anchors)
    n_thr = len(_thresholds(integrand, cl, sl, grid[:2]))
    points = list(anchors)
    if sl > 0:
        for k in range(n_thr):
            for sign in (1.0, -1.0):
                def edge(r, k=k, sign=sign):
                    num, den = _thresholds(integrand, cl, sl, r)[k]
                    return np.broadcast_to(num, np.shape(r)) - sign * np.broadcast_to(den, np.shape(r))
                points += _roots(edge, grid)
            for j in range(k):
                def cross(r, j=j, k=k):
                    th = _thresholds(integrand, cl, sl, r)
                    (nj, dj), (nk, dk) = th[j], th[k]
                    tj, tk = np.clip(_tau(nj, dj), -2, 2), np.clip(_tau(nk, dk), -2, 2)
                    inside = (np.abs(tj) < 1) | (np.abs(tk) < 1)
                    return np.where(inside, tj - tk, np.nan)
                points += _roots(cross, grid)
    return np.unique([p for p in points if lo < p < hi])


# --- the inner integral --------------------------------------------------------------------

def _inner_pieces_many(integrand, cl, sl, rs):
    """Pieces (k, a, b, clustered) of the inner azimuth [0, φ_max] at every radius rs[k]: cut at
    every threshold inside (−1, 1) (and geometrically toward V = N for ``normal_kink``), no wider
    than :data:`_INNER_WIDTH`; ``clustered`` marks the piece that ends at a horizon cut."""
    taus = np.array([_tau(n, d) for n, d in _thresholds(integrand, cl, sl, rs)]).reshape(-1, rs.size)
    r0 = float(np.arctan2(sl, cl)) * (1.0 if integrand.frame == "mirror" else 0.5)
    rows = []
    for k in range(rs.size):
        horizon = taus[0, k]
        if horizon >= 1.0:
            continue
        phi_max = math.pi if horizon <= -1.0 else math.acos(horizon)
        cuts = {0.0, phi_max}
        for t in taus[1:, k]:
            if -1.0 < t < 1.0:
                p = math.acos(t)
                if 0.0 < p < phi_max:
                    cuts.add(p)
        if integrand.normal_kink and sl > 0:
            gap = abs(rs[k] - r0)
            for f in (0.3, 1.0, 3.0, 10.0, 30.0, 100.0):
                if 0.0 < f * gap < phi_max:
                    cuts.add(f * gap)
        cuts = sorted(cuts)
        cut_horizon = phi_max < math.pi
        for a, b in zip(cuts[:-1], cuts[1:]):
            n_split = max(1, math.ceil((b - a) / _INNER_WIDTH))
            step = (b - a) / n_split
            for i in range(n_split):
                x = a + i * step
                y = b if i == n_split - 1 else a + (i + 1) * step
                rows.append((k, x, y, cut_horizon and b == phi_max and i == n_split - 1))
    return rows


def _inner_pieces(integrand, cl, sl, r):
    """Pieces (a, b, clustered) of the inner azimuth at one radius r (:func:`_inner_pieces_many`)."""
    return [(a, b, c) for _, a, b, c in _inner_pieces_many(integrand, cl, sl, np.array([float(r)]))]


def _directions(integrand, cl, sl, r, phi):
    """(L, V, N·V, jacobian × 2, geo) at radii r and azimuths phi (broadcast)."""
    L = np.array([sl, 0.0, cl])
    r, phi = np.broadcast_arrays(np.asarray(r), np.asarray(phi))
    cp, sp = np.cos(phi), np.sin(phi)
    if integrand.frame == "mirror":
        ca, sa = np.cos(r), np.sin(r)
        V = np.stack([-ca * sl + sa * cp * cl, sa * sp, ca * cl + sa * cp * sl], -1)
        jac = 2.0 * sa
        geo = {"cos_axis": ca}
    else:
        cd, sd = np.cos(r), np.sin(r)
        H = np.stack([sd * cp, sd * sp, cd], -1)
        lh = sl * sd * cp + cl * cd
        V = 2.0 * lh[..., None] * H - L
        V[..., 2] = 2.0 * lh * cd - cl
        jac = 2.0 * 4.0 * lh * sd
        geo = {"cos_axis": cd, "lh": lh, "tan2": (sd / cd) ** 2}
    return L, V, V[..., 2], jac, geo


def _values(integrand, cl, sl, r, phi):
    L, V, nv, jac, geo = _directions(integrand, cl, sl, r, phi)
    Lb = np.broadcast_to(L, V.shape)
    with np.errstate(all="ignore"):
        f = integrand.f(Lb, V, np.full(nv.shape, cl), nv, geo)
    g = np.where(nv > 0, f * nv * jac, 0.0)
    return np.nan_to_num(g, nan=0.0, posinf=0.0)


def _sum_by(owner, weights, n):
    """Σ of ``weights`` per owner index (np.bincount, which has no long double: np.add.at then)."""
    if weights.dtype == np.float64:
        return np.bincount(owner, weights, minlength=n)
    out = np.zeros(n, weights.dtype)
    np.add.at(out, owner, weights)
    return out


def inner_integrals(integrand, cl, sl, rs, atol=0.0):
    """(values, errors, evaluations) of the azimuthal integrals at the outer radii ``rs``, all at
    once: the pieces of every radius (:func:`_inner_pieces`) by Gauss–Legendre pairs, each bisected
    until its pair agrees to 1e-15 of its radius's integral or to ``atol`` per unit azimuth (a floor
    from the outer integral's scale: at the edge of the domain N·V is computed with cancellation,
    whose rounding would otherwise be refined forever)."""
    rs = np.atleast_1d(np.asarray(rs))
    rs = rs.astype(LONG if rs.dtype == LONG else float)
    dtype = rs.dtype
    xk = _rule(dtype)[0]
    floor, rounds = (1e-15, _INNER_ROUNDS) if dtype == np.float64 else (_LONG_FLOOR, _LONG_INNER_ROUNDS)
    rows = _inner_pieces_many(integrand, cl, sl, rs)
    total, error = np.zeros(rs.size, dtype), np.zeros(rs.size, dtype)
    if not rows:
        return total, error, 0
    owner = np.array([x[0] for x in rows])
    a = np.array([x[1] for x in rows], dtype)
    b = np.array([x[2] for x in rows], dtype)
    clu = np.array([x[3] for x in rows], bool)
    u0, u1 = np.zeros(a.size, dtype), np.ones(a.size, dtype)
    evals = 0
    for round_ in range(rounds):
        u = 0.5 * (u0 + u1)[:, None] + 0.5 * (u1 - u0)[:, None] * xk
        lin = a[:, None] + (b - a)[:, None] * u
        cur = a[:, None] + (b - a)[:, None] * (1.0 - (1.0 - u) ** 2)
        phi = np.where(clu[:, None], cur, lin)
        dphi = np.where(clu[:, None], 2.0 * (b - a)[:, None] * (1.0 - u), (b - a)[:, None])
        g = _values(integrand, cl, sl, rs[owner][:, None], phi) * dphi
        evals += phi.size
        q2, diff, rnd = gauss_kronrod(g, 0.5 * (u1 - u0))
        scale = np.abs(total) + _sum_by(owner, np.abs(q2), rs.size)
        width = (b - a) * (u1 - u0)
        done = diff <= np.maximum(floor * scale[owner], atol * width / np.pi)
        if round_ == rounds - 1:
            done[:] = True
        total += _sum_by(owner[done], q2[done], rs.size)
        error += _sum_by(owner[done], diff[done] + rnd[done], rs.size)
        keep = ~done
        if not keep.any():
            break
        mid = 0.5 * (u0 + u1)
        owner, a, b, clu = (np.concatenate([x[keep], x[keep]]) for x in (owner, a, b, clu))
        u0, u1 = np.concatenate([u0[keep], mid[keep]]), np.concatenate([mid[keep], u1[keep]])
    return total, error, evals


def inner_integral(integrand, cl, sl, r, atol=0.0):
    """(value, error, evaluations) of the azimuthal integral at one outer radius r."""
    v, e, n = inner_integrals(integrand, cl, sl, [r], atol)
    return float(v[0]), float(e[0]), n


# --- the outer integral --------------------------------------------------------------------

_OUTER_ROUNDS = 40


def _outer_quad(outer, edges, epsrel):
    """∫ outer over the pieces ``edges``, globally adaptive: every interval by a Gauss–Legendre pair
    (N = 12 and 24 nodes; all the nodes of a round in one vectorised call of ``outer``, which maps
    radii to (inner value, inner error) pairs), the intervals whose disagreement exceeds their share of
    epsrel × |integral| bisected, until the summed disagreement is below it.  (value, summed
    disagreement + integrated inner error, notes).  An interval narrower than 1e-14 of the range is
    accepted as it is (rounding)."""
    edges = np.asarray(edges)
    edges = edges.astype(LONG if edges.dtype == LONG else float)
    lo, hi = edges[:-1], edges[1:]
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    xk, _, wk = _rule(edges.dtype)
    span = float(hi.sum() - lo.sum()) if lo.size else 0.0
    value = error = inner_err = edges.dtype.type(0)
    notes = []
    for round_ in range(_OUTER_ROUNDS):
        if lo.size == 0:
            break
        r = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * xk
        vals = outer(r.ravel()).reshape(r.shape + (2,))
        q1, diff, rnd = gauss_kronrod(vals[..., 0], 0.5 * (hi - lo))
        inner = 0.5 * (hi - lo) * (np.abs(vals[..., 1]) @ wk)
        q = [None, q1]
        estimate = value + q[1].sum()
        tol = epsrel * abs(estimate)
        remaining = error + diff.sum()
        tiny = (hi - lo) <= (1e-14 if edges.dtype == np.float64 else 1e-17) * max(span, 1e-300)
        if remaining <= tol or round_ == _OUTER_ROUNDS - 1:
            done = np.ones(lo.size, bool)
            if remaining > tol:
                notes.append(f"outer: {remaining:.2g} left of {tol:.2g} after {_OUTER_ROUNDS} rounds")
        else:
            done = (diff <= 0.25 * tol * (hi - lo) / max(span, 1e-300)) | tiny
        value += q[1][done].sum()
        error += diff[done].sum() + rnd[done].sum()
        inner_err += inner[done].sum()
        mid = 0.5 * (lo + hi)
        lo, hi = np.concatenate([lo[~done], mid[~done]]), np.concatenate([mid[~done], hi[~done]])
    return value, error + inner_err, notes


def _outer_range(integrand, cl, sl):
    """[0, r_max]: beyond r_max no direction of the shell is above the horizon."""
    theta = float(np.arctan2(sl, cl))
    if integrand.frame == "mirror":
        return 0.0, min(np.pi, 0.5 * np.pi + theta)
    return 0.0, min(0.5 * np.pi, 0.5 * (0.5 * np.pi + theta))


#: The long-double route's allowance for what stays double (the breakpoints, the horizon and threshold
#: cuts, the thresholds' own arithmetic), relative: 2 ε of a double.  Calibrated on mpmath: Cook–Torrance
#: (Torrance–Sparrow) at 89.9999°/89.99999°, m = 0.052342, 30-digit nested quadrature
#: (:mod:`sweep.ct_mp`), the long-double values were 1.9e-16 and 1.5e-16 off (their quadrature estimates
#: 4e-17 and 6e-17).  NOT enough everywhere: for Cook–Torrance (Torrance–Sparrow) at 89.99999°–89.9999999°
#: the long-double values were up to 1.2e-13 off the mpmath ones (250× their error; the package's disk
#: sides with mpmath), so those cells take the mpmath route (:data:`sweep.sharp.MP_GRAZING_THETA`); the
#: cause (likely the double-precision L·H-level cuts at cos θ ~ 1e-7) is not found.
EXTENDED_CUT_RTOL = 2 * EPS


def hemisphere_albedo(integrand: Integrand, theta_deg: float, epsrel: float = EPSREL,
                      extended: bool = False) -> Truth:
    """a(θ) by the nested quadrature of the module docstring, with its error estimate.

    ``extended``: every node, weight, integrand value and sum in numpy's 80-bit long double (ε = 1.1e-19;
    the breakpoints stay doubles: a kink misplaced by δ costs O(δ²)), so that the truth's error can fall to
    the rounding of the double it is stored as; the value is that double, the error adds the rounding.
    Special functions the integrand takes from scipy stay doubles: their share is ``integrand.f_rtol``."""
    cl, sl = incidence(theta_deg)
    lo, hi = _outer_range(integrand, cl, sl)
    points = outer_breakpoints(integrand, cl, sl, lo, hi)
    edges = np.concatenate([[lo], points, [hi]])
    eps = EPS
    if extended:
        cl = np.sin(np.radians(LONG(90) - LONG(theta_deg)))
        sl = np.sin(np.radians(LONG(theta_deg)))
        edges, eps = edges.astype(LONG), float(np.finfo(LONG).eps)
    state = {"evals": 0, "peak": 0.0}

    def outer(r):
        v, e, n = inner_integrals(integrand, cl, sl, r, atol=(1e-16 if not extended else 1e-19) * state["peak"])
        state["evals"] += n
        state["peak"] = max(state["peak"], float(np.max(np.abs(v), initial=0.0)))
        return np.stack([v, e], -1)

    value, error, notes = _outer_quad(outer, edges, epsrel)
    error += (64 * eps + integrand.f_rtol) * abs(value)
    if extended:
        stored = float(value)
        error = float(error) + float(abs(LONG(stored) - value)) + EXTENDED_CUT_RTOL * abs(stored)
        value = stored
    return Truth(value, error, f"quad/{integrand.frame}" + ("/long_double" if extended else ""), state["evals"], notes)


# --- the projected disk (patch models) ---------------------------------------------------------

def disk_rho_max(s, psi):
    """ρ_max(ψ) = s cos ψ + √(1 − s² sin² ψ): where the ray from (−s, 0) at angle ψ leaves the unit disk."""
    c, sn = np.cos(psi), np.sin(psi)
    return s * c + np.sqrt(np.maximum(1.0 - (s * sn) ** 2, 0.0))


def _gl_pair(fun, a, b, rounds=14, clustered=False):
    """∫_a^b fun by bisected Gauss–Legendre pairs (vectorised fun): (value, error).  ``clustered``:
    in u with x = b − (b − a)(1 − u)², which takes a √(b − x) endpoint out."""
    if clustered:
        g = lambda u: fun(b - (b - a) * (1.0 - u) ** 2) * 2.0 * (b - a) * (1.0 - u)
        return _gl_pair(g, 0.0, 1.0, rounds)
    work = [(a, b)]
    total, error = 0.0, 0.0
    for k in range(rounds):
        lo = np.array([w[0] for w in work])
        hi = np.array([w[1] for w in work])
        t = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * _XK
        k21, diff, rnd = gauss_kronrod(fun(t), 0.5 * (hi - lo))
        q = [None, k21]
        scale = max(abs(total) + np.sum(np.abs(q[1])), 1e-300)
        done = diff <= 1e-15 * scale
        if k == rounds - 1:
            done[:] = True
        total += float(np.sum(q[1][done]))
        error += float(np.sum(diff[done] + rnd[done]))
        mid = 0.5 * (lo + hi)
        work = [(lo[i], mid[i]) for i in np.nonzero(~done)[0]] + [(mid[i], hi[i]) for i in np.nonzero(~done)[0]]
        if not work:
            break
    return total, error


def disk_albedo(xi, theta_deg, radial_kinks=(), radial_scales=(), ellipse_radius=None,
                symmetric=True, epsrel: float = EPSREL, psi_radii=None, horizon_layer=False) -> Truth:
    """a(θ) = ∫∫ ξ(ρ, ψ) ρ dρ dψ over the unit disk, polar about (−sin θ, 0).

    ``xi(rho, psi)`` is the BRDF as a function of the polar coordinates (m = ρ for the patch models);
    ``radial_kinks`` its kinks or jumps in ρ (the same for every ψ); ``ellipse_radius(psi)`` a kink or
    jump at a ψ-dependent radius (the elliptical patch), or None; ``radial_scales`` extra inner points.
    The outer integral in ψ (quad) splits where ρ_max(ψ) meets a kink radius.
    """
    cl, s = incidence(theta_deg)
    top = np.pi if symmetric else 2 * np.pi
    def inner(psi):
        rmax = float(disk_rho_max(s, psi))
        cuts = {0.0, rmax}
        for k in (*radial_kinks, *radial_scales):
            if 0.0 < k < rmax:
                cuts.add(float(k))
        extra = [] if ellipse_radius is None else [float(ellipse_radius(psi))]
        extra += [] if psi_radii is None else list(psi_radii(psi))
        for k in extra:
            if 0.0 < k < rmax:
                cuts.add(k)
        cuts = sorted(cuts)
        v, e = 0.0, 0.0
        for a, b in zip(cuts[:-1], cuts[1:]):
            vi, ei = _gl_pair(lambda rho: xi(rho, np.full(rho.shape, psi)) * rho, a, b,
                              clustered=horizon_layer and b == rmax)
            v, e = v + vi, e + ei
        return np.array([v, e])

    points = []
    for k in radial_kinks:
        if s > 0 and k > 0:
            c = (s * s + k * k - 1.0) / (2.0 * s * k)
            if -1.0 < c < 1.0:
                points += [float(np.arccos(c))] + ([2 * np.pi - float(np.arccos(c))] if not symmetric else [])
    if ellipse_radius is not None:
        grid = np.linspace(0.0, top, 20001)
        points += _roots(lambda p: disk_rho_max(s, p) - np.array([ellipse_radius(x) for x in np.atleast_1d(p)]), grid)
    if s > 0.5:     # toward ψ = π the disk's chord ρ_max → 1 − s shrinks: its scale √(2(1 − s)) geometric
        w = math.sqrt(2.0 * max(1.0 - s, 1e-300))
        near = [math.pi - w * k for k in (0.25, 0.5, 1, 2, 4, 8, 16, 32, 64) if w * k < 1.0]
        points += near + ([math.pi + (math.pi - x) for x in near] if not symmetric else [])
    if cl < 0.1:    # ρ_max(ψ) = s cos ψ + √(1 − s² sin² ψ) has a √ layer of width ~cos θ about ψ = π/2
        # (the root's minimum cos θ there): cuts graded into it, so that the outer quad does not find
        # the layer by bisection alone (a precaution; the truths from 03:45 on were computed with them)
        for centre in ((0.5 * math.pi,) if symmetric else (0.5 * math.pi, 1.5 * math.pi)):
            points += [centre + sign * cl * k for k in 2.0 ** np.arange(-8, 9) for sign in (-1.0, 1.0)
                       if cl * k < 0.5]
    edges = np.unique(np.concatenate([[0.0], [p for p in points if 0 < p < top], [top]]))
    value, error, notes = _outer_quad(lambda psis: np.array([inner(p) for p in psis]), edges, epsrel)
    factor = 2.0 if symmetric else 1.0
    value, error = factor * value, factor * error
    error += 64 * EPS * abs(value)
    return Truth(value, error, "quad/disk", 0, notes)


# --- the projected disk, vectorised (He–Torrance) ------------------------------------------------

def _disk_roots(s, cl, cos_psi):
    """(ρ_max, |ρ_min|) of the ray from (−s, 0) at angle ψ through the unit disk, without cancellation:
    ρ² − 2 s cos ψ ρ − cos²θ = 0, q = √(cos²θ + s² cos²ψ), ρ_max |ρ_min| = cos²θ."""
    q = np.sqrt(cl * cl + (s * cos_psi) ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        rho_max = np.where(cos_psi >= 0, s * cos_psi + q, cl * cl / (q - s * cos_psi))
        rho_min = np.where(cos_psi >= 0, cl * cl / (q + s * cos_psi), q - s * cos_psi)
    return rho_max, rho_min


def _level_radii(s, cl, cos_psi, c):
    """The radii ρ± = s cos ψ ± √(cos²θ − c² + s² cos²ψ) where the ray meets the circle N·V = c (NaN where not)."""
    disc = cl * cl - c * c + (s * cos_psi) ** 2
    with np.errstate(invalid="ignore"):
        root = np.sqrt(np.where(disc >= 0, disc, np.nan))
    return s * cos_psi + root, s * cos_psi - root


_DISK_INNER_ROUNDS = 30


def _disk_inner(xi, s, cl, psi, radial_points, layer_levels, atol):
    """(values, errors, evaluations) of ∫₀^{ρ_max(ψ)} ξ(ρ, ψ) ρ dρ at every ψ of ``psi`` at once: pieces cut at
    the radial points and at the level radii of N·V = c (c in ``layer_levels``), each by an adaptive
    Gauss–Kronrod 21 pair; the piece that ends at ρ_max in u with ρ = b − (b − a)(1 − u)² (a √(ρ_max − ρ)
    end, N·V → 0).  The error adds the series' truncation bound of ξ integrated."""
    n = psi.size
    cp = np.cos(psi)
    rmax, _ = _disk_roots(s, cl, cp)
    cand = [np.zeros(n), rmax]
    for k in radial_points:
        cand.append(np.full(n, float(k)))
    for c in layer_levels:
        cand += list(_level_radii(s, cl, cp, c))
    C = np.stack(cand, -1)
    C = np.where(np.isfinite(C) & (C >= 0) & (C <= rmax[:, None]), C, np.nan)
    C = np.sort(C, -1)                                     # NaNs last
    a, b = C[:, :-1], C[:, 1:]
    ok = np.isfinite(a) & np.isfinite(b) & (b > a)
    owner = np.nonzero(ok)[0]
    a, b = a[ok], b[ok]
    clu = b == rmax[owner]
    u0, u1 = np.zeros(a.size), np.ones(a.size)
    total, error = np.zeros(n), np.zeros(n)
    evals = 0
    for round_ in range(_DISK_INNER_ROUNDS):
        if a.size == 0:
            break
        u = 0.5 * (u0 + u1)[:, None] + 0.5 * (u1 - u0)[:, None] * _XK
        w = (b - a)[:, None]
        rho = np.where(clu[:, None], b[:, None] - w * (1.0 - u) ** 2, a[:, None] + w * u)
        to_edge = np.where(clu[:, None], w * (1.0 - u) ** 2, rmax[owner][:, None] - rho)
        drho = np.where(clu[:, None], 2.0 * w * (1.0 - u), w)
        f, tail = xi(rho, np.broadcast_to(psi[owner][:, None], rho.shape), to_edge)
        evals += rho.size
        k21, diff, rnd = gauss_kronrod(f * rho * drho, 0.5 * (u1 - u0))
        trunc = 0.5 * (u1 - u0) * ((tail * rho * drho) @ _WK)
        scale = np.abs(total) + np.bincount(owner, np.abs(k21), minlength=n)
        done = diff <= np.maximum(1e-15 * scale[owner], atol * (b - a) * (u1 - u0))
        if round_ == _DISK_INNER_ROUNDS - 1:
            done[:] = True
        total += np.bincount(owner[done], k21[done], minlength=n)
        error += np.bincount(owner[done], (diff + rnd + trunc)[done], minlength=n)
        keep = ~done
        mid = 0.5 * (u0 + u1)
        owner, a, b, clu = (np.concatenate([x[keep], x[keep]]) for x in (owner, a, b, clu))
        u0, u1 = np.concatenate([u0[keep], mid[keep]]), np.concatenate([mid[keep], u1[keep]])
    return total, error, evals


def disk_albedo_vectorised(xi, theta_deg, radial_points=(), layer_levels=(), epsrel: float = EPSREL,
                           f_rtol: float = 0.0) -> Truth:
    """a(θ) = 2 ∫₀^π ∫₀^{ρ_max(ψ)} ξ(ρ, ψ) ρ dρ dψ on the projected disk, polar about (−sin θ, 0), for a BRDF
    symmetric about the plane of incidence; every node of a round of the outer quadrature (:func:`_outer_quad`)
    and of the inner one (:func:`_disk_inner`) in one call of ``xi(rho, psi, to_edge)`` → (f, truncation
    bound), ``to_edge`` = ρ_max(ψ) − ρ computed without cancellation.  Outer cuts: where ρ_max(ψ) meets a
    radial point, where a level circle N·V = c becomes tangent to the ray, graded toward ψ = π (the chord
    1 − s shrinks) and toward ψ = π/2 at grazing incidence (the √ layer of ρ_max, width ~cos θ)."""
    cl, s = incidence(theta_deg)
    points = []
    for k in radial_points:
        if s > 0 and k > 0:
            c = (s * s + k * k - 1.0) / (2.0 * s * k)
            if -1.0 < c < 1.0:
                points.append(float(np.arccos(c)))
    for c in layer_levels:
        if s > 0 and c > cl:
            x = math.sqrt(c * c - cl * cl) / s
            if x < 1.0:
                points.append(math.acos(x))
    if s > 0.5:
        w = math.sqrt(2.0 * max(1.0 - s, 1e-300))
        points += [math.pi - w * k for k in (0.25, 0.5, 1, 2, 4, 8, 16, 32, 64) if w * k < 1.0]
    if cl < 0.1:
        points += [0.5 * math.pi + sign * cl * k for k in 2.0 ** np.arange(-8, 9) for sign in (-1.0, 1.0)
                   if cl * k < 0.5]
    edges = np.unique(np.concatenate([[0.0], [p for p in points if 0 < p < math.pi], [math.pi]]))
    state = {"evals": 0, "peak": 0.0}

    def outer(psis):
        v, e, n = _disk_inner(xi, s, cl, psis, radial_points, layer_levels, atol=1e-17 * state["peak"])
        state["evals"] += n
        state["peak"] = max(state["peak"], float(np.max(np.abs(v), initial=0.0)))
        return np.stack([v, e], -1)

    value, error, notes = _outer_quad(outer, edges, epsrel)
    value, error = 2.0 * value, 2.0 * error
    error += (64 * EPS + f_rtol) * abs(value)
    return Truth(value, error, "quad/disk", state["evals"], notes)
