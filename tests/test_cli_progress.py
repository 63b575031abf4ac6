"""The command line shows its progress on a terminal and nothing when piped (issue 41): a bar on
standard error driven by the engine's chunk loop (``brdfs.numerics.albedo.reporting_progress``).
The 2 s before the bar appears are set to 0 here (``BRDFS_PROGRESS_AFTER``) to keep the runs short."""
import io
import os
import pty
import subprocess
import sys

from brdfs.cli import main

ALBEDO = [sys.executable, "-m", "brdfs", "albedo", "phong", "--param", "n=20", "--theta", "0:80:10"]


def _env():
    src = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")
    return dict(os.environ, BRDFS_PROGRESS_AFTER="0", PYTHONPATH=src)


def test_a_piped_run_shows_no_progress(monkeypatch, capsys):
    monkeypatch.setenv("BRDFS_PROGRESS_AFTER", "0")
    assert main(ALBEDO[3:]) == 0                 # standard error captured: a pipe, not a terminal
    out, err = capsys.readouterr()
    assert err == "" and out.count("engine/azimuthal") == 9


def test_a_run_on_a_terminal_shows_a_progress_bar_on_stderr():
    leader, follower = pty.openpty()
    run = subprocess.Popen(ALBEDO, stdout=subprocess.DEVNULL, stderr=follower, env=_env())
    os.close(follower)
    seen = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:                          # the follower closed: the run is over
            break
        if not chunk:
            break
        seen += chunk
    os.close(leader)
    assert run.wait(timeout=120) == 0
    assert b"brdfs albedo phong [" in seen and b"100.0 %" in seen
    assert seen.endswith(b"\r\x1b[K")            # cleared at the end


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_the_lut_command_counts_the_albedo_values_on_a_terminal(monkeypatch, tmp_path):
    monkeypatch.setenv("BRDFS_PROGRESS_AFTER", "0")
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert main(["lut", "phong", "--param", "n=2:20:2", "--mu", "4", "--rtol", "1e-6", "-o", str(tmp_path / "t.npy")]) == 0
    shown = terminal.getvalue()
    assert "brdfs lut phong" in shown and "albedo values" in shown and shown.endswith("\r\x1b[K")


def test_no_bar_before_the_threshold(monkeypatch, tmp_path):
    monkeypatch.setenv("BRDFS_PROGRESS_AFTER", "1000")
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert main(["albedo", "phong", "--param", "n=20", "--theta", "0:80:10"]) == 0
    assert terminal.getvalue() == ""
