"""The artifact registry: declarations (read without importing, and by the decorators), dependency
resolution, config subsets."""

import importlib
import pkgutil
import subprocess
import sys
import textwrap

import pandas as pd
import pytest

import brdfs.artifacts
from brdfs.pipeline import declarations

from brdfs.pipeline import registry as artifacts


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
def empty_registry(monkeypatch):
    """A registry holding nothing of the package: neither scanned nor imported declarations."""
    monkeypatch.setattr(artifacts, "_ARTIFACTS", {})
    monkeypatch.setattr(artifacts, "_COMPARISONS", {})
    monkeypatch.setattr(artifacts, "_package_declarations", lambda: ({}, {}))


@pytest.fixture
def toy_registry(empty_registry):
    """Two toy tables, ``extra_toy_b`` depending on ``extra_toy_a``, counting their computations."""
    calls = []

    def compute_a(cfg, deps):
        calls.append("a")
        return pd.DataFrame({"x": [0.1, 1 / 3]})

    def compute_b(cfg, deps):
        calls.append("b")
        return deps["extra_toy_a"].assign(y=deps["extra_toy_a"]["x"] * cfg["toy"]["factor"])

    compute_a.__module__, compute_b.__module__ = "toy_a", "toy_b"
    artifacts.table("extra_toy_a", config=(), chapter=None)(compute_a)
    artifacts.table("extra_toy_b", deps=("extra_toy_a",), config=("toy",), chapter=None)(compute_b)
    return calls


def test_dependencies_are_computed_once(toy_registry):
    cfg = {"seed": 0, "tolerance": {}, "toy": {"factor": 3.0}}
    cache = {}
    first = artifacts.compute_tables(cfg, ["extra_toy_b", "extra_toy_a"], cache)
    artifacts.compute_tables(cfg, ["extra_toy_b"], cache)
    assert toy_registry == ["a", "b"]
    assert first["extra_toy_b"]["y"].tolist() == [0.1 * 3.0, 1 / 3 * 3.0]


def test_dependency_cycles_are_reported(empty_registry):
    def compute(cfg, deps):
        return pd.DataFrame({"x": [1]})

    for name, dep, module in (("extra_loop_a", "extra_loop_b", "m_a"), ("extra_loop_b", "extra_loop_a", "m_b")):
        fn = lambda cfg, deps: compute(cfg, deps)  # noqa: E731  (a distinct function per module)
        fn.__module__ = module
        artifacts.table(name, deps=(dep,), chapter=None)(fn)
    with pytest.raises(ValueError, match="dependency cycle: extra_loop_a -> extra_loop_b -> extra_loop_a"):
        artifacts.compute_tables({"seed": 0, "tolerance": {}}, ["extra_loop_a"], {})


def test_two_tables_in_one_module_or_one_name_twice_are_refused(empty_registry):
    def one(cfg, deps):
        return pd.DataFrame()

    def two(cfg, deps):
        return pd.DataFrame()

    artifacts.table("extra_one", chapter=None)(one)
    with pytest.raises(ValueError, match="one table or figure per module"):
        artifacts.table("extra_two", chapter=None)(two)
    two.__module__ = "elsewhere"
    with pytest.raises(ValueError, match="registered twice"):
        artifacts.table("extra_one", chapter=None)(two)


def test_compute_must_return_a_dataframe(toy_registry):
    def empty(cfg, deps):
        return pd.DataFrame()

    empty.__module__ = "toy_empty"
    artifacts.table("extra_empty", chapter=None)(empty)
    with pytest.raises(TypeError, match="non-empty DataFrame"):
        artifacts.get_artifact("extra_empty").compute({"seed": 0, "tolerance": {}}, {})


def test_the_scan_of_the_decorator_lines_declares_what_importing_the_modules_registers():
    scanned, scanned_comparisons = artifacts.artifacts(), artifacts.comparisons()
    for module in pkgutil.iter_modules(brdfs.artifacts.__path__):
        if not module.name.startswith("_"):
            importlib.import_module(f"brdfs.artifacts.{module.name}")
    assert artifacts._ARTIFACTS == scanned                # name, kind, module, deps, config, resources, chapter
    assert artifacts._COMPARISONS == scanned_comparisons  # artifact, module, tables, config
    assert artifacts.get_artifact("extra_microfacet_albedo").deps == (
        "extra_pumping_albedo_phong", "extra_pumping_albedo_blinn")  # tuple(mf.PUMPING_TABLES.values())
    assert artifacts.get_artifact("fig_1_1_surface_elements").config == ("diagrams",)  # dg.SECTION


def test_listing_the_artifacts_imports_no_artifact_module_nor_the_numerical_libraries():
    code = ("import sys; from brdfs.pipeline import registry; a = registry.artifacts(); c = registry.comparisons(); "
            "[x.sources for x in (*a.values(), *c.values())]; "
            "print(len(a), len(c), sorted(m for m in sys.modules if m.startswith('brdfs.artifacts') "
            "or m.split('.')[0] in ('numpy', 'pandas', 'scipy', 'matplotlib')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split(" ", 2)
    assert int(out[0]) >= 68 and int(out[1]) >= 13
    assert out[2].strip() == "[]"


def test_a_decorator_argument_the_scan_cannot_read_is_reported_with_its_file_and_line(tmp_path, monkeypatch):
    path = tmp_path / "extra_toy_scan.py"
    path.write_text(textwrap.dedent("""\
        from brdfs.artifacts import _microfacet_energy as mf
        from brdfs.pipeline.registry import table

        NAME = "extra_toy_scan"
        DEPS = (*mf.PUMPING_TABLES.values(), "table_3_1_blinn_constants")


        @table(NAME, deps=DEPS, config=("toy",), resources={"runtime": 1}, chapter=2)
        def compute(cfg, deps):
            pass
        """))
    monkeypatch.setattr(artifacts, "_module_file", lambda module, real=artifacts._module_file:
                        path if module == "brdfs.artifacts.extra_toy_scan" else real(module))
    declarations._scope.cache_clear()
    (entry,) = declarations._declarations_in("brdfs.artifacts.extra_toy_scan")
    assert (entry.name, entry.kind, entry.config, entry.chapter, entry.resources["runtime"]) == (
        "extra_toy_scan", "table", ("toy",), 2, 1)
    assert entry.deps == ("extra_pumping_albedo_phong", "extra_pumping_albedo_blinn", "table_3_1_blinn_constants")

    path.write_text(path.read_text().replace("config=(\"toy\",)", "config=sections()"))
    declarations._scope.cache_clear()
    artifacts._parse.cache_clear()
    with pytest.raises(artifacts.DeclarationError, match=r"extra_toy_scan.py:8: cannot read: 'sections\(\)'"):
        declarations._declarations_in("brdfs.artifacts.extra_toy_scan")
    declarations._scope.cache_clear()


def test_thesis_artifacts_default_to_their_numbers_chapter_and_an_extra_must_declare_its_own(empty_registry):
    def compute(cfg, deps):
        return pd.DataFrame({"x": [1]})

    def extra(cfg, deps):
        return compute(cfg, deps)

    compute.__module__, extra.__module__ = "toy_figure", "toy_extra"
    artifacts.figure("fig_4_99_toy")(compute)
    assert artifacts.get_artifact("fig_4_99_toy").chapter == 4
    with pytest.raises(artifacts.DeclarationError, match="extra_toy_chapter: declare the report chapter"):
        artifacts.table("extra_toy_chapter")(extra)


def test_make_all_removes_exactly_the_results_no_rule_writes_any_more_and_says_so_in_one_line(tmp_path, capsys):
    from brdfs.pipeline import io

    table = artifacts.get_artifact("table_3_2_ward_cmax")
    render = next(a for a in artifacts.artifacts().values() if a.renders)
    kept = [table.csv, table.png, artifacts.log_of(table.step), artifacts.benchmark_of(table.step),
            f"{render.renders}/panel.exr", f"{render.renders}/.snakemake_timestamp", artifacts.COMPARISON,
            artifacts.log_of("merge_comparison"), artifacts.REPORT_TABLE.format(name=table.name),
            "results/report.html", "results/benchmarks/sweep_summary.csv"]      # not the rules': left alone
    stale = ["results/benchmarks/rules/batches/batch_chapter_3.tsv", "results/logs/batches/batch_chapter_3.log",
             "results/tables/table_9_9_gone.csv", "results/tables/.table_3_2_ward_cmax.1f2e.csv"]  # a killed job's
    for relative in kept + stale:
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / relative).write_text("x")
    for relative, record in [(table.csv, kept), ("results/tables/table_9_9_gone.csv", stale)]:
        record.append(io.digest_path(relative).as_posix())
        (tmp_path / record[-1]).parent.mkdir(exist_ok=True)
        (tmp_path / record[-1]).write_text("0" * 64)

    assert artifacts.stale_results(tmp_path) == sorted(stale)
    assert artifacts.main(["remove-stale", str(tmp_path)]) == 0
    (line,) = capsys.readouterr().out.splitlines()
    assert line == f"removed {len(stale)} results no rule writes any more: {' '.join(sorted(stale))}"
    assert [r for r in kept + stale if (tmp_path / r).exists()] == kept
    assert not (tmp_path / "results/benchmarks/rules/batches").exists()    # the directories they leave empty
    assert artifacts.stale_results(tmp_path) == [] and artifacts.main(["remove-stale", str(tmp_path)]) == 0
    assert capsys.readouterr().out == ""
