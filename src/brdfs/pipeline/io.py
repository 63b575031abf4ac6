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
    """Write ``df`` without its index, atomically, every float in its shortest exact repr.

    pandas formats floats through ``str``, which numpy's ``legacy='1.13'`` print options (set
    by some libraries on import) cut to 12 digits: the options are pinned here.
    """
    import numpy as np

    with atomic_output(path) as tmp, np.printoptions(legacy=False):
        df.to_csv(tmp, index=False)


def read_csv(path: str | os.PathLike, **kwargs) -> pd.DataFrame:
    """Read a CSV written by :func:`write_csv`; floats read back exactly."""
    import pandas as pd

    return pd.read_csv(path, **kwargs)


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
        except BaseException:
            logger.exception("failed")
            raise
        finally:
            logger.removeHandler(handler)
