"""`make lint` (workflow/scripts/lint_check.py) fails on every `snakemake --lint` message but the one
README "Lint" explains (a conda environment per rule), and `make test` runs it first."""

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from brdfs.pipeline.io import REPO_ROOT

SCRIPT = REPO_ROOT / "workflow" / "scripts" / "lint_check.py"
_spec = importlib.util.spec_from_file_location("lint_check", SCRIPT)
lint_check = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lint_check)

CONDA = """Lints for rule {rule} (line 14, /x/workflow/rules/artifacts.smk):
    * Specify a conda environment or container for each rule.:
      This way, the used software for each specific step is documented, and the
      workflow can be executed on any machine without prerequisites.
      Also see:
      https://snakemake.readthedocs.io/en/latest/snakefiles/deployment.html#integrated-package-management
"""
NO_LOG = """    * No log directive defined:
      Without a log directive, all output will be printed to the terminal. In
      distributed environments, this means that errors are harder to discover.
"""
PROFILE = "Using workflow specific profile profiles/default for setting default command line arguments.\n"


def test_the_explained_message_alone_passes_any_other_fails():
    assert lint_check.unexplained(PROFILE + CONDA.format(rule="artifact") + "\n" + CONDA.format(rule="check"), 1) == []
    assert lint_check.unexplained("Congratulations, your workflow is in a good condition!\n", 0) == []
    other = CONDA.format(rule="check") + NO_LOG
    assert lint_check.unexplained(other, 1) == ["rule check (line 14, /x/workflow/rules/artifacts.smk): No log directive defined"]
    snakefile = "Lints for snakefile /x/Snakefile:\n    * Absolute path \"/x\" in line 3:\n      Do not use absolute paths.\n"
    assert len(lint_check.unexplained(snakefile, 1)) == 1


def test_a_linter_that_did_not_run_through_fails():
    assert lint_check.unexplained("SyntaxError in file Snakefile, line 3:\n", 1) == [
        "unexpected output: SyntaxError in file Snakefile, line 3:",
        "snakemake --lint exited with status 1 without linting"]
    assert lint_check.unexplained("", 1) == ["snakemake --lint exited with status 1 without linting"]
    assert lint_check.unexplained(CONDA.format(rule="artifact"), 2)


def copy_workflow(destination: Path) -> Path:
    for name in ("Snakefile", "config.yaml", "workflow", "data", "src"):
        source = REPO_ROOT / name
        if source.is_dir():
            shutil.copytree(source, destination / name, symlinks=True,
                            ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        else:
            shutil.copy2(source, destination / name)
    return destination


def lint(directory: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(directory / "src")}
    return subprocess.run([sys.executable, str(SCRIPT), "--directory", str(directory), *args], capture_output=True,
                          text=True, env=env, timeout=120)


def test_the_workflow_as_it_is_passes():
    clean = lint(REPO_ROOT)
    assert clean.returncode == 0, clean.stdout + clean.stderr
    assert clean.stdout.startswith(f'lint: only "{lint_check.EXPLAINED}"'), clean.stdout


def test_a_rule_without_a_log_fails(tmp_path):
    tree = copy_workflow(tmp_path)
    with open(tree / "Snakefile", "a") as snakefile:
        snakefile.write('\n\nrule injected:\n    output:\n        "results/injected.txt",\n'
                        '    shell:\n        "touch {output}"\n')
    run = lint(tree)
    assert run.returncode == 1, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    assert lines[0].startswith("lint: rule injected (line ") and lines[0].endswith("No log directive defined")
    assert lines[1:] == [f'lint: FAILED, messages other than "{lint_check.EXPLAINED}" (README, Checks, Lint)'], lines


def test_make_test_runs_lint_first():
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS")}
    plan = subprocess.run(["make", "-n", "--no-print-directory", "-o", ".venv/.installed", "test"], cwd=REPO_ROOT,
                          capture_output=True, text=True, env=env, timeout=60).stdout.splitlines()
    lint_lines = [i for i, line in enumerate(plan) if "lint_check.py" in line]
    pytest_lines = [i for i, line in enumerate(plan) if "-m pytest" in line]
    assert lint_lines and pytest_lines and lint_lines[0] < pytest_lines[0], plan
