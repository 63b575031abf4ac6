"""Chapter-4 artifacts end to end, in-process: tables, figures, and the four comparisons."""

import copy

import numpy as np
import pytest

from brdfs.pipeline import registry as artifacts
from brdfs.pipeline.config import load_config

TABLES = ["table_4_1_exponential_patch", "table_4_2_limit_comparison", "table_4_3_generalized_lambert",
          "fig_4_5_basic_albedo", "extra_readings_table_4_1", "extra_readings_table_4_3"]


@pytest.fixture(scope="module")
def cfg():
    cfg = copy.deepcopy(load_config())
    cfg["patch"]["limit_n"] = [10.0, 1000.0]          # keep the Phong/Blinn confirmations cheap here
    cfg["patch"]["limit_s"] = [8.0, 512.0]
    cfg["readings"]["table_4_3"]["steps"] = [0.0002, 0.0001, 0.00005]   # the chosen step and its neighbours
    return cfg


@pytest.fixture(scope="module")
def tables(cfg):
    return artifacts.compute_tables(cfg, TABLES, {})


def _fragment(cfg, tables, name):
    check = artifacts.get_comparison(name)
    return check.fragment(cfg, {t: tables[t] for t in check.tables}).set_index(["param_value", "quantity"])


def test_table_4_1_closed_forms_agree_with_quadrature(tables):
    df = tables["table_4_1_exponential_patch"]
    for name in ("C_max", "I_12", "a_diffuse"):
        gap = np.abs(df[name] - df[f"{name}_integrated"])
        assert np.all(gap <= df[f"{name}_err"] + df[f"{name}_integrated_err"])


def test_table_4_1_verdicts(cfg, tables):
    fragment = _fragment(cfg, tables, "patch_exponential")
    explained = set(fragment.index[fragment["verdict"] == "reproduces under a reading"])
    cut = {(s, "C_max") for s in ("8", "16", "64", "128", "512")}
    i12 = {(s, "I_12") for s in ("0.25", "0.5", "1", "2", "4", "8", "16")}
    assert explained == cut | i12 and not (fragment["verdict"] == "differs").any()
    assert all(fragment.loc[k, "reading"] == "'%.4f' cut to 6 characters" for k in cut)
    assert all(fragment.loc[k, "reading"] == "I_12 = 1 int_1^2 p(R) dR, rounded" for k in i12)
    assert all(fragment.loc[k, "group_score"] == "12/12" for k in cut | i12)


def test_table_4_3_verdicts(cfg, tables):
    fragment = _fragment(cfg, tables, "patch_generalized_lambert")
    assert (fragment.xs("f_max", level="quantity")["verdict"] == "reproduces").all()
    c_max = fragment.xs("C_max", level="quantity")["verdict"]
    assert c_max.loc["0"] == "reproduces" and (c_max.drop("0") == "reproduces under a reading").all()
    differing = fragment[fragment["verdict"] != "reproduces"]
    assert (differing["reading"] == "left, h = 0.0001, to 2, clip node unclipped").all()
    assert (differing["group_score"] == "21/21").all()
    assert (tables["table_4_3_generalized_lambert"]["theta_max_deg"].iloc[1:] == 90.0).all()


def test_table_4_2_limits_and_their_confirmation(cfg, tables):
    fragment = _fragment(cfg, tables, "limit_comparison")
    assert fragment.loc[("inf", "mean_albedo"), "verdict"].tolist() == ["differs", "reproduces"]
    assert fragment.loc[("inf", "mean_albedo"), "value_under_reading"].iloc[0] == 0.5
    df = tables["table_4_2_limit_comparison"]
    numeric = df[df["kind"] == "numerical"]
    for model_name, quantity, limit in [("phong", "mean_albedo", 2 / 3), ("blinn", "mean_albedo", 0.5),
                                        ("patch_exponential", "mean_albedo", 1.0),
                                        ("patch_exponential", "albedo_exactly_90deg", 0.5)]:
        gaps = np.abs(numeric[(numeric["model"] == model_name) & (numeric["quantity"] == quantity)]["value"] - limit)
        assert gaps.iloc[-1] < gaps.iloc[0] and gaps.iloc[-1] < 3e-3, (model_name, quantity)


def test_basic_brdf_bound_reproduces(cfg, tables):
    fragment = _fragment(cfg, tables, "basic_brdf")
    assert fragment["verdict"].tolist() == ["reproduces"]
    assert fragment["computed"].iloc[0] == pytest.approx(2 / 3 - np.sqrt(3) / (2 * np.pi), rel=1e-14)


@pytest.mark.parametrize("name", ["fig_4_3_basic_brdf", "fig_4_6_basic_mean_albedo", "fig_4_10_elliptical_brdf",
                                  "fig_4_12_weight_density", "fig_4_13_inverse_cdf", "fig_4_14_exponential_albedo",
                                  "fig_4_15_exponential_brdf"])
def test_figures_compute_and_draw(cfg, name, tmp_path):
    artifact = artifacts.get_artifact(name)
    df = artifacts.compute_tables(cfg, [name], {})[name]
    artifact.write(df, tmp_path / "a.csv", tmp_path / "a.png")
    assert (tmp_path / "a.png").stat().st_size > 0
    value = [c for c in df.columns if c + "_err" in df.columns]
    assert value and all(np.all(df[c + "_err"] >= 0) for c in value)
