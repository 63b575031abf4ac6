"""The Makefile's build lock (README "Crashes"): every target that lets Snakemake write runs under
an exclusive flock on .snakemake/make.lock; a second build fails at once with one line; a
Snakemake lock left by a killed run is cleared (`snakemake --unlock`) only while holding the flock.

A stand-in for snakemake (SNAKEMAKE=...) records each call and whether the flock was held, so that
none of this runs a build; `make check-crash` does the same with real SIGKILLed builds."""

import fcntl
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from brdfs.pipeline.io import REPO_ROOT

pytestmark = pytest.mark.skipif(shutil.which("flock") is None or shutil.which("make") is None,
                                reason="needs make and flock(1)")

LOCK = ".snakemake/make.lock"
MESSAGE = "another build is running (lock held: {})"
FAKE_SNAKEMAKE = """#!/bin/sh
# Records its arguments and whether the build lock is held; --unlock clears the Snakemake lock.
if flock --nonblock {lock} true; then held=free; else held=held; fi
echo "$held $*" >> calls.log
if [ "$1" = --unlock ]; then rm -rf .snakemake/locks; fi
"""


@pytest.fixture
def tree(tmp_path: Path) -> Path:
    """A checkout with only what the Makefile reads, and a stand-in for snakemake."""
    for name in ("Makefile", "requirements.lock", "pyproject.toml", "workflow/scripts/ensure_llvm.sh"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(REPO_ROOT / name, tmp_path / name)
    (tmp_path / ".venv").symlink_to(Path(sys.executable).parent.parent)
    fake = tmp_path / "fake-snakemake"
    fake.write_text(FAKE_SNAKEMAKE.format(lock=LOCK))
    fake.chmod(0o755)
    return tmp_path


def make(tree: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS")}
    return subprocess.run(["make", "--no-print-directory", "-o", ".venv/.installed", f"SNAKEMAKE={tree / 'fake-snakemake'}",
                           *args], cwd=tree, capture_output=True, text=True, env=env, timeout=60)


def calls(tree: Path) -> list[str]:
    log = tree / "calls.log"
    return log.read_text().splitlines() if log.exists() else []


def hold_lock(tree: Path):
    (tree / ".snakemake").mkdir(exist_ok=True)
    handle = open(tree / LOCK, "a")
    fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    return handle


@pytest.mark.parametrize("target", ["all", "report", "clean"])
def test_a_second_build_fails_at_once_with_one_line_and_runs_nothing(tree, target):
    (tree / "results").mkdir()
    (tree / "results" / "kept.csv").write_text("x\n")
    with hold_lock(tree):
        run = make(tree, target, "TARGETS=results/tables/table_3_2_ward_cmax.png")
    assert run.returncode != 0
    expected = f"make {'all' if target == 'report' else target}: " + MESSAGE.format(tree / LOCK)
    # Our line, then make's own "*** [Makefile:N: all] Error 75".
    assert run.stderr.splitlines()[0] == expected, run.stderr
    assert len(run.stderr.splitlines()) == 2 and "Error 75" in run.stderr.splitlines()[1], run.stderr
    assert calls(tree) == []  # snakemake never started
    assert (tree / "results" / "kept.csv").exists()  # clean removed nothing


def test_make_all_passes_targets_to_snakemake_under_the_lock_and_releases_it(tree):
    run = make(tree, "all", "TARGETS=results/a.png results/b.png")
    assert run.returncode == 0, run.stderr
    assert calls(tree) == ["held --profile workflow/profiles/default results/a.png results/b.png"]
    with hold_lock(tree):  # released when make is done
        pass


def test_a_stale_snakemake_lock_is_cleared_under_the_flock_then_the_build_runs(tree):
    locks = tree / ".snakemake" / "locks"
    locks.mkdir(parents=True)
    (locks / "0.output.lock").write_text("results/tables/table_3_2_ward_cmax.csv\n")
    run = make(tree, "all")
    assert run.returncode == 0, run.stderr
    assert calls(tree) == ["held --unlock", "held --profile workflow/profiles/default"]
    assert "clearing the Snakemake lock of a run that was killed" in run.stdout
    assert not locks.exists()


def test_make_clean_keeps_the_lock_file_and_removes_the_rest(tree):
    for path in ("results/tables/x.csv", ".snakemake/metadata/x", ".snakemake/locks/0.input.lock"):
        (tree / path).parent.mkdir(parents=True, exist_ok=True)
        (tree / path).write_text("x\n")
    run = make(tree, "clean")
    assert run.returncode == 0, run.stderr
    assert not (tree / "results").exists()
    assert sorted(p.name for p in (tree / ".snakemake").iterdir()) == ["make.lock"]
