"""Layers in one direction: the physics layer imports nothing of the layers above it (numerics, render,
pipeline, artifacts), not even inside a function, and models that need tables receive them from above.

The static scan parses every file under ``src/brdfs/physics/`` (``ast``: every ``import`` and
``from … import`` statement wherever it stands, module level, function or class body, ``try`` or ``if``;
relative imports resolved against the file's package), so a deferred import cannot hide a cycle.
"""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PHYSICS = SRC / "brdfs" / "physics"
UPPER = ("brdfs.numerics", "brdfs.render", "brdfs.pipeline", "brdfs.artifacts")


def _package_of(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts if path.name == "__init__.py" else parts[:-1]).removesuffix(".__init__")


def imported_modules(tree: ast.AST, package: str) -> list[tuple[int, str]]:
    """(line, module) of every import in ``tree``, at any depth; ``from x import y`` yields ``x.y`` too
    (``from brdfs import numerics``), relative imports resolved against ``package``."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*parent, base] if base else parent)
            found.append((node.lineno, base))
            found += [(node.lineno, f"{base}.{alias.name}") for alias in node.names]
    return found


def upper_layer_imports(source: str, package: str) -> list[tuple[int, str]]:
    return [(line, mod) for line, mod in imported_modules(ast.parse(source), package)
            if any(mod == up or mod.startswith(up + ".") for up in UPPER)]


def _physics_files():
    return sorted(PHYSICS.rglob("*.py"))


def test_the_scan_sees_every_physics_module():
    names = {p.relative_to(PHYSICS).as_posix() for p in _physics_files()}
    assert {"models/base.py", "models/smith_microfacet.py", "models/pumped.py", "tables.py"} <= names


@pytest.mark.parametrize("path", _physics_files(), ids=lambda p: p.relative_to(PHYSICS).as_posix())
def test_no_physics_module_imports_an_upper_layer_even_inside_a_function(path):
    found = upper_layer_imports(path.read_text(), _package_of(path))
    assert not found, "\n".join(f"{path.relative_to(SRC)}:{line}: imports {mod}" for line, mod in found)


@pytest.mark.parametrize("snippet", [
    "from brdfs.numerics.pumping import tabulate_albedo",
    "def f():\n    from brdfs.numerics.pumping import AlbedoTable\n    return AlbedoTable",
    "class A:\n    def g(self):\n        import brdfs.render.tracer",
    "try:\n    from brdfs import pipeline\nexcept ImportError:\n    pass",
    "from ...artifacts import _microfacet_energy",
])
def test_the_scan_finds_deferred_aliased_and_relative_imports_of_an_upper_layer(snippet):
    assert upper_layer_imports(snippet, "brdfs.physics.models")


def test_the_scan_leaves_the_physics_and_core_layers_alone():
    code = "from brdfs.core.estimate import Estimate\nfrom . import base\nfrom ..tables import AlbedoTable\nimport numpy"
    assert upper_layer_imports(code, "brdfs.physics.models") == []


def test_importing_the_physics_layer_loads_no_module_of_an_upper_layer_nor_pandas():
    code = ("import brdfs.physics.models, brdfs.physics.tables, sys; "
            "print(sorted(m for m in sys.modules if m.startswith(('brdfs.', 'pandas'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    loaded = eval(out)     # noqa: S307 - our own printed list
    assert not [m for m in loaded if m.startswith((*UPPER, "pandas"))], loaded
