"""The workflow plans from scans of the package's source that parse only what they need: the import
statements (an artifact's code inputs, ``registry._imports_of``) and the module-level statements
(the decorator declarations, ``declarations._top_level``). Each must read what the module's full
syntax tree holds, on every module of the package, and on source written to mislead a scan."""

import ast
import sys
import textwrap
from pathlib import Path

import pytest

from brdfs.pipeline import declarations, registry

PACKAGE = Path(registry.__file__).resolve().parents[1]
MODULES = sorted(PACKAGE.rglob("*.py"))


def _names_of_tree(source: str) -> set[str]:
    return registry._imported_names(registry._statements(ast.parse(source).body))


def _names_of_scan(source: str, package: str = "brdfs") -> set[str]:
    statements, _ = registry._import_statements(source, package)
    return registry._imported_names(registry._statements(ast.parse(statements).body))


def _in_package(names):
    return {n for n in names if n == "brdfs" or n.startswith("brdfs.")}


@pytest.fixture(scope="module")
def trees():
    """Every module of the package: its path, source and syntax tree."""
    return [(path, source, ast.parse(source)) for path in MODULES for source in [path.read_text(encoding="utf-8")]]


def test_the_import_scan_reads_every_import_the_syntax_tree_holds_in_every_package_module(trees):
    assert len(trees) > 100
    for path, source, tree in trees:
        imported = registry._imported_names(registry._statements(tree.body))
        assert _names_of_scan(source, package="") == imported, path  # every import statement
        assert _in_package(registry._imported_names_of(path)) == _in_package(imported), path
        assert not registry._import_statements(source)[1], path  # scanned, not parsed whole
        declarations._module_statements(source)  # raises where the module would be parsed whole


# Imports a scan for "import" at a line's start would miss, and text that is no import.
MISLEADING = r'''"""A docstring that shows code:

from brdfs.physics import fresnel
    import brdfs.numerics.albedo
"""
import os, brdfs.core.estimate as est
from brdfs.pipeline import (io,  # a comment with "quotes" and from brdfs.render import x
    registry)
x = 'it''s'; import brdfs.physics.lobes
s = "\" from brdfs.numerics import grazing"
if True: from brdfs.physics import geometry
from brdfs.physics \
    import sampling
if True: \
    import brdfs.physics.fresnel
y = 1; \
    import brdfs.numerics.quadrature
y = 2
\
import brdfs.render.scene
try:
    pass
except ImportError: \
  \
    from brdfs.physics import distributions


def f():
    r"""raw: \\""" + '#'
    try:
        import brdfs.numerics.pumping
    except ImportError:
        raise ValueError("no") from None
    yield from range(3)  # from brdfs.render import mitsuba
    t = f"""{1}
from brdfs.render import spectrum"""


class C:
    from brdfs.physics.models import phong
# import brdfs.render.mitsuba (it's a comment)
    # from brdfs.render import spectrum
'''


def test_the_import_scan_skips_strings_and_comments_and_finds_imports_after_colons_semicolons_and_continuations():
    assert _names_of_scan(MISLEADING, package="") == _names_of_tree(MISLEADING)
    assert _in_package(_names_of_tree(MISLEADING)) == {
        "brdfs.core.estimate", "brdfs.pipeline", "brdfs.pipeline.io", "brdfs.pipeline.registry",
        "brdfs.physics.lobes", "brdfs.physics", "brdfs.physics.geometry", "brdfs.physics.sampling",
        "brdfs.numerics.pumping", "brdfs.physics.models", "brdfs.physics.models.phong",
        "brdfs.physics.fresnel", "brdfs.numerics.quadrature", "brdfs.render.scene", "brdfs.physics.distributions"}


def test_an_import_the_scan_cuts_short_falls_back_to_the_modules_syntax_tree(tmp_path):
    path = tmp_path / "toy.py"
    path.write_text("from brdfs.physics import (fresnel,  # see f(x)\n    lobes)\n")
    with pytest.raises(SyntaxError):  # the statement's text ends at the comment's ")"
        ast.parse(registry._import_statements(path.read_text())[0])
    assert registry._imported_names_of(path) == {"brdfs.physics", "brdfs.physics.fresnel", "brdfs.physics.lobes"}


def _read(nodes):
    """What the declarations' scan uses of a module's body: module-level assignments and imports, and
    the decorators of functions (with their line numbers)."""
    out = []
    for node in nodes:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.decorator_list:
            out.append([ast.dump(d, include_attributes=True) for d in node.decorator_list])
        elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.Import, ast.ImportFrom)):
            out.append(ast.dump(node, include_attributes=True))
    return out


def test_the_module_level_scan_reads_what_the_syntax_tree_holds_in_every_package_module(trees):
    for path, _, tree in trees:
        assert _read(declarations._top_level(path)) == _read(tree.body), path


TOP_LEVEL = '''\
#!/usr/bin/env python
"""Docstring with a line that looks like a statement:
NOT_A_CONSTANT = 1
"""
import brdfs.pipeline.registry as reg
from brdfs.pipeline.registry import figure, table
A = 1; B = (2,
3)
pass; C = "x"
D: tuple = ("y", """
E = 4
""")
F = 1 + \\
2
try:
    G = 5
except ImportError:
    G = 6
else:
    H = 7
match = [1]
SECTIONS = dict(
a=1,
b=2)


@table("extra_toy", deps=(A,
 "b"),
       config=SECTIONS)  # a comment
def compute(cfg, deps):
    I = 8  # a local, not a constant
    return I


@reg.figure("fig_9_9_toy",
)
async def other(cfg, deps):
    pass


@staticmethod
class K:
    L = 9
'''


def test_the_module_level_scan_follows_strings_brackets_continuations_and_decorators(tmp_path):
    path = tmp_path / "toy.py"
    path.write_text(TOP_LEVEL)
    nodes = declarations._top_level(path)
    assert _read(nodes) == _read(ast.parse(TOP_LEVEL).body)
    assigned = [t.id for n in nodes if isinstance(n, ast.Assign) for t in n.targets]
    assert assigned == ["A", "B", "C", "F", "match", "SECTIONS"]  # D is annotated; G, H in a try
    assert not any(isinstance(n, ast.ClassDef) for n in nodes)


def test_a_statement_the_module_level_scan_splits_wrongly_falls_back_to_the_whole_syntax_tree(tmp_path, monkeypatch):
    path = tmp_path / "toy.py"
    text = "X = f(\na=1,\nb=2)\n"  # a bracket's lines at column 0: one statement
    path.write_text(text)
    assert [s for _, s in declarations._module_statements(text)] == [text]
    path.write_text("X = (\n\"\"\"\n)\n")  # a string that never ends: not Python at all
    with pytest.raises(SyntaxError):
        declarations._top_level(path)
    path.write_text(text)
    lines = [(k + 1, line) for k, line in enumerate(text.splitlines(keepends=True))]
    monkeypatch.setattr(declarations, "_module_statements", lambda source: lines)  # as if the depth were lost
    assert _read(declarations._top_level(path)) == _read(ast.parse(text).body)  # "a=1," alone would be a tuple


# Module-level statements after a form feed (which sets the column to 0) and after a string and ";".
AFTER_FORM_FEEDS_AND_STRINGS = [
    "def helper():\n    pass\n\f@table('x')\ndef compute(cfg, deps):\n    pass\n",
    '"""Doc."""\n\fX = 1\n',
    "class C:\n    pass\n\fX = 1\n",
    "def f():\n    pass\n  \fX = 1\n",
    "def f():\n    x = 1\n\f\n\f    y = 2\nX = 1\n",
    '"""Doc."""; X = 1\n',
    "'x'; X = 1\n",
]


@pytest.mark.parametrize("source", AFTER_FORM_FEEDS_AND_STRINGS)
def test_the_module_level_scan_reads_statements_after_form_feeds_and_strings(tmp_path, source):
    path = tmp_path / "toy.py"
    path.write_text(source)
    read = _read(declarations._top_level(path))
    assert read == _read(ast.parse(source).body)
    assert read  # the constant or the decorator is there


BROKEN = [("from brdfs.physics import fresnel\n\ndef f():\n    return (1,\n", 4),
          ("import brdfs.physics\n\ndef f():\n    return [1, 2)]\n", 4),
          ("def f():\n    return 'no end\n\nX = 1\n", 2)]


@pytest.mark.parametrize(("source", "line"), BROKEN)
def test_a_module_whose_brackets_do_not_pair_or_string_does_not_end_fails_the_scans_naming_file_and_line(
        tmp_path, source, line):
    path = tmp_path / "toy.py"
    path.write_text(source)
    for scan in (registry._imported_names_of, declarations._top_level):
        with pytest.raises(SyntaxError) as error:
            scan(path)
        assert (error.value.filename, error.value.lineno) == (str(path), line), scan


@pytest.mark.skipif(sys.version_info < (3, 12), reason="a quote inside a same-quote f-string is PEP 701's")
def test_a_module_that_misleads_the_bracket_count_is_read_from_its_syntax_tree(tmp_path):
    source = 'def helper():\n    return f"{"("}"\n\n\n@table("x")\ndef compute(cfg, deps):\n    pass\n'
    path = tmp_path / "toy.py"
    path.write_text(source)
    assert _read(declarations._top_level(path)) == _read(ast.parse(source).body) != []


def test_the_modules_a_package_imports_by_name_are_code_inputs_of_the_artifacts_that_import_it():
    """The model modules (imported by ``physics.models`` from its directory) and the Mitsuba plugin
    modules (imported by ``plugins`` from ``PLUGIN_MODULES``) are read by no import statement the
    scan can see but the provenance imports of their packages: a changed model or plugin must rerun the
    artifacts that use it (before, an edited ``plugins/patch.py`` left Figs. 4.9, 4.16, 4.17 as they were)."""
    import pkgutil

    import brdfs.physics.models as models
    from brdfs.pipeline.registry import artifacts
    from brdfs.render.mitsuba.plugins import PLUGIN_MODULES

    sources = {name: set(artifact.sources) for name, artifact in artifacts().items()}
    model_files = {f"src/brdfs/physics/models/{m.name}.py" for m in pkgutil.iter_modules(models.__path__)}
    plugin_files = {f"src/brdfs/render/mitsuba/plugins/{name}.py" for name in (*PLUGIN_MODULES, "_common")}
    assert model_files <= sources["fig_2_1_albedo_classical"], model_files - sources["fig_2_1_albedo_classical"]
    for render in ("fig_4_16_patch_metals", "fig_3_8_material_spheres", "fig_4_18_generalized_lambert"):
        assert plugin_files | model_files <= sources[render], (plugin_files | model_files) - sources[render]
