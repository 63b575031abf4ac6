"""The artifact registry's declarations, read from the decorator lines without importing the modules.

Snakemake lists every artifact while it plans (``workflow/rules/common.smk``:
:func:`brdfs.pipeline.registry.artifacts`). Importing the ~70 artifact modules would run numpy,
scipy, pandas and matplotlib (1.96 s); parsing their module-level statements (not the bodies of
their functions: :func:`_top_level`, about 3x faster than parsing the whole modules) and evaluating
each ``@table``/``@figure``/``@check``/``@comparison`` call's arguments imports none of them. The
arguments are evaluated by :func:`_evaluate`, which knows literals, module-level constants
(``NAME = "..."``), constants of imported package modules (``dg.SECTION``, ``from m import NAME``),
``*`` inside tuples and lists, ``tuple(...)``/``list(...)``/``sorted(...)`` and
``d.values()``/``d.keys()``; anything else is a :class:`~brdfs.pipeline.registry.DeclarationError`
naming the file and line. The values go through the same constructor as the decorators'
(``registry._declare_artifact``), and ``tests/pipeline/test_registry.py`` checks that the scan
and the imported modules declare the same.
"""

from __future__ import annotations

import ast
import functools
import inspect
import re
from pathlib import Path

from brdfs.pipeline import registry



# --- the module-level statements a scan reads, without parsing the functions' bodies ---------------

# Lexemes of Python source: strings, comments and a backslash's continued line (stepped over whole:
# registry._STRINGS_AND_COMMENTS), a quote that starts no string that ends, brackets (their depth),
# and a newline followed by a line that starts in column 0 and is neither blank nor a comment: at
# depth 0, the start of a module-level statement. A form feed sets the column to 0 (Python's
# tokenizer): only spaces and tabs after the line's last form feed indent it.
_LEXEMES = re.compile(registry._STRINGS_AND_COMMENTS + r"""
  | (?P<quote>["'])
  | (?P<open>[(\[{])
  | (?P<close>[)\]}])
  | (?P<line>\n(?=(?:[ \t\f]*\f)?[^ \t\f\#\n]))
""", re.VERBOSE | re.DOTALL)
_FIRST_WORD = re.compile(r"[ \t\f]*(@|[A-Za-z_]\w*)")
#: First words of the module-level statements that bind no constant and import nothing at module
#: level: compound statements (their bodies are not the module's body) and their clauses.
_SKIPPED = {"if", "elif", "else", "for", "while", "try", "except", "finally", "with", "class", "def", "async"}


def _module_statements(source: str) -> list[tuple[int, str]]:
    """The module-level statements of ``source``: (first line, text), in order.

    Raises
    ------
    SyntaxError
        A string does not end or the brackets do not pair (what :func:`registry._unpaired
        <brdfs.pipeline.registry._unpaired>` finds for the import scan): the statements cannot be
        told apart, and the module may not parse.
    """
    starts, depth = [0], 0
    for match in _LEXEMES.finditer(source):
        if match.lastgroup == "open":
            depth += 1
        elif match.lastgroup == "close":
            depth -= 1
            if depth < 0:
                break
        elif match.lastgroup == "line" and depth == 0:
            starts.append(match.start() + 1)
        elif match.lastgroup == "quote":
            depth = -1
            break
    if depth != 0:
        raise SyntaxError("a string that does not end or brackets that do not pair")
    starts.append(len(source))
    statements, line = [], 1
    for a, b in zip(starts, starts[1:]):
        if a < b:
            statements.append((line, source[a:b]))
            line += source.count("\n", a, b)
    return statements


def _parsed(text: str, line: int) -> list[ast.stmt]:
    """The statements of ``text``, which starts on line ``line`` of its file, with the file's line numbers."""
    return ast.parse("\n" * (line - 1) + text).body


def _top_level(path: Path) -> tuple[ast.stmt, ...]:
    """What the scan reads of a module's body: every module-level statement but a compound one (their
    syntax trees, lines as in the file), and each decorated ``def`` with its decorators and an empty body.

    Parsing only these statements is about 3x faster than parsing the module (what Snakemake
    waits for while it plans); ``tests/pipeline/test_source_scan.py`` holds them equal to the module's
    syntax tree on every module of the package. A statement that does not parse alone (a split the
    scan got wrong), and a module whose strings do not end or whose brackets do not pair
    (:func:`_module_statements`), fall back to parsing the whole module: a syntax error is raised
    naming the file and line."""
    try:
        nodes, decorators = [], []
        for line, text in _module_statements(path.read_text(encoding="utf-8")):
            word = _FIRST_WORD.match(text)
            word = word.group(1) if word else ""
            if word == "@":
                decorators.append((line, text))
            elif word in ("def", "async") and decorators:
                stub = "".join(t for _, t in decorators) + ("async " if word == "async" else "") + "def _(): pass\n"
                nodes += _parsed(stub, decorators[0][0])
                decorators = []
            else:
                if word not in _SKIPPED:
                    nodes += _parsed(text, line)
                decorators = []
        return tuple(nodes)
    except SyntaxError:
        return tuple(registry._parse(path).body)


class _Scope:
    """What the module-level statements of one source file bind, for :func:`_evaluate`, and those
    statements (``nodes``: :func:`_top_level`)."""

    def __init__(self, module: str, path: Path):
        self.module, self.path = module, path
        self.values: dict[str, ast.expr] = {}  # NAME = <expression>
        self.modules: dict[str, str] = {}  # local name -> a package module (import ... as / from pkg import mod)
        self.imported: dict[str, tuple[str, str]] = {}  # local name -> (module, name) of `from module import name`
        self.nodes = _top_level(path)
        for node in self.nodes:
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                self.values[node.targets[0].id] = node.value
            elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and node.value is not None:
                self.values[node.target.id] = node.value
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if a.asname:
                        self.modules[a.asname] = a.name
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                for a in node.names:
                    full = f"{node.module}.{a.name}"
                    if registry._module_file(full) is not None:
                        self.modules[a.asname or a.name] = full
                    else:
                        self.imported[a.asname or a.name] = (node.module, a.name)

    def error(self, node: ast.AST, why: str) -> registry.DeclarationError:
        return registry.DeclarationError(
            f"{self.path}:{getattr(node, 'lineno', '?')}: {why}: {ast.unparse(node)!r} (the registry reads "
            "decorator arguments without importing the module: use literals, module constants or constants "
            "of imported package modules)")


@functools.lru_cache(maxsize=None)
def _scope(module: str) -> _Scope:
    path = registry._module_file(module)
    if path is None:
        raise registry.DeclarationError(f"{module}: not a module of the package")
    return _Scope(module, path)


_CALLS = {"tuple": tuple, "list": list, "sorted": sorted}
_METHODS = {"values": dict.values, "keys": dict.keys}


def _evaluate(node: ast.expr, scope: _Scope, depth: int = 0):
    """The value of a decorator argument: literals, names bound to them, ``tuple(...)``, ``d.values()``."""
    if depth > 50:
        raise scope.error(node, "constants refer to each other in a loop")
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, (ast.Tuple, ast.List)):
        items = []
        for element in node.elts:
            if isinstance(element, ast.Starred):
                items.extend(_evaluate(element.value, scope, depth + 1))
            else:
                items.append(_evaluate(element, scope, depth + 1))
        return tuple(items) if isinstance(node, ast.Tuple) else items
    if isinstance(node, ast.Dict) and None not in node.keys:
        return {_evaluate(k, scope, depth + 1): _evaluate(v, scope, depth + 1) for k, v in zip(node.keys, node.values)}
    if isinstance(node, ast.Name):
        return _constant(node.id, scope, node, depth)
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in scope.modules:
        return _constant(node.attr, _scope(scope.modules[node.value.id]), node, depth)
    if isinstance(node, ast.Call) and not node.keywords:
        func = node.func
        if isinstance(func, ast.Name) and func.id in _CALLS and len(node.args) == 1 and func.id not in scope.values:
            return _CALLS[func.id](_evaluate(node.args[0], scope, depth + 1))
        if isinstance(func, ast.Attribute) and func.attr in _METHODS and not node.args:
            value = _evaluate(func.value, scope, depth + 1)
            if isinstance(value, dict):
                return list(_METHODS[func.attr](value))
    raise scope.error(node, "cannot read")


def _constant(name: str, scope: _Scope, node: ast.AST, depth: int):
    if name in scope.values:
        return _evaluate(scope.values[name], scope, depth + 1)
    if name in scope.imported:
        module, original = scope.imported[name]
        return _constant(original, _scope(module), node, depth + 1)
    if name in scope.modules:
        raise scope.error(node, f"{name} is a module, not a constant")
    raise scope.error(node, f"{name} is not a module-level constant")


def _declarations_in(module: str) -> list[registry.Artifact | registry.Comparison]:
    """The declarations of one artifact module, read from its decorator lines."""
    scope = _scope(module)
    registry_names = {local: name for local, (mod, name) in scope.imported.items() if mod == registry.__name__}
    registry_aliases = {local for local, mod in scope.modules.items() if mod == registry.__name__}
    found = []
    for node in scope.nodes:
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for decorator in node.decorator_list:
            if not isinstance(decorator, ast.Call):
                continue
            func = decorator.func
            if isinstance(func, ast.Name) and func.id in registry_names:
                kind = registry_names[func.id]
            elif isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) \
                    and func.value.id in registry_aliases:
                kind = func.attr
            else:
                continue
            if kind not in registry._DECORATORS:
                continue
            args = [_evaluate(a, scope) for a in decorator.args]
            kwargs = {k.arg: _evaluate(k.value, scope) for k in decorator.keywords if k.arg is not None}
            if len(kwargs) != len(decorator.keywords):
                raise scope.error(decorator, "**kwargs in a decorator")
            try:
                bound = inspect.signature(registry._DECORATORS[kind]).bind(*args, **kwargs)
            except TypeError as exc:
                raise scope.error(decorator, str(exc)) from exc
            bound.apply_defaults()
            if kind == "comparison":
                found.append(registry._declare_comparison(module, **bound.arguments))
            else:
                found.append(registry._declare_artifact(kind, module, **bound.arguments))
    return found


@functools.lru_cache(maxsize=None)
def package_declarations() -> tuple[dict[str, registry.Artifact], dict[str, registry.Comparison]]:
    """Every declaration of ``src/brdfs/artifacts/<name>.py`` (``_*.py`` are helpers), read statically."""
    found_artifacts: dict[str, registry.Artifact] = {}
    found_comparisons: dict[str, registry.Comparison] = {}
    for path in sorted(registry._ARTIFACTS_DIR.glob("*.py")):
        if path.name.startswith("_"):
            continue
        for entry in _declarations_in(f"brdfs.artifacts.{path.stem}"):
            if isinstance(entry, registry.Artifact):
                registry._register(found_artifacts, entry.name, entry)
            else:
                registry._register(found_comparisons, entry.artifact, entry)
    return found_artifacts, found_comparisons
