"""requirements.lock (pip-compile of pyproject.toml, `make lock`) holds the exact versions, with
hashes, of everything the make targets install; pyproject.toml holds only lower bounds."""

import re

import pytest
from packaging.requirements import Requirement

from brdfs.pipeline.io import REPO_ROOT

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11

#: The extras `make venv` installs from the lock (Makefile LOCK_EXTRAS).
LOCKED_EXTRAS = ("pipeline", "cluster", "render", "docs", "test")


def lock_entries() -> dict[str, tuple[str, list[str]]]:
    """name -> (version, hashes) of every requirement of requirements.lock."""
    entries, name = {}, None
    for line in (REPO_ROOT / "requirements.lock").read_text().splitlines():
        stripped = line.strip().rstrip("\\").strip()
        pin = re.fullmatch(r"([A-Za-z0-9_.\-]+)==([^\s;]+)", stripped)
        if pin:
            name = pin[1].lower().replace("_", "-")
            entries[name] = (pin[2], [])
        elif stripped.startswith("--hash=") and name is not None:
            entries[name][1].append(stripped)
    return entries


def project_requirements():
    project = tomllib.loads((REPO_ROOT / "pyproject.toml").read_text())["project"]
    core = [Requirement(r) for r in project["dependencies"]]
    extras = [Requirement(r) for extra in LOCKED_EXTRAS for r in project["optional-dependencies"][extra]]
    return core, extras


def test_the_core_needs_only_numpy_and_scipy_with_lower_bounds():
    core, _ = project_requirements()
    assert sorted(r.name for r in core) == ["numpy", "scipy"]
    assert all(s.operator == ">=" for r in core for s in r.specifier)


def test_pyproject_pins_nothing_exactly_and_the_lock_satisfies_every_requirement():
    core, extras = project_requirements()
    entries = lock_entries()
    for requirement in core + extras:
        assert not any(s.operator == "==" for s in requirement.specifier), f"{requirement}: exact pins go into the lock"
        name = requirement.name.lower().replace("_", "-")
        assert name in entries, f"{name} is not in requirements.lock: run `make lock`"
        assert requirement.specifier.contains(entries[name][0]), \
            f"{requirement}: the lock has {entries[name][0]}: run `make lock`"


def test_every_line_of_the_lock_is_an_exact_pin_with_hashes():
    text = (REPO_ROOT / "requirements.lock").read_text()
    entries = lock_entries()
    assert len(entries) > 50
    assert all(hashes for _, hashes in entries.values()), [n for n, (_, h) in entries.items() if not h]
    body = [line.strip() for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    assert all("==" in line or line.startswith("--hash=") for line in body), \
        [line for line in body if "==" not in line and not line.startswith("--hash=")]
