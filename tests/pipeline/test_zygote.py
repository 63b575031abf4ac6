"""The pre-loaded parent of the artifact jobs (brdfs.pipeline.zygote): the same bytes as a job run in
its own process (a table-like figure, and a render: CSV, PNG and OpenEXR), a parent that holds no Dr.Jit
or Mitsuba (its forked child starts them itself: ``import drjit`` starts threads, which must not be
forked), a failing job's status and traceback on the job's side, a job killed while its child runs takes
the child with it, and no parent means the job runs itself."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
import yaml

from brdfs.pipeline import job, registry, zygote

ROOT = Path(__file__).resolve().parents[2]
NAME = "fig_4_2_base_circle_relations"  # no inputs, ~0.3 s
#: The cheapest render (direct light from point lights), at a tiny preset (:func:`_job`).
RENDER = "fig_4_18_generalized_lambert"


@pytest.fixture(scope="module")
def parent(tmp_path_factory):
    """A running parent on a socket of its own, and its process; killed at the end."""
    sock = tmp_path_factory.mktemp("zygote") / "z.sock"
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    env.pop(zygote.ENV, None)
    proc = subprocess.Popen([sys.executable, "-m", "brdfs.pipeline.zygote", str(sock)], cwd=ROOT, env=env)
    try:
        deadline = time.monotonic() + 60
        while not sock.exists():
            assert proc.poll() is None, "the parent exited"
            assert time.monotonic() < deadline, "the parent did not listen within 60 s"
            time.sleep(0.05)
        yield sock, proc
    finally:                   # a parent that failed to listen is not left behind
        proc.kill()
        proc.wait()


def _job(where: Path, name: str = NAME) -> dict:
    artifact = registry.get_artifact(name)
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    config["renders"]["preview"].update(min_width=48, min_height=32, spp=8)
    return dict(name=name, log=str(where / "job.log"), outputs=list(artifact.outputs), tables=[], config=config)


def _outputs(where: Path) -> dict[str, bytes]:
    return {str(p.relative_to(where)): p.read_bytes() for p in sorted((where / "results").rglob("*"))
            if p.is_file() and p.name != "timing.json"}


def _client(where: Path, sock: Path, job_: dict) -> subprocess.Popen:
    """A job process like workflow/scripts/artifact.py, in ``where``, talking to the parent."""
    code = textwrap.dedent(f"""
        import pickle, sys
        from brdfs.pipeline import zygote
        job = pickle.loads({repr(__import__('pickle').dumps(job_))})
        print("ran in the parent" if zygote.run_in_zygote(job) else "no parent")
    """)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), **{zygote.ENV: str(sock)})
    return subprocess.Popen([sys.executable, "-c", code], cwd=where, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


@pytest.mark.parametrize("name, suffixes", [(NAME, {".csv", ".png"}), (RENDER, {".csv", ".png", ".exr"})])
def test_a_job_in_the_parent_writes_the_same_bytes_as_a_job_in_its_own_process(parent, tmp_path, monkeypatch,
                                                                               name, suffixes):
    if name == RENDER:
        _mitsuba_or_skip()
    alone, forked = tmp_path / "alone", tmp_path / "forked"
    alone.mkdir()
    forked.mkdir()
    client = _client(forked, parent[0], _job(forked, name))
    out, err = client.communicate(timeout=120)
    assert client.returncode == 0, err
    assert out.strip() == "ran in the parent"
    monkeypatch.chdir(alone)
    job.run(**_job(alone, name))
    expected = _outputs(alone)
    assert {Path(path).suffix for path in expected} >= suffixes
    assert _outputs(forked) == expected


def _mitsuba_or_skip() -> None:
    from brdfs.render.mitsuba import MissingLLVM, use_variant
    try:
        use_variant("llvm_ad_rgb")
    except MissingLLVM as exc:
        pytest.skip(str(exc))


def test_the_parent_holds_no_drjit_nor_mitsuba(parent):
    maps = Path(f"/proc/{parent[1].pid}/maps").read_text()
    assert "drjit" not in maps and "mitsuba" not in maps, "the parent loaded Dr.Jit or Mitsuba"


def test_a_failing_job_in_the_parent_fails_its_job_with_the_traceback_on_the_jobs_stderr(parent, tmp_path):
    bad = dict(_job(tmp_path), name="no_such_artifact_anywhere")
    client = _client(tmp_path, parent[0], bad)
    out, err = client.communicate(timeout=120)
    assert client.returncode != 0
    assert "no_such_artifact_anywhere" in err and "Traceback" in err
    assert not (tmp_path / "results").exists()


def test_a_job_killed_while_its_child_runs_takes_the_child_with_it(parent, tmp_path):
    """The child watches its job's connection: SIGKILL of the job ends the child before it writes
    (sampling_chi2 computes for seconds; the child is seen alive when its job is killed)."""
    sock, proc = parent
    slow = dict(_job(tmp_path), name="sampling_chi2",
                outputs=list(registry.get_artifact("sampling_chi2").outputs))
    client = _client(tmp_path, sock, slow)
    deadline = time.monotonic() + 30
    while not (children := _children(proc.pid)):
        assert time.monotonic() < deadline and client.poll() is None, "no child started"
        time.sleep(0.01)
    client.send_signal(signal.SIGKILL)
    client.wait()
    deadline = time.monotonic() + 10
    while _children(proc.pid) & children:
        assert time.monotonic() < deadline, "a child outlived its killed job"
        time.sleep(0.02)
    assert not (tmp_path / "results" / "checks" / "sampling_chi2.csv").exists()


def _children(pid: int) -> set[int]:
    """The live (not zombie) children of ``pid``."""
    out = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout
    alive = set()
    for child in map(int, out.split()):
        try:
            if Path(f"/proc/{child}/stat").read_text().split()[2] != "Z":
                alive.add(child)
        except FileNotFoundError:
            pass
    return alive


def test_without_a_parent_the_job_runs_itself(tmp_path, monkeypatch):
    monkeypatch.delenv(zygote.ENV, raising=False)
    assert zygote.run_in_zygote({"name": NAME}) is False
    monkeypatch.setenv(zygote.ENV, str(tmp_path / "nobody_listens.sock"))
    assert zygote.run_in_zygote({"name": NAME}) is False
