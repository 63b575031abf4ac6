"""One artifact job: compute a registered table, figure or check and write its CSV and PNG, each
atomically (and a rendered figure's OpenEXR directory).

Run by ``workflow/scripts/artifact.py`` in the job's own process, or in a child of the pre-loaded
parent of :mod:`brdfs.pipeline.zygote`; the same code either way. Its outputs are the artifact's
``Artifact.outputs``, every one of them declared by the rule. Its dependencies are read from their
CSVs. The log names each step and, every few seconds, the step still running
(:func:`brdfs.pipeline.io.logged`).
"""

from __future__ import annotations

from collections.abc import Sequence

from brdfs.pipeline import io, registry


def run(name: str, log: str, outputs: Sequence[str], tables: Sequence[str], config: dict) -> None:
    """Compute artifact ``name`` from the CSVs ``tables`` and ``config``; write it, logging to ``log``."""
    with io.logged(log) as logger:
        artifact = registry.get_artifact(name)
        undeclared = [path for path in artifact.outputs if path not in set(outputs)]
        if undeclared:
            raise RuntimeError(f"{name}: outputs {undeclared} are not declared by the rule")
        io.step(logger, f"read {len(tables)} input tables")
        frames = registry.read_tables(tables)
        io.step(logger, f"compute {name}")
        df = artifact.compute(config, frames)
        io.step(logger, f"write {artifact.csv} and plot {artifact.png}"
                + (f", renders to {artifact.renders}" if artifact.renders else ""))
        artifact.write(df, artifact.csv, artifact.png, artifact.renders, record=True)
        logger.info("%s: %d rows -> %s", name, len(df), artifact.csv)
