"""One ``brdfs explore`` server per test process, with a user's models imported (``--import``), shared by
the server's and the browser's tests.  It starts at once and is waited for on first use, so that its
start-up overlaps Chromium's."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

USER_MODELS = Path(__file__).with_name("user_models.py")


class ExploreProcess:
    """``brdfs explore --no-browser --port 0 --import tests/explore/user_models.py`` in a subprocess."""

    def __init__(self):
        self.proc = subprocess.Popen([sys.executable, "-m", "brdfs", "explore", "--no-browser", "--port", "0",
                                      "--import", str(USER_MODELS)],
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        self._url = None

    @property
    def url(self) -> str:
        """The base URL, read from the server's 'serving on' line (waiting for it the first time)."""
        while self._url is None:
            line = self.proc.stdout.readline()
            if not line:
                raise AssertionError("brdfs explore did not start")
            if "serving on" in line:
                self._url = line.split("serving on ")[1].split()[0].rstrip("/")
        return self._url

    def stop(self):
        self.proc.terminate()
        self.proc.wait(timeout=10)


@pytest.fixture(scope="session")
def explore_process():
    server = ExploreProcess()
    yield server
    server.stop()


@pytest.fixture(scope="session")
def explore_url(explore_process):
    """Base URL of the shared ``brdfs explore`` server."""
    return explore_process.url
