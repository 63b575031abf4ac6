"""File input and output shared by the pipeline scripts and the tests.

Every output is written atomically (to a temporary file in the same directory,
then renamed), so a failing step never leaves a partial file behind. CSV files
are read back with pandas' default float parser, which since pandas 3 is exact
(round-trip): a number written and read back is the same double (tested).

Results are trusted by content, not by time stamp. A CSV's shape is checked against the contract
(docs/contract.md, "Columns": :func:`check_frame`) when it is written and when a job reads it
(:func:`read_result`). The workflow's scripts record the SHA-256 of every output they write
(``record=True``) beside it, in ``<dir>/.digests/<name>.sha256``; a result whose bytes no longer
match (truncated, edited by hand, or left without a record by an older build) is *damaged*:
``make all`` rebuilds it (``python -m brdfs.pipeline.io damaged`` lists them for ``--forcerun``),
and a job that reads one stops with one line naming the file (:class:`ResultError`).
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import tempfile
import threading
import time
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy and pandas are imported by the functions that need them, so that the
    import pandas as pd  # workflow can plan (REPO_ROOT, the registry) without importing them

#: The repository root (``src/brdfs/pipeline/io.py`` -> four levels up).
REPO_ROOT = Path(__file__).resolve().parents[3]


class ResultError(ValueError):
    """A damaged result: the message is one line naming the file and what is wrong."""


#: Where the digest of ``<dir>/<name>`` is recorded: ``<dir>/.digests/<name>.sha256``.
DIGESTS = ".digests"
#: The results whose digests ``make all`` checks (every one is written with ``record=True``).
CHECKED_RESULTS = ("results/tables", "results/figures", "results/checks")


#: Touched by a whole ``make all`` that succeeded (the Makefile's BUILD_COMPLETE): every result was up to
#: date by Snakemake's judgement (content: code, params, inputs) at that time.
BUILD_COMPLETE = ".snakemake/complete_build"

#: What :func:`damage` says of a result without a recorded digest.
NO_RECORD = "no record of its writing (an older build, or not written by the workflow)"


def digest_path(path: str | os.PathLike) -> Path:
    """The file recording the SHA-256 of ``path`` as it was written."""
    path = Path(path)
    return path.parent / DIGESTS / f"{path.name}.sha256"


def sha256(path: str | os.PathLike) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def damage(path: str | os.PathLike) -> str | None:
    """What is wrong with the result ``path`` (None: its bytes are those its job wrote)."""
    record = digest_path(path)
    if not record.is_file():
        return NO_RECORD
    if sha256(path) != record.read_text(encoding="ascii").strip():
        return "its content changed since it was written (truncated or edited)"
    return None


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, record: bool = False) -> Iterator[Path]:
    """Yield a temporary path that replaces ``path`` only if the block succeeds.

    Parameters
    ----------
    path : str or os.PathLike
        The final output path. Its directory is created if missing.
    record : bool
        Record the SHA-256 of the new content (:func:`digest_path`) before it replaces ``path``
        (a kill in between leaves a file that does not match its record: rebuilt, never trusted).

    Yields
    ------
    pathlib.Path
        A fresh path in the same directory with the same suffix (so that
        writers inferring the format from the suffix behave the same).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # A fresh name, created by the writer itself (so with the usual permissions).
    tmp = path.with_name(f".{path.stem}.{uuid.uuid4().hex}{path.suffix}")
    try:
        yield tmp
        if record:
            with atomic_output(digest_path(path)) as digest:
                digest.write_text(sha256(tmp) + "\n", encoding="ascii")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def write_csv(df: pd.DataFrame, path: str | os.PathLike, record: bool = False) -> None:
    """Write ``df`` without its index, atomically, every float in its shortest exact repr, after
    checking its shape (:func:`check_frame`); ``record``: record its digest (:func:`atomic_output`).

    pandas formats floats through ``str``, which numpy's ``legacy='1.13'`` print options (set
    by some libraries on import) cut to 12 digits: the options are pinned here.
    """
    import numpy as np

    check_frame(df, path)
    with atomic_output(path, record) as tmp, np.printoptions(legacy=False):
        df.to_csv(tmp, index=False)


def read_csv(path: str | os.PathLike, **kwargs) -> pd.DataFrame:
    """Read a CSV written by :func:`write_csv`; floats read back exactly."""
    import pandas as pd

    return pd.read_csv(path, **kwargs)


def verify(path: str | os.PathLike) -> None:
    """Raise a one-line :class:`ResultError` if ``path`` has a recorded digest its bytes do not match."""
    if digest_path(path).is_file() and (problem := damage(path)):
        raise ResultError(f"{path}: damaged, {problem}; `make all` rebuilds it")


def read_result(path: str | os.PathLike) -> pd.DataFrame:
    """A result CSV a job reads: its bytes those its job wrote (where a digest was recorded) and its
    shape the contract's (:func:`check_frame`).

    Raises
    ------
    ResultError
        One line naming the file and what is wrong.
    """
    verify(path)
    try:
        df = read_csv(path)
    except Exception as error:  # a parser's error of any kind: the file is no CSV of ours
        raise ResultError(f"{path}: damaged, not a readable CSV ({str(error).splitlines()[0]}); "
                          "`make all` rebuilds it") from None
    check_frame(df, path, error=ResultError)
    return df


#: Columns of every render CSV (docs/contract.md, "Columns": one row per (panel, object)).
RENDER_COLUMNS = ("figure", "panel", "panel_title", "object", "pixels", "luminance", "luminance_err",
                  "width", "height", "spp", "passes", "preset", "variant")


def frame_problem(df: pd.DataFrame) -> str | None:
    """What in ``df`` breaks the contract's shape of a result table (None: nothing): no rows, a
    repeated or unnamed column, an error column ``<x>_err`` without its ``<x>``, not numeric or
    negative, a render table without the render columns."""
    if df.empty or len(df.columns) == 0:
        return "no rows"
    columns = [str(c) for c in df.columns]
    if len(set(columns)) != len(columns):
        return f"a repeated column: {sorted(c for c in set(columns) if columns.count(c) > 1)}"
    if unnamed := [c for c in columns if not c or c.startswith("Unnamed:")]:
        return f"an unnamed column ({unnamed[0]!r})"
    for column in (c for c in columns if c.endswith("_err")):
        if column[:-4] not in columns:
            return f"column {column} without {column[:-4]}"
        values = df[column]
        if values.dtype.kind not in "fiu":
            return f"column {column} is not numeric ({values.dtype})"
        if (values < 0).any():
            return f"column {column} is negative in row {int((values < 0).to_numpy().argmax())}"
    if "luminance_err" in columns and (missing := [c for c in RENDER_COLUMNS if c not in columns]):
        return f"a render table without the columns {missing}"
    return None


def check_frame(df: pd.DataFrame, path: str | os.PathLike, error: type[Exception] = ValueError) -> None:
    """Raise ``error`` (one line naming ``path``) if ``df`` breaks the contract's shape (:func:`frame_problem`)."""
    if (problem := frame_problem(df)) is not None:
        raise error(f"{path}: {problem} (docs/contract.md, Columns)")


def damaged_results(root: str | os.PathLike = ".") -> dict[str, str]:
    """Every CSV and PNG under ``root``'s :data:`CHECKED_RESULTS` whose bytes are not those its job
    wrote, with what is wrong: relative path -> problem."""
    root = Path(root)
    found = {}
    for directory in CHECKED_RESULTS:
        for path in sorted((root / directory).rglob("*")):
            relative = path.relative_to(root)
            if path.suffix in (".csv", ".png") and DIGESTS not in relative.parts and not path.name.startswith("."):
                if (problem := damage(path)) is not None:
                    found[relative.as_posix()] = problem
    return found


def main(argv: list[str] | None = None) -> int:
    """``python -m brdfs.pipeline.io damaged [ROOT]``: the damaged results (:func:`damaged_results`),
    one path a line on stdout (for ``snakemake --forcerun``), each with what is wrong on stderr."""
    import sys

    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] != "damaged" or len(args) > 2:
        print("usage: python -m brdfs.pipeline.io damaged [ROOT]", file=sys.stderr)
        return 2
    damaged = damaged_results(args[1] if len(args) == 2 else ".")
    unrecorded = [path for path, problem in damaged.items() if problem == NO_RECORD]
    for path, problem in damaged.items():
        print(path)
        if problem != NO_RECORD:
            print(f"{path}: damaged, {problem}: rebuilt", file=sys.stderr)
    if unrecorded:
        print(f"{unrecorded[0]}" + (f" and {len(unrecorded) - 1} more results" if len(unrecorded) > 1 else "")
              + f": {NO_RECORD}: rebuilt", file=sys.stderr)
    return 0


def roundtrip_csv(df: pd.DataFrame) -> pd.DataFrame:
    """Return ``df`` as it reads back after :func:`write_csv` (same dtypes, same values)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "table.csv"
        write_csv(df, path)
        return read_csv(path)


#: Seconds between the progress lines of :func:`logged` while a step runs.
HEARTBEAT_S = 10.0


@contextlib.contextmanager
def _heartbeat(logger: logging.Logger, every_s: float) -> Iterator[None]:
    """Log ``running: <step>, <elapsed> s`` every ``every_s`` seconds until the block ends.

    The step is the last message logged with :func:`step` (``logger.step``).
    """
    stop = threading.Event()
    start = time.monotonic()

    def beat():
        while not stop.wait(every_s):
            logger.info("running: %s, %.0f s elapsed", getattr(logger, "current_step", "?"), time.monotonic() - start)

    thread = threading.Thread(target=beat, name="brdfs-heartbeat", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join()
        logger.info("done in %.1f s", time.monotonic() - start)


def step(logger: logging.Logger, name: str) -> None:
    """Log the start of a step (``compute``, ``plot``, ...), named in the progress lines that follow."""
    logger.current_step = name
    logger.info("step: %s", name)


@contextlib.contextmanager
def logged(path: str | os.PathLike, heartbeat_s: float | None = HEARTBEAT_S) -> Iterator[logging.Logger]:
    """Send logging, stdout and stderr of the block to ``path``; log any exception, and progress.

    Every ``heartbeat_s`` seconds the log gets a line with the current step (see :func:`step`)
    and the time elapsed, so that a long rule shows it is alive; the last line gives the total.
    Logs hold wall times; artifacts never do.

    Parameters
    ----------
    path : str or os.PathLike
        The log file, overwritten.
    heartbeat_s : float or None, optional
        Seconds between progress lines (None: none).

    Yields
    ------
    logging.Logger
        The ``brdfs`` logger, writing to ``path`` at INFO level.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    logger = logging.getLogger("brdfs")
    with open(path, "w", encoding="utf-8") as stream:
        handler = logging.StreamHandler(stream)
        handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
        logger.addHandler(handler)
        logger.setLevel(logging.INFO)
        beat = _heartbeat(logger, heartbeat_s) if heartbeat_s else contextlib.nullcontext()
        try:
            with contextlib.redirect_stdout(stream), contextlib.redirect_stderr(stream), beat:
                yield logger
        except ResultError as error:   # the damaged file is the whole story: one line, no stack
            logger.error("%s", error)
            raise SystemExit(str(error)) from None
        except BaseException:
            logger.exception("failed")
            raise
        finally:
            logger.removeHandler(handler)


if __name__ == "__main__":
    raise SystemExit(main())
