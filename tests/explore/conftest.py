"""One ``brdfs explore`` server per test process, with a user's models imported (``--import``), shared by
the server's and the browser's tests."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

USER_MODELS = Path(__file__).with_name("user_models.py")


@pytest.fixture(scope="session")
def explore_url():
    """Base URL of ``brdfs explore --no-browser --port 0 --import tests/explore/user_models.py``."""
    proc = subprocess.Popen([sys.executable, "-m", "brdfs", "explore", "--no-browser", "--port", "0",
                             "--import", str(USER_MODELS)],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        for line in proc.stdout:
            if "serving on" in line:
                yield line.split("serving on ")[1].split()[0].rstrip("/")
                break
        else:
            raise AssertionError("brdfs explore did not start")
    finally:
        proc.terminate()
        proc.wait(timeout=10)
