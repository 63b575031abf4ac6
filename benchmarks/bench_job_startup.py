"""Start-up of an artifact job: what a fresh interpreter pays before ``compute`` runs.

A job is one process (workflow/rules/artifacts.smk). Before its artifact computes anything, the
process starts Python, unpickles Snakemake's job object when the rule runs a ``script:`` (which
imports a part of Snakemake), imports the pipeline's io and registry, and imports the artifact's
module with everything it imports at its top. This script repeats exactly that in fresh
interpreters and prints the fastest wall and CPU time (user + system) of ``--runs`` runs per
artifact, so that the start-up can be compared between trees (``--src``) and entry points
(``--preamble``)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_job_startup.py
    PYTHONPATH=src .venv/bin/python benchmarks/bench_job_startup.py --src /tmp/old/src --preamble snakemake
    PYTHONPATH=src .venv/bin/python benchmarks/bench_job_startup.py --preamble snakemake --zygote

The minimum over runs is the figure least disturbed by other processes on a shared machine; the
CPU time is the part that adds up over the ~75 jobs of a rebuild on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

DEFAULT = ("fig_4_2_base_circle_relations", "table_3_2_ward_cmax", "extra_microfacet_albedo")

# What Snakemake's ``script:`` preamble imports before the script runs (snakemake.script.PythonScript).
SNAKEMAKE_PREAMBLE = "import pickle; from snakemake.logging import logger; from snakemake.iocontainers import Snakemake\n"
JOB = "from brdfs.pipeline import io, registry\nregistry.get_artifact({name!r})\n"


def one_run(name: str, src: str, preamble: str) -> tuple[float, float]:
    """Wall and CPU seconds of one fresh interpreter doing a job's start-up for ``name``."""
    code = (SNAKEMAKE_PREAMBLE if preamble == "snakemake" else "") + JOB.format(name=name)
    env = {**os.environ, "PYTHONPATH": src, "MPLBACKEND": "Agg"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


ZYGOTE_CLIENT = "from brdfs.pipeline import zygote\n"


def one_forked_run(name: str, src: str, preamble: str) -> tuple[float, float]:
    """The same under ``make all``'s pre-loaded parent (brdfs.pipeline.zygote): the job process (Python,
    the preamble, the client module) plus a child forked from an interpreter that has imported
    ``zygote.PRELOAD``, importing the artifact's module (this process must have preloaded them)."""
    code = (SNAKEMAKE_PREAMBLE if preamble == "snakemake" else "") + ZYGOTE_CLIENT
    env = {**os.environ, "PYTHONPATH": src, "MPLBACKEND": "Agg"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    pid = os.fork()
    if pid == 0:
        from brdfs.pipeline import registry

        registry.get_artifact(name)
        os._exit(0)
    os.waitpid(pid, 0)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=DEFAULT)
    parser.add_argument("--src", default=str(Path(__file__).resolve().parents[1] / "src"))
    parser.add_argument("--preamble", choices=("snakemake", "none"), default="none",
                        help="import what Snakemake's script: preamble imports (default: none, a shell: job)")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--zygote", action="store_true",
                        help="as under make all: the job process plus a child of the pre-loaded parent (run "
                             "with PYTHONPATH=<src>, so that this process preloads that tree)")
    args = parser.parse_args()
    run = one_run
    if args.zygote:
        from brdfs.pipeline import zygote

        zygote.preload()
        run = one_forked_run
    print(f"src={args.src} preamble={args.preamble} zygote={args.zygote} runs={args.runs} (min wall s, min CPU s)")
    for name in args.names:
        runs = [run(name, args.src, args.preamble) for _ in range(args.runs)]
        print(f"{name:40s} {min(w for w, _ in runs):6.2f} {min(c for _, c in runs):6.2f}")


if __name__ == "__main__":
    main()
