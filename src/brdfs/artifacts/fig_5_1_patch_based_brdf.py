"""Figure 5.1: patch-based BRDF, f(L, V) = χ(H) · F(d(R, V)) (Sec. 5.2).

Left, on the base plane: the base circle, the projection R_P = L'_P of the mirror direction, the
patch {V : d(R, V) = |V_P − R_P| ≤ p} ∩ base circle (the lens of
:func:`brdfs.physics.patch_geometry.circle_intersection`, d = sin θ_L, R = p), a V inside it
with its distance and the projection H_P of the bisecting vector. H is Sec. 5.2.2's "bisecting
vector function": the bisector of R and V, H = (R + V)/|R + V| (not the half vector of L and V —
"H and H are generally not the same"); N·H is symmetric in L and V because mirroring both L and V
maps R + V onto L + R(V). Right: f in the plane of incidence for χ(H) = (N·H)^a (a = −1: the
"patch-based metallic" character of Sec. 5.2.3) and F the patch's indicator, unnormalised (c_p
omitted); in that plane N·H = cos((θ_L + θ_V)/2) on the mirror side, so χ rises as 1/cos across
the patch. θ_L, p, a and V are choices (config ``diagrams.fig_5_1``).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics.patch_geometry import circle_intersection
from brdfs.physics import geometry as geo
from brdfs.physics.models.patch import projected_distance
from brdfs.pipeline.registry import figure

NAME = "fig_5_1_patch_based_brdf"


def bisector(L, V):
    """Sec. 5.2.2's bisecting vector H(L, V) = (R + V)/|R + V|, R = L' the mirror of L (arrays (..., 3))."""
    h = geo.mirror(L) + V
    return h / np.linalg.norm(h, axis=-1, keepdims=True)


def patch_brdf(L, V, p, a):
    """χ(N·H) · 1[d(R, V) ≤ p] with χ(x) = x^a and H the :func:`bisector` of R and V, unnormalised
    (eq. 5.9 without c_p; Sec. 5.2.3)."""
    inside = projected_distance(L, V) <= p
    n_dot_h = np.clip(bisector(L, V)[..., 2], 1e-300, None)  # H is on the upper hemisphere inside the patch
    return np.where(inside & (V[..., 2] > 0), n_dot_h ** a, 0.0)


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``kind, quantity, value`` for the drawn points and ``kind = slice`` rows ``theta_v_deg``, ``f``."""
    c = cfg[dg.SECTION]["fig_5_1"]
    p, a = float(c["patch_radius"]), float(c["character_exponent"])
    L = geo.light_direction(c["theta_l_deg"])
    V = geo.direction(c["theta_v_deg"], c["phi_v_deg"])
    R = geo.mirror(L)
    lens = circle_intersection(float(np.hypot(*R[:2])), p)
    points = dg.frame({**dg.vec("R_P", R[:2]), **dg.vec("V_P", V[:2]), **dg.vec("H_P", bisector(L, V)[:2]),
                       "patch_radius": p, "character_exponent": a, "distance": float(projected_distance(L, V)),
                       "patch_area": float(lens.area), "f": float(patch_brdf(L, V, p, a))}).assign(kind="point")
    # Signed viewing angle in the plane of incidence: positive toward the mirror side (φ = 180°).
    theta = np.linspace(-90.0, 90.0, int(round(180.0 / c["slice_step_deg"])) + 1)
    Vs = geo.direction(np.abs(theta), np.where(theta >= 0, 180.0, 0.0))
    f = patch_brdf(np.broadcast_to(L, Vs.shape), Vs, p, a)
    curve = pd.DataFrame({"kind": "slice", "quantity": "f", "theta_v_deg": theta, "value": f})
    return pd.concat([points, curve], ignore_index=True)[["kind", "quantity", "theta_v_deg", "value"]]


def plot(df: pd.DataFrame, path) -> None:
    v = dg.values(df[df["kind"] == "point"])
    s = df[df["kind"] == "slice"]
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(8.4, 3.8))
    ax = fig.add_axes([0.02, 0.05, 0.45, 0.82])
    ax.set_aspect("equal"), ax.axis("off")
    t = np.linspace(0, 2 * np.pi, 300)
    ax.plot(np.cos(t), np.sin(t), "k", lw=1.0)
    Rp, Vp, Hp, p = dg.get(v, "R_P", 2), dg.get(v, "V_P", 2), dg.get(v, "H_P", 2), v["patch_radius"]
    d = float(np.hypot(*Rp))
    poly = dg.rotate2(dg.lens_polygon(d, p), dg.angle_of(Rp)) if d > 0 else dg.lens_polygon(0.0, p)
    ax.fill(poly[:, 0], poly[:, 1], color="tab:blue", alpha=0.3, lw=0, label=f"patch, area {v['patch_area']:.3f}")
    labels = {"R": (Rp, "R$_P$ = L'$_P$", "tab:red", (0.0, -0.07), "top"),
              "V": (Vp, "V$_P$", "tab:blue", (0.0, 0.07), "bottom"),
              "H": (Hp, "H$_P$", "tab:green", (0.13, 0.0), "center"),
              "L": (-Rp, "L$_P$", "tab:orange", (0.0, 0.07), "bottom")}
    for q, name, col, offset, va in labels.values():
        ax.plot(*q, "o", color=col, ms=4)
        ax.text(q[0] + offset[0], q[1] + offset[1], name, color=col, fontsize=8, ha="center", va=va)
    ax.plot(*np.stack([Rp, Vp]).T, "k", lw=1.0)
    ax.text(0.0, -1.1, f"d(R, V) = |V$_P$ − R$_P$| = {v['distance']:.3f} ≤ p = {p:g}", fontsize=8, ha="center",
            va="top")
    ax.plot(0, 0, "k.", ms=4), ax.text(0.0, -0.06, "O", fontsize=8, ha="center", va="top")
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, 1.02), fontsize=8)  # above the circle, not on it
    ax.set_xlim(-1.05, 1.05), ax.set_ylim(-1.3, 1.35)
    ax.set_title("base plane", fontsize=9)
    ax2 = fig.add_axes([0.58, 0.14, 0.4, 0.7])
    ax2.plot(s["theta_v_deg"], s["value"], color="tab:blue")
    ax2.set(xlabel="signed θ$_V$ in the plane of incidence [deg] (mirror side > 0)",
            ylabel="f / c$_p$ [1/sr]", xlim=(-90, 90), title=f"χ(N·H) = (N·H)$^{{{v['character_exponent']:g}}}$, H = bisector of R and V")
    fig.suptitle("Fig. 5.1: patch-based BRDF f = χ(H) · F(d(R, V))", fontsize=10)
    dg.save(fig, path)
