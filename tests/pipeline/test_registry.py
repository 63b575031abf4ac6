"""The artifact registry: declarations, dependency resolution, config subsets."""

import pandas as pd
import pytest

from brdfs.pipeline import registry as artifacts
from brdfs.pipeline.published import COMPARISON_COLUMNS


def test_registered_artifacts_and_their_paths():
    table = artifacts.get_artifact("table_1_2_metal_reflectance")
    assert (table.kind, table.deps, table.config) == ("table", (), ("metal_reflectance",))
    assert table.csv == "results/tables/table_1_2_metal_reflectance.csv"
    assert table.png == "results/tables/table_1_2_metal_reflectance.png"
    assert "src/brdfs/artifacts/table_1_2_metal_reflectance.py" in table.sources
    assert "src/brdfs/artifacts/extra_metal_a0_readings.py" not in table.sources
    assert "src/brdfs/physics/fresnel.py" in table.sources                  # imported, transitively
    assert "src/brdfs/artifacts/_pumping_figures.py" not in table.sources  # not imported
    readings = artifacts.get_artifact("extra_metal_a0_readings")
    assert "src/brdfs/artifacts/table_1_2_metal_reflectance.py" in readings.sources  # a sibling it imports
    pumping = artifacts.get_artifact("fig_2_3_phong_pumping")
    assert "src/brdfs/artifacts/_pumping_figures.py" in pumping.sources
    assert "src/brdfs/numerics/pumping.py" in pumping.sources
    check = artifacts.get_comparison("metal_a0")
    assert check.fragment_csv == "results/checks/published/metal_a0.csv"


def test_unknown_names_are_reported():
    with pytest.raises(KeyError, match="no table or figure 'table_9_9_nothing'"):
        artifacts.get_artifact("table_9_9_nothing")
    with pytest.raises(KeyError, match="no comparison"):
        artifacts.get_comparison("nothing")


@pytest.mark.parametrize("name", ["table_1_2", "Table_1_2_x", "fig_1_1_x", "table_x_metal"])
def test_table_names_follow_the_contract(name):
    with pytest.raises(ValueError, match="does not match"):
        artifacts.table(name)


def test_config_subset_holds_the_declared_sections_plus_seed_and_tolerance():
    cfg = {"seed": 1, "tolerance": {}, "a": 1, "b": 2}
    assert artifacts.config_subset(cfg, ("a",)) == {"seed": 1, "tolerance": {}, "a": 1}
    with pytest.raises(KeyError, match="lacks the sections"):
        artifacts.config_subset(cfg, ("c",))


@pytest.fixture
def toy_registry(monkeypatch):
    """Two toy tables, ``extra_toy_b`` depending on ``extra_toy_a``, counting their computations."""
    monkeypatch.setattr(artifacts, "_ARTIFACTS", {})
    monkeypatch.setattr(artifacts, "_load_all", lambda: None)
    calls = []

    def compute_a(cfg, deps):
        calls.append("a")
        return pd.DataFrame({"x": [0.1, 1 / 3]})

    def compute_b(cfg, deps):
        calls.append("b")
        return deps["extra_toy_a"].assign(y=deps["extra_toy_a"]["x"] * cfg["toy"]["factor"])

    compute_a.__module__, compute_b.__module__ = "toy_a", "toy_b"
    artifacts.table("extra_toy_a", config=())(compute_a)
    artifacts.table("extra_toy_b", deps=("extra_toy_a",), config=("toy",))(compute_b)
    return calls


def test_dependencies_are_computed_once(toy_registry):
    cfg = {"seed": 0, "tolerance": {}, "toy": {"factor": 3.0}}
    cache = {}
    first = artifacts.compute_tables(cfg, ["extra_toy_b", "extra_toy_a"], cache)
    artifacts.compute_tables(cfg, ["extra_toy_b"], cache)
    assert toy_registry == ["a", "b"]
    assert first["extra_toy_b"]["y"].tolist() == [0.1 * 3.0, 1 / 3 * 3.0]


def test_dependency_cycles_are_reported(monkeypatch):
    monkeypatch.setattr(artifacts, "_ARTIFACTS", {})
    monkeypatch.setattr(artifacts, "_load_all", lambda: None)

    def compute(cfg, deps):
        return pd.DataFrame({"x": [1]})

    for name, dep, module in (("extra_loop_a", "extra_loop_b", "m_a"), ("extra_loop_b", "extra_loop_a", "m_b")):
        fn = lambda cfg, deps: compute(cfg, deps)  # noqa: E731  (a distinct function per module)
        fn.__module__ = module
        artifacts.table(name, deps=(dep,))(fn)
    with pytest.raises(ValueError, match="dependency cycle: extra_loop_a -> extra_loop_b -> extra_loop_a"):
        artifacts.compute_tables({"seed": 0, "tolerance": {}}, ["extra_loop_a"], {})


def test_two_tables_in_one_module_or_one_name_twice_are_refused(monkeypatch):
    monkeypatch.setattr(artifacts, "_ARTIFACTS", {})

    def one(cfg, deps):
        return pd.DataFrame()

    def two(cfg, deps):
        return pd.DataFrame()

    artifacts.table("extra_one")(one)
    with pytest.raises(ValueError, match="one table or figure per module"):
        artifacts.table("extra_two")(two)
    two.__module__ = "elsewhere"
    with pytest.raises(ValueError, match="registered twice"):
        artifacts.table("extra_one")(two)


def test_compute_must_return_a_dataframe(toy_registry):
    def empty(cfg, deps):
        return pd.DataFrame()

    empty.__module__ = "toy_empty"
    artifacts.table("extra_empty")(empty)
    with pytest.raises(TypeError, match="non-empty DataFrame"):
        artifacts.get_artifact("extra_empty").compute({"seed": 0, "tolerance": {}}, {})


def test_compute_all_comparisons_gives_the_merged_comparison(all_comparisons):
    merged = all_comparisons
    assert tuple(merged.columns) == COMPARISON_COLUMNS
    assert set(merged["artifact"]) == set(artifacts.comparisons())
