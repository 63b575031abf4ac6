"""The data dictionary of the results: every column of every CSV under ``results/``, with its unit and meaning.

One fact in one place: ``docs/contract.md``, section "Data dictionary", is the one human-written source. It
holds a table of units and a table of entries (``column | files | unit | meaning``); an entry's column is a
name or a pattern in which ``<x>`` stands for another column of the same CSV (``<x>_err``: the error of
``<x>``), and its files are ``*`` or comma-separated globs of a CSV's path under ``results/`` without
``.csv`` (a name that means different things in different CSVs has one entry per meaning, over disjoint
files). The columns themselves come from the CSVs: the committed copy of every result,
``tests/data/results_baseline/`` (``make baseline`` records it from a build, and
:func:`brdfs.pipeline.regression.check_results` holds a build's columns to it), so that no list of columns
is kept by hand beside the artifacts that write them.

:func:`generate` resolves every (file, column) to exactly one entry and refuses, naming each, a column
without an entry, a column two entries claim, an entry no column uses and a unit the units table does not
define. The result, one row per (file, column) with ``file, column, dtype, unit, meaning``, is shipped in
the wheel (``brdfs/pipeline/data/data_dictionary.csv``; :func:`load`) and shown in the documentation
(:func:`rst_page`, the page "Data dictionary" that ``docs/_ext/data_dictionary_page.py`` writes);
``tests/pipeline/test_data_dictionary.py`` holds it equal to what the contract generates.

Why a file in the package and not a pipeline artifact: the dictionary depends on the contract and on the
CSVs' columns, not on any computed number, so it needs no job of its own (a rule would have to list all
87 CSVs as inputs and rerun whenever any number moves); users who never build ``results/`` (the wheel,
the documentation) get it all the same; and a build cannot drift from it, since its columns are held to
the baseline the dictionary is generated from.

``python -m brdfs.pipeline.data_dictionary`` writes it; ``--check`` only compares.
"""

from __future__ import annotations

import fnmatch
import functools
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from brdfs.pipeline import io

if TYPE_CHECKING:
    import pandas as pd

CONTRACT = io.REPO_ROOT / "docs" / "contract.md"
SECTION = "Data dictionary"
RESULTS_BASELINE = io.REPO_ROOT / "tests" / "data" / "results_baseline"
PACKAGED = Path(__file__).resolve().parent / "data" / "data_dictionary.csv"
FIELDS = ("file", "column", "dtype", "unit", "meaning")
#: The unit of an entry whose column is a pattern: the unit of the column ``<x>`` stands for.
SAME_UNIT = "as <x>"
_PLACEHOLDER = "<x>"
#: The files of an entry for every CSV.
ANY = "*"
#: The directories of results/ whose CSVs it describes (:data:`brdfs.pipeline.io.CHECKED_RESULTS`).
_DIRECTORIES = {Path(d).name for d in io.CHECKED_RESULTS}


class DictionaryError(ValueError):
    """The contract's data dictionary does not describe the CSVs: one line per problem."""


@dataclass(frozen=True)
class Entry:
    """One row of the contract's table of entries."""

    column: str
    files: tuple[str, ...]
    unit: str
    meaning: str
    line: int

    def match(self, file: str, column: str) -> str | None:
        """None if the entry does not describe ``column`` of ``file``; else what ``<x>`` stands for ('' if none)."""
        found = _regex(self.column).fullmatch(column)
        if found is None or not any(_glob(glob).fullmatch(file) for glob in self.files):
            return None
        return found.groupdict().get("x", "")

    def __str__(self) -> str:
        return f"docs/contract.md:{self.line} ({self.column} in {', '.join(self.files)})"


@functools.lru_cache(maxsize=None)
def _regex(column: str) -> re.Pattern:
    return re.compile("(?P<x>.+)".join(re.escape(part) for part in column.split(_PLACEHOLDER)))


@functools.lru_cache(maxsize=None)
def _glob(glob: str) -> re.Pattern:
    return re.compile(fnmatch.translate(glob))


# --- the contract ------------------------------------------------------------------------------------


def _cells(line: str) -> list[str]:
    """The cells of a markdown table row; ``\\|`` is a bar inside a cell."""
    cells = re.split(r"(?<!\\)\|", line.strip().removeprefix("|").removesuffix("|"))
    return [cell.strip().replace("\\|", "|") for cell in cells]


def _plain(cell: str) -> str:
    """A cell's code span without its backticks (``\\`C_max\\``` -> ``C_max``)."""
    return cell[1:-1] if len(cell) >= 2 and cell[0] == cell[-1] == "`" else cell


def _list(cell: str) -> tuple[str, ...]:
    """A comma-separated cell's items, each without its backticks."""
    return tuple(_plain(item.strip()) for item in cell.split(","))


def _tables(text: str) -> list[tuple[list[str], list[tuple[int, list[str]]]]]:
    """The markdown tables of the section :data:`SECTION`: (header, [(line number, cells), ...])."""
    lines = text.splitlines()
    try:
        start = next(i for i, line in enumerate(lines) if line.strip() == f"## {SECTION}")
    except StopIteration:
        raise DictionaryError(f"docs/contract.md has no section '## {SECTION}'") from None
    tables, current = [], None
    for number, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("## "):
            break
        if not line.lstrip().startswith("|"):
            current = None
        elif current is None:
            current = (_cells(line), [])
            tables.append(current)
        elif not set(line.replace("|", "").strip()) <= set("-: "):
            current[1].append((number, _cells(line)))
    return tables


def parse(text: str) -> tuple[dict[str, str], list[Entry]]:
    """The units (unit -> what it is) and the entries of the contract's data dictionary.

    Raises
    ------
    DictionaryError
        Naming every malformed row: a missing cell, an empty unit or meaning, an unknown unit.
    """
    units, groups, rows, entries, problems = {}, {}, [], [], []
    for header, table in _tables(text):
        if header == ["unit", "meaning"]:
            units.update((_plain(cells[0]), cells[1]) for _, cells in table)
        elif header == ["group", "files"]:
            groups.update((_plain(cells[0]), _list(cells[1])) for _, cells in table)
        elif header == ["column", "files", "unit", "meaning"]:
            rows.extend(table)
    for number, cells in rows:
        if len(cells) != 4 or not all(cells):
            problems.append(f"docs/contract.md:{number}: a data-dictionary row needs a column, files, "
                            f"a unit and a meaning, got {cells}")
            continue
        files = tuple(glob for name in _list(cells[1]) for glob in groups.get(name, (name,)))
        entries.append(Entry(_plain(cells[0]), files, _plain(cells[2]), cells[3], number))
    if not units or not entries:
        problems.append(f"docs/contract.md, {SECTION}: no table '| unit | meaning |' or no table "
                        "'| column | files | unit | meaning |'")
    for entry in entries:
        if entry.unit not in units and not (entry.unit == SAME_UNIT and _PLACEHOLDER in entry.column):
            problems.append(f"{entry}: unit {entry.unit!r} is not in the units table"
                            + (f" ({SAME_UNIT!r} needs a pattern with {_PLACEHOLDER})" if entry.unit == SAME_UNIT
                               else ""))
    if problems:
        raise DictionaryError("\n".join(problems))
    return units, entries


# --- the CSVs ----------------------------------------------------------------------------------------


def _dtype(values: pd.Series) -> str:
    """``int``, ``float``, ``bool``, ``str``, or ``empty`` (every value missing), as the column reads back."""
    present = values.dropna()
    if present.empty:
        return "empty"
    kind = values.dtype.kind
    if kind == "b" or (kind == "O" and all(isinstance(v, bool) for v in present)):
        return "bool"
    return {"i": "int", "u": "int", "f": "float"}.get(kind, "str")


def result_columns(root: str | Path = RESULTS_BASELINE) -> dict[str, list[tuple[str, str]]]:
    """Every CSV's columns with their dtypes, by path under ``results/`` without ``.csv``.

    ``root`` is a results baseline (``<path>.csv.gz``, :data:`RESULTS_BASELINE`) or a build's ``results/``.
    """
    root = Path(root)
    found = {}
    for path in sorted([*root.rglob("*.csv.gz"), *root.rglob("*.csv")]):
        relative = path.relative_to(root).as_posix()
        if io.DIGESTS in path.parts or path.name.startswith(".") or relative.split("/")[0] not in _DIRECTORIES:
            continue
        df = io.read_csv(path)
        found[relative.removesuffix(".gz").removesuffix(".csv")] = [(str(c), _dtype(df[c])) for c in df.columns]
    return found


# --- the dictionary ----------------------------------------------------------------------------------


def resolve(entries: list[Entry], columns: dict[str, list[tuple[str, str]]]) -> tuple[list[dict], list[str]]:
    """One row per (file, column) with its unit and meaning, and the problems (one line each)."""
    rows, problems, used = [], [], set()

    def describe(file: str, column: str) -> tuple[Entry, str] | str:
        found = [(e, x) for e in entries if (x := e.match(file, column)) is not None]
        if len(found) > 1:  # an entry that names its files takes precedence over the entry for every file
            found = [(e, x) for e, x in found if e.files != (ANY,)] or found
        if not found:
            return f"results/{file}.csv: column {column!r} has no entry in docs/contract.md ({SECTION})"
        if len(found) > 1:
            return (f"results/{file}.csv: column {column!r} has {len(found)} entries: "
                    + "; ".join(str(e) for e, _ in found))
        return found[0]

    def unit(file: str, column: str, names: set[str], seen: tuple[str, ...] = ()) -> tuple[Entry, str, str | None]:
        """The entry of ``column``, what its ``<x>`` stands for, and its unit (following ``as <x>`` to the
        column ``<x>`` stands for; None after recording why there is none). A column without an entry
        raises the problem as a LookupError."""
        found = describe(file, column)
        if isinstance(found, str):
            raise LookupError(found)
        entry, x = found
        used.add(entry)
        if entry.unit != SAME_UNIT:
            return entry, x, entry.unit
        if x not in names or x in seen:
            problems.append(f"results/{file}.csv: {column!r} takes the unit of {x!r}, "
                            + ("a loop" if x in seen else "which the CSV does not have"))
            return entry, x, None
        return entry, x, unit(file, x, names, (*seen, column))[2]

    for file, file_columns in columns.items():
        names = {c for c, _ in file_columns}
        for column, dtype in file_columns:
            try:
                entry, x, column_unit = unit(file, column, names)
            except LookupError as error:
                problems.append(str(error))
                continue
            if column_unit is not None:
                rows.append({"file": f"results/{file}.csv", "column": column, "dtype": dtype, "unit": column_unit,
                             "meaning": entry.meaning.replace(_PLACEHOLDER, f"`{x}`")})
    problems.extend(f"{entry}: no column of any CSV uses this entry" for entry in entries if entry not in used)
    return rows, list(dict.fromkeys(problems))


def generate(contract: str | Path = CONTRACT, results: str | Path = RESULTS_BASELINE) -> pd.DataFrame:
    """The data dictionary (columns :data:`FIELDS`) of the CSVs under ``results`` from ``contract``.

    Raises
    ------
    DictionaryError
        Every problem, one line each (:func:`parse`, :func:`resolve`).
    """
    import pandas as pd

    _, entries = parse(Path(contract).read_text(encoding="utf-8"))
    rows, problems = resolve(entries, result_columns(results))
    if problems:
        raise DictionaryError(f"{len(problems)} problems of the data dictionary:\n" + "\n".join(problems))
    return pd.DataFrame(rows, columns=list(FIELDS))


def load() -> pd.DataFrame:
    """The data dictionary shipped with the package: ``file, column, dtype, unit, meaning``."""
    return io.read_csv(PACKAGED, keep_default_na=False)


# --- the documentation's page --------------------------------------------------------------------

_RST_SPECIAL = re.compile(r"([\\*_|`<>\[\]])")

_INTRO = """\
Data dictionary
===============

Every column of every CSV the pipeline writes under ``results/tables``, ``results/figures`` and
``results/checks``, with its type, unit and meaning: {columns} columns of {files} CSVs. The source is one
table written by hand, the section "Data dictionary" of :doc:`the output contract <contract>`; the package
ships what it generates, so that your scripts can read it::

    from brdfs.pipeline import data_dictionary
    df = data_dictionary.load()        # file, column, dtype, unit, meaning
    df[df.file == "results/tables/table_3_2_ward_cmax.csv"]

``dtype`` is the type the column reads back with pandas (``empty``: every value of that CSV is missing;
an integer column with missing values reads as ``float``). An ``<x>_err`` column is the absolute error
estimate of ``<x>``, in its unit.

Units
-----

"""


def rst_text(markdown: str) -> str:
    """A contract cell as reStructuredText: code spans become literals, the rest is escaped."""
    parts = markdown.split("`")
    return "".join(f"``{part}``" if i % 2 else _RST_SPECIAL.sub(r"\\\1", part) for i, part in enumerate(parts) if part)


def _table(header: tuple[str, ...], rows, widths: str) -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1", f"   :widths: {widths}", ""]
    for row in (header, *rows):
        lines += [f"   * - {row[0]}"] + [f"     - {cell}" for cell in row[1:]]
    return lines + [""]


def rst_page(dictionary: pd.DataFrame | None = None, units: dict[str, str] | None = None) -> str:
    """The documentation's page (reStructuredText): the units, then one table per CSV, grouped by directory
    (default: the shipped dictionary, :func:`load`, and the contract's units)."""
    dictionary = load() if dictionary is None else dictionary
    units = parse(CONTRACT.read_text(encoding="utf-8"))[0] if units is None else units
    lines = [_INTRO.format(columns=len(dictionary), files=dictionary["file"].nunique())]
    lines += _table(("unit", "meaning"), ((f"``{u}``", rst_text(m)) for u, m in units.items()), "15 85")
    for directory, files in dictionary.groupby(dictionary["file"].str.rsplit("/", n=1).str[0], sort=True):
        directory = rst_text(directory)
        lines += [directory, "-" * len(directory), ""]
        for file, rows in files.groupby("file", sort=True):
            name = rst_text(Path(file).name)
            lines += [name, "~" * len(name), ""]
            lines += _table(("column", "dtype", "unit", "meaning"),
                            ((f"``{r.column}``", r.dtype, f"``{r.unit}``", rst_text(r.meaning))
                             for r in rows.itertuples()), "22 9 10 59")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """``python -m brdfs.pipeline.data_dictionary [--check] [RESULTS]``: write (or compare) the packaged
    dictionary generated from docs/contract.md and the CSVs under RESULTS (default: the results baseline)."""
    args = list(sys.argv[1:] if argv is None else argv)
    check = "--check" in args
    args = [a for a in args if a != "--check"]
    try:
        df = generate(CONTRACT, args[0] if args else RESULTS_BASELINE)
    except DictionaryError as error:
        print(error, file=sys.stderr)
        return 1
    if check:
        same = PACKAGED.is_file() and load().equals(df.astype(str))
        print(f"{PACKAGED}: " + ("up to date" if same else "differs from docs/contract.md: "
                                 "python -m brdfs.pipeline.data_dictionary"), file=sys.stderr)
        return 0 if same else 1
    io.write_csv(df, PACKAGED)
    print(f"{PACKAGED}: {len(df)} columns of {df['file'].nunique()} CSVs", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
