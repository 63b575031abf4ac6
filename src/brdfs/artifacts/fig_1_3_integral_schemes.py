"""Figure 1.3: schemes of the BRDF's integral formulae — albedo (eq. 1.13) and composition (eq. 1.21).

Left: light from L on a surface f is reflected into the whole hemisphere; the reflected fraction
is the albedo a_f(L). Right: the construction of the composition C_{f1,f2}(L, V) (Sec. 1.1.4):
light from L on f1 is reflected into the hemisphere, returned unaltered by a (nearly) spherical
mirror and arrives on f2 from the whole hemisphere; the radiance leaving f2 in V is the
composition. L is the direction *to* the light, as in Fig. 1.2: its arrow starts at the surface
(at f1) and points toward the light (a star beyond the label), like V toward the observer. The
elements sit at ∓a of the mirror's centre: a spherical mirror images its centre
of curvature onto itself inverted, so rays leaving −a return near +a (to O(a²)). The rays are
traced (reflection r' = r − 2(r·n)n at the mirror); sizes and angles are choices (config
``diagrams.fig_1_3``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.pipeline.registry import figure

NAME = "fig_1_3_integral_schemes"


def trace(start, angles_rad):
    """Rays from ``start`` (inside the unit circle) at ``angles_rad``: mirror hit point and the
    reflected ray's crossing of the x axis (the surface plane)."""
    d = np.stack([np.cos(angles_rad), np.sin(angles_rad)], -1)
    b = d @ start
    s = -b + np.sqrt(b * b - (start @ start - 1.0))  # |start + s d| = 1
    hit = start + s[:, None] * d
    out = d - 2 * np.sum(d * hit, -1, keepdims=True) * hit  # unit normal of the unit circle = hit
    back = -hit[:, 1] / out[:, 1]
    return hit, hit[:, 0] + back * out[:, 0]


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``ray, angle_deg, hit_x, hit_y, land_x`` of the traced rays and the offset ``a``."""
    c = cfg[dg.SECTION]["fig_1_3"]
    a = float(c["offset"])
    angles = np.linspace(c["ray_min_deg"], 180.0 - c["ray_min_deg"], int(c["rays"]))
    hit, land = trace(np.array([-a, 0.0]), np.radians(angles))
    return pd.DataFrame({"ray": np.arange(angles.size), "offset": a, "theta_l_deg": c["theta_l_deg"],
                         "theta_v_deg": c["theta_v_deg"], "angle_deg": angles, "hit_x": hit[:, 0],
                         "hit_y": hit[:, 1], "land_x": land})


def plot(df: pd.DataFrame, path) -> None:
    fig, (left, right) = dg.new_canvas(9.0, 3.6, ncols=2)
    a = float(df["offset"].iloc[0])
    tl, tv = np.radians(df["theta_l_deg"].iloc[0]), np.radians(df["theta_v_deg"].iloc[0])
    L = np.array([-np.sin(tl), np.cos(tl)])
    V = np.array([np.sin(tv), np.cos(tv)])
    # Albedo: reflected into the whole hemisphere.
    left.plot([-1.1, 1.1], [0, 0], "k", lw=1.0)
    left.plot([-0.12, 0.12], [0, 0], "k", lw=4)
    for ang in np.radians(df["angle_deg"]):
        dg.arrow(left, (0, 0), 0.7 * np.array([np.cos(ang), np.sin(ang)]), color="tab:blue", lw=0.7)
    # L (to the light, as in Fig. 1.2) is drawn on top of the rays from the surface out, its head,
    # label and the light (star) beyond the fan of rays.
    dg.arrow(left, (0, 0), 0.86 * L, color="tab:orange", lw=2.0, zorder=4)
    dg.label(left, 0.96 * L, "L", color="tab:orange")
    left.plot(*(1.09 * L), "*", color="tab:orange", ms=11, zorder=4)
    left.text(-0.1, -0.18, "f", fontsize=10)
    left.text(-1.0, 1.0, r"$a_f(L)=\int_\Omega f(L,V)\cos\Theta_V\,d\omega_V$", fontsize=9)
    left.set_xlim(-1.15, 1.15), left.set_ylim(-0.3, 1.15)
    left.set_title("albedo (eq. 1.13)", fontsize=9)
    # Composition: f1 at -a, spherical mirror, f2 at +a.
    t = np.linspace(0, np.pi, 200)
    right.plot(np.cos(t), np.sin(t), color="0.3", lw=2.0)
    right.plot([-1.1, 1.1], [0, 0], "k", lw=1.0)
    for x, name in ((-a, "f1"), (a, "f2")):
        right.plot([x - 0.06, x + 0.06], [0, 0], "k", lw=4)
        right.text(x - 0.04, -0.17, name, fontsize=9)
    for row in df.itertuples():
        right.plot([-a, row.hit_x, row.land_x], [0, row.hit_y, 0], color="tab:blue", lw=0.5, alpha=0.45, zorder=1)
    # L and V on top of the rays, thick; their labels on an opaque ground that masks the rays only.
    dg.arrow(right, (-a, 0), (-a, 0) + 0.6 * L, color="tab:orange", lw=2.0, zorder=4)
    dg.label(right, (-a, 0) + 0.72 * L, "L", color="tab:orange", masked=True)
    right.plot(*((-a, 0) + 0.85 * L), "*", color="tab:orange", ms=11, zorder=4)
    dg.arrow(right, (a, 0), (a, 0) + 0.6 * V, color="tab:green", lw=2.0, zorder=4)
    dg.label(right, (a, 0) + 0.72 * V, "V", color="tab:green", masked=True)
    right.text(-1.05, 1.02, "spherical mirror", fontsize=8, color="0.3")
    right.text(0.05, -0.36, r"$C_{f_1,f_2}(L,V)=\int_\Omega f_1(L,X) f_2(X,V)\cos\Theta_X\,d\omega_X$",
               fontsize=9, ha="center")
    right.set_xlim(-1.15, 1.15), right.set_ylim(-0.48, 1.15)
    right.set_title("composition (eq. 1.21)", fontsize=9)
    fig.suptitle("Fig. 1.3: schemes of the BRDF's integral formulae", fontsize=10)
    dg.save(fig, path)
