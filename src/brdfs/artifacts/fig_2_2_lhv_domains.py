"""Figure 2.2: the domains of L, H and V in the divergence argument of Sec. 2.2.1.

For every L of a small cap (the domain of L, around a near-grazing direction) the viewing
directions V whose half vector H lies in a cap of half-angle δ_H around N form the "spherically
mirrored" set V = 2(L·H)H − L. If the L domain is too big compared with the H cap (left) these
sets have no common part; if it is small (right) they share a *critical region*. All shown on the
base plane (orthogonal projection of the upper hemisphere). Directions from
:mod:`brdfs.physics.geometry`; membership tested with ``n_dot_h``. Cap sizes and L are choices
(config ``diagrams.fig_2_2``). The critical region is found on a grid of V (``grid``) against a
grid of L of the domain (``l_samples`` per radius and ring).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _diagrams as dg
from brdfs.physics import geometry as geo
from brdfs.pipeline.registry import figure

NAME = "fig_2_2_lhv_domains"


def rotation_to(axis):
    """A rotation matrix taking N = (0, 0, 1) to the unit vector ``axis``."""
    axis = np.asarray(axis, float)
    z = np.array([0.0, 0.0, 1.0])
    v, c = np.cross(z, axis), float(axis @ z)
    if np.allclose(v, 0):
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1 + c)


def cap(centre, radius_deg, rings=3, per_ring=24):
    """Directions of a spherical cap (centre and rings up to its boundary), shape (M, 3)."""
    rot = rotation_to(centre)
    pts = [np.array([0.0, 0.0, 1.0])]
    for r in np.linspace(radius_deg / rings, radius_deg, rings):
        pts.extend(geo.direction(np.full(per_ring, r), np.linspace(0, 360, per_ring, endpoint=False)))
    return np.asarray(pts) @ rot.T


def mirrored(L, H):
    """V = 2 (L·H) H − L: the direction whose half vector with L is H."""
    return 2.0 * geo.dot(L, H)[..., None] * H - L


def critical_mask(Ls, cos_cap, xy):
    """For V on the base-plane grid ``xy`` (upper hemisphere): N·H(L, V) ≥ cos δ_H for every L in ``Ls``."""
    inside = (xy ** 2).sum(-1) < 1.0
    V = np.concatenate([xy, np.sqrt(np.clip(1 - (xy ** 2).sum(-1, keepdims=True), 0, None))], -1)
    ok = inside.copy()
    for L in Ls:
        ok &= geo.n_dot_h(np.broadcast_to(L, V.shape), V) >= cos_cap
    return ok


@figure(NAME, config=(dg.SECTION,), resources={"runtime": 1})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Per panel: the caps (``kind = setting``), the outlines (``kind = l_domain | h_cap | v_set``,
    x, y on the base plane) and the critical region's area on the base plane (projected solid angle)."""
    c = cfg[dg.SECTION]["fig_2_2"]
    L0 = geo.direction(c["l_theta_deg"], c["l_phi_deg"])
    cos_cap = float(np.cos(np.radians(c["h_cap_deg"])))
    n = int(c["grid"])
    g = np.linspace(-1, 1, n)
    xy = np.stack(np.meshgrid(g, g, indexing="xy"), -1)
    cell = (g[1] - g[0]) ** 2
    frames = []
    for panel, l_radius in (("left", c["l_cap_deg_left"]), ("right", c["l_cap_deg_right"])):
        if c["l_theta_deg"] + l_radius >= 90.0:
            raise ValueError(f"diagrams.fig_2_2: l_theta_deg + l_cap_deg_{panel} = {c['l_theta_deg'] + l_radius} "
                             "reaches below the horizon (must be < 90)")
        Ls = cap(L0, l_radius, rings=int(c["l_samples"]), per_ring=4 * int(c["l_samples"]))
        mask = critical_mask(Ls, cos_cap, xy)
        rows = [{"panel": panel, "kind": "setting", "item": q, "x": val, "y": np.nan} for q, val in
                (("l_cap_deg", l_radius), ("h_cap_deg", c["h_cap_deg"]), ("critical_area", mask.sum() * cell),
                 ("grid_cell", cell))]
        def outline(pts, kind, item):  # points below the horizon are not drawn (NaN)
            return [{"panel": panel, "kind": kind, "item": item, "x": q[0] if q[2] >= 0 else np.nan,
                     "y": q[1] if q[2] >= 0 else np.nan} for q in np.concatenate([pts, pts[:1]])]

        ring = cap(L0, l_radius, rings=1, per_ring=72)[1:]
        rows += outline(ring, "l_domain", "L")
        h_ring = cap([0, 0, 1], c["h_cap_deg"], rings=1, per_ring=72)[1:]
        rows += outline(h_ring, "h_cap", "H")
        for j, L in enumerate(ring[:: 18]):  # four L on the domain's boundary
            V = mirrored(np.broadcast_to(L, h_ring.shape), h_ring)
            rows += outline(V, "v_set", f"V(L{j + 1})")
        ys, xs = np.nonzero(mask)
        rows += [{"panel": panel, "kind": "critical", "item": "cell", "x": g[i], "y": g[k]} for k, i in zip(ys, xs)]
        frames.append(pd.DataFrame(rows))
    return pd.concat(frames, ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    fig, axes = dg.new_canvas(8.4, 4.4, ncols=2)
    t = np.linspace(0, 2 * np.pi, 200)
    for ax, (panel, g) in zip(axes, df.groupby("panel", sort=False)):
        s = g[g["kind"] == "setting"].set_index("item")["x"]
        ax.plot(np.cos(t), np.sin(t), "k", lw=0.8)
        crit = g[g["kind"] == "critical"]
        if len(crit):
            ax.scatter(crit["x"], crit["y"], s=3.5, color="tab:purple", marker="s", lw=0, label="critical region")
        for kind, col in (("l_domain", "tab:orange"), ("h_cap", "tab:green"), ("v_set", "tab:blue")):
            for item, o in g[g["kind"] == kind].groupby("item", sort=False):
                ax.plot(o["x"], o["y"], color=col, lw=0.9,
                        label={"l_domain": "domain of L", "h_cap": "cap of H", "v_set": "V sets"}[kind]
                        if item in ("L", "H", "V(L1)") else None)
        ax.set_xlim(-1.1, 1.1), ax.set_ylim(-1.1, 1.1)
        ax.set_title(f"{panel}: L domain {s['l_cap_deg']:g}°, H cap {s['h_cap_deg']:g}°\n"
                     f"critical region (projected) {s['critical_area']:.4f}", fontsize=8)
        ax.legend(loc="lower left", fontsize=7)
    fig.suptitle("Fig. 2.2: domains of L, H and V on the base plane", fontsize=10)
    dg.save(fig, path)
