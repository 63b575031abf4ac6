"""Cook–Torrance with eq. 2.10's G (Torrance–Sparrow) by a nested mpmath quadrature (tanh-sinh, 30 digits),
for the grazing cells whose double-precision truths were suspect (issue 24, session 5).

Half-vector frame (as :mod:`sweep.third_route`): L = (s, 0, c), H = (sin δ cos φ, sin δ sin φ, cos δ),
L·H = c cos δ + s sin δ cos φ, N·V = 2 (L·H) cos δ − c, dω_V = 4 (L·H) sin δ dδ dφ, so with
f = D G/(N·L N·V), D = e^{−tan²δ/m²}/(4π m² cos⁴δ) (eq. 2.9, F = 1) and G = min(1, 2 cos δ N·V/L·H,
2 cos δ N·L/L·H) (eq. 2.10):

    a(θ) = 2 ∫ dδ ∫₀^{φ_h(δ)} D G 4 (L·H) sin δ / c dφ.

At each δ the integrand's pieces in φ are cut where L·H (decreasing in φ) reaches the horizon
c/(2 cos δ), the shadowing level 2 c cos δ and the masking level 2 c cos δ/(4 cos²δ − 1); the outer
integral is cut where one of them reaches the ends cos(δ ∓ θ) of L·H's range, at δ = π/4 and π/3 (where
two levels meet) and at the lobe's scales atan(k m).  mpmath's error estimates are summed.  Nothing here
imports the package.
"""
from __future__ import annotations

import math

import mpmath as mp

from sweep.third_route import Truth

DPS = 30


def _levels(c, cd):
    out = [c / (2 * cd), 2 * c * cd]
    if 4 * cd * cd > 1:
        out.append(2 * c * cd / (4 * cd * cd - 1))
    return out


def cook_torrance_ts_albedo(m, theta_deg, dps: int = DPS) -> Truth:
    with mp.workdps(dps):
        th = mp.radians(mp.mpf(float(theta_deg)))
        s, c = mp.sin(th), mp.cos(th)
        m = mp.mpf(m)
        err = [mp.mpf(0)]

        def inner(delta):
            cd, sd = mp.cos(delta), mp.sin(delta)
            d = mp.exp(-(sd / cd) ** 2 / m ** 2) / (4 * mp.pi * m * m * cd ** 4)
            if s * sd == 0:
                return mp.mpf(0)

            def phi_of(level):
                t = (level - c * cd) / (s * sd)
                return None if t >= 1 else (mp.pi if t <= -1 else mp.acos(t))
            horizon = phi_of(c / (2 * cd))
            if horizon is None:
                return mp.mpf(0)
            cuts = sorted({mp.mpf(0), horizon, *[p for p in map(phi_of, _levels(c, cd)[1:])
                                                  if p is not None and 0 < p < horizon]})

            def g(phi):
                lh = c * cd + s * sd * mp.cos(phi)
                nv = 2 * lh * cd - c
                G = min(mp.mpf(1), 2 * cd * nv / lh, 2 * cd * c / lh)
                return d * G * 4 * lh * sd / c
            v, e = mp.quad(g, cuts, error=True)
            err[0] += abs(e)
            return v

        top = (mp.pi / 2 + th) / 2
        pts = {mp.mpf(0), top, mp.pi / 4, mp.pi / 3}
        pts |= {mp.atan(m * k) for k in (0.25, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 5, 6, 7, 8)}

        def edge(level_index, sign):
            def fn(delta):
                cd = mp.cos(delta)
                lv = _levels(c, cd)
                if level_index >= len(lv):
                    return None
                return lv[level_index] - mp.cos(delta - sign * th)
            return fn
        grid = sorted(set([float(top) * k / 4000 for k in range(4001)]
                          + [float(a) + sg * float(top) * 10.0 ** -e for a in (0.0, float(th) / 2, float(top))
                             for e in range(1, 15) for sg in (-1, 1)]))
        grid = [x for x in grid if 0 <= x <= float(top)]
        for k in range(3):
            for sign in (1, -1):
                fn = edge(k, sign)
                prev = None
                for x in grid:
                    v = fn(mp.mpf(x))
                    if v is not None and prev is not None and prev[1] is not None and v * prev[1] < 0:
                        pts.add(mp.findroot(fn, (mp.mpf(prev[0]), mp.mpf(x)), solver="anderson"))
                    prev = (x, v)
        pts = sorted(p for p in pts if 0 <= p <= top)
        v, e = mp.quad(inner, pts, error=True)
        value = 2 * v
        stored = float(value)
        # the outer estimate (the inner integrals' own estimates, summed in the notes, are mpmath's
        # level differences at each node: far cruder than their effect on the outer sum)
        error = float(2 * abs(e)) + float(abs(mp.mpf(stored) - value))
        return Truth(stored, error, "mp_2d/half+independent", 0, [f"mp {mp.nstr(value, 22)}",
                                                                 f"inner err sum {mp.nstr(2 * err[0], 3)}"])
