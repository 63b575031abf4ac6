"""File input and output shared by the pipeline scripts and the tests.

Every output is written atomically (to a temporary file in the same directory,
then renamed), so a failing step never leaves a partial file behind. CSV files
are read back with pandas' default float parser, which since pandas 3 is exact
(round-trip): a number written and read back is the same double (tested).
"""

from __future__ import annotations

import contextlib
import logging
import os
import tempfile
import uuid
from collections.abc import Iterator
from pathlib import Path

import pandas as pd

#: The repository root (``src/brdfs/pipeline/io.py`` -> four levels up).
REPO_ROOT = Path(__file__).resolve().parents[3]


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path that replaces ``path`` only if the block succeeds.

    Parameters
    ----------
    path : str or os.PathLike
        The final output path. Its directory is created if missing.

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
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def write_csv(df: pd.DataFrame, path: str | os.PathLike) -> None:
    """Write ``df`` without its index, atomically."""
    with atomic_output(path) as tmp:
        df.to_csv(tmp, index=False)


def read_csv(path: str | os.PathLike, **kwargs) -> pd.DataFrame:
    """Read a CSV written by :func:`write_csv`; floats read back exactly."""
    return pd.read_csv(path, **kwargs)


def roundtrip_csv(df: pd.DataFrame) -> pd.DataFrame:
    """Return ``df`` as it reads back after :func:`write_csv` (same dtypes, same values)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "table.csv"
        write_csv(df, path)
        return read_csv(path)


@contextlib.contextmanager
def logged(path: str | os.PathLike) -> Iterator[logging.Logger]:
    """Send logging, stdout and stderr of the block to ``path``; log any exception.

    Parameters
    ----------
    path : str or os.PathLike
        The log file, overwritten.

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
        try:
            with contextlib.redirect_stdout(stream), contextlib.redirect_stderr(stream):
                yield logger
        except BaseException:
            logger.exception("failed")
            raise
        finally:
            logger.removeHandler(handler)
