"""Drawing helpers of the geometric diagrams (Figs. 1.1–1.4, 2.2, 4.1, 4.2, 4.4, 5.1).

A diagram's ``compute`` returns the drawn key quantities as a long table ``quantity, value``
(computed with the package's geometry code); its ``plot`` draws from that table only, so the
numbers in the CSV are the ones in the picture (tests check them against the geometry).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import geometry as geo

from brdfs.physics.patch_geometry import circle_intersection
from brdfs.pipeline import plotting

SECTION = "diagrams"
#: Oblique (cabinet) projection of 3D points (x, y, z) onto the drawing plane.
_OBLIQUE = np.array([[1.0, 0.0], [0.42 * np.cos(np.radians(35)), 0.42 * np.sin(np.radians(35))], [0.0, 1.0]])


def frame(values: dict) -> pd.DataFrame:
    """``{quantity: value}`` as the long table of a diagram's CSV (insertion order kept)."""
    return pd.DataFrame({"quantity": list(values), "value": [float(v) for v in values.values()]})


def values(df: pd.DataFrame) -> dict:
    return dict(zip(df["quantity"], df["value"]))


def vec(prefix: str, v) -> dict:
    """``{prefix_x: v[0], prefix_y: v[1], prefix_z: v[2]}`` (2 or 3 components)."""
    return {f"{prefix}_{c}": float(x) for c, x in zip("xyz", np.asarray(v, float))}


def get(d: dict, prefix: str, n: int = 3) -> np.ndarray:
    return np.array([d[f"{prefix}_{c}"] for c in "xyz"[:n]])


def light_and_view(c: dict) -> tuple[np.ndarray, np.ndarray]:
    """L and V of a diagram's config (``theta_l_deg``, ``phi_l_deg``, ``theta_v_deg``, ``phi_v_deg``)."""
    return geo.direction(c["theta_l_deg"], c["phi_l_deg"]), geo.direction(c["theta_v_deg"], c["phi_v_deg"])


def project(p) -> np.ndarray:
    """Oblique projection of 3D points (..., 3) to 2D (..., 2)."""
    return np.asarray(p, float) @ _OBLIQUE


def lens_polygon(d: float, R: float, points: int = 720) -> np.ndarray:
    """Boundary of C(Q, R) ∩ unit disk, Q = (d, 0), from :func:`circle_intersection`'s α, β.

    Counter-clockwise: the arc φ ∈ [−α, α] of the unit circle, then the arc ψ ∈ [π − β, π + β]
    of the circle of radius R around Q (one of them is empty or whole when a disk is nested).
    """
    lens = circle_intersection(d, R)
    alpha, beta = float(lens.alpha), float(lens.beta)
    phi = np.linspace(-alpha, alpha, points)
    psi = np.linspace(np.pi - beta, np.pi + beta, points)
    unit_arc = np.stack([np.cos(phi), np.sin(phi)], -1) if alpha > 0 else np.empty((0, 2))
    r_arc = np.stack([d + R * np.cos(psi), R * np.sin(psi)], -1) if beta > 0 else np.empty((0, 2))
    return np.concatenate([unit_arc, r_arc])


def shoelace_area(poly) -> float:
    x, y = np.asarray(poly, float).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def rotate2(p, angle_rad: float, about=(0.0, 0.0)) -> np.ndarray:
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    a = np.asarray(about, float)
    return (np.asarray(p, float) - a) @ np.array([[c, s], [-s, c]]) + a


def new_canvas(width=5.0, height=4.0, ncols=1):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, ncols, figsize=(width, height), squeeze=False)
    for ax in axes.ravel():
        ax.set_aspect("equal")
        ax.axis("off")
    return fig, list(axes.ravel())


def arrow(ax, start, end, label=None, color="k", offset=None, lw=1.3, gap=0.09, zorder=3, **text):
    """An arrow from ``start`` to ``end``; its label sits ``gap`` beyond the arrowhead along the
    arrow (centred there, so it touches neither head nor shaft), or at ``end + offset`` if given."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    ax.annotate("", xy=end, xytext=start, zorder=zorder,
                arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, shrinkA=0, shrinkB=0))
    if label:
        if offset is None:
            where = end + gap * (end - start) / np.linalg.norm(end - start)
            ax.text(*where, label, color=color, ha="center", va="center", **text)
        else:
            ax.text(end[0] + offset[0], end[1] + offset[1], label, color=color, **text)


def label(ax, where, text, color="k", masked=False, **kw):
    """A label centred at ``where``; ``masked`` puts it on an opaque white ground above the thin
    lines (zorder < 3) it would otherwise sit on, below arrows (zorder ≥ 3.5)."""
    if masked:
        kw.update(bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none"), zorder=3.4)
    ax.text(*np.asarray(where, float), text, color=color, ha="center", va="center", **kw)


def arc(ax, center, radius, a0_rad, a1_rad, label=None, color="k", label_radius=None, **text):
    """A circular arc from angle a0 to a1 (radians, drawing plane), optionally labelled at its middle."""
    t = np.linspace(a0_rad, a1_rad, 60)
    c = np.asarray(center, float)
    ax.plot(c[0] + radius * np.cos(t), c[1] + radius * np.sin(t), color=color, lw=0.8)
    if label:
        m = 0.5 * (a0_rad + a1_rad)
        r = label_radius or radius * 1.25
        ax.text(c[0] + r * np.cos(m), c[1] + r * np.sin(m), label, color=color, ha="center", va="center", **text)


def angle_of(v) -> float:
    v = np.asarray(v, float)
    return float(np.arctan2(v[1], v[0]))


def drop_to_base(ax, p, label, color, label_offset=(0.02, -0.07)):
    """The dotted drop from the (projected) tip of ``p`` to its foot on the base plane, with the foot
    labelled; returns the foot."""
    foot = project(np.asarray(p, float) * [1, 1, 0])
    ax.plot(*np.stack([project(p), foot]).T, color=color, lw=0.6, ls=":")
    ax.text(*(foot + label_offset), label, color=color, fontsize=8)
    return foot


def hemisphere_canvas():
    """A canvas with the hemisphere outline (the vector diagrams, Figs. 1.4 and 4.1)."""
    fig, (ax,) = new_canvas(5.6, 4.4)
    hemisphere(ax)
    return fig, ax


def hemisphere_silhouette(points: int = 200) -> np.ndarray:
    """The projected outline of the unit hemisphere's dome (2D points, left to right over the top).

    The oblique projection p ↦ p·O is linear, so the unit sphere maps onto the ellipse whose
    boundary point in the direction w (a unit 2-vector) is the image of x = O w / |O w|; x lies on
    the upper hemisphere iff x_z = w_y ≥ 0 (O's z row is (0, 1)). The dome's outline is that half
    of the ellipse; it touches the projected base circle, which therefore never sticks out.
    """
    s = np.linspace(np.pi, 0.0, points)
    x = np.stack([np.cos(s), np.sin(s)], -1) @ _OBLIQUE.T
    return project(x / np.linalg.norm(x, axis=-1, keepdims=True))


def hemisphere(ax, color="0.55"):
    """Outline of the unit hemisphere (:func:`hemisphere_silhouette`) and its base circle in the
    oblique projection."""
    t = np.linspace(0, 2 * np.pi, 200)
    base = project(np.stack([np.cos(t), np.sin(t), 0 * t], -1))
    ax.plot(base[:, 0], base[:, 1], color=color, lw=0.8)
    ax.plot(*hemisphere_silhouette().T, color=color, lw=0.8)


def arc3(ax, a, b, radius, label=None, color="k", label_radius=None, **text):
    """The arc of radius ``radius`` around the origin from direction ``a`` to ``b`` (3D, along their
    great circle), projected; labelled at its middle at ``label_radius`` (default 1.3 radius)."""
    a, b = (np.asarray(u, float) / np.linalg.norm(u) for u in (a, b))
    angle = np.arccos(np.clip(a @ b, -1.0, 1.0))
    t = np.linspace(0.0, 1.0, 60)[:, None]
    way = (np.sin((1 - t) * angle) * a + np.sin(t * angle) * b) / np.sin(angle)  # slerp
    ax.plot(*project(radius * way).T, color=color, lw=0.8)
    if label:
        mid = way[len(way) // 2]
        ax.text(*project((label_radius or 1.3 * radius) * mid), label, color=color, ha="center", va="center", **text)


def save(fig, path):
    plotting.savefig(fig, path)
