"""The Utah teapot as a triangle mesh, tessellated from Newell's bicubic Bézier patches.

The data are Martin Newell's 1975 teapot, 32 bicubic patches over 306 control points
(``data/teapot.bpt`` beside this module, shipped in the wheel; source and licence in ``data/TEAPOT.md``), in Newell's own
coordinates: **z up**, the teapot standing on z = 0, x ∈ [−3, 3.434] (handle at −x, spout at +x),
y ∈ [−2, 2], z ∈ [0, 3.15]. A patch with control points C_ij (i, j = 0..3) is the surface

    P(u, v) = Σ_ij B_i(u) B_j(v) C_ij,  B_k(t) = C(3, k) t^k (1 − t)^(3−k)   (Bernstein basis),

and its outward normal is ∂P/∂v × ∂P/∂u (Newell's patch orientation). Where that cross product
vanishes — the poles of the lid's knob and of the bottom, where one patch row collapses into a
point — the vertex normal is the area-weighted mean of the normals of the triangles around the
welded vertex (there: ±z). Coincident vertices of neighbouring patches are welded and the
triangles that collapse at the poles are dropped, so the mesh renders without cracks or NaN
normals. The surface is Newell's, not a closed solid: the spout's mouth is open, the lid leaves
the thin gap 1.3 < r < 1.4 to the rim at z = 2.4, handle and spout pierce the body untrimmed.

Nothing here imports Mitsuba except :func:`to_mitsuba` and :func:`mitsuba_mesh`.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: Newell's patch data as shipped in the repository (nothing is downloaded).
DATA = Path(__file__).resolve().parent / "data" / "teapot.bpt"
#: Height of Newell's teapot (z of the knob's top) in his units.
NEWELL_HEIGHT = 3.15
#: Triangles' grid resolution per patch side used by the scenes (32 · 2 · n² triangles).
SUBDIVISIONS = 8
#: Positions closer than this (in Newell units) are one vertex after welding.
WELD_TOLERANCE = 1e-9


@dataclass(frozen=True)
class BezierPatches:
    """Bicubic Bézier patches: ``control[k, i, j]`` is control point C_ij (3,) of patch k."""

    control: np.ndarray  # (patches, 4, 4, 3)


@dataclass(frozen=True)
class TriangleMesh:
    """A triangle mesh: ``vertices`` (V, 3), ``faces`` (F, 3) vertex indices (counter-clockwise seen
    from outside), unit ``normals`` (V, 3) per vertex."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray


def read_newell(path=DATA) -> tuple[np.ndarray, np.ndarray]:
    """``(indices, points)`` of a Newell-format file: a patch count, one line of 16 comma-separated
    1-based control-point indices per patch, a point count, one ``x,y,z`` line per point.
    Returns 0-based ``indices`` (patches, 16) and ``points`` (points, 3)."""
    lines = [ln.strip() for ln in Path(path).read_text().splitlines() if ln.strip()]
    n_patches = int(lines[0])
    indices = np.array([[int(i) for i in ln.split(",")] for ln in lines[1:1 + n_patches]]) - 1
    n_points = int(lines[1 + n_patches])
    points = np.array([[float(x) for x in ln.split(",")] for ln in lines[2 + n_patches:2 + n_patches + n_points]])
    if indices.shape != (n_patches, 16) or points.shape != (n_points, 3):
        raise ValueError(f"{path}: expected {n_patches} patches × 16 indices and {n_points} points × 3, "
                         f"read {indices.shape} and {points.shape}")
    return indices, points


def newell_teapot(path=DATA) -> BezierPatches:
    """Newell's 32 teapot patches (z up, Newell units)."""
    indices, points = read_newell(path)
    return BezierPatches(points[indices].reshape(-1, 4, 4, 3))


def bernstein(t) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Bernstein basis B_k(t) and its derivative B_k'(t), each (..., 4)."""
    t = np.asarray(t, float)[..., None]
    s = 1.0 - t
    basis = np.concatenate([s**3, 3 * t * s**2, 3 * t**2 * s, t**3], -1)
    slope = np.concatenate([-3 * s**2, 3 * s**2 - 6 * t * s, 6 * t * s - 3 * t**2, 3 * t**2], -1)
    return basis, slope


def evaluate(patches: BezierPatches, u, v) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points P, ∂P/∂u and ∂P/∂v of every patch on the grid u × v: each (patches, len(u), len(v), 3)."""
    bu, du = bernstein(u)
    bv, dv = bernstein(v)
    c = patches.control
    point = np.einsum("ai,bj,kijc->kabc", bu, bv, c)
    tangent_u = np.einsum("ai,bj,kijc->kabc", du, bv, c)
    tangent_v = np.einsum("ai,bj,kijc->kabc", bu, dv, c)
    return point, tangent_u, tangent_v


def _grid_faces(n: int, patches: int) -> np.ndarray:
    """Two triangles per grid cell of each patch's (n+1)² vertices, ordered so that their normal is
    ∂P/∂v × ∂P/∂u (outward)."""
    a = (np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]).ravel()   # cell (i, j) at u_i, v_j
    cell = np.stack([np.stack([a, a + 1, a + n + 2], -1), np.stack([a, a + n + 2, a + n + 1], -1)], 1).reshape(-1, 3)
    return (cell[None] + (np.arange(patches) * (n + 1) ** 2)[:, None, None]).reshape(-1, 3)


def _weld(points: np.ndarray, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """``(unique_points, inverse)``: points within ``tolerance`` (on a grid of that size) become one."""
    keys = np.round(points / tolerance).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return points[first], inverse.ravel()


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Area-weighted normals (the cross products, length = 2 · area) of the triangles (F, 3)."""
    p0, p1, p2 = (vertices[faces[:, k]] for k in range(3))
    return np.cross(p1 - p0, p2 - p0)


def tessellate(patches: BezierPatches, n: int = SUBDIVISIONS) -> TriangleMesh:
    """The patches as one welded triangle mesh, ``n`` × ``n`` grid cells (2 triangles each) per patch.

    Vertex normals are the normalised ∂P/∂v × ∂P/∂u averaged over the welded copies of a vertex;
    at a pole (the cross product vanishes) the area-weighted normal of the surrounding triangles.
    """
    if int(n) < 1:
        raise ValueError(f"n = {n!r}: the tessellation needs at least 1 cell per patch side")
    n = int(n)
    t = np.linspace(0.0, 1.0, n + 1)
    point, tu, tv = evaluate(patches, t, t)
    raw_normal = np.cross(tv, tu).reshape(-1, 3)
    length = np.linalg.norm(raw_normal, axis=-1)
    # Degenerate where |∂P/∂v × ∂P/∂u| is round-off against the patch's squared size (a collapsed
    # row's tangent is a sum of equal points with weights summing to 0, not exactly 0).
    extent = np.ptp(patches.control.reshape(len(patches.control), -1, 3), axis=1).max(-1)
    regular = length > 1e-9 * np.repeat(extent**2, (n + 1) ** 2)
    unit = np.where(regular[:, None], raw_normal / np.where(regular, length, 1.0)[:, None], 0.0)
    vertices, inverse = _weld(point.reshape(-1, 3), WELD_TOLERANCE)
    faces = inverse[_grid_faces(n, len(patches.control))]
    faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])]
    summed = np.zeros_like(vertices)
    np.add.at(summed, inverse, unit)
    from_faces = np.zeros_like(vertices)
    np.add.at(from_faces, faces.ravel(), np.repeat(face_normals(vertices, faces), 3, axis=0))
    has_regular = np.zeros(len(vertices), bool)
    np.logical_or.at(has_regular, inverse, regular)
    normals = np.where(has_regular[:, None], summed, from_faces)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    return TriangleMesh(vertices, faces.astype(np.int64), normals)


def surface_area(mesh: TriangleMesh) -> float:
    """Σ of the triangles' areas."""
    return 0.5 * float(np.linalg.norm(face_normals(mesh.vertices, mesh.faces), axis=-1).sum())


def signed_volume(mesh: TriangleMesh) -> float:
    """(1/3) ∮ x · n dA over the triangles (divergence theorem; exact for a closed mesh, positive when
    the faces' normals point outward)."""
    p0, p1, p2 = (mesh.vertices[mesh.faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", p0, np.cross(p1, p2)).sum() / 6.0)


def teapot_mesh(n: int = SUBDIVISIONS, height: float = NEWELL_HEIGHT, base=(0.0, 0.0, 0.0)) -> TriangleMesh:
    """Newell's teapot tessellated (:func:`tessellate`), scaled to ``height`` and standing with the
    centre of its bottom at ``base`` (z up)."""
    mesh = tessellate(newell_teapot(), n)
    s = float(height) / NEWELL_HEIGHT
    return TriangleMesh(mesh.vertices * s + np.asarray(base, float), mesh.faces, mesh.normals)


def teapot_part(x, y, scale=1.0, n: int = SUBDIVISIONS) -> tuple:
    """The teapot as a scene part of :mod:`brdfs.render.mitsuba.scenes` (``{"type": "mesh", ...}``,
    with vertex ``normals``): its footprint's length, handle to spout, is 1.6 · ``scale`` — the
    diameter of the sphere stand-in it replaces, so the scenes' layouts keep their spacing — its
    footprint is centred on (x, y), it stands on z = 0, spout toward +x (height 0.78 · ``scale``)."""
    mesh = tessellate(newell_teapot(), n)
    lo, hi = mesh.vertices.min(0), mesh.vertices.max(0)
    s = 1.6 * float(scale) / (hi[0] - lo[0])
    shift = np.array([float(x), float(y), 0.0]) - s * np.array([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2]])
    return ({"type": "mesh", "vertices": mesh.vertices * s + shift, "faces": mesh.faces, "normals": mesh.normals},)


def to_mitsuba(mesh: TriangleMesh, name: str = "teapot", props=None):
    """An ``mi.Mesh`` with the mesh's positions, faces and vertex normals (a variant must be set);
    ``props`` (an ``mi.Properties``, e.g. with a ``bsdf``) is passed to the constructor."""
    return mitsuba_mesh(name, mesh.vertices, mesh.faces, mesh.normals, props)


def mitsuba_mesh(name: str, vertices, faces, normals=None, props=None):
    """An ``mi.Mesh`` from arrays: positions (V, 3), triangles (F, 3) and, where given, vertex normals
    (V, 3) for smooth shading (flat without them: the pyramids)."""
    import mitsuba as mi

    vertices, faces = np.asarray(vertices, np.float32), np.asarray(faces, np.uint32)
    out = mi.Mesh(name, len(vertices), len(faces), props=props if props is not None else mi.Properties(),
                  has_vertex_normals=normals is not None)
    params = mi.traverse(out)
    params["vertex_positions"] = mi.Float(vertices.ravel())
    if normals is not None:
        params["vertex_normals"] = mi.Float(np.asarray(normals, np.float32).ravel())
    params["faces"] = mi.UInt32(faces.ravel())
    params.update()
    return out
