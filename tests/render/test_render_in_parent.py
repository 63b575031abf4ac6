"""A render job in the pre-loaded parent of ``make all`` (brdfs.pipeline.zygote) writes the same bytes
(CSV, PNG, OpenEXR) as the same job in a process of its own, and the parent holds no Dr.Jit or Mitsuba:
its forked child starts them itself (issue 42: the renders' start-up)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import yaml

from brdfs.pipeline import job, registry, zygote

ROOT = Path(__file__).resolve().parents[2]
#: The cheapest render (direct light from point lights), at a tiny preset below.
NAME = "fig_4_18_generalized_lambert"


def _job(where: Path) -> dict:
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    config["renders"]["preview"].update(min_width=48, min_height=32, spp=8)
    return dict(name=NAME, log=str(where / "job.log"), outputs=list(registry.get_artifact(NAME).outputs), tables=[],
                config=config)


def _run_in_parent(where: Path, sock: Path) -> str:
    """The job as ``workflow/scripts/artifact.py`` runs it, from a fresh process in ``where``, through
    the parent at ``sock``."""
    code = textwrap.dedent(f"""
        import pickle
        from brdfs.pipeline import zygote
        print("ran in the parent" if zygote.run_in_zygote(pickle.loads({pickle.dumps(_job(where))!r})) else "no parent")
    """)
    env = {k: v for k, v in os.environ.items() if k != zygote.ENV}
    env.update(PYTHONPATH=str(ROOT / "src"), MPLBACKEND="Agg", **{zygote.ENV: str(sock)})
    done = subprocess.run([sys.executable, "-c", code], cwd=where, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip().splitlines()[-1]


def _outputs(where: Path) -> dict[str, bytes]:
    return {str(p.relative_to(where)): p.read_bytes() for p in sorted((where / "results").rglob("*"))
            if p.is_file() and p.name != "timing.json"}


def test_a_render_job_in_the_parent_writes_the_bytes_of_a_render_job_in_its_own_process(mitsuba, tmp_path,
                                                                                         monkeypatch):
    sock = tmp_path / "parent.sock"
    env = {k: v for k, v in os.environ.items() if k != zygote.ENV}
    env["PYTHONPATH"] = str(ROOT / "src")
    parent = subprocess.Popen([sys.executable, "-m", "brdfs.pipeline.zygote", str(sock)], cwd=ROOT, env=env)
    try:
        deadline = time.monotonic() + 60
        while not sock.exists():
            assert parent.poll() is None, "the parent exited"
            assert time.monotonic() < deadline, "the parent did not listen within 60 s"
            time.sleep(0.05)
        maps = Path(f"/proc/{parent.pid}/maps").read_text()
        assert "drjit" not in maps and "mitsuba" not in maps, "the parent loaded Dr.Jit or Mitsuba"
        alone, forked = tmp_path / "alone", tmp_path / "forked"
        alone.mkdir()
        forked.mkdir()
        assert _run_in_parent(forked, sock) == "ran in the parent"
        monkeypatch.chdir(alone)
        job.run(**_job(alone))          # in this process, as a job without the parent runs
    finally:
        parent.kill()
        parent.wait()
    expected = _outputs(alone)
    assert {Path(p).suffix for p in expected} >= {".csv", ".png", ".exr"}
    assert _outputs(forked) == expected
