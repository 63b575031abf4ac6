"""Registry of the thesis's tables and figures and of their comparisons with the print.

An artifact module (one per table or figure, in :mod:`brdfs.artifacts`) declares::

    @table("table_1_2_metal_reflectance", deps=(), config=("metal_reflectance",))
    def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame: ...

    def plot(df: pd.DataFrame, path) -> None: ...   # the PNG of the artifact

    @comparison("metal_a0", tables=("table_1_2_metal_reflectance",))
    def rows(cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame: ...

``@figure`` is ``@table`` for ``results/figures``. ``deps``/``tables`` name the
artifacts whose tidy DataFrames the function receives (read from their CSVs, so
that in the pipeline and in-process they are the same numbers); ``config`` names
the config.yaml sections the function reads: ``cfg`` holds exactly those plus
``seed`` and ``tolerance``, so that the pipeline reruns an artifact when, and
only when, a section it reads changes. ``chapter`` is the thesis chapter the HTML
report files it under (default: the number in a ``fig_N_M``/``table_N_M`` name;
``extra_*`` and checks declare it, None for numerics and extensions beyond the
thesis). ``resources`` are its rule's threads, memory and run time. Every artifact
is one job, in every mode (``make all``, plain ``snakemake``, a single target). A
comparison's rows go through :func:`brdfs.pipeline.published.make_fragment`.

The registry knows what only it can know: which artifacts exist, their config
sections, dependencies, resources and chapters, and the package source
files each module imports (so that an edit reruns exactly the artifacts it
affects). Scheduling is Snakemake's; the registry's one dependency resolution
(:func:`dependency_order`, the only place a cycle is detected) serves in-process
runs (:func:`compute_tables`, the regression baseline).

The declarations are read in two ways that agree (``tests/pipeline/test_registry.py``):

- :func:`artifacts` and :func:`comparisons` read the decorator lines of
  ``src/brdfs/artifacts/*.py`` without importing the modules
  (:mod:`brdfs.pipeline.declarations`), so that Snakemake lists every artifact while
  it plans without the 1.96 s of importing them with numpy, scipy, pandas and
  matplotlib. A decorator argument is therefore a literal, a module-level
  constant or a constant of an imported package module (or ``tuple``/``d.values()``
  of those); anything else is a :class:`DeclarationError` naming the file and line.
- Importing a module runs its decorators, which register the functions;
  :meth:`Artifact.compute` and :meth:`Comparison.fragment` import their module on
  first use. Decorators run outside the package (a test's toy artifact) register
  artifacts the scan cannot see.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import importlib
import inspect
import re
import tempfile
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from brdfs.pipeline import io

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made, not when the workflow plans
    import pandas as pd

_PACKAGE_ROOT = Path(__file__).resolve().parents[1]
_ARTIFACTS_DIR = _PACKAGE_ROOT / "artifacts"

ComputeFn = Callable[[dict, dict], "pd.DataFrame"]

#: Resources of an artifact's rule unless its decorator says otherwise (runtime in minutes).
DEFAULT_RESOURCES = {"threads": 1, "mem_mb": 2000, "runtime": 10}

#: Sections every artifact receives.
COMMON_SECTIONS = ("seed", "tolerance")
_DIRECTORIES = {"table": "results/tables", "figure": "results/figures", "check": "results/checks"}
_NAME_PATTERNS = {
    "table": re.compile(r"(table_\d+_\d+|extra)_[a-z0-9_]+"),
    "figure": re.compile(r"(fig_\d+_\d+|extra)_[a-z0-9_]+"),
    "check": re.compile(r"[a-z0-9_]+"),
    "comparison": re.compile(r"[a-z0-9_]+"),
}
_NUMBERED = re.compile(r"(?:fig|table)_(\d+)_\d+_")

#: An artifact that reads this config section renders: beside its CSV and PNG it writes each panel's
#: linear radiance as OpenEXR into ``results/renders/<name>/`` (:attr:`Artifact.renders`), by
#: :data:`RENDERS_WRITER`'s ``write_renders(df, directory)``.
RENDERS_SECTION = "renders"
RENDERS_DIRECTORY = "results/renders"
RENDERS_WRITER = "brdfs.artifacts._render_figures"

#: Default of ``chapter=``: derived from the artifact's name.
AUTO = "auto"

# --- where the workflow writes (workflow/rules/*.smk take every path from here) ---------------------

#: The thesis's printed values, and the comparison of every published artifact with them (rules check
#: and merge_comparison), with its HTML page and the count of verdicts.
PUBLISHED = "data/published_values.csv"
COMPARISON = "results/checks/published_comparison.csv"
COMPARISON_HTML = "results/checks/published_comparison.html"
VERDICT_COUNTS_CSV = "results/checks/published_verdicts.csv"
VERDICT_COUNTS_PNG = "results/checks/published_verdicts.png"
#: The report's reading aids (rule report_pages): the landing table and each table artifact as HTML.
REPORT_LANDING = "results/report/landing.html"
REPORT_LANDING_CSV = "results/report/landing.csv"
REPORT_CHAPTERS_CSV = "results/report/chapters.csv"
REPORT_TABLE = "results/report/tables/{name}.html"
#: The steps of the workflow that are not artifacts, by the name of their log and timings.
STEPS = ("checks/comparisons", "merge_comparison", "report_pages")
#: The directories under results/ that only the workflow's rules write into: a file in them that no rule
#: writes (an artifact, a rule or a batch that no longer exists) is stale (:func:`stale_results`).
WORKFLOW_DIRECTORIES = ("results/tables", "results/figures", "results/checks", "results/renders", "results/report",
                        "results/logs", "results/benchmarks/rules")


def log_of(step: str) -> str:
    """The log of a job: ``step`` is ``<kind directory>/<name>`` for an artifact, else one of :data:`STEPS`."""
    return f"results/logs/{step}.log"


def benchmark_of(step: str) -> str:
    """The timings Snakemake records of a job (``benchmark:``), as :func:`log_of`."""
    return f"results/benchmarks/rules/{step}.tsv"


class DeclarationError(ValueError):
    """A decorator line the registry cannot read without importing its module, or a bad declaration."""


def _canonical(value):
    """``value`` with every mapping's keys sorted, recursively (lists keep their order)."""
    if isinstance(value, dict):
        return {key: _canonical(value[key]) for key in sorted(value, key=repr)}
    if isinstance(value, list):
        return [_canonical(v) for v in value]
    return value


class ConfigSubset(dict):
    """The config sections of a rule's ``params``: a dict in the file's key order (what an artifact
    iterates), whose ``repr`` sorts the keys of every mapping in it. Snakemake records and compares
    a rule's params by their ``repr`` (``snakemake.persistence``), so the same configuration written
    in another key order plans no job; the job's script unpickles this class with the order intact."""

    def __repr__(self) -> str:
        return repr(_canonical(dict(self)))

    __str__ = __repr__


def config_subset(cfg: dict, sections: Iterable[str]) -> ConfigSubset:
    """The sections of ``cfg`` an artifact reads, plus :data:`COMMON_SECTIONS`, in a
    :class:`ConfigSubset` (its repr does not depend on the order of keys).

    Raises
    ------
    KeyError
        If a section is missing from ``cfg``.
    """
    wanted = dict.fromkeys((*COMMON_SECTIONS, *sections))
    missing = [s for s in wanted if s not in cfg]
    if missing:
        raise KeyError(f"config.yaml lacks the sections {missing}")
    return ConfigSubset((s, cfg[s]) for s in wanted)


def config_digest(cfg: dict, sections: Iterable[str]) -> str:
    """A rule's config param: the names of its sections and a digest of their canonical form.

    ``'seed,tolerance,ward_cmax@<16 hex digits>'``: the SHA-256 of the :class:`ConfigSubset`'s
    repr, which sorts the keys of every mapping. Snakemake reruns a rule whose params changed
    (their repr is recorded), so a changed value reruns it and a reordered key does not, while the
    report shows one short line instead of the sections themselves. The job reads the sections
    from the workflow's config (``Artifact.compute`` and ``Comparison.fragment`` select them).

    >>> a = config_digest({"seed": 1, "tolerance": {"rtol": 1e-10, "atol": 0.0}}, ())
    >>> a == config_digest({"tolerance": {"atol": 0.0, "rtol": 1e-10}, "seed": 1}, ())
    True
    >>> a == config_digest({"seed": 2, "tolerance": {"rtol": 1e-10, "atol": 0.0}}, ())
    False
    >>> a.split("@")[0]
    'seed,tolerance'
    """
    import hashlib

    subset = config_subset(cfg, sections)
    digest = hashlib.sha256(repr(subset).encode("utf-8")).hexdigest()[:16]
    return f"{','.join(subset)}@{digest}"


# --- the source files an artifact depends on ------------------------------------------------------


@functools.lru_cache(maxsize=None)
def _module_file(module: str) -> Path | None:
    """The source file of a ``brdfs`` module (an absolute, resolved path), or None outside the package."""
    if module != "brdfs" and not module.startswith("brdfs."):
        return None
    base = _PACKAGE_ROOT.joinpath(*module.split(".")[1:])
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


@functools.lru_cache(maxsize=None)
def _parse(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def _statements(nodes: Iterable[ast.AST]) -> Iterable[ast.AST]:
    """Every statement of ``nodes`` and of the blocks inside them (functions, classes, if, try, ...)."""
    for node in nodes:
        yield node
        for block in ("body", "orelse", "finalbody", "handlers", "cases"):
            yield from _statements(getattr(node, block, None) or ())


def _imported_names(statements: Iterable[ast.AST]) -> set[str]:
    """The absolute module names the import statements among ``statements`` run or bind
    (``from m import a`` gives ``m`` and ``m.a``: ``a`` may be a submodule)."""
    names: set[str] = set()
    for node in statements:
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.update((node.module, *(f"{node.module}.{a.name}" for a in node.names)))
    return names


#: Python's string literals and comments, and a backslash that continues a line: the text a scan of
#: source must step over whole (here and in :mod:`brdfs.pipeline.declarations`), so that nothing inside
#: a string or a comment counts, and a continued line is no new line. A regular expression's
#: alternatives (re.VERBOSE, re.DOTALL), to be followed by the scan's own.
_STRINGS_AND_COMMENTS = r"""
    "{3}[^"\\]*(?:(?:\\.|"(?!""))[^"\\]*)*"{3}
  | '{3}[^'\\]*(?:(?:\\.|'(?!''))[^'\\]*)*'{3}
  | "[^"\\\n]*(?:\\.[^"\\\n]*)*"
  | '[^'\\\n]*(?:\\.[^'\\\n]*)*'
  | \#[^\n]*
  | \\\n"""
# An import statement's keyword where a statement starts (a line's first word, or after ``;`` or the
# ``:`` of ``if x: import y``, also on a line a backslash continues), outside strings and comments: a
# docstring's ``from brdfs import model`` is no import. ``raise E from e`` and ``yield from`` are no
# statement's start. The text before the source is a newline (``_import_statements`` prepends it).
_IMPORT_SCAN = re.compile(_STRINGS_AND_COMMENTS + r"""
  | [\n;:][ \t\f]*(?:\\\n[ \t\f]*)*(?P<statement>(?:from|import)\b)
""", re.VERBOSE | re.DOTALL)
# The rest of an import statement: its line (and backslash continuations), or through the ``)`` of
# ``from m import (a, b)``.
_IMPORT_REST = re.compile(r"(?:[^\n\\(]|\\\n)*(?:\([^)]*\)[^\n]*)?")


def _import_statements(source: str, package: str = "brdfs") -> tuple[str, bool]:
    """The text of every import statement of ``source`` that names ``package``, one after another,
    as Python source (at most a few lines of each: what follows a ``;`` on its line comes along), and
    whether the rest, strings and comments taken out, has a quote or brackets that do not pair
    (:func:`_unpaired`)."""
    source = "\n" + source
    found, code, end = [], [], 0
    for match in _IMPORT_SCAN.finditer(source):
        code.append(source[end:match.start()])
        end = match.end()
        start = match.start("statement")
        if start >= 0:
            statement = source[start:_IMPORT_REST.match(source, match.end()).end()]
            if package in statement:
                found.append(statement)
    code.append(source[end:])
    return "\n".join(found), _unpaired("".join(code))


def _unpaired(code: str) -> bool:
    """Whether ``code`` (source with its strings and comments taken out) has a quote, the start of a
    string that does not end, or brackets that do not pair: a module that does not parse, or text
    that misleads a scan of it (a scan then parses the whole module: a syntax error fails the
    workflow's planning, naming the file and line, as importing the module would; one that keeps
    them paired, ``x = = 1`` in a function's body, is found when a job imports the module)."""
    return '"' in code or "'" in code or any(code.count(a) != code.count(b) for a, b in ("()", "[]", "{}"))


def _imported_names_of(path: Path) -> set[str]:
    """The absolute package modules ``path`` imports: the names :func:`_imported_names` reads from the
    module's syntax tree, from the syntax tree of its import statements alone (found by
    :func:`_import_statements`, about 8x faster than parsing the module while the workflow plans;
    ``tests/pipeline/test_source_scan.py`` holds the two equal on every module of the package). A
    statement the scan cuts short (a ``)`` in a comment inside its parentheses) fails to parse, and
    then the whole module is parsed, as is a module whose strings or brackets are :func:`_unpaired`."""
    statements, suspect = _import_statements(path.read_text(encoding="utf-8"))
    if not suspect:
        try:
            return _imported_names(_statements(ast.parse(statements).body))
        except SyntaxError:
            pass
    return _imported_names(_statements(_parse(path).body))


@functools.lru_cache(maxsize=None)
def _imports_of(path: Path) -> frozenset[Path]:
    """The package source files ``path`` imports directly (absolute ``brdfs`` imports, also inside functions)."""
    found = set()
    for name in _imported_names_of(path):
        parts = name.split(".")
        # ``import brdfs.a.b`` also runs brdfs/__init__ and brdfs/a/__init__.
        for k in range(1, len(parts) + 1):
            file = _module_file(".".join(parts[:k]))
            if file is not None:
                found.add(file)
    return frozenset(found)


def _sources_of(path: Path) -> list[str]:
    """The source files a module's results can depend on, relative to the repository root.

    The module and, transitively, every package module it imports, read from the import
    statements, so that an edit reruns exactly the artifacts it affects.
    """
    todo = [path.resolve()]
    seen: set[Path] = set()
    while todo:
        path = todo.pop()
        if path not in seen:
            seen.add(path)
            todo.extend(_imports_of(path) - seen)
    return sorted(_relative(p) for p in seen)


@functools.lru_cache(maxsize=None)
def _relative(path: Path) -> str:
    """``path`` (absolute) relative to the repository root, as the rules name their inputs."""
    return path.relative_to(io.REPO_ROOT).as_posix()


# --- declarations ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Artifact:
    """A registered table, figure or check.

    Attributes
    ----------
    name : str
        The file stem, e.g. ``table_1_2_metal_reflectance``.
    kind : str
        ``'table'``, ``'figure'`` or ``'check'``.
    module : str
        The module that defines ``compute`` and ``plot``.
    deps : tuple of str
        Artifacts whose DataFrames ``compute`` receives.
    config : tuple of str
        The config.yaml sections ``compute`` reads.
    resources : dict
        ``threads``, ``mem_mb`` and ``runtime`` (minutes) of its rule, for a cluster's scheduler
        (:data:`DEFAULT_RESOURCES` updated by the decorator's ``resources``).
    chapter : int or None
        The thesis chapter the report files it under; None: numerics and extensions beyond the thesis.
    fn : callable or None
        ``compute(cfg, deps) -> DataFrame`` once its module is imported (not part of the declaration).
    """

    name: str
    kind: str
    module: str
    deps: tuple[str, ...] = ()
    config: tuple[str, ...] = ()
    resources: dict = dataclasses.field(default_factory=lambda: dict(DEFAULT_RESOURCES))
    chapter: int | None = None
    fn: ComputeFn | None = dataclasses.field(default=None, compare=False, repr=False)

    @property
    def csv(self) -> str:
        """The tidy CSV, relative to the repository root."""
        return f"{_DIRECTORIES[self.kind]}/{self.name}.csv"

    @property
    def png(self) -> str:
        """The rendering, relative to the repository root."""
        return f"{_DIRECTORIES[self.kind]}/{self.name}.png"

    @property
    def renders(self) -> str | None:
        """The directory of a rendering artifact's OpenEXR files (one per panel), else None."""
        return f"{RENDERS_DIRECTORY}/{self.name}" if RENDERS_SECTION in self.config else None

    @property
    def step(self) -> str:
        """``<kind directory>/<name>``, e.g. ``tables/table_3_2_ward_cmax``: the name of its log and timings."""
        return f"{Path(_DIRECTORIES[self.kind]).name}/{self.name}"

    @property
    def outputs(self) -> tuple[str, ...]:
        """Every output of its rule: the CSV, the PNG and, if it renders, :attr:`renders` (a directory)."""
        return (self.csv, self.png) + ((self.renders,) if self.renders else ())

    @property
    def sources(self) -> list[str]:
        """The source files the artifact can depend on (see :func:`_sources_of`)."""
        return _sources_of(_source_file(self.module, self.fn))

    def _function(self) -> ComputeFn:
        return self.fn or _loaded(_ARTIFACTS, self.name, self.module).fn

    def compute(self, cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
        """Compute the artifact's tidy DataFrame from ``cfg`` and its dependencies."""
        import pandas as pd

        df = self._function()(config_subset(cfg, self.config), _select(self.name, "dependencies", self.deps, deps))
        if not isinstance(df, pd.DataFrame) or df.empty or not df.columns.is_unique:
            raise TypeError(f"{self.name}: compute must return a non-empty DataFrame with unique columns")
        return df.reset_index(drop=True)

    def plot(self, df: pd.DataFrame, path: str | Path) -> None:
        """Draw the artifact with its module's ``plot(df, path)``."""
        importlib.import_module(self.module).plot(df, path)

    def write(self, df: pd.DataFrame, csv: str | Path, png: str | Path, renders: str | Path | None = None,
              record: bool = False) -> None:
        """Write the CSV (its shape checked) and the PNG, each atomically, and the OpenEXR renders into
        ``renders`` if given; ``record``: with the CSV's and PNG's digests
        (:func:`brdfs.pipeline.io.atomic_output`)."""
        io.write_csv(df, csv, record)
        with io.atomic_output(png, record) as tmp:
            self.plot(df, tmp)
        if renders is not None:
            importlib.import_module(RENDERS_WRITER).write_renders(df, renders)


@dataclass(frozen=True)
class Comparison:
    """A registered comparison of one artifact of ``data/published_values.csv``.

    Attributes
    ----------
    artifact : str
        The ``artifact`` column of the published values.
    module : str
        The module that defines ``rows``.
    tables : tuple of str
        Artifacts whose DataFrames ``fn`` receives.
    config : tuple of str
        The config.yaml sections ``fn`` reads.
    fn : callable or None
        ``rows(cfg, tables) -> DataFrame``, the input of :func:`brdfs.pipeline.published.make_fragment`,
        once its module is imported.
    """

    artifact: str
    module: str
    tables: tuple[str, ...] = ()
    config: tuple[str, ...] = ()
    fn: ComputeFn | None = dataclasses.field(default=None, compare=False, repr=False)

    @property
    def fragment_csv(self) -> str:
        """The fragment, relative to the repository root."""
        return f"results/checks/published/{self.artifact}.csv"

    @property
    def sources(self) -> list[str]:
        """The source files the comparison can depend on (see :func:`_sources_of`)."""
        return _sources_of(_source_file(self.module, self.fn))

    def fragment(self, cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
        """The comparison fragment (see :func:`brdfs.pipeline.published.make_fragment`)."""
        from brdfs.pipeline import published

        fn = self.fn or _loaded(_COMPARISONS, self.artifact, self.module).fn
        rows = fn(config_subset(cfg, self.config), _select(self.artifact, "tables", self.tables, tables))
        return published.make_fragment(self.artifact, rows)


def _source_file(module: str, fn: Callable | None) -> Path:
    path = _module_file(module)
    if path is None and fn is not None:
        path = Path(inspect.getsourcefile(fn))
    if path is None:
        raise KeyError(f"no source file for module {module!r}")
    return path


def _select(owner: str, what: str, names: tuple[str, ...], given: dict) -> dict:
    """The DataFrames ``names`` of ``given``, or a KeyError naming the missing ones."""
    missing = [n for n in names if n not in given]
    if missing:
        raise KeyError(f"{owner}: missing {what} {missing}")
    return {n: given[n] for n in names}


def _check_name(kind: str, name: str) -> None:
    if not _NAME_PATTERNS[kind].fullmatch(name):
        raise ValueError(f"{kind} name {name!r} does not match {_NAME_PATTERNS[kind].pattern}")


def _declare_artifact(kind: str, module: str, name: str, deps: Iterable[str] = (), config: Iterable[str] = (),
                      resources: dict | None = None, chapter: int | None | str = AUTO) -> Artifact:
    """The one constructor of a declaration, for the decorators and for the static scan alike."""
    _check_name(kind, name)
    unknown = set(resources or {}) - set(DEFAULT_RESOURCES)
    if unknown:
        raise ValueError(f"{name}: unknown resources {sorted(unknown)}; known: {sorted(DEFAULT_RESOURCES)}")
    numbered = _NUMBERED.match(name)
    if chapter == AUTO:
        if not numbered:
            raise DeclarationError(f"{name}: declare the report chapter (chapter=N for the chapter whose claims it "
                                   "examines, chapter=None for numerics and extensions beyond the thesis)")
        chapter = int(numbered[1])
    if chapter is not None and not (isinstance(chapter, int) and chapter >= 1):
        raise DeclarationError(f"{name}: chapter must be a thesis chapter number or None, not {chapter!r}")
    return Artifact(name, kind, module, tuple(deps), tuple(config), {**DEFAULT_RESOURCES, **(resources or {})},
                    chapter)


def _declare_comparison(module: str, artifact: str, tables: Iterable[str] = (),
                        config: Iterable[str] = ()) -> Comparison:
    _check_name("comparison", artifact)
    return Comparison(artifact, module, tuple(tables), tuple(config))


# Registered at run time by the decorators (modules imported in this process), by name.
_ARTIFACTS: dict[str, Artifact] = {}
_COMPARISONS: dict[str, Comparison] = {}


def _register(registry: dict, key: str, entry: Artifact | Comparison) -> None:
    """Add ``entry``; re-registering from the same module (a reload) replaces it."""
    old = registry.get(key)
    if old is not None and old.module != entry.module:
        raise ValueError(f"{key!r} is registered twice: in {old.module} and {entry.module}")
    if isinstance(entry, Artifact):
        others = [a.name for a in registry.values() if a.module == entry.module and a.name != key]
        if others:
            raise ValueError(f"{entry.module} already defines {others}: one table or figure per module")
    registry[key] = entry


def _artifact_decorator(kind: str, *args, **kwargs):
    _check_name(kind, args[0] if args else kwargs["name"])

    def decorate(fn: ComputeFn) -> ComputeFn:
        entry = _declare_artifact(kind, fn.__module__, *args, **kwargs)
        _register(_ARTIFACTS, entry.name, dataclasses.replace(entry, fn=fn))
        return fn

    return decorate


def table(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
          chapter: int | None | str = AUTO):
    """Register ``compute(cfg, deps) -> DataFrame`` as the table ``name``.

    Parameters
    ----------
    name : str
        ``table_<N>_<M>_<slug>`` for thesis table N.M, ``extra_<slug>`` otherwise;
        written to ``results/tables/<name>.csv`` and ``.png``.
    deps : iterable of str
        Tables or figures whose DataFrames ``compute`` receives, by name.
    config : iterable of str
        The config.yaml sections ``compute`` reads (``seed`` and ``tolerance`` always come).
    resources : dict, optional
        Overrides of :data:`DEFAULT_RESOURCES` for its rule.
    chapter : int or None
        The thesis chapter of its place in the report: by default N of ``table_N_M``; an
        ``extra_*`` declares it (None: numerics and extensions beyond the thesis).
    """
    return _artifact_decorator("table", name, deps, config, resources, chapter)


def figure(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
           chapter: int | None | str = AUTO):
    """Register ``compute(cfg, deps) -> DataFrame`` (the plotted data) as the figure ``name``.

    As :func:`table`, with names ``fig_<N>_<M>_<slug>`` or ``extra_<slug>``,
    written to ``results/figures/``.
    """
    return _artifact_decorator("figure", name, deps, config, resources, chapter)


def check(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
          chapter: int | None | str = AUTO):
    """Register ``compute(cfg, deps) -> DataFrame`` (a verification's tidy results) as the check ``name``.

    As :func:`table`, with any ``[a-z0-9_]+`` name, written to ``results/checks/<name>.csv`` and ``.png``.
    """
    return _artifact_decorator("check", name, deps, config, resources, chapter)


def comparison(artifact: str, tables: Iterable[str] = (), config: Iterable[str] = ()):
    """Register ``rows(cfg, tables) -> DataFrame`` as the comparison of ``artifact``.

    Parameters
    ----------
    artifact : str
        An ``artifact`` of ``data/published_values.csv``; the fragment is
        ``results/checks/published/<artifact>.csv``.
    tables : iterable of str
        Tables or figures whose DataFrames ``rows`` receives, by name.
    config : iterable of str
        The config.yaml sections ``rows`` reads.
    """
    _check_name("comparison", artifact)

    def decorate(fn: ComputeFn) -> ComputeFn:
        entry = _declare_comparison(fn.__module__, artifact, tables, config)
        _register(_COMPARISONS, artifact, dataclasses.replace(entry, fn=fn))
        return fn

    return decorate


_DECORATORS = {"table": table, "figure": figure, "check": check, "comparison": comparison}


def _loaded(registry: dict, key: str, module: str):
    """The run-time entry of ``key``, importing ``module`` (which registers it) if need be."""
    if key not in registry:
        importlib.import_module(module)
    if key not in registry:
        raise DeclarationError(f"{module} was scanned as declaring {key!r} but registers no such entry")
    return registry[key]


def _package_declarations() -> tuple[dict[str, Artifact], dict[str, Comparison]]:
    """Every declaration of ``src/brdfs/artifacts/<name>.py``, read without importing the modules
    (:func:`brdfs.pipeline.declarations.package_declarations`)."""
    from brdfs.pipeline import declarations

    return declarations.package_declarations()


def artifacts() -> dict[str, Artifact]:
    """Every table, figure and check, by name: the package's (read without importing) and any registered
    at run time by decorators outside it."""
    return {**_package_declarations()[0], **_ARTIFACTS}


def comparisons() -> dict[str, Comparison]:
    """Every comparison, by artifact of the published values (as :func:`artifacts`)."""
    return {**_package_declarations()[1], **_COMPARISONS}


def workflow_files(registered: dict[str, Artifact] | None = None,
                   compared: dict[str, Comparison] | None = None) -> tuple[set[str], set[str]]:
    """What the workflow's rules write: the files (every output, log and timings) and the directories
    (a render's OpenEXR directory, whose files its job names), relative to the repository root."""
    registered = artifacts() if registered is None else registered
    compared = comparisons() if compared is None else compared
    files = {COMPARISON, COMPARISON_HTML, VERDICT_COUNTS_CSV, VERDICT_COUNTS_PNG, REPORT_LANDING, REPORT_LANDING_CSV,
             REPORT_CHAPTERS_CSV}
    files |= {REPORT_TABLE.format(name=name) for name, a in registered.items() if a.kind == "table"}
    files |= {c.fragment_csv for c in compared.values()}
    for step in (*STEPS, *(a.step for a in registered.values())):
        files |= {log_of(step), benchmark_of(step)}
    directories = {a.renders for a in registered.values() if a.renders}
    for a in registered.values():
        files |= set(a.outputs) - directories
    return files, directories


def stale_results(root: str | Path = ".") -> list[str]:
    """The files under ``root``'s :data:`WORKFLOW_DIRECTORIES` that no rule writes any more (nor their
    digests, ``.digests/<name>.sha256``, nor Snakemake's own marks), relative to ``root``, sorted."""
    root = Path(root)
    files, directories = workflow_files()
    stale = []
    for top in WORKFLOW_DIRECTORIES:
        for path in (root / top).rglob("*"):
            relative = path.relative_to(root)
            if path.is_dir() or any(relative.as_posix().startswith(d + "/") for d in directories):
                continue
            produced = relative.as_posix()
            if relative.parent.name == io.DIGESTS and path.suffix == ".sha256":
                produced = (relative.parent.parent / path.stem).as_posix()
            if produced not in files and not path.name.startswith(".snakemake"):
                stale.append(relative.as_posix())
    return sorted(stale)


def remove_stale_results(root: str | Path = ".") -> list[str]:
    """Remove :func:`stale_results` (and the directories they leave empty); return what was removed."""
    root = Path(root)
    stale = stale_results(root)
    for relative in stale:
        (root / relative).unlink()
    kept = {root / d for d in workflow_files()[1]}
    for parent in sorted({(root / r).parent for r in stale}, key=lambda p: len(p.parts), reverse=True):
        while parent not in kept and parent != root and not any(parent.iterdir()):
            parent.rmdir()
            parent = parent.parent
    return stale


def main(argv: list[str] | None = None) -> int:
    """``python -m brdfs.pipeline.registry remove-stale [ROOT]`` (``make all``): remove the results no rule
    writes any more, saying in one line what went."""
    import sys

    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] != "remove-stale" or len(args) > 2:
        print("usage: python -m brdfs.pipeline.registry remove-stale [ROOT]", file=sys.stderr)
        return 2
    removed = remove_stale_results(args[1] if len(args) == 2 else ".")
    if removed:
        print(f"removed {len(removed)} results no rule writes any more: {' '.join(removed)}")
    return 0


def get_artifact(name: str) -> Artifact:
    """The table or figure ``name``.

    A job imports only the module of the same name (registering it), without scanning the others.
    """
    if name not in _ARTIFACTS and name.isidentifier() and (_ARTIFACTS_DIR / f"{name}.py").is_file():
        importlib.import_module(f"brdfs.artifacts.{name}")
    if name in _ARTIFACTS:
        return _ARTIFACTS[name]
    registered = artifacts()
    if name not in registered:
        raise KeyError(f"no table or figure {name!r}; registered: {sorted(registered)}")
    return registered[name]


def get_comparison(artifact: str) -> Comparison:
    """The comparison of ``artifact``."""
    registered = comparisons()
    if artifact not in registered:
        raise KeyError(f"no comparison {artifact!r}; registered: {sorted(registered)}")
    return registered[artifact]


# --- dependencies ----------------------------------------------------------------------------------


def dependency_order(names: Iterable[str], registered: dict[str, Artifact] | None = None,
                     done: Iterable[str] = ()) -> list[str]:
    """``names`` and, before each, its dependencies not in ``done``, each once.

    The one dependency resolution of the package (depth first, dependencies in their declared
    order) and the one place a cycle is detected.

    Raises
    ------
    ValueError
        On a dependency cycle, naming it.
    KeyError
        On a dependency that is not registered.
    """
    registered = artifacts() if registered is None else registered
    done, order = set(done), []

    def visit(name: str, path: tuple[str, ...]) -> None:
        if name in path:
            raise ValueError(f"dependency cycle: {' -> '.join((*path, name))}")
        if name in done:
            return
        if name not in registered:
            raise KeyError(f"no table or figure {name!r}" + (f" (a dependency of {path[-1]})" if path else ""))
        for d in registered[name].deps:
            visit(d, (*path, name))
        done.add(name)
        order.append(name)

    for name in names:
        visit(name, ())
    return order


def read_tables(paths: Iterable[str | Path]) -> dict[str, pd.DataFrame]:
    """Read artifact CSVs, keyed by artifact name (the file stem), each checked
    (:func:`brdfs.pipeline.io.read_result`: a damaged one is a one-line ResultError)."""
    return {Path(p).stem: io.read_result(p) for p in paths}


def compute_tables(cfg: dict, names: Iterable[str], cache: dict[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
    """Compute artifacts and, first, their dependencies, each once.

    Parameters
    ----------
    cfg : dict
        The whole validated config.
    names : iterable of str
        The artifacts wanted.
    cache : dict
        Artifacts already computed, by name; filled in place. Each DataFrame is
        stored as it reads back from its CSV, as the pipeline's next rule sees it.

    Returns
    -------
    dict
        The wanted DataFrames, by name.
    """
    names = list(names)
    for name in dependency_order(names, done=cache):
        artifact = get_artifact(name)
        cache[name] = io.roundtrip_csv(artifact.compute(cfg, {d: cache[d] for d in artifact.deps}))
    return {name: cache[name] for name in names}


def compute_all_comparisons(cfg: dict, only: Iterable[str] | None = None) -> pd.DataFrame:
    """Every registered comparison, computed in-process and merged.

    Parameters
    ----------
    cfg : dict
        The whole validated config (see :func:`brdfs.pipeline.config.load_config`).
    only : iterable of str, optional
        The comparisons to compute (default: all).

    Returns
    -------
    pandas.DataFrame
        As ``results/checks/published_comparison.csv``.
    """
    from brdfs.pipeline import published

    cache: dict[str, pd.DataFrame] = {}
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for c in comparisons().values():
            if only is not None and c.artifact not in set(only):
                continue
            paths.append(Path(tmp) / Path(c.fragment_csv).name)
            io.write_csv(c.fragment(cfg, compute_tables(cfg, c.tables, cache)), paths[-1])
        return published.merge_fragments(paths)


if __name__ == "__main__":
    raise SystemExit(main())
