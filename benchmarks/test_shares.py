"""Each issue's share of the test suite: which tests an issue added or changed since a base commit,
and what they cost in wall and CPU seconds.

Issues 40, 41 and 42 each set a budget for the tests they add (40: at most 12 s, 41: at most 8 s, 42:
render tests no slower than at the base). This script keeps the attribution and the measurement in
one place::

    # which test functions each issue added or changed since e0ba585 (git blame of their lines)
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py attribute [--base e0ba585]

    # run each issue's tests (alone, one process) and report wall and CPU seconds; with --old, the
    # changed ones also in a checkout of the base (run there with its own src/)
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py measure --issues 40 41 [--repeat 3] [--old DIR]

    # sum per issue the per-test records of a whole-suite run (make test with the recording plugin)
    PYTHONPATH=src:benchmarks .venv/bin/python -m pytest -n 2 -p test_shares --shares-out /tmp/rec
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py suite /tmp/rec

    # an issue's tests (new, changed and removed) in several checkouts, alternately
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py trees --issue 40 --repeat 2 \
        base=/work/old-e0ba585 before=/tmp/before here=.

    # the costliest test functions of that run (existing at the base), here and at the base
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py compare /tmp/rec --old /work/old-e0ba585 --top 40

    # the render tests now and in a checkout of the base (run there with its own src)
    PYTHONPATH=src .venv/bin/python benchmarks/test_shares.py render --old /work/old-e0ba585

Attribution: a test function (module level or in a class) is *new* when the base has no function of
that name in that file, *changed* when its source (decorators included) differs. A new test belongs
to the issue of the commit that added its ``def``; a changed one to the issues of the commits that git
blame gives for its lines since the base; a removed one (a function of the base no longer
there, often merged into another) to the issue of the commit that removed its ``def``; a commit's issue is the number its
message names ("issue 40", "issue 39/40"), else that of the branch it was merged from ("Merge branch
's3-41'"); commits named by neither are "other". A parametrized function counts with all its cases.

Timing: the recording plugin (``-p test_shares``) times every test's setup, call and teardown by the
wall clock and by CPU time, the process's own (every thread) plus that of the children it waited for
(``resource.getrusage``), so a test that spawns ``snakemake`` pays for it. On a shared, loaded machine
the CPU time is the steadier figure; both are reported. A share is the sum over the issue's tests of
setup + call + teardown: what they add to a serial run, collection and interpreter start excluded
(``measure`` prints those apart, as the whole process's time).
"""

from __future__ import annotations

import argparse
import ast
import json
import os
import re
import resource
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BASE = "e0ba585"
BUDGETS = {"40": "at most 12 s added", "41": "at most 8 s added", "42": "render tests no slower than at the base"}
RENDER_TESTS = ("tests/render", "tests/artifacts/test_render_figures.py",
                "tests/physics/test_models_protocol.py::test_a_user_model_renders_as_a_material_and_shows_sky_times_albedo")


# ----------------------------------------------------------------------------- the recording plugin

def _cpu() -> float:
    """CPU seconds of this process (all threads) and of the children it has waited for."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


class _Recorder:
    def __init__(self, out: Path):
        self.out = out
        self.records: dict[str, dict[str, float]] = defaultdict(lambda: {"wall": 0.0, "cpu": 0.0})

    def _timed(self, item):
        wall, cpu = time.perf_counter(), _cpu()
        yield
        record = self.records[item.nodeid]
        record["wall"] += time.perf_counter() - wall
        record["cpu"] += _cpu() - cpu

    def write(self, worker: str) -> None:
        self.out.mkdir(parents=True, exist_ok=True)
        (self.out / f"records-{worker}.json").write_text(json.dumps(self.records, indent=0))


def pytest_addoption(parser):
    parser.addoption("--shares-out", default=None, help="directory for per-test wall/CPU records (test_shares)")


def pytest_configure(config):
    out = config.getoption("--shares-out", default=None)
    if out:
        recorder = _Recorder(Path(out))
        config._shares_recorder = recorder

        class _Hooks:
            @pytest.hookimpl(hookwrapper=True)
            def pytest_runtest_setup(self, item):
                yield from recorder._timed(item)

            @pytest.hookimpl(hookwrapper=True)
            def pytest_runtest_call(self, item):
                yield from recorder._timed(item)

            @pytest.hookimpl(hookwrapper=True)
            def pytest_runtest_teardown(self, item):
                yield from recorder._timed(item)

        config.pluginmanager.register(_Hooks(), "test_shares_hooks")


def pytest_sessionfinish(session):
    recorder = getattr(session.config, "_shares_recorder", None)
    if recorder is not None and recorder.records:
        recorder.write(os.environ.get("PYTEST_XDIST_WORKER", "main"))


def read_records(out: Path) -> dict[str, dict[str, float]]:
    records: dict[str, dict[str, float]] = {}
    for path in sorted(out.glob("records-*.json")):
        records.update(json.loads(path.read_text()))
    return records


# ----------------------------------------------------------------------------- attribution

def _git(*args: str, cwd: Path = ROOT) -> str:
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True).stdout


def _issues_of_message(message: str) -> set[str]:
    first = message.splitlines()[0] if message else ""
    found = set()
    for match in re.finditer(r"\bissues? ((?:\d+[/, ]*(?:and )?)+)", first):
        found |= set(re.findall(r"\d+", match.group(1)))
    return found


def commit_issues(base: str) -> dict[str, set[str]]:
    """Each commit since ``base`` -> the issues it belongs to (its message, else its merged branch)."""
    issues: dict[str, set[str]] = {}
    log = _git("log", "--format=%H%x00%P%x00%s%x1e", f"{base}..HEAD")
    entries = [e.strip("\n").split("\x00") for e in log.split("\x1e") if e.strip()]
    for sha, _parents, subject in entries:
        issues[sha] = _issues_of_message(subject)
    for sha, parents, subject in entries:
        parents = parents.split()
        branch = re.match(r"Merge branch '(?:s\d+-|issue-)(\d+)", subject)
        if len(parents) == 2 and branch:
            for merged in _git("rev-list", f"{parents[0]}..{parents[1]}").split():
                if not issues.get(merged):
                    issues[merged] = {branch.group(1)}
            issues[sha] = issues[sha] or {branch.group(1)}
    return issues


def _test_functions(source: str) -> dict[str, tuple[int, int, str]]:
    """``name`` or ``Class::name`` -> (first line, last line, source with decorators) of each test."""
    tree = ast.parse(source)
    lines = source.splitlines()
    found = {}

    def add(node, prefix=""):
        first = min([node.lineno] + [d.lineno for d in node.decorator_list])
        found[prefix + node.name] = (first, node.end_lineno, "\n".join(lines[first - 1:node.end_lineno]))

    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name.startswith("test"):
            add(node)
        elif isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
            for inner in node.body:
                if isinstance(inner, (ast.FunctionDef, ast.AsyncFunctionDef)) and inner.name.startswith("test"):
                    add(inner, node.name + "::")
    return found


def _blamed_commits(path: str, first: int, last: int, base: str) -> set[str]:
    out = _git("blame", "--porcelain", "-w", "-L", f"{first},{last}", f"{base}..HEAD", "--", path)
    commits = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and re.fullmatch(r"[0-9a-f]{40}", parts[0]):
            commits.add(parts[0])
    boundary = {line.split()[0] for line in out.splitlines() if line.startswith("boundary")}
    return commits - boundary


def _introducing_commit(path: str, function: str, base: str) -> str:
    """The first commit since ``base`` whose diff adds ``def function(`` to ``path``."""
    found = _git("log", "--reverse", "--format=%H", "-S", f"def {function}(", f"{base}..HEAD", "--", path).split()
    return found[0] if found else ""


def attribute(base: str = BASE) -> list[dict]:
    """One row per test function added or changed since ``base``: file, name, status, issues."""
    issues = commit_issues(base)
    base_sha = _git("rev-parse", base).strip()
    rows = []
    changed_files = _git("diff", "--name-only", "--diff-filter=AM", f"{base}..HEAD", "--", "tests/").split()
    for path in changed_files:
        if not (path.endswith(".py") and Path(path).name.startswith("test_")):
            continue
        now = _test_functions((ROOT / path).read_text())
        try:
            before = _test_functions(_git("show", f"{base}:{path}"))
        except subprocess.CalledProcessError:
            before = {}
        for name, (first, last, source) in now.items():
            if name in before and before[name][2] == source:
                continue
            if name in before:
                commits = _blamed_commits(path, first, last, base) - {base_sha}
            else:
                commits = {_introducing_commit(path, name.split("::")[-1], base)}
            owners = sorted({i for c in commits for i in issues.get(c, set())} or {"other"}, key=str)
            rows.append({"nodeid": f"{path}::{name}", "status": "new" if name not in before else "changed",
                         "issues": owners})
        for name in sorted(set(before) - set(now)):   # removed (or merged into another test)
            found = _git("log", "--format=%H", "-S", f"def {name.split('::')[-1]}(", f"{base}..HEAD", "--", path).split()
            owners = sorted(issues.get(found[0], set()) if found else set(), key=str) or ["other"]
            rows.append({"nodeid": f"{path}::{name}", "status": "removed", "issues": owners})
    return rows


def by_issue(rows: list[dict]) -> dict[str, list[dict]]:
    grouped = defaultdict(list)
    for row in rows:
        for issue in row["issues"]:
            grouped[issue].append(row)
    return dict(sorted(grouped.items()))


def _matches(nodeid: str, function_id: str) -> bool:
    """A recorded node id (with its parameters) belongs to a function id ``file::[Class::]name``."""
    return nodeid == function_id or nodeid.startswith(function_id + "[")


# ----------------------------------------------------------------------------- measurement

def run_pytest(nodeids: list[str], out: Path, cwd: Path = ROOT, src: Path | None = None,
               extra: tuple[str, ...] = ()) -> tuple[float, float, int]:
    """Run pytest serially on ``nodeids`` with the recording plugin; the process's wall, CPU, exit code."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(src or cwd / "src"), str(ROOT / "benchmarks")])}
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:xdist", "-p", "test_shares",
               "--shares-out", str(out), *extra, *nodeids]
    before, wall = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    run = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if run.returncode != 0:
        print(run.stdout[-3000:], run.stderr[-3000:], sep="\n", file=sys.stderr)
    return wall, cpu, run.returncode


def _defined_in(tree: Path, function_id: str) -> bool:
    """Whether the checkout ``tree`` defines the test function ``file::[Class::]name``."""
    path, name = function_id.split("::", 1)
    try:
        return name in _test_functions((tree / path).read_text())
    except FileNotFoundError:
        return False


def share(records: dict[str, dict[str, float]], function_ids: list[str]) -> tuple[float, float, int]:
    """Summed wall and CPU seconds of the recorded tests of ``function_ids``, and their count."""
    chosen = [r for nodeid, r in records.items() if any(_matches(nodeid, f) for f in function_ids)]
    return sum(r["wall"] for r in chosen), sum(r["cpu"] for r in chosen), len(chosen)


def _print_share(label: str, wall: float, cpu: float, count: int, process: tuple[float, float] | None = None) -> None:
    line = f"{label:<28} {count:>5} tests  wall {wall:7.2f} s  CPU {cpu:7.2f} s"
    if process is not None:
        line += f"   (whole process: wall {process[0]:6.1f} s, CPU {process[1]:6.1f} s)"
    print(line)


def _slowest(records: dict[str, dict[str, float]], function_ids: list[str], count: int) -> None:
    chosen = sorted(((r["cpu"], r["wall"], n) for n, r in records.items()
                     if any(_matches(n, f) for f in function_ids)), reverse=True)[:count]
    for cpu, wall, nodeid in chosen:
        print(f"    CPU {cpu:6.2f} s  wall {wall:6.2f} s  {nodeid}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    p = commands.add_parser("attribute", help="list each issue's new and changed tests")
    p.add_argument("--base", default=BASE)
    p.add_argument("--json", type=Path, help="also write the rows as JSON")
    p = commands.add_parser("measure", help="run each issue's tests alone and report their share")
    p.add_argument("--base", default=BASE)
    p.add_argument("--issues", nargs="+", default=sorted(BUDGETS))
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--slowest", type=int, default=8)
    p.add_argument("--out", type=Path, default=Path("/tmp/test_shares"))
    p.add_argument("--old", type=Path, help="a checkout of the base: run the changed tests there too")
    p = commands.add_parser("suite", help="sum per issue the records of a whole-suite run")
    p.add_argument("records", type=Path)
    p.add_argument("--base", default=BASE)
    p.add_argument("--slowest", type=int, default=5)
    p = commands.add_parser("trees", help="an issue's tests (new, changed, removed) in several checkouts")
    p.add_argument("--issue", required=True)
    p.add_argument("--base", default=BASE)
    p.add_argument("trees", nargs="+", metavar="LABEL=DIR", help="checkouts, each run with its own src/")
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--out", type=Path, default=Path("/tmp/test_shares_trees"))
    p = commands.add_parser("compare", help="the costliest tests of a suite run (existing here and at the base), here and at the base")
    p.add_argument("records", type=Path)
    p.add_argument("--old", type=Path, required=True, help="a checkout of the base (run with its own src/)")
    p.add_argument("--base", default=BASE)
    p.add_argument("--top", type=int, default=40)
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--out", type=Path, default=Path("/tmp/test_shares_compare"))
    p = commands.add_parser("render", help="the render tests here and in a checkout of the base")
    p.add_argument("--old", type=Path, required=True, help="a checkout of the base (run with its own src/)")
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--out", type=Path, default=Path("/tmp/test_shares_render"))
    args = parser.parse_args(argv)

    if args.command == "attribute":
        rows = attribute(args.base)
        for issue, chosen in by_issue(rows).items():
            print(f"issue {issue}: {sum(r['status'] == 'new' for r in chosen)} new, "
                  f"{sum(r['status'] == 'changed' for r in chosen)} changed, "
                  f"{sum(r['status'] == 'removed' for r in chosen)} removed test functions")
            for row in chosen:
                print(f"    {row['status']:<8} {row['nodeid']}" + (f"  (with {', '.join(i for i in row['issues'] if i != issue)})"
                                                                if len(row["issues"]) > 1 else ""))
        if args.json:
            args.json.write_text(json.dumps(rows, indent=1))
        return 0

    if args.command == "measure":
        grouped = by_issue(attribute(args.base))
        status = 0
        for issue in args.issues:
            ids = [r["nodeid"] for r in grouped.get(issue, [])]
            removed = [r["nodeid"] for r in grouped.get(issue, []) if r["status"] == "removed"]
            ids = [i for i in ids if i not in removed]
            new = [r["nodeid"] for r in grouped.get(issue, []) if r["status"] == "new"]
            changed = [r["nodeid"] for r in grouped.get(issue, []) if r["status"] == "changed"]
            for attempt in range(args.repeat):
                out = args.out / f"issue-{issue}-{attempt}"
                for stale in out.glob("records-*.json"):
                    stale.unlink()
                wall, cpu, code = run_pytest(ids, out)
                status |= code
                records = read_records(out)
                _print_share(f"issue {issue} run {attempt + 1}", *share(records, ids), process=(wall, cpu))
                _print_share("    new tests", *share(records, new))
                _print_share("    changed tests", *share(records, changed))
                if args.old and changed + removed:   # what they cost at the base, run in its checkout
                    old = args.out / f"issue-{issue}-{attempt}-base"
                    for stale in old.glob("records-*.json"):
                        stale.unlink()
                    wall, cpu, code = run_pytest(changed + removed, old, cwd=args.old)
                    _print_share("    changed and removed tests at the base", *share(read_records(old), changed + removed),
                                 process=(wall, cpu))
            _slowest(records, ids, args.slowest)
            print(f"    budget: {BUDGETS.get(issue, '-')}")
        return status

    if args.command == "suite":
        records = read_records(args.records)
        print(f"{'whole suite':<28} {len(records):>5} tests  wall {sum(r['wall'] for r in records.values()):7.2f} s"
              f"  CPU {sum(r['cpu'] for r in records.values()):7.2f} s  (summed over tests)")
        for issue, chosen in by_issue(attribute(args.base)).items():
            ids = [r["nodeid"] for r in chosen if r["status"] != "removed"]
            new = [r["nodeid"] for r in chosen if r["status"] == "new"]
            _print_share(f"issue {issue}", *share(records, ids))
            _print_share(f"issue {issue} (new only)", *share(records, new))
            _slowest(records, ids, args.slowest)
        render = [n for n in records if n.startswith(RENDER_TESTS)]
        _print_share("render tests", *share(records, render))
        return 0

    if args.command == "trees":
        chosen = sorted({r["nodeid"] for r in attribute(args.base) if args.issue in r["issues"]})
        trees = [t.split("=", 1) for t in args.trees]
        present = {label: [f for f in chosen if _defined_in(Path(path), f)] for label, path in trees}
        cost = {label: defaultdict(lambda: [0.0, 0.0]) for label, _ in trees}
        for attempt in range(args.repeat):
            for label, path in trees:
                out = args.out / f"{label}-{attempt}"
                for stale in out.glob("records-*.json"):
                    stale.unlink()
                wall, cpu, _ = run_pytest(present[label], out, cwd=Path(path))
                records = read_records(out)
                _print_share(f"{label} run {attempt + 1}", *share(records, present[label]), process=(wall, cpu))
                for nodeid, record in records.items():
                    entry = cost[label][nodeid.split("[")[0]]
                    entry[0] += record["wall"] / args.repeat
                    entry[1] += record["cpu"] / args.repeat
        print("mean CPU seconds per test function: " + "  ".join(f"{label:>8}" for label, _ in trees))
        for function in chosen:
            cells = "  ".join(f"{cost[label][function][1]:8.2f}" if function in present[label] else f"{'-':>8}"
                              for label, _ in trees)
            print(f"{cells}  {function}")
        print("  ".join(f"{sum(c[1] for c in cost[label].values()):8.2f}" for label, _ in trees) + "  in all (CPU)")
        print("  ".join(f"{sum(c[0] for c in cost[label].values()):8.2f}" for label, _ in trees) + "  in all (wall)")
        return 0

    if args.command == "compare":
        functions = defaultdict(float)
        for nodeid, record in read_records(args.records).items():
            functions[nodeid.split("[")[0]] += record["cpu"]
        at_base = []
        for function in sorted(functions, key=functions.get, reverse=True):
            path, name = function.split("::", 1)
            try:
                known = _test_functions(_git("show", f"{args.base}:{path}"))
                here_too = _test_functions((ROOT / path).read_text())
            except (subprocess.CalledProcessError, FileNotFoundError):
                continue
            if name in known and name in here_too:
                at_base.append(function)
            if len(at_base) == args.top:
                break
        here, base = defaultdict(float), defaultdict(float)
        for attempt in range(args.repeat):
            for label, cwd, into in (("base", args.old, base), ("here", ROOT, here)):
                out = args.out / f"{label}-{attempt}"
                for stale in out.glob("records-*.json"):
                    stale.unlink()
                run_pytest(at_base, out, cwd=cwd)
                for nodeid, record in read_records(out).items():
                    into[nodeid.split("[")[0]] += record["cpu"] / args.repeat
        print(f"{'CPU here':>9} {'at base':>8} {'change':>8}  test (the {len(at_base)} costliest of the suite run "
              f"that exist at the base)")
        for function in sorted(at_base, key=lambda f: here[f] - base[f], reverse=True):
            print(f"{here[function]:9.2f} {base[function]:8.2f} {here[function] - base[function]:+8.2f}  {function}")
        print(f"{sum(here.values()):9.2f} {sum(base.values()):8.2f} {sum(here.values()) - sum(base.values()):+8.2f}  in all")
        return 0

    if args.command == "render":
        status = 0
        for attempt in range(args.repeat):
            for label, cwd in (("render tests, base", args.old), ("render tests, here", ROOT)):
                out = args.out / f"{label.split(', ')[1]}-{attempt}"
                for stale in out.glob("records-*.json"):
                    stale.unlink()
                wall, cpu, code = run_pytest(list(RENDER_TESTS), out, cwd=cwd)
                status |= code
                records = read_records(out)
                _print_share(f"{label} run {attempt + 1}", sum(r["wall"] for r in records.values()),
                             sum(r["cpu"] for r in records.values()), len(records), process=(wall, cpu))
        return status
    return 2


if __name__ == "__main__":
    sys.exit(main())
