"""Headless Chromium for the browser checks (report_check.py, docs_check.py): Debian's chromium, which
`make chromium` installs, started with no network chatter and a fresh profile per run."""
from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--hide-scrollbars",
]


def chromium(check: str) -> str:
    """The browser's path; exits with one line naming ``check`` (e.g. ``docs-check``) when there is none."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit(f"{check}: no chromium found; run `make chromium` first")


def run_chromium(check: str, args: list[str], profile: Path, budget_ms: int, timeout: int) -> subprocess.CompletedProcess:
    """Chromium on ``args`` with the profile directory ``profile`` and a virtual-time budget."""
    command = [chromium(check), *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--virtual-time-budget={budget_ms}", *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout)
