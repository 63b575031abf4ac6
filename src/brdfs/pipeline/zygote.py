"""A pre-loaded parent for artifact jobs, so that a job does not pay the heavy imports.

One job is one process (``workflow/rules/artifacts.smk``), and before an artifact computes anything its
process imports numpy, pandas, matplotlib and scipy: about 0.8 CPU-s a job, some 50 CPU-s over the
rebuild's ~60 non-render jobs (``benchmarks/bench_job_startup.py``). ``make all`` therefore starts this
parent beside Snakemake (``python -m brdfs.pipeline.zygote SOCKET``). It imports those packages once
(:data:`PRELOAD`) and waits on a Unix socket. A job's script (``workflow/scripts/artifact.py``) sends it
the job (name, log, outputs, input tables, config) with the job's own stdout and stderr, and the
parent forks a child that runs exactly what the script would run in its own process
(:func:`brdfs.pipeline.job.run`), writes to the job's stdout and stderr, and sends back its exit
status. The job process waits for that status and exits with it, so Snakemake sees one job as before.

* Without the parent (a plain ``snakemake``, a single target, a cluster job) the script runs the job
  itself: :func:`run_in_zygote` returns False. Either way the outputs are the same bytes
  (``tests/pipeline/test_zygote.py``).
* Renders go through it too: the parent never imports Dr.Jit or Mitsuba (whose thread pool and LLVM
  state must not be forked; ``import drjit`` alone starts threads), so a render's child starts them
  itself, as its own process would. The parent also imports colour-science (through
  :func:`brdfs.physics.spectral_colour.colour_module`, which keeps numpy's print options) and the
  renders' shared module: about 2.5 CPU-s of each of the 12 render jobs' start-up (issue 42).
* A child dies with its job: it watches the connection, and when the job process is gone (killed by
  Snakemake, by Ctrl-C or by SIGKILL) it exits at once, so no orphan writes an output after its job
  was cancelled. Outputs are written atomically (:mod:`brdfs.pipeline.io`), so nothing half-written
  stays behind.
* Snakemake's benchmark of such a job measures the waiting job process: its wall time is right, its
  CPU time is not the child's (timings are never compared).

This module imports only the standard library at its top: the job side must stay cheap.
"""

from __future__ import annotations

import os
import pickle
import socket
import sys
import threading
import time
import traceback

#: The environment variable that names the parent's socket for the jobs (set by ``make all``).
ENV = "BRDFS_ZYGOTE"
#: What the parent imports once: what nearly every artifact imports, and the renders' shared module
#: (which imports no mitsuba or drjit: they must never be imported here, module docstring).
PRELOAD = ("numpy", "pandas", "matplotlib.pyplot", "scipy.special", "scipy.optimize", "scipy.integrate",
           "scipy.stats", "brdfs.physics.models", "brdfs.numerics.albedo", "brdfs.pipeline.io",
           "brdfs.pipeline.registry", "brdfs.pipeline.plotting", "brdfs.pipeline.job",
           "brdfs.artifacts._render_figures")
_HEADER = 8


def run_in_zygote(job: dict) -> bool:
    """Run ``job`` (the keyword arguments of :func:`brdfs.pipeline.job.run`) in the parent named by
    ``$BRDFS_ZYGOTE``; False when there is none (then the caller runs it). Exits the process with the
    child's status when the child failed."""
    path = os.environ.get(ENV)
    if not path:
        return False
    client = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        client.connect(path)
    except OSError:
        client.close()
        return False
    with client:
        data = pickle.dumps((os.getcwd(), job))
        socket.send_fds(client, [len(data).to_bytes(_HEADER, "big")], [sys.stdout.fileno(), sys.stderr.fileno()])
        client.sendall(data)
        status = client.recv(1)
    if not status:
        raise RuntimeError(f"{job.get('name')}: the pre-loaded parent ({ENV}={path}) closed without a status")
    if status[0] != 0:
        sys.exit(status[0])
    return True


def _receive(conn: socket.socket) -> tuple[tuple[str, dict], list[int]]:
    header, fds, _, _ = socket.recv_fds(conn, _HEADER, 2)
    size = int.from_bytes(header, "big")
    chunks, got = [], 0
    while got < size:
        chunk = conn.recv(min(1 << 20, size - got))
        if not chunk:
            raise EOFError("the job closed before its request was read")
        chunks.append(chunk)
        got += len(chunk)
    return pickle.loads(b"".join(chunks)), fds


def _die_with_the_job(conn: socket.socket) -> None:
    """Exit at once when the job process is gone (the connection closes without a byte)."""
    try:
        conn.recv(1)
    finally:
        os._exit(1)


def _child(conn: socket.socket) -> None:
    status = 1
    try:
        (cwd, job), (out, err) = _receive(conn)
        os.chdir(cwd)
        os.dup2(out, 1)
        os.dup2(err, 2)
        os.close(out)
        os.close(err)
        threading.Thread(target=_die_with_the_job, args=(conn,), daemon=True).start()
        from brdfs.pipeline.job import run

        run(**job)
        status = 0
    except SystemExit as stop:
        status = stop.code if isinstance(stop.code, int) and 0 < stop.code < 256 else 1
    except BaseException:
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        try:
            conn.sendall(bytes([status]))
        finally:
            os._exit(status)


def _die_with_the_build(parent: int) -> None:
    """Exit when the build that started us is gone (a SIGKILL skips its clean-up)."""
    while os.getppid() == parent:
        time.sleep(1.0)
    os._exit(0)


def preload() -> None:
    """Import :data:`PRELOAD` (matplotlib with the Agg backend) and colour-science into this process."""
    import importlib

    import matplotlib

    matplotlib.use("Agg")
    for module in PRELOAD:
        importlib.import_module(module)
    from brdfs.physics.spectral_colour import colour_module

    colour_module()


def load_compiled_routes() -> None:
    """The compiled single-angle routes, loaded from numba's cache once for every forked job (eight
    artifacts ask for single angles; each paid numba's import and loads).  After the socket listens: on a
    fresh clone this compiles them (about half a minute), while the first jobs wait in the backlog."""
    from brdfs.numerics.compiled_cache import fill

    fill()


def serve(path: str) -> None:
    """Import :data:`PRELOAD`, listen on ``path``, load the compiled routes and fork a child per job until
    killed."""
    import signal

    preload()
    signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # children report to their job, never to us
    threading.Thread(target=_die_with_the_build, args=(os.getppid(),), daemon=True).start()
    if os.path.exists(path):
        os.unlink(path)
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(path)
    server.listen(64)
    load_compiled_routes()
    while True:
        conn, _ = server.accept()
        if os.fork() == 0:
            server.close()
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            _child(conn)
        conn.close()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: python -m brdfs.pipeline.zygote SOCKET", file=sys.stderr)
        sys.exit(2)
    serve(sys.argv[1])
