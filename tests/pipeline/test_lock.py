"""requirements.lock (pip-compile of pyproject.toml) pins what pyproject.toml pins."""

import re

import pytest

from brdfs.pipeline.io import REPO_ROOT

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11


def locked() -> dict[str, str]:
    pins = {}
    for line in (REPO_ROOT / "requirements.lock").read_text().splitlines():
        match = re.fullmatch(r"([A-Za-z0-9_.\-]+)==([^\s;]+)", line.strip())
        if match:
            pins[match[1].lower().replace("_", "-")] = match[2]
    return pins


def test_every_exact_pin_of_pyproject_is_locked_at_the_same_version_and_every_line_is_pinned():
    project = tomllib.loads((REPO_ROOT / "pyproject.toml").read_text())["project"]
    requirements = [*project["dependencies"], *project["optional-dependencies"]["test"]]
    pins = locked()
    for requirement in requirements:
        name, _, version = requirement.partition("==")
        name = re.split(r"[<>=!~;\[ ]", name)[0].lower().replace("_", "-")
        assert name in pins, f"{name} is not in requirements.lock: run `make lock`"
        if version:
            assert pins[name] == version.strip(), f"{name}: pyproject {version}, lock {pins[name]}: run `make lock`"
    body = [line for line in (REPO_ROOT / "requirements.lock").read_text().splitlines()
            if line.strip() and not line.lstrip().startswith("#")]
    assert all("==" in line for line in body), [line for line in body if "==" not in line]
