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
only when, a section it reads changes. A comparison's rows go through
:func:`brdfs.pipeline.published.make_fragment`.

Modules of this package are imported on first use of the registry.
"""

from __future__ import annotations

import ast
import functools
import importlib
import inspect
import pkgutil
import re
import sys
import tempfile
from collections.abc import Callable, Iterable
import dataclasses
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from brdfs.pipeline import io
from brdfs.pipeline import published

_PACKAGE_ROOT = Path(__file__).resolve().parents[1]

ComputeFn = Callable[[dict, dict[str, pd.DataFrame]], pd.DataFrame]

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


def config_subset(cfg: dict, sections: Iterable[str]) -> dict:
    """The sections of ``cfg`` an artifact reads, plus :data:`COMMON_SECTIONS`.

    Raises
    ------
    KeyError
        If a section is missing from ``cfg``.
    """
    wanted = dict.fromkeys((*COMMON_SECTIONS, *sections))
    missing = [s for s in wanted if s not in cfg]
    if missing:
        raise KeyError(f"config.yaml lacks the sections {missing}")
    return {s: cfg[s] for s in wanted}


def _module_file(module: str) -> Path | None:
    """The source file of a ``brdfs`` module, or None outside the package."""
    if module != "brdfs" and not module.startswith("brdfs."):
        return None
    base = _PACKAGE_ROOT.joinpath(*module.split(".")[1:])
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


@functools.lru_cache(maxsize=None)
def _imports_of(path: Path) -> frozenset[Path]:
    """The package source files ``path`` imports directly (absolute ``brdfs`` imports)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
        else:
            continue
        for name in names:
            parts = name.split(".")
            # ``import brdfs.a.b`` also runs brdfs/__init__ and brdfs/a/__init__.
            for k in range(1, len(parts) + 1):
                file = _module_file(".".join(parts[:k]))
                if file is not None:
                    found.add(file.resolve())
    return frozenset(found)


def _sources_of(fn: Callable) -> list[str]:
    """The source files ``fn``'s results can depend on, relative to the repository root.

    The module defining ``fn`` and, transitively, every package module it imports, read
    from the import statements, so that an edit reruns exactly the artifacts it affects.
    """
    todo = [Path(inspect.getsourcefile(fn)).resolve()]
    seen: set[Path] = set()
    while todo:
        path = todo.pop()
        if path not in seen:
            seen.add(path)
            todo.extend(_imports_of(path) - seen)
    return sorted(p.relative_to(io.REPO_ROOT).as_posix() for p in seen)


@dataclass(frozen=True)
class Artifact:
    """A registered table or figure.

    Attributes
    ----------
    name : str
        The file stem, e.g. ``table_1_2_metal_reflectance``.
    kind : str
        ``'table'`` or ``'figure'``.
    deps : tuple of str
        Artifacts whose DataFrames ``compute`` receives.
    config : tuple of str
        The config.yaml sections ``compute`` reads.
    fn : callable
        ``compute(cfg, deps) -> DataFrame``.
    resources : dict
        ``threads``, ``mem_mb`` and ``runtime`` (minutes) of its rule, for a cluster's scheduler
        (:data:`DEFAULT_RESOURCES` updated by the decorator's ``resources``).
    batch : str or None
        The job it is computed in together with other cheap artifacts (:func:`default_batch`), so
        that each does not pay a process start-up; None for a job of its own.
    """

    name: str
    kind: str
    deps: tuple[str, ...]
    config: tuple[str, ...]
    fn: ComputeFn
    resources: dict = dataclasses.field(default_factory=lambda: dict(DEFAULT_RESOURCES))
    batch: str | None = None

    @property
    def csv(self) -> str:
        """The tidy CSV, relative to the repository root."""
        return f"{_DIRECTORIES[self.kind]}/{self.name}.csv"

    @property
    def png(self) -> str:
        """The rendering, relative to the repository root."""
        return f"{_DIRECTORIES[self.kind]}/{self.name}.png"

    @property
    def sources(self) -> list[str]:
        """The source files the artifact can depend on (see :func:`_sources_of`)."""
        return _sources_of(self.fn)

    def compute(self, cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
        """Compute the artifact's tidy DataFrame from ``cfg`` and its dependencies."""
        df = self.fn(config_subset(cfg, self.config), _select(self.name, "dependencies", self.deps, deps))
        if not isinstance(df, pd.DataFrame) or df.empty or not df.columns.is_unique:
            raise TypeError(f"{self.name}: compute must return a non-empty DataFrame with unique columns")
        return df.reset_index(drop=True)

    def plot(self, df: pd.DataFrame, path: str | Path) -> None:
        """Draw the artifact with its module's ``plot(df, path)``."""
        sys.modules[self.fn.__module__].plot(df, path)

    def write(self, df: pd.DataFrame, csv: str | Path, png: str | Path) -> None:
        """Write the CSV and the PNG, each atomically."""
        io.write_csv(df, csv)
        with io.atomic_output(png) as tmp:
            self.plot(df, tmp)


@dataclass(frozen=True)
class Comparison:
    """A registered comparison of one artifact of ``data/published_values.csv``.

    Attributes
    ----------
    artifact : str
        The ``artifact`` column of the published values.
    tables : tuple of str
        Artifacts whose DataFrames ``fn`` receives.
    config : tuple of str
        The config.yaml sections ``fn`` reads.
    fn : callable
        ``rows(cfg, tables) -> DataFrame``, the input of :func:`brdfs.pipeline.published.make_fragment`.
    """

    artifact: str
    tables: tuple[str, ...]
    config: tuple[str, ...]
    fn: ComputeFn

    @property
    def fragment_csv(self) -> str:
        """The fragment, relative to the repository root."""
        return f"results/checks/published/{self.artifact}.csv"

    @property
    def sources(self) -> list[str]:
        """The source files the comparison can depend on (see :func:`_sources_of`)."""
        return _sources_of(self.fn)

    def fragment(self, cfg: dict, tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
        """The comparison fragment (see :func:`brdfs.pipeline.published.make_fragment`)."""
        rows = self.fn(config_subset(cfg, self.config), _select(self.artifact, "tables", self.tables, tables))
        return published.make_fragment(self.artifact, rows)


def _select(owner: str, what: str, names: tuple[str, ...], given: dict[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
    """The DataFrames ``names`` of ``given``, or a KeyError naming the missing ones."""
    missing = [n for n in names if n not in given]
    if missing:
        raise KeyError(f"{owner}: missing {what} {missing}")
    return {n: given[n] for n in names}


_ARTIFACTS: dict[str, Artifact] = {}
_COMPARISONS: dict[str, Comparison] = {}


def _check_name(kind: str, name: str) -> None:
    if not _NAME_PATTERNS[kind].fullmatch(name):
        raise ValueError(f"{kind} name {name!r} does not match {_NAME_PATTERNS[kind].pattern}")


def _register(registry: dict, key: str, entry: Artifact | Comparison) -> None:
    """Add ``entry``; re-registering the same function (a module reload) replaces it."""
    old, fn = registry.get(key), entry.fn
    if old is not None and (old.fn.__module__, old.fn.__qualname__) != (fn.__module__, fn.__qualname__):
        raise ValueError(f"{key!r} is registered twice: in {old.fn.__module__} and {fn.__module__}")
    registry[key] = entry


#: ``batch=`` of a decorator: the artifact goes into :func:`default_batch`.
AUTO = "auto"
_CHAPTER = re.compile(r"(?:fig|table)_(\d+)_")


def default_batch(name: str) -> str:
    """The batch of a cheap artifact: its thesis chapter (``chapter_3``), or ``extra``.

    >>> default_batch("fig_4_13_inverse_cdf"), default_batch("extra_ward_in_range")
    ('chapter_4', 'extra')
    """
    match = _CHAPTER.match(name)
    return f"chapter_{match[1]}" if match else "extra"


def _artifact_decorator(kind: str, name: str, deps: Iterable[str], config: Iterable[str], resources: dict | None,
                        batch: str | None):
    _check_name(kind, name)
    unknown = set(resources or {}) - set(DEFAULT_RESOURCES)
    if unknown:
        raise ValueError(f"{name}: unknown resources {sorted(unknown)}; known: {sorted(DEFAULT_RESOURCES)}")
    declared = {**DEFAULT_RESOURCES, **(resources or {})}

    def decorate(fn: ComputeFn) -> ComputeFn:
        others = [a.name for a in _ARTIFACTS.values() if a.fn.__module__ == fn.__module__ and a.name != name]
        if others:
            raise ValueError(f"{fn.__module__} already defines {others}: one table or figure per module")
        group = default_batch(name) if batch == AUTO else batch
        _register(_ARTIFACTS, name, Artifact(name, kind, tuple(deps), tuple(config), fn, declared, group))
        return fn

    return decorate


def table(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
          batch: str | None = AUTO):
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
    batch : str or None
        The job it shares with other cheap artifacts (default: its chapter, :func:`default_batch`);
        None for an expensive artifact, which gets a job of its own.
    """
    return _artifact_decorator("table", name, deps, config, resources, batch)


def figure(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
           batch: str | None = AUTO):
    """Register ``compute(cfg, deps) -> DataFrame`` (the plotted data) as the figure ``name``.

    As :func:`table`, with names ``fig_<N>_<M>_<slug>`` or ``extra_<slug>``,
    written to ``results/figures/``.
    """
    return _artifact_decorator("figure", name, deps, config, resources, batch)


def check(name: str, deps: Iterable[str] = (), config: Iterable[str] = (), resources: dict | None = None,
          batch: str | None = None):
    """Register ``compute(cfg, deps) -> DataFrame`` (a verification's tidy results) as the check ``name``.

    As :func:`table`, with any ``[a-z0-9_]+`` name, written to ``results/checks/<name>.csv`` and ``.png``;
    a job of its own by default.
    """
    return _artifact_decorator("check", name, deps, config, resources, batch)


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
        _register(_COMPARISONS, artifact, Comparison(artifact, tuple(tables), tuple(config), fn))
        return fn

    return decorate


def _load_all() -> None:
    """Import every artifact module of this package (registering its artifacts)."""
    import brdfs.artifacts as package

    for module in pkgutil.iter_modules(package.__path__):
        if not module.name.startswith("_"):
            importlib.import_module(f"{package.__name__}.{module.name}")


def artifacts() -> dict[str, Artifact]:
    """Every registered table and figure, by name."""
    _load_all()
    return dict(_ARTIFACTS)


def comparisons() -> dict[str, Comparison]:
    """Every registered comparison, by artifact of the published values."""
    _load_all()
    return dict(_COMPARISONS)


def batches() -> dict[str, list[Artifact]]:
    """The batched artifacts by batch, each list in dependency order (a member's dependencies in
    the same batch come first).

    Raises
    ------
    ValueError
        If two batches depend on each other (their jobs could never start).
    """
    registered = artifacts()
    groups: dict[str, list[Artifact]] = {}
    for name in _dependency_order(registered):
        a = registered[name]
        if a.batch is not None:
            groups.setdefault(a.batch, []).append(a)
    needs = {b: {registered[d].batch or d for a in members for d in a.deps} - {b} for b, members in groups.items()}
    for b in needs:
        seen, todo = set(), list(needs[b])
        while todo:
            x = todo.pop()
            if x == b:
                raise ValueError(f"batch {b!r} depends on itself through other batches")
            if x not in seen:
                seen.add(x)
                todo.extend(needs.get(x, ()))
    return groups


def chain_lengths() -> dict[str, int]:
    """For every artifact, the number of jobs that wait for it, one after another (the longest
    chain of dependants below it, batches counted as one job): a scheduler that starts long chains
    first keeps both cores busy to the end."""
    registered = artifacts()
    users: dict[str, set[str]] = {name: set() for name in registered}
    for a in registered.values():
        for d in a.deps:
            users[d].add(a.name)
    memo: dict[str, int] = {}

    def length(name):
        if name not in memo:
            memo[name] = 1 + max((length(u) for u in users[name]), default=0)
        return memo[name]

    return {name: length(name) for name in registered}


def _dependency_order(registered: dict[str, Artifact]) -> list[str]:
    order: list[str] = []

    def visit(name, path):
        if name in order:
            return
        if name in path:
            raise ValueError(f"dependency cycle: {' -> '.join((*path, name))}")
        for d in registered[name].deps:
            visit(d, (*path, name))
        order.append(name)

    for name in sorted(registered):
        visit(name, ())
    return order


def get_artifact(name: str) -> Artifact:
    """The table or figure ``name``.

    Imports only the module of the same name (one job need not import every artifact, nor the
    libraries only some of them use: 1.6 s → ~1 s of start-up); every module only if that fails.
    """
    if name not in _ARTIFACTS and name.isidentifier():
        try:
            importlib.import_module(f"brdfs.artifacts.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"brdfs.artifacts.{name}":
                raise
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


def read_tables(paths: Iterable[str | Path]) -> dict[str, pd.DataFrame]:
    """Read artifact CSVs, keyed by artifact name (the file stem)."""
    return {Path(p).stem: io.read_csv(p) for p in paths}


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

    def resolve(name: str, path: tuple[str, ...]) -> pd.DataFrame:
        if name in path:
            raise ValueError(f"dependency cycle: {' -> '.join((*path, name))}")
        if name not in cache:
            artifact = get_artifact(name)
            deps = {d: resolve(d, (*path, name)) for d in artifact.deps}
            cache[name] = io.roundtrip_csv(artifact.compute(cfg, deps))
        return cache[name]

    return {name: resolve(name, ()) for name in names}


def compute_all_comparisons(cfg: dict, only: Iterable[str] | None = None) -> pd.DataFrame:
    """Every registered comparison, computed in-process and merged.

    Parameters
    ----------
    cfg : dict
        The whole validated config (see :func:`brdfs.pipeline.config.load_config`).

    Returns
    -------
    pandas.DataFrame
        As ``results/checks/published_comparison.csv``.
    """
    cache: dict[str, pd.DataFrame] = {}
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for c in comparisons().values():
            if only is not None and c.artifact not in set(only):
                continue
            paths.append(Path(tmp) / Path(c.fragment_csv).name)
            io.write_csv(c.fragment(cfg, compute_tables(cfg, c.tables, cache)), paths[-1])
        return published.merge_fragments(paths)
