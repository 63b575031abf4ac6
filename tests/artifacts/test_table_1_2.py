"""Table 1.2 (normal-incidence reflectance of metals) end to end, in-process."""

from fractions import Fraction

import pandas as pd
import pytest

from brdfs.pipeline import registry as artifacts
from brdfs.artifacts.extra_metal_a0_readings import _swap
from brdfs.pipeline.config import load_config

# Table 1.2 as printed: metal, lambda [nm], n, k, a0 [%]
THESIS_TABLE_1_2 = [
    ("aluminium", 578, "0.93", "6.33", "91.5"),
    ("gold", 550, "0.331", "2.324", "81.5"),
    ("silver", 589, "0.18", "3.64", "95.1"),
    ("mercury", 600, "1.39", "4.32", "77.2"),
    ("chromium", 579, "2.97", "4.58", "69.8"),
    ("nickel", 589, "1.79", "3.33", "62.1"),
    ("platinum", 589, "2.06", "4.26", "70.1"),
]


@pytest.fixture(scope="module")
def cfg():
    return load_config()


@pytest.fixture(scope="module")
def tables(cfg):
    return artifacts.compute_tables(cfg, ["table_1_2_metal_reflectance", "extra_metal_a0_readings"], {})


@pytest.fixture(scope="module")
def fragment(cfg, tables):
    return artifacts.get_comparison("metal_a0").fragment(cfg, tables).set_index("param_value")


def test_config_holds_the_printed_inputs(cfg):
    metals = cfg["metal_reflectance"]["metals"]
    assert [(m["name"], m["lambda_nm"], m["ior_re"], m["ior_im"]) for m in metals] == [
        (name, lam, float(n), float(k)) for name, lam, n, k, _ in THESIS_TABLE_1_2
    ]


def test_a0_is_eq_1_40_within_its_error(tables):
    table = tables["table_1_2_metal_reflectance"].set_index("metal")
    assert list(table.columns) == ["lambda_nm", "ior_re", "ior_im", "a0_percent", "a0_percent_err"]
    for name, _, n, k, _ in THESIS_TABLE_1_2:
        n, k = Fraction(n), Fraction(k)
        exact = 100 * ((n - 1) ** 2 + k**2) / ((n + 1) ** 2 + k**2)
        row = table.loc[name]
        assert abs(Fraction(row["a0_percent"]) - exact) <= Fraction(row["a0_percent_err"])
        assert 0 < row["a0_percent_err"] < 1e-12


def test_verdicts(fragment):
    verdicts = {"chromium": "input misprint", "platinum": "differs"}
    for name, *_ , printed in THESIS_TABLE_1_2:
        assert fragment.loc[name, "published"] == printed
        assert fragment.loc[name, "verdict"] == verdicts.get(name, "reproduces")
    assert all("results/tables/extra_metal_a0_readings.csv" in e for e in fragment.loc[list(verdicts), "evidence"])


def test_chromium_print_is_k_misprinted_with_digits_transposed(fragment):
    row = fragment.loc["chromium"]
    assert row["computed"] == pytest.approx(67.662, abs=1e-3)
    assert row["reading"] == "k = 4.85 (digits 2 and 3 of the printed 4.58 transposed)"
    assert row["value_under_reading"] == pytest.approx(69.758, abs=1e-3)
    assert row["reason"].startswith("misprinted input: k = 4.85 (digits 2 and 3 of the printed 4.58 transposed) gives 69.76")


def test_platinum_is_within_its_rounding_box_but_the_box_reading_does_not_beat_its_placebo(fragment):
    row = fragment.loc["platinum"]
    assert round(row["computed"], 1) == 70.0 and row["verdict"] == "differs"
    assert row["reading"].startswith("inputs anywhere within") and round(row["value_under_reading"], 1) == 70.1
    assert row["family_size"] == "5" and "not above the placebo" in row["reason"]


def test_readings_table(tables):
    readings = tables["extra_metal_a0_readings"]
    assert set(readings["group"]) == {"Table 1.2 a0", "Table 1.2 a0, input misprints"}
    box = readings[readings["group"] == "Table 1.2 a0"]
    assert sorted(box["half_width"].unique()) == [0, 0.25, 0.5, 1, 2]
    assert len(box) == 5 * len(THESIS_TABLE_1_2)


def test_digit_transpositions():
    assert [_swap("4.58", i) for i in range(3)] == ["5.48", "4.85", None]
    assert [_swap("3.33", i) for i in range(2)] == [None, None]
    assert [_swap("2.06", i) for i in range(2)] == ["0.26", "2.60"]


def test_table_writes_its_csv_and_png(tmp_path, tables):
    artifact = artifacts.get_artifact("table_1_2_metal_reflectance")
    artifact.write(tables["table_1_2_metal_reflectance"], tmp_path / "t.csv", tmp_path / "t.png")
    assert (tmp_path / "t.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert pd.read_csv(tmp_path / "t.csv").equals(tables["table_1_2_metal_reflectance"])
