"""The workflow end to end: `snakemake` builds a few cheap artifacts in a fresh copy of the repository.

So that the test command exercises the rules (generic artifact rule, logs, benchmarks, atomic
outputs, up-to-date detection) and not only the package.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd

from brdfs.pipeline import registry
from brdfs.pipeline.io import REPO_ROOT

SNAKEMAKE = Path(sys.executable).with_name("snakemake")
TARGETS = ["results/tables/table_1_2_metal_reflectance.png", "results/figures/fig_5_1_patch_based_brdf.png"]


def snakemake(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(cwd / "src"),
           "PATH": f"{SNAKEMAKE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    return subprocess.run([str(SNAKEMAKE), "--cores", "1", *args], cwd=cwd, capture_output=True, text=True,
                          env=env, timeout=300)


def test_snakemake_builds_cheap_artifacts_with_logs_and_benchmarks_then_has_nothing_to_do(tmp_path):
    for name in ("Snakefile", "config.yaml", "workflow", "data", "src"):
        source = REPO_ROOT / name
        (shutil.copytree if source.is_dir() else shutil.copy)(source, tmp_path / name,
                                                              **({"symlinks": True} if source.is_dir() else {}))
    run = snakemake(tmp_path, *TARGETS)
    assert run.returncode == 0, run.stderr[-3000:]

    for target in TARGETS:
        png, csv = tmp_path / target, (tmp_path / target).with_suffix(".csv")
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert not pd.read_csv(csv).empty
        name = png.stem
        kind, job = ("batches", registry.get_artifact(name).batch) if registry.get_artifact(name).batch \
            else (png.parent.name, name)
        log = (tmp_path / "results" / "logs" / kind / f"{job}.log").read_text()
        assert f"step: compute {name}" in log and "done in" in log, log
        assert (tmp_path / "results" / "benchmarks" / "rules" / kind / f"{job}.tsv").is_file()
    # Atomic writes leave no temporary behind.
    assert not [p for p in (tmp_path / "results").rglob(".*") if p.is_file()]

    again = snakemake(tmp_path, "-n", *TARGETS)
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr, again.stdout
