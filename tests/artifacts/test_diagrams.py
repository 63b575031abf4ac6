"""The geometric diagrams draw the numbers the package's geometry computes."""
import numpy as np
import pytest

from brdfs.artifacts import _diagrams as dg
from brdfs.artifacts.fig_1_3_integral_schemes import trace
from brdfs.artifacts.fig_2_2_lhv_domains import rotation_to
from brdfs.physics.patch_geometry import basic_albedo_at, circle_intersection
from brdfs.physics import geometry as geo
from brdfs.pipeline import registry
from brdfs.pipeline.config import load_config


@pytest.fixture(scope="module")
def cfg():
    return load_config()


def _compute(name, cfg):
    return registry.get_artifact(name).compute(cfg, {})


def test_fig_4_4_segments_add_up_and_chord_end_lies_on_both_circles(cfg):
    v = dg.values(_compute("fig_4_4_circle_intersection", cfg))
    assert v["t1"] + v["t2"] == pytest.approx(v["area"], rel=1e-12)
    P, Q = dg.get(v, "P", 2), np.array([v["d"], 0.0])
    assert np.hypot(*P) == pytest.approx(1.0, rel=1e-12)
    assert np.hypot(*(P - Q)) == pytest.approx(v["R"], rel=1e-12)
    # eq. 4.10, the law of cosines, at the drawn angles
    d, R = v["d"], v["R"]
    assert d * d + 1 - 2 * d * np.cos(v["alpha_rad"]) == pytest.approx(R * R, rel=1e-12)
    assert d * d + R * R - 2 * d * R * np.cos(v["beta_rad"]) == pytest.approx(1.0, rel=1e-12)


def test_fig_4_4_drawn_lens_polygon_has_the_computed_area(cfg):
    v = dg.values(_compute("fig_4_4_circle_intersection", cfg))
    poly = dg.lens_polygon(v["d"], v["R"], points=4000)
    assert dg.shoelace_area(poly) == pytest.approx(v["area"], rel=1e-5)


def test_fig_4_2_every_case_is_drawn_with_its_area_and_albedo(cfg):
    df = _compute("fig_4_2_base_circle_relations", cfg)
    for row in df.itertuples():
        assert dg.shoelace_area(dg.lens_polygon(row.d, row.R, points=4000)) == pytest.approx(row.area, rel=1e-5)
        assert row.albedo == pytest.approx(row.area / (np.pi * min(1.0, row.R**2)), rel=1e-12)
        assert row.albedo == float(basic_albedo_at(row.d, row.R).value)
    kinds = {(r.d <= abs(1 - r.R), r.R < 1) for r in df.itertuples()}
    assert kinds == {(True, True), (False, True), (False, False), (True, False)}  # the four relations


def test_fig_1_4_drawn_vectors_obey_the_notation(cfg):
    v = dg.values(_compute("fig_1_4_notation", cfg))
    L, V, R, H, N = (dg.get(v, k) for k in "LVRHN")
    np.testing.assert_allclose(R, 2 * (N @ L) * N - L, atol=1e-15)
    np.testing.assert_allclose(H, (L + V) / np.linalg.norm(L + V), atol=1e-15)
    assert np.degrees(np.arccos(R @ V)) == pytest.approx(v["alpha_deg"], abs=1e-9)
    assert np.degrees(np.arccos(N @ H)) == pytest.approx(v["delta_deg"], abs=1e-9)
    h = L + V
    assert np.linalg.norm(h - (N @ h) * N) == pytest.approx(v["projected_distance"], rel=1e-12)


def test_fig_4_1_m_is_the_distance_of_the_drawn_projections_and_symmetric(cfg):
    v = dg.values(_compute("fig_4_1_brdf_geometry", cfg))
    Vp, Lmp = dg.get(v, "V")[:2], dg.get(v, "Lm")[:2]
    Lp, Vmp = dg.get(v, "L")[:2], dg.get(v, "Vm")[:2]
    assert np.hypot(*(Vp - Lmp)) == pytest.approx(v["m"], rel=1e-12)
    assert np.hypot(*(Lp - Vmp)) == pytest.approx(v["m"], rel=1e-12)


def test_fig_2_2_critical_region_empty_for_big_l_domain_and_valid_for_small(cfg):
    df = _compute("fig_2_2_lhv_domains", cfg)
    s = df[df.kind == "setting"].set_index(["panel", "item"])["x"]
    assert s["left", "critical_area"] == 0.0 < s["right", "critical_area"]
    c = cfg["diagrams"]["fig_2_2"]
    # Every drawn critical V, with any L of the small domain (random, not the sampled grid):
    crit = df[(df.panel == "right") & (df.kind == "critical")]
    xy = crit[["x", "y"]].to_numpy()
    V = np.column_stack([xy, np.sqrt(1 - (xy**2).sum(1))])
    rng = np.random.default_rng(cfg["seed"])
    L0 = geo.direction(c["l_theta_deg"], c["l_phi_deg"])
    local = geo.direction(c["l_cap_deg_right"] * np.sqrt(rng.uniform(0, 1, 40)), rng.uniform(0, 360, 40))
    Ls = local @ rotation_to(L0).T  # random L of the domain, not the grid the figure used
    nh = np.array([geo.n_dot_h(np.broadcast_to(L, V.shape), V) for L in Ls])
    # cells are tested at their centre on a grid: allow the half-vector cap a margin of one grid step
    assert np.all(np.degrees(np.arccos(np.clip(nh, -1, 1))) <= c["h_cap_deg"] + 1.0)


def test_fig_1_3_spherical_mirror_returns_rays_from_f1_near_f2(cfg):
    df = _compute("fig_1_3_integral_schemes", cfg)
    a = df.offset.iloc[0]
    assert np.allclose(np.hypot(df.hit_x, df.hit_y), 1.0)
    assert np.all(np.abs(df.land_x - a) <= 4 * a * a)
    # halving the offset shrinks the miss by about four (the O(a²) image error)
    _, land = trace(np.array([-a / 2, 0.0]), np.radians(df.angle_deg.to_numpy()))
    assert np.max(np.abs(land - a / 2)) < 0.35 * np.max(np.abs(df.land_x - a))


def test_fig_1_1_drawn_normals_make_the_stated_angles_and_eq_1_3_holds(cfg):
    v = dg.values(_compute("fig_1_1_surface_elements", cfg))
    line = np.array([1.0, 0.0])
    assert np.degrees(np.arccos(dg.get(v, "N1", 2) @ line)) == pytest.approx(v["theta1_deg"], abs=1e-12)
    assert np.degrees(np.arccos(dg.get(v, "N2", 2) @ -line)) == pytest.approx(v["theta2_deg"], abs=1e-12)
    assert v["omega1_A1_cos1"] == pytest.approx(v["omega2_A2_cos2"], rel=1e-14)


def test_fig_5_1_patch_and_slice_follow_the_projected_distance(cfg):
    df = _compute("fig_5_1_patch_based_brdf", cfg)
    c = cfg["diagrams"]["fig_5_1"]
    v = dg.values(df[df.kind == "point"])
    assert v["distance"] <= v["patch_radius"] and v["f"] > 0
    d = geo.sin_incidence(c["theta_l_deg"])
    assert v["patch_area"] == float(circle_intersection(d, c["patch_radius"]).area)
    s = df[df.kind == "slice"]
    lit = s[s.value > 0].theta_v_deg
    # in the plane of incidence the patch is sin θ_V ∈ [sin θ_L − p, sin θ_L + p] on the mirror side
    lo = np.degrees(np.arcsin(max(d - c["patch_radius"], 0.0)))
    hi = np.degrees(np.arcsin(min(d + c["patch_radius"], 1.0)))
    step = c["slice_step_deg"]
    assert lit.min() == pytest.approx(lo, abs=step) and lit.max() == pytest.approx(hi, abs=step)


def test_fig_5_1_character_is_one_over_cos_of_the_bisector_of_r_and_v_across_the_patch(cfg):
    # Sec. 5.2.2: H bisects R and V; in the plane of incidence (mirror side) N·H = cos((θ_L + θ_V)/2).
    df = _compute("fig_5_1_patch_based_brdf", cfg)
    c = cfg["diagrams"]["fig_5_1"]
    lit = df[(df.kind == "slice") & (df.value > 0)]
    expected = 1.0 / np.cos(np.radians(0.5 * (c["theta_l_deg"] + lit.theta_v_deg)))
    np.testing.assert_allclose(lit.value, expected, rtol=1e-12)
    assert lit.value.max() / lit.value.min() > 1.4            # visibly 1/cos, not flat at 1.00–1.04
    v = dg.values(df[df.kind == "point"])
    L = geo.light_direction(c["theta_l_deg"])
    V = geo.direction(c["theta_v_deg"], c["phi_v_deg"])
    h = geo.mirror(L) + V
    np.testing.assert_allclose(dg.get(v, "H_P", 2), (h / np.linalg.norm(h))[:2], atol=1e-15)
