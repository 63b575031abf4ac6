"""A model says everything about itself: no code outside ``physics/models/`` switches on a model's
name, sniffs a model's parameters with ``hasattr`` or tells models apart by their module.

The scan parses every file of ``src/brdfs`` (``ast``, so strings in docstrings and comments do not
count) and looks for

* comparisons (``==``, ``!=``, ``in``, ``not in``) of a registered model's name with a variable or
  with an object's ``.name`` (a model told apart by its name); selecting rows of a tidy table by its
  ``model`` column (``df["model"] == "blinn"``, ``row.model == "ward"``) is data, not a model fact,
* ``hasattr(x, "p")`` or ``getattr(x, "p", ...)`` where ``p`` is a parameter of a registered model,
* ``type(x).__module__`` (or any ``.__module__`` of a ``type(...)`` call).
"""
from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

from brdfs.physics.models import MODELS

SRC = Path(__file__).resolve().parents[1] / "src" / "brdfs"
MODELS_DIR = SRC / "physics" / "models"


def _model_names():
    return set(MODELS)


def _parameter_names():
    return {f.name for cls in MODELS.values() for f in dataclasses.fields(cls)}


def _strings(node):
    """String constants of a node that is a string or a tuple/list/set of strings."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return [s for elt in node.elts for s in _strings(elt)]
    return []


def _is_name_holder(node):
    """A variable, or an object's ``.name`` (also as ``getattr(x, "name", ...)``): what a model's name
    is held in when code switches on it."""
    if isinstance(node, ast.Name) or (isinstance(node, ast.Attribute) and node.attr == "name"):
        return True
    return (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "getattr"
            and len(node.args) >= 2 and _strings(node.args[1]) == ["name"])


def findings(tree, names, params):
    """(line, what) of every model-name comparison, parameter sniff and module test in ``tree``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            sides = [node.left, *node.comparators]
            if any(_is_name_holder(side) for side in sides):
                hits = [s for side in sides for s in _strings(side) if s in names]
                if hits:
                    out.append((node.lineno, f"compares with model name(s) {hits}"))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("hasattr", "getattr"):
            if len(node.args) >= 2:
                hits = [s for s in _strings(node.args[1]) if s in params]
                if hits and (node.func.id == "hasattr" or len(node.args) == 3):
                    out.append((node.lineno, f"{node.func.id} on model parameter {hits}"))
        elif isinstance(node, ast.Attribute) and node.attr == "__module__":
            if isinstance(node.value, ast.Call) and isinstance(node.value.func, ast.Name) and node.value.func.id == "type":
                out.append((node.lineno, "type(...).__module__"))
    return out


def _sources():
    return sorted(p for p in SRC.rglob("*.py") if MODELS_DIR not in p.parents)


@pytest.mark.parametrize("path", _sources(), ids=lambda p: str(p.relative_to(SRC)))
def test_no_module_outside_the_models_switches_on_a_models_name_or_parameters(path):
    found = findings(ast.parse(path.read_text(), str(path)), _model_names(), _parameter_names())
    assert not found, "\n".join(f"{path.relative_to(SRC)}:{line}: {what}" for line, what in found)


@pytest.mark.parametrize("snippet, expected", [
    ('if m.name == "patch_basic": pass', "compares with model name(s) ['patch_basic']"),
    ('ok = name in ("phong", "blinn")', "compares with model name(s) ['phong', 'blinn']"),
    ('ok = getattr(m, "name", "") != "ward"', "compares with model name(s) ['ward']"),
    ('ok = hasattr(model, "ratio")', "hasattr on model parameter ['ratio']"),
    ('g = getattr(model, "G", None)', "getattr on model parameter ['G']"),
    ('k = type(model).__module__', "type(...).__module__"),
])
def test_the_scan_finds_each_kind_of_fact_kept_outside_its_model(snippet, expected):
    found = findings(ast.parse(snippet), _model_names(), _parameter_names())
    assert [what for _, what in found] == [expected]


def test_the_scan_leaves_building_a_model_by_name_and_selecting_table_rows_alone():
    code = 'f = model("phong", n=20)\nx = getattr(obj, "n")\nrows = df[df["model"] == "blinn"]'
    assert findings(ast.parse(code), _model_names(), _parameter_names()) == []
