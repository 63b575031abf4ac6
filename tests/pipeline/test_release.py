"""A release that can be cited: the version is written once (``brdfs.__version__``) and the citation,
the changelog and the wheel's metadata (pyproject's dynamic version and long description) carry it
with its release date."""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

import yaml

import brdfs

ROOT = Path(__file__).resolve().parents[2]


def _newest_changelog_entry():
    match = re.search(r"^## (\S+) — (\d{4}-\d{2}-\d{2})$", (ROOT / "CHANGELOG.md").read_text(), re.MULTILINE)
    assert match, "CHANGELOG.md: no entry '## VERSION — YYYY-MM-DD'"
    return match.group(1), match.group(2)


def test_the_citation_and_the_changelog_carry_the_packages_version_and_release_date():
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert re.fullmatch(r"\d+\.\d+\.\d+", brdfs.__version__)
    assert str(citation["version"]) == brdfs.__version__
    assert str(citation["date-released"]) == brdfs.__release_date__
    assert _newest_changelog_entry() == (brdfs.__version__, brdfs.__release_date__)


def test_the_wheels_version_and_description_come_from_the_package_and_the_changelog():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "version" not in project["project"] and {"version", "readme"} <= set(project["project"]["dynamic"])
    dynamic = project["tool"]["setuptools"]["dynamic"]
    assert dynamic["version"] == {"attr": "brdfs.__version__"}
    assert "CHANGELOG.md" in dynamic["readme"]["file"]
