"""Every reading accepted for a group of the thesis's prints recomputes one of its entries as
printed, and stops doing so when its parameter moves one grid step."""

from __future__ import annotations

import numpy as np
import pytest

import brdfs
from brdfs.artifacts import extra_readings_chapter_3 as chapter_3
from brdfs.artifacts import extra_readings_table_4_3 as table_4_3
from brdfs.artifacts.extra_metal_a0_readings import box_range
from brdfs.artifacts.table_1_2_metal_reflectance import a0_percent
from brdfs.artifacts.table_4_1_exponential_patch import _closed_forms
from brdfs.pipeline.published import rounds_to
from brdfs.pipeline import readings
from brdfs.pipeline.readings import digits_of, printed_digits


def _table_4_3(step: float, clip_node: str = "unclipped", rule: str = "left") -> tuple[float, float]:
    family, values = table_4_3.reading_values([1.0], 1.9, [step], rules=(rule,))
    name = family[(family["rule"] == rule) & (family["end"] == "2") & (family["clip_node"] == clip_node)]["reading"].iloc[0]
    return values[name][0]


def test_table_4_3_is_eq_4_22_summed_with_step_1e_4_and_the_clip_node_counted_whole():
    c_max, a_diffuse = _table_4_3(1e-4)
    assert rounds_to("0.22556", c_max) and rounds_to("0.75895", a_diffuse)       # d = 1 as printed


@pytest.mark.parametrize(("step", "clip_node"), [(2e-4, "unclipped"), (5e-5, "unclipped"), (1e-4, "clipped")])
def test_table_4_3_one_grid_step_away_does_not_print_it(step, clip_node):
    c_max, a_diffuse = _table_4_3(step, clip_node)
    assert not (rounds_to("0.22556", c_max) and rounds_to("0.75895", a_diffuse))


@pytest.mark.parametrize(("rule", "prints"), [("fixed4_width6", True), ("fixed4_width5", False),
                                              ("fixed4_width7", False), ("fixed3_width6", False), ("round", False)])
def test_table_4_1_c_max_is_printed_as_4_decimals_cut_to_6_characters(rule, prints):
    c_max = float(_closed_forms(np.array([8.0]))["C_max"][0])                   # printed 10.216
    assert (digits_of(c_max, "10.216", rule) == printed_digits("10.216")) is prints


@pytest.mark.parametrize(("factor", "prints"), [(1.0, True), (0.5, False), (2.0, False), (np.pi, False)])
def test_table_4_1_i12_is_int_1_2_p_without_the_pi_of_eq_4_50(factor, prints):
    weight = float(_closed_forms(np.array([1.0]))["I_12_weight"][0])            # printed 0.44002
    assert rounds_to("0.44002", factor * weight) is prints


@pytest.mark.parametrize(("step", "prints"), [(30.0, True), (15.0, False), (10.0, False)])
def test_table_3_1_corrected_blinn_n_2_is_the_maximum_over_a_30_degree_grid(step, prints):
    grid = np.arange(0.0, 90.0 + 1e-9, step)
    a = brdfs.albedo(brdfs.model("blinn_cosmin", n=2.0, C=1.0), grid, rtol=1e-9).value
    assert rounds_to("0.368", 1.0 / a.max()) is prints


@pytest.mark.parametrize(("steps", "prints"), [(90, True), (100, False)])
def test_table_3_3_new_model_n_512_is_eq_3_37_by_90_midpoints_in_cos2_theta(steps, prints):
    u, w = readings.rule_weights("midpoint", 0.0, 1.0, steps)
    a = brdfs.albedo(brdfs.model("phong_cosmin", n=512.0), np.degrees(np.arccos(np.sqrt(u))), rtol=1e-8).value
    assert rounds_to("0.975", float(np.sum(w * a))) is prints


def test_the_box_of_the_inputs_has_its_extremes_at_the_proven_corners():
    low, high = box_range("2.06", "4.26", 0.5)
    n, k = np.meshgrid(np.linspace(2.055, 2.065, 41), np.linspace(4.255, 4.265, 41))
    inside = a0_percent(n.ravel(), k.ravel())[0]
    assert low <= inside.min() + 1e-12 and inside.max() <= high + 1e-12
    assert inside.min() == pytest.approx(low, abs=1e-12) and inside.max() == pytest.approx(high, abs=1e-12)


@pytest.mark.parametrize("rule, degree", [("left", 0), ("right", 0), ("midpoint", 1), ("trapezoid", 1),
                                          ("simpson", 3)])
def test_each_elementary_rule_is_exact_to_its_degree_and_the_grid_sum_is_the_same_rule(rule, degree):
    """∫₀^b x^k dx = b^(k+1)/(k+1) for k ≤ the rule's degree, and not for k = degree + 1; the
    prefix sums of Table 4.3 over a longer grid give the weights' sums."""
    n, h = 8, 0.25
    x, w = readings.rule_weights(rule, 0.0, n * h, n)
    b = n * h
    for k in range(degree + 2):
        exact = b ** (k + 1) / (k + 1)
        assert (abs(w @ x**k - exact) < 1e-12) == (k <= degree)
    if rule != "midpoint":
        grid = np.arange(2 * n + 1) * h
        values = np.stack([grid**2, np.cos(grid)])
        assert readings.grid_rule_sum(rule, values, h, n) == pytest.approx([w @ x**2, w @ np.cos(x)], rel=1e-14)
    assert readings.rule_weights("simpson", 0.0, 1.0, 7)[0].size == 0
