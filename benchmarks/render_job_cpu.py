"""CPU seconds of each render job of a rebuild, whole job and panels, as ``make all`` runs them (issue 42).

A render job is one process (``workflow/scripts/artifact.py``). This script runs each rendered figure's
job (``brdfs.pipeline.job.run``, writing into ``results/`` of the tree it runs in) one after the other
and prints per job its wall and CPU seconds (user + system), the CPU seconds of its panels (the
figure's ``results/renders/<name>/timing.json``: the renders alone) and the rest (start-up, scene
set-up, noise figures, PNG, EXR and CSV):

* ``--mode alone``: each job in a fresh interpreter (Snakemake's ``script:`` preamble included), as a
  plain ``snakemake`` runs it;
* ``--mode parent`` (default): each job in a child forked from this process after
  :func:`brdfs.pipeline.zygote.preload`, as under ``make all``'s pre-loaded parent (the job's own
  small client process, ~0.15 CPU-s, is not counted).

CPU seconds add up over the jobs whatever else runs on the machine (a shared machine inflates them
by ~10 %); the wall time of the rebuild on 2 idle cores is about their sum / 2 plus Snakemake's own
start (~4 s), the jobs packing well (many short ones)::

    PYTHONPATH=src .venv/bin/python benchmarks/render_job_cpu.py [--mode alone|parent] [figure ...]
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

#: The rendered figures, longest first.
FIGURES = ("fig_4_16_patch_metals", "fig_2_8_pumping_render", "fig_4_9_sampling_efficiency",
           "fig_4_11_anisotropic_metals", "fig_3_9_metals_new_model", "fig_3_10_metal_teapots",
           "fig_3_11_silver_mirror", "fig_3_12_plastics", "fig_3_13_ceramics", "fig_4_17_patch_shapes",
           "fig_3_8_material_spheres", "fig_4_18_generalized_lambert")

ALONE = """import pickle; from snakemake.logging import logger; from snakemake.iocontainers import Snakemake
from brdfs.pipeline import job, registry
from brdfs.pipeline.config import load_config
name = {name!r}
job.run(name=name, log={log!r}, outputs=list(registry.get_artifact(name).outputs), tables=[], config=load_config())
"""


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _alone(name: str, log: str) -> None:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    env.pop("BRDFS_ZYGOTE", None)
    subprocess.run([sys.executable, "-c", ALONE.format(name=name, log=log)], check=True, env=env)


def _forked(name: str, log: str) -> None:
    from brdfs.pipeline import registry
    from brdfs.pipeline.config import load_config

    config = load_config()
    pid = os.fork()
    if pid == 0:
        status = 1
        try:
            from brdfs.pipeline.job import run

            run(name=name, log=log, outputs=list(registry.get_artifact(name).outputs), tables=[], config=config)
            status = 0
        finally:
            os._exit(status)
    _, status = os.waitpid(pid, 0)
    if status:
        raise RuntimeError(f"{name}: the forked job failed (status {status})")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("figures", nargs="*", default=FIGURES)
    parser.add_argument("--mode", choices=("alone", "parent"), default="parent")
    parser.add_argument("--log", default="/tmp/render_job_cpu.log")
    args = parser.parse_args(argv)
    if args.mode == "parent":
        from brdfs.pipeline import zygote

        zygote.preload()
    total_cpu = total_panels = 0.0
    for name in args.figures:
        cpu, wall = _children_cpu(), time.perf_counter()
        (_alone if args.mode == "alone" else _forked)(name, args.log)
        cpu, wall = _children_cpu() - cpu, time.perf_counter() - wall
        timing = Path("results/renders") / name / "timing.json"
        panels = sum(p["cpu_s"] for p in json.loads(timing.read_text())["panels"]) if timing.is_file() else float("nan")
        total_cpu += cpu
        total_panels += panels
        print(f"{name:32s} wall {wall:6.2f} s  CPU {cpu:6.2f} s  panels {panels:6.2f}  rest {cpu - panels:5.2f}", flush=True)
    print(f"{'total (' + args.mode + ')':32s} CPU {total_cpu:6.1f} s  panels {total_panels:6.1f} s  "
          f"idle 2-core wall about {total_cpu / 2 + 4:.0f} s (sum / 2 + Snakemake's start)")


if __name__ == "__main__":
    main()
