"""`make lint`: `snakemake --lint`, failing on every message but the one README "Lint" explains.

Snakemake's linter prints one block per rule or Snakefile it objects to::

    Lints for rule artifact (line 14, /…/workflow/rules/artifacts.smk):
        * Specify a conda environment or container for each rule.:
          This way, the used software for each specific step is documented, …

and exits 1 if it printed any. The one message this workflow keeps, on purpose, is the conda
environment per rule (every rule runs the same package in the one environment `make venv` builds
from requirements.lock; README "Checks", "Lint"). Anything else fails: another lint, for any rule
or Snakefile (the one planning mode: `make all` plans as a plain `snakemake` does); a workflow that does
not load; output this script cannot read.

    python workflow/scripts/lint_check.py [--snakemake PATH] [--directory DIR]

Exit status 0 when only the explained message was printed, 1 otherwise, with one line per
unexplained message (and, if Snakemake did not lint, its output).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

# The one lint the README explains: no conda environment or container per rule.
EXPLAINED = "Specify a conda environment or container for each rule."

_ITEM = re.compile(r"^Lints for (?P<item>.+):$")
_TITLE = re.compile(r"^    \* (?P<title>.+):$")
_BODY = re.compile(r"^      \S")
# Lines that are not lints: the profile in use, `--config` on the command line, the all-clear.
_NOISE = re.compile(r"^(Using workflow specific profile .*"
                    r"|Config file .* is extended by additional config specified via the command line\."
                    r"|Congratulations, your workflow is in a good condition!)$")


def lints(text: str) -> tuple[list[tuple[str, str]], list[str]]:
    """The (item, title) of every lint in ``snakemake --lint`` output, and the lines that are none."""
    found, unread, item = [], [], None
    for line in text.splitlines():
        if not line.strip() or _NOISE.match(line):
            continue
        if m := _ITEM.match(line):
            item = m["item"]
        elif (m := _TITLE.match(line)) and item is not None:
            found.append((item, m["title"]))
        elif _BODY.match(line) and item is not None:
            continue
        else:
            unread.append(line)
    return found, unread


def unexplained(text: str, returncode: int) -> list[str]:
    """One line per problem in one ``snakemake --lint`` run: every lint but EXPLAINED, and any
    sign that the linter did not run through (an exit status other than 0 or 1, output that is not
    a lint, exit status 1 without a lint)."""
    found, unread = lints(text)
    problems = [f"{item}: {title}" for item, title in found if title != EXPLAINED]
    problems += [f"unexpected output: {line}" for line in unread]
    if returncode not in (0, 1) or (returncode == 1 and not found):
        problems.append(f"snakemake --lint exited with status {returncode} without linting")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--snakemake", default=str(Path(sys.executable).with_name("snakemake")))
    parser.add_argument("--directory", default=".", help="the workflow to lint (default: here)")
    args = parser.parse_args(argv)
    env = {**os.environ, "COLUMNS": "200"}
    run = subprocess.run([args.snakemake, "--lint"], cwd=args.directory, env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    problems = unexplained(run.stdout, run.returncode)
    for problem in problems:
        print(f"lint: {problem}")
    if problems and not lints(run.stdout)[0]:
        print(run.stdout, end="")
    if problems:
        print(f"lint: FAILED, messages other than \"{EXPLAINED}\" (README, Checks, Lint)")
        return 1
    print(f"lint: only \"{EXPLAINED}\" (explained in README, Checks, Lint)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
