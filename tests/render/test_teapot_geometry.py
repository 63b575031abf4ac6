"""The Utah teapot mesh is Newell's surface: his data, his bounding box, converging area and volume,
outward normals, welded seams and sane poles (z up, Newell units unless scaled)."""
from __future__ import annotations

import numpy as np
import pytest

from brdfs.render.mitsuba import geometry as g


@pytest.fixture(scope="module")
def patches():
    return g.newell_teapot()


@pytest.fixture(scope="module")
def meshes(patches):
    return {n: g.tessellate(patches, n) for n in (8, 16, 32)}


def test_the_data_file_holds_newells_32_patches_of_16_indices_into_306_points():
    indices, points = g.read_newell()
    assert indices.shape == (32, 16) and points.shape == (306, 3)
    assert indices.min() == 0 and indices.max() == 305
    # Newell's classic landmarks: the rim's first point, the knob's top, the bottom's centre.
    assert points[0].tolist() == [1.4, 0.0, 2.4]
    assert [0.0, 0.0, 3.15] in points.tolist() and [0.0, 0.0, 0.0] in points.tolist()


def test_the_data_have_the_teapots_fourfold_and_mirror_symmetries_exactly(patches):
    # A transcription slip in any control point breaks one of these (Newell's data are exact).
    c = patches.control
    quarter_turn = np.array([[0, 1, 0], [-1, 0, 0], [0, 0, 1]])       # (x, y) -> (y, -x)
    for first, turn in ((0, quarter_turn), (4, quarter_turn), (8, quarter_turn), (20, quarter_turn),
                        (24, quarter_turn), (28, quarter_turn.T)):      # rim, body ×2, lid ×2, bottom
        for k in range(4):
            np.testing.assert_array_equal(c[first + k] @ turn.T, c[first + (k + 1) % 4])
    for a in (12, 14, 16, 18):                                          # handle and spout: y -> -y
        np.testing.assert_array_equal((c[a] * [1, -1, 1])[:, ::-1], c[a + 1])


def test_every_patch_corner_is_a_data_point_and_a_mesh_vertex(patches, meshes):
    _, points = g.read_newell()
    corner, _, _ = g.evaluate(patches, [0.0, 1.0], [0.0, 1.0])       # a Bézier patch interpolates its corners
    corners = corner.reshape(-1, 3)
    on_data = np.min(np.linalg.norm(corners[:, None] - points[None], axis=-1), axis=1)
    assert on_data.max() < 1e-12
    on_mesh = np.min(np.linalg.norm(corners[:, None] - meshes[8].vertices[None], axis=-1), axis=1)
    assert on_mesh.max() < 1e-12


def test_bounding_box_is_the_classic_teapots_with_z_up(meshes):
    lo, hi = meshes[32].vertices.min(0), meshes[32].vertices.max(0)
    np.testing.assert_allclose(lo, [-3.0, -2.0, 0.0], atol=1e-12)       # handle's back, body's sides, bottom
    np.testing.assert_allclose(hi[1:], [2.0, 3.15], atol=1e-12)          # body's side, knob's top
    assert hi[0] == pytest.approx(3.434, abs=1e-3)                        # the spout's lip (interior maximum)


def test_area_and_volume_converge_at_second_order_as_the_tessellation_refines(meshes):
    area = [g.surface_area(meshes[n]) for n in (8, 16, 32)]
    volume = [g.signed_volume(meshes[n]) for n in (8, 16, 32)]
    for q in (area, volume):
        ratio = (q[1] - q[0]) / (q[2] - q[1])      # flat triangles on a smooth surface: error ∝ h²
        assert 3.5 < ratio < 4.5
    assert area[2] == pytest.approx(52.88, abs=0.05) and volume[2] == pytest.approx(25.93, abs=0.05)


def test_normals_point_outward_so_the_divergence_volume_is_positive(meshes):
    mesh = meshes[8]
    assert g.signed_volume(mesh) > 0
    faces = g.face_normals(mesh.vertices, mesh.faces)
    along = np.einsum("fj,fkj->fk", faces, mesh.normals[mesh.faces])
    assert (along > 0).all()                                     # vertex normals agree with every triangle
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=-1), 1.0, atol=1e-12)
    top = np.argmax(mesh.vertices[:, 2])
    bottom = np.argmin(np.linalg.norm(mesh.vertices, axis=-1))
    np.testing.assert_allclose(mesh.normals[top], [0, 0, 1], atol=1e-12)       # the knob's pole
    np.testing.assert_allclose(mesh.normals[bottom], [0, 0, -1], atol=1e-12)   # the bottom's pole


def test_seams_are_welded_and_the_poles_leave_no_degenerate_triangle(meshes):
    mesh = meshes[8]
    assert len(np.unique(np.round(mesh.vertices, 9), axis=0)) == len(mesh.vertices)
    areas = np.linalg.norm(g.face_normals(mesh.vertices, mesh.faces), axis=-1)
    assert areas.min() > 1e-8
    # Body seams are shared: an edge inside the body appears in exactly two triangles.
    edges = np.sort(mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, count = np.unique(edges, axis=0, return_counts=True)
    assert count.max() == 2


def test_teapot_part_stands_on_the_floor_with_the_stand_ins_footprint():
    (part,) = g.teapot_part(1.0, -2.0, scale=0.5, n=4)
    v = np.asarray(part["vertices"])
    lo, hi = v.min(0), v.max(0)
    assert part["type"] == "mesh" and lo[2] == pytest.approx(0.0, abs=1e-12)
    assert hi[0] - lo[0] == pytest.approx(0.8, rel=1e-12)                    # the sphere's diameter 1.6 · scale
    np.testing.assert_allclose(0.5 * (lo + hi)[:2], [1.0, -2.0], atol=1e-12)  # footprint centred on (x, y)
    assert hi[2] / (hi[0] - lo[0]) == pytest.approx(3.15 / 6.428, rel=1e-3)  # Newell's proportions kept


def test_bad_subdivision_count_is_named():
    with pytest.raises(ValueError, match="n = 0"):
        g.tessellate(g.newell_teapot(), 0)


def test_mitsuba_mesh_carries_the_vertices_faces_and_normals(mitsuba):
    mesh = g.teapot_mesh(n=4)
    shape = g.to_mitsuba(mesh)
    assert shape.vertex_count() == len(mesh.vertices) and shape.face_count() == len(mesh.faces)
    assert shape.has_vertex_normals()
    box = shape.bbox()
    np.testing.assert_allclose([box.min.z, box.max.z], [0.0, 3.15], atol=1e-5)
    params = mitsuba.traverse(shape)
    np.testing.assert_allclose(np.asarray(params["vertex_normals"]).reshape(-1, 3), mesh.normals, atol=1e-6)
