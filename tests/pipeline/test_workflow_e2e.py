"""The workflow end to end: `snakemake` plans and builds a few cheap artifacts in a fresh copy of the repository.

So that the test command exercises the rules (generic artifact rule, logs, benchmarks, atomic
outputs, up-to-date detection also after the config's keys are reordered, report captions) and not only the package, and that planning
has no side effects: it writes nothing and reads no output.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
import yaml

from brdfs.pipeline import io, registry
from brdfs.pipeline.io import REPO_ROOT

SNAKEMAKE = Path(sys.executable).with_name("snakemake")
TARGETS = ["results/tables/table_1_2_metal_reflectance.png", "results/figures/fig_5_1_patch_based_brdf.png"]


def copy_repository(destination: Path) -> Path:
    for name in ("Snakefile", "config.yaml", "workflow", "data", "src"):
        source = REPO_ROOT / name
        (shutil.copytree if source.is_dir() else shutil.copy)(source, destination / name,
                                                              **({"symlinks": True} if source.is_dir() else {}))
    for cache in destination.rglob("__pycache__"):
        shutil.rmtree(cache)
    return destination


def snakemake(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(cwd / "src"), "PYTHONDONTWRITEBYTECODE": "1",
           "PATH": f"{SNAKEMAKE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    return subprocess.run([str(SNAKEMAKE), "--cores", "1", *args], cwd=cwd, capture_output=True, text=True,
                          env=env, timeout=300)


def planned_jobs(run: subprocess.CompletedProcess) -> dict[str, int]:
    """The "Job stats" table of a dry run: jobs by rule (empty when nothing is to be done)."""
    if "Job stats:" not in run.stdout + run.stderr:
        return {}
    table = (run.stdout + run.stderr).split("Job stats:")[1].split("\n\n")[0]
    return {m[1]: int(m[2]) for m in re.finditer(r"^(\S+)\s+(\d+)$", table, re.M) if m[1] != "total"}


def tree(root: Path) -> dict[str, tuple[int, int]]:
    """Every file under ``root`` (size and modification time) but Snakemake's own cache of file times."""
    return {p.relative_to(root).as_posix(): (p.stat().st_size, p.stat().st_mtime_ns) for p in root.rglob("*")
            if p.is_file() and not p.relative_to(root).as_posix().startswith(".snakemake/iocache/")}


def test_planning_one_table_from_scratch_yields_exactly_one_job(tmp_path):
    run = snakemake(copy_repository(tmp_path), "-n", "results/tables/table_3_2_ward_cmax.png")
    assert run.returncode == 0, run.stderr[-3000:]
    assert planned_jobs(run) == {"artifact": 1}


def test_planning_the_whole_workflow_writes_nothing_and_reads_no_output(tmp_path):
    """Also with `1e-10` (YAML 1.2) in config.yaml and nested `--config` values (deep-merged into the
    file's sections): the configuration is valid and every rule is planned. (One plan of the whole
    workflow for both claims: each costs a Snakemake start and a DAG of every artifact.)"""
    copy_repository(tmp_path)
    config_yaml = tmp_path / "config.yaml"
    config_yaml.write_text(config_yaml.read_text().replace("rtol: 1.0e-10", "rtol: 1e-10"))
    assert "rtol: 1e-10" in config_yaml.read_text()
    # A comparison no parser reads: planning that read the outputs would stop on it.
    (tmp_path / "results" / "checks").mkdir(parents=True, exist_ok=True)
    (tmp_path / "results" / "checks" / "published_comparison.csv").write_text('artifact,"unterminated\n')
    before = tree(tmp_path)
    run = snakemake(tmp_path, "-n", "--config", "tolerance={atol: 1e-15}", "ward_cmax={m: [0.4, 1e-1]}")
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert tree(tmp_path) == before
    assert not (tmp_path / ".snakemake" / "report_captions").exists()
    assert "results/checks/published/metal_a0.csv" in run.stdout and "merge_comparison" in run.stdout
    assert "results/figures/fig_2_1_albedo_classical.png" in run.stdout
    assert "results/tables/table_3_2_ward_cmax.png" in run.stdout
    jobs = planned_jobs(run)
    assert jobs["check"] == jobs["merge_comparison"] == 1
    # one job per artifact: no other rule computes one (a render's rule also declares its EXRs)
    assert set(jobs) == {"all", "artifact", "render_artifact", "check", "merge_comparison", "report_pages"}, jobs
    assert jobs["artifact"] + jobs["render_artifact"] >= 68 and jobs["render_artifact"] >= 12


def test_snakemake_builds_cheap_artifacts_with_logs_benchmarks_and_captions_then_has_nothing_to_do(tmp_path, capsys):
    copy_repository(tmp_path)
    run = snakemake(tmp_path, *TARGETS)
    assert run.returncode == 0, run.stderr[-3000:]

    for target in TARGETS:
        png, csv = tmp_path / target, (tmp_path / target).with_suffix(".csv")
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert not pd.read_csv(csv).empty
        kind, name = png.parent.name, png.stem
        log = (tmp_path / "results" / "logs" / kind / f"{name}.log").read_text()
        assert f"step: compute {name}" in log and "done in" in log, log
        assert (tmp_path / "results" / "benchmarks" / "rules" / kind / f"{name}.tsv").is_file()
    # Atomic writes leave no temporary behind; every file the build wrote is one the registry says a rule
    # writes (what `make all` does not remove as stale: outputs, digests, logs, timings).
    assert not [p for p in (tmp_path / "results").rglob(".*") if p.is_file()]
    assert registry.stale_results(tmp_path) == []

    # The report of these two: each PNG with its committed caption, rendered by the one template.
    report = snakemake(tmp_path, "--report", "report.html", *TARGETS)
    assert report.returncode == 0, report.stderr[-3000:]
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "Table 1.2" in html and "Figure 5.1" in html and "not built yet" in html
    # A job's parameters show its config sections' names and digest, not the sections (no config dump).
    assert "seed,tolerance,metal_reflectance@" in html and "'lambda_nm': 578" not in html

    # The same configuration with its keys sorted (top level and nested) plans no job: params are
    # compared by a repr that sorts every mapping (registry.ConfigSubset). (So the build has nothing
    # left to do: were a job planned in the file's own order, it would be planned here too.)
    config_yaml = tmp_path / "config.yaml"
    original = yaml.safe_load(config_yaml.read_text())
    config_yaml.write_text(yaml.safe_dump(original, sort_keys=True))
    rewritten = yaml.safe_load(config_yaml.read_text())
    assert rewritten == original   # numbers stay numbers
    assert list(rewritten) != list(original) and list(rewritten["tolerance"]) != list(original["tolerance"])
    sorted_keys = snakemake(tmp_path, "-n", *TARGETS)
    assert sorted_keys.returncode == 0, sorted_keys.stderr[-3000:]
    assert "Nothing to be done" in sorted_keys.stdout + sorted_keys.stderr, sorted_keys.stdout[-3000:]

    # A damaged result (truncated) is listed by `python -m brdfs.pipeline.io damaged`, which `make all`
    # passes to --forcerun: exactly its job is planned again, also with the sorted configuration given as
    # --configfile over the file's own order (the other way to run it: it plans no other job).
    (tmp_path / "sorted.yaml").write_text(yaml.safe_dump(original, sort_keys=True))
    config_yaml.write_text(yaml.safe_dump(original, sort_keys=False))
    # (Figure 5.1 is damaged: Table 1.2, whose section is a list of mappings, must stay planned for nothing.)
    damaged = "results/figures/fig_5_1_patch_based_brdf.csv"
    (tmp_path / damaged).write_text((tmp_path / damaged).read_text()[:-20])
    capsys.readouterr()
    assert io.main(["damaged", str(tmp_path)]) == 0
    listed = capsys.readouterr()
    assert listed.out.split() == [damaged], listed
    assert listed.err.startswith(f"{damaged}: damaged, its content changed")
    rebuilt = snakemake(tmp_path, "-n", *TARGETS, "--configfile", "sorted.yaml", "--forcerun", *listed.out.split())
    assert planned_jobs(rebuilt) == {"artifact": 1} and "fig_5_1_patch_based_brdf" in rebuilt.stdout, rebuilt.stdout

    # A changed value in the section one target reads reruns that target alone (its digest changed).
    rewritten["metal_reflectance"]["metals"][4]["ior_im"] = 4.85
    config_yaml.write_text(yaml.safe_dump(rewritten, sort_keys=True))
    changed = snakemake(tmp_path, "-n", *TARGETS)
    assert changed.returncode == 0, changed.stderr[-3000:]
    assert planned_jobs(changed) == {"artifact": 1} and "table_1_2_metal_reflectance" in changed.stdout, changed.stdout


def test_a_copy_of_the_built_tree_plans_nothing_in_either_mode(tmp_path):
    """After `make all`, a plain `snakemake -n` plans nothing, also with the config's keys reordered (one
    job per artifact in every mode: the same inputs and params recorded)."""
    outputs = [REPO_ROOT / "results" / "checks" / "published_comparison.csv",
               *(REPO_ROOT / path for a in registry.artifacts().values() for path in (a.csv, a.png))]
    code = [p for d in ("src", "workflow") for p in (REPO_ROOT / d).rglob("*") if p.is_file() and "__pycache__" not in p.parts]
    code += [REPO_ROOT / "Snakefile", REPO_ROOT / "config.yaml"]
    if not all(p.is_file() for p in outputs) or max(p.stat().st_mtime for p in code) > min(p.stat().st_mtime for p in outputs):
        pytest.skip("results/ is not a complete build newer than the code (make all): nothing to plan nothing from")
    copy_repository(tmp_path)
    for name in ("results", ".snakemake/metadata"):
        shutil.copytree(REPO_ROOT / name, tmp_path / name, symlinks=True)
    for cache in (tmp_path / "src").rglob("__pycache__"):
        shutil.rmtree(cache)
    # with the keys of config.yaml reordered (the --configfile mode is planned on the small tree above)
    config_yaml = tmp_path / "config.yaml"
    config_yaml.write_text(yaml.safe_dump(yaml.safe_load(config_yaml.read_text()), sort_keys=True))
    plain = snakemake(tmp_path, "-n")
    assert "Nothing to be done" in plain.stdout + plain.stderr, plain.stdout[-3000:]
