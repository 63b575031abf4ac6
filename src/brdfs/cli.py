"""The ``brdfs`` command line: the package's front doors from a shell.

::

    brdfs models                                  # names, parameters, ranges, strategies
    brdfs albedo phong --param n=20 --theta 0:90:15
    brdfs albedo ggx --param alpha=0.3 --theta 60 --json
    brdfs chi2 phong_cosmin --param n=128 --theta 30,80
    brdfs compare                                 # printed numbers that reproduce / differ, by chapter
    brdfs explore --no-browser --port 8123        # the BRDF explorer in the browser (brdfs.explore)
    brdfs lut ggx --param alpha=0.01:1:32 --mu 32 -o ggx.npy   # E(mu, alpha), E_avg(alpha) for renderers
    brdfs --import my_model.py albedo my_model --param n=20 --theta 0,60   # a model of your own

``--import MODULE_OR_FILE`` (repeatable, before the sub-command) imports a module or a ``.py`` file
that registers models (:func:`brdfs.user_models.import_models`); the models of installed packages
(entry-point group ``brdfs.models``) are loaded first.  ``--param`` takes ``KEY=VALUE`` pairs, several
after one ``--param`` or the option repeated; a key given twice is refused.

``--theta`` takes one angle, a comma-separated list, or ``start:stop:step`` with the stop included.
Every error (an unknown model or method, a bad parameter, option or angle) prints the usage line
and one ``error:`` line naming the argument and its value, and exits with status 2.  The
computations are :func:`brdfs.albedo` (one call per angle, so that ``evaluations`` is the angle's
own cost), :func:`brdfs.numerics.chi2.chi2_test` and the pipeline's
``results/checks/published_comparison.csv``; only the standard library and the package's core
(numpy, scipy) are imported.

``brdfs albedo`` and ``brdfs lut`` show a progress bar on standard error when it is a terminal and
the run has lasted 2 s (``BRDFS_PROGRESS_AFTER`` seconds, if set), nothing when it is piped: the
engine's chunk loop reports to it (:func:`brdfs.numerics.albedo.reporting_progress`).
"""
from __future__ import annotations

import argparse
import csv
import inspect
import json
import math
import os
import re
import sys
import time
import warnings
from collections import Counter
from pathlib import Path

import numpy as np

EXIT_USAGE = 2
_NUMBER = re.compile(r"^[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?$|^[+-]?(inf|nan)$", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """argparse, with every sub-command's errors as ``usage`` + one ``error:`` line, status 2."""


def _parse_value(text: str):
    """``20`` -> 20, ``1e-3`` -> 0.001, ``none`` -> None, ``true``/``false`` -> bool, else the text."""
    lowered = text.strip().lower()
    if re.fullmatch(r"[+-]?\d+", lowered):
        return int(lowered)
    if _NUMBER.match(lowered):
        return float(lowered)
    return {"none": None, "true": True, "false": False}.get(lowered, text.strip())


def _key_values(pairs, what: str) -> dict:
    """``["n=20", "G=smith"]`` -> ``{"n": 20, "G": "smith"}``; ``what`` names the option in errors.

    ``pairs`` may hold lists (``--param n=20 p=0.5 --param C=1``: one list per option); a key given
    twice is refused.
    """
    texts = {}
    for pair in _flat(pairs):
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise argparse.ArgumentTypeError(f"{what} {pair!r}: expected KEY=VALUE")
        key = key.strip()
        if key in texts:
            raise argparse.ArgumentTypeError(f"{what} {key}: given twice ({key}={texts[key]} and {key}={value.strip()})")
        texts[key] = value.strip()
    return {key: _parse_value(text) for key, text in texts.items()}


def _flat(pairs):
    for item in pairs or ():
        yield from ([item] if isinstance(item, str) else item)


def parse_theta(spec: str) -> np.ndarray:
    """Angles in degrees: ``"60"``, ``"0,30,60"`` or ``"0:90:5"`` (start:stop:step, stop included).

    >>> parse_theta("0:90:30").tolist(), parse_theta("10,20").tolist()
    ([0.0, 30.0, 60.0, 90.0], [10.0, 20.0])
    """
    text = spec.strip()
    try:
        if ":" in text:
            start, stop, step = (float(p) for p in text.split(":"))
            if not (math.isfinite(start) and math.isfinite(stop) and math.isfinite(step)) or step <= 0 or stop < start:
                raise ValueError
            count = int(math.floor((stop - start) / step + 1e-9)) + 1
            return start + step * np.arange(count)
        values = [float(p) for p in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--theta {spec!r}: expected an angle, a list a,b,c or start:stop:step (step > 0, stop >= start)") from None
    return np.array(values)


# --- brdfs models ------------------------------------------------------------------------------

def _value_text(value) -> str:
    """A parameter value as ``--param`` takes it: ``20`` (not ``20.0``), ``0.5``, ``smith``."""
    if isinstance(value, float):
        return f"{value:.15g}"
    return str(value)


def _not_buildable(cls) -> list[str]:
    """The parameters of ``cls``'s examples that the command line cannot give (Python functions)."""
    return sorted({k for example in cls.examples.values() for k, v in example.items() if callable(v)})


def _model_rows():
    from brdfs.physics.models import MODELS
    rows = []
    for name, cls in MODELS.items():
        ranges = {k: v.text() for k, v in cls.param_ranges.items()}
        choices = {k: list(v) for k, v in getattr(cls, "param_choices", {}).items()}
        texts = dict(cls.param_texts)             # what a parameter takes that is neither a range nor a choice
        unbuildable = _not_buildable(cls)
        typical = cls.examples.get("typical", {})
        rows.append({"model": name, "chapter": str(cls.chapter), "parameters": {**ranges, **choices}, "described": texts,
                     "typical": None if unbuildable else typical,
                     "example_param": None if unbuildable else " ".join(f"{k}={_value_text(v)}"
                                                                        for k, v in typical.items()),
                     "command_line": not unbuildable, "needs_python": unbuildable,
                     "strategies": list(cls.strategies)})
    return rows


def _models(args) -> int:
    rows = _model_rows()
    if args.json:
        print(json.dumps(rows, indent=1))
        return 0
    for row in rows:
        params = ", ".join([*(f"{k}: {v}" for k, v in row["described"].items()),
                            *(f"{k} in {v}" if isinstance(v, str) else f"{k} in {{{', '.join(map(str, v))}}}"
                              for k, v in row["parameters"].items())])
        if row["command_line"]:
            usage = f"e.g. --param {row['example_param']}" if row["example_param"] else "no parameters needed"
        else:
            usage = f"not buildable from the command line ({', '.join(row['needs_python'])}: a Python function)"
        print(f"{row['model']:<24} {params or '(no parameters)'}")
        print(f"{'':<24} {usage}; samplers: {', '.join(row['strategies'])}")
    return 0


# --- progress on a terminal -------------------------------------------------------------------

class _Progress:
    """A one-line progress bar on standard error, drawn only on a terminal and only once the run
    has lasted ``after`` seconds (``BRDFS_PROGRESS_AFTER``, default 2), redrawn at most ten times a
    second, cleared by :meth:`close`.  :meth:`fraction` shows a known share of the work done,
    :meth:`count` a running count (of albedo values) where the total is not known."""

    WIDTH = 30

    def __init__(self, label, stream=None):
        self.label, self.stream = label, sys.stderr if stream is None else stream
        self.on = bool(getattr(self.stream, "isatty", lambda: False)())
        self.after = float(os.environ.get("BRDFS_PROGRESS_AFTER", "2"))
        self.start, self.drawn_at = time.monotonic(), -math.inf
        self.drawn, self.counted, self.last = False, 0, 0

    def fraction(self, done):
        filled = int(self.WIDTH * min(max(done, 0.0), 1.0))
        self._draw(f"[{'#' * filled}{'.' * (self.WIDTH - filled)}] {100 * done:5.1f} %", done >= 1.0)

    def count(self, done, total):
        """An engine callback (``done`` of ``total`` elements of its current call) as a running count."""
        self.counted += done - self.last if done >= self.last else done
        self.last = done
        self._draw(f"{self.counted:,} albedo values", False)

    def _draw(self, text, final):
        now = time.monotonic()
        if not self.on or now - self.start < self.after or (now - self.drawn_at < 0.1 and not final):
            return
        self.drawn_at, self.drawn = now, True
        self.stream.write(f"\r{self.label} {text} {now - self.start:.1f} s\x1b[K")
        self.stream.flush()

    def close(self):
        if self.drawn:
            self.stream.write("\r\x1b[K")
            self.stream.flush()
            self.drawn = False


# --- brdfs albedo ------------------------------------------------------------------------------

def _albedo_rows(model, theta, method, rtol, atol, options):
    import brdfs
    from brdfs.numerics.albedo import reporting_progress
    rows, bar = [], _Progress(f"brdfs albedo {model.name}")
    try:
        for k, t in enumerate(theta):
            with warnings.catch_warnings(record=True) as caught, \
                    reporting_progress(lambda done, total, k=k: bar.fraction((k + done / total) / len(theta))):
                warnings.simplefilter("always")
                est = brdfs.albedo(model, float(t), method=method, rtol=rtol, atol=atol, **options)
            if caught:
                bar.close()                       # the warnings' lines below, not across the bar
            rows.append(_albedo_row(t, est, caught))
    finally:
        bar.close()
    return rows


def _albedo_row(t, est, caught):
    """One angle's row; its warnings on standard error."""
    route = getattr(est, "route", None)
    row = {"theta_deg": float(t), "value": float(est.value), "error": float(est.error),
           "evaluations": int(est.evaluations), "status": str(np.asarray(est.status).item())}
    if route is not None:
        row["route"] = str(np.asarray(route).item()) if np.ndim(route) == 0 or np.size(route) == 1 else str(route)
    for w in caught:
        print(f"brdfs: warning at theta = {t:g} deg: {w.message}", file=sys.stderr)
    return row


def _albedo(args) -> int:
    import brdfs
    model = brdfs.model(args.model, **args.param)
    rows = _albedo_rows(model, args.theta, args.method, args.rtol, args.atol, args.option)
    if args.json:
        print(json.dumps(rows, indent=1))
    elif args.csv:
        writer = csv.DictWriter(sys.stdout, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows({k: repr(v) if isinstance(v, float) else v for k, v in r.items()} for r in rows)
    else:
        extra = ["route"] if "route" in rows[0] else []
        print(f"{'theta_deg':>10} {'value':>20} {'error':>10} {'evaluations':>11} {'status':<16}"
              + "".join(f" {k}" for k in extra))
        for r in rows:
            print(f"{r['theta_deg']:>10.6g} {r['value']:>20.15g} {r['error']:>10.2e} {r['evaluations']:>11d} "
                  f"{r['status']:<16}" + "".join(f" {r[k]}" for k in extra))
    return 0


# --- brdfs chi2 --------------------------------------------------------------------------------

def _chi2(args) -> int:
    import brdfs
    from brdfs.numerics.chi2 import chi2_test
    model = brdfs.model(args.model, **args.param)
    strategy = args.strategy or model.strategies[0]
    if strategy not in model.strategies:
        raise argparse.ArgumentTypeError(
            f"--strategy {strategy!r}: {args.model} samples by one of {list(model.strategies)}")
    rows = []
    for t in args.theta:
        r = chi2_test(model, float(t), strategy=strategy, n_samples=args.samples, seed=args.seed)
        rows.append({"theta_deg": float(t), "strategy": strategy, "statistic": r.statistic, "dof": r.dof,
                     "p_value": r.p_value, "pdf_mass": r.pdf_mass, "accepted_fraction": r.accepted_fraction,
                     "weight_error": r.weight_error, "n_samples": r.n_samples,
                     "passes": bool(r.p_value > args.significance)})
    if args.json:
        print(json.dumps(rows, indent=1))
    else:
        print(f"{'theta_deg':>10} {'strategy':<18} {'chi2':>10} {'dof':>5} {'p_value':>9} {'pdf_mass':>9} "
              f"{'accepted':>9} verdict")
        for r in rows:
            print(f"{r['theta_deg']:>10.6g} {r['strategy']:<18} {r['statistic']:>10.2f} {r['dof']:>5d} "
                  f"{r['p_value']:>9.3g} {r['pdf_mass']:>9.6f} {r['accepted_fraction']:>9.4f} "
                  f"{'passes' if r['passes'] else 'FAILS'} (significance {args.significance:g})")
    return 0 if all(r["passes"] for r in rows) else 1


# --- brdfs compare -----------------------------------------------------------------------------

def _chapter(source: str) -> str:
    m = re.search(r"(\d+)(?:\.\d+)*", source or "")
    return f"chapter {m.group(1)}" if m else "other"


def _compare(args) -> int:
    path = Path(args.results) / "checks" / "published_comparison.csv"
    if not path.is_file():
        raise argparse.ArgumentTypeError(f"--results {args.results!r}: no {path} (build it: make all)")
    with path.open(newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
    used = ("artifact", "source", "model", "param", "param_value", "quantity", "published", "computed", "verdict", "reason")
    if not rows or not set(used) <= set(reader.fieldnames or ()) or any(None in r for r in rows):
        raise ValueError(f"{path}: not a comparison file (no rows, a row too long, or not the columns {', '.join(used)})")
    by_chapter: dict[str, Counter] = {}
    for r in rows:
        by_chapter.setdefault(_chapter(r["source"]), Counter())[r["verdict"]] += 1
    total = Counter(r["verdict"] for r in rows)
    if args.json:
        print(json.dumps({"total": dict(total), "chapters": {k: dict(v) for k, v in sorted(by_chapter.items())},
                          "differing": [{k: r[k] for k in ("artifact", "source", "model", "param", "param_value",
                                                           "quantity", "published", "computed", "reason")}
                                        for r in rows if r["verdict"] != "reproduces"]}, indent=1))
        return 0
    print(f"{len(rows)} printed numbers: " + ", ".join(f"{n} {v}" for v, n in total.most_common()))
    for chapter, counts in sorted(by_chapter.items()):
        print(f"  {chapter:<10} " + ", ".join(f"{n} {v}" for v, n in counts.most_common()))
    if args.differing:
        for r in rows:
            if r["verdict"] != "reproduces":
                print(f"  {r['source']}: {r['quantity']} ({r['model']} {r['param']}={r['param_value']}) printed "
                      f"{r['published']}, computed {float(r['computed']):.6g} -- {r['reason']}")
    return 0


# --- brdfs lut ---------------------------------------------------------------------------------

def _lut(args) -> int:
    from brdfs import lut

    sweeps = [pair for pair in _flat(args.param) if ":" in pair.partition("=")[2]]
    if len(sweeps) != 1:
        raise argparse.ArgumentTypeError(f"--param: give exactly one swept parameter NAME=START:STOP:N, got "
                                         f"{len(sweeps)}" + (f" ({' '.join(sweeps)})" if sweeps else ""))
    param, values = lut.parse_sweep(sweeps[0])
    fixed = _key_values([pair for pair in _flat(args.param) if pair not in sweeps], "--param")
    from brdfs.numerics.albedo import reporting_progress
    start = time.perf_counter()
    bar = _Progress(f"brdfs lut {args.model}")
    try:
        with reporting_progress(bar.count):
            table = lut.albedo_lut(args.model, param, values, n_mu=args.mu, rtol=args.rtol, fixed=fixed)
    finally:
        bar.close()
    path = lut.write(table, args.output, args.format)
    seconds = time.perf_counter() - start
    print(f"wrote {path}: E({param}, mu) {table.E.shape[0]} x {table.E.shape[1]} and E_avg({param}) of {args.model}"
          f" in {seconds:.1f} s; largest error: E {table.E_error.max():.2e}, E_avg {table.E_avg_error.max():.2e}"
          f" (rtol {args.rtol:g})")
    if not table.converged:
        print(f"brdfs: warning: {np.sum(table.E_status != 'converged')} cells and "
              f"{np.sum(table.E_avg_status != 'converged')} averages did not converge to rtol {args.rtol:g}; "
              f"their errors are in the file", file=sys.stderr)
        return 1
    return 0


# --- the parser --------------------------------------------------------------------------------

def _common_model_args(p):
    p.add_argument("model", help="a model name (`brdfs models` lists them)")
    p.add_argument("--param", "-p", action="append", nargs="+", metavar="KEY=VALUE", default=[],
                   help="model parameters, one or more (e.g. --param n=20 p=0.5)")
    p.add_argument("--theta", "-t", type=parse_theta, required=True, metavar="SPEC",
                   help="incidence angles in degrees: 60, a list 0,30,60, or start:stop:step (stop included)")
    output = p.add_mutually_exclusive_group()
    output.add_argument("--json", action="store_true", help="print a JSON list, one object per angle")
    return output


def build_parser() -> argparse.ArgumentParser:
    from brdfs.numerics.albedo import ALBEDO_METHODS
    from brdfs import __version__
    parser = _Parser(prog="brdfs", description="Albedos, samplers and the thesis comparison of the brdfs package.")
    parser.add_argument("--version", action="version", version=f"brdfs {__version__}")
    parser.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE_OR_FILE",
                        help="import a module or a .py file that registers models first (repeatable)")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=_Parser)

    p = sub.add_parser("models", help="list the models: names, parameters and their ranges, samplers")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(run=_models)

    p = sub.add_parser("albedo", help="directional albedo a(theta) with its error estimate",
                       description="Directional albedo a(theta) = integral of f cos theta_V (eq. 1.18) by "
                                   "brdfs.albedo, one call per angle: value, error, evaluations, status.")
    output = _common_model_args(p)
    methods = sorted(ALBEDO_METHODS)
    p.add_argument("--method", "-m", default=_default_method(), choices=methods, metavar="METHOD",
                   help=f"one of {', '.join(methods)} (default: %(default)s)")
    p.add_argument("--rtol", type=float, default=None, help="relative tolerance (default 1e-10)")
    p.add_argument("--atol", type=float, default=None, help="absolute tolerance (default 1e-14)")
    p.add_argument("--option", "-o", action="append", nargs="+", metavar="KEY=VALUE", default=[],
                   help="method options, one or more (e.g. --method monte_carlo --option n_samples=1e5)")
    output.add_argument("--csv", action="store_true", help="print CSV")
    p.set_defaults(run=_albedo)

    p = sub.add_parser("chi2", help="chi-square test of a model's sampler against its pdf",
                       description="Pearson chi-square test of model.sample against model.pdf "
                                   "(brdfs.numerics.chi2.chi2_test); exit status 1 when a test fails.")
    _common_model_args(p)
    p.add_argument("--strategy", "-s", default=None, help="the sampler (default: the model's own first strategy)")
    p.add_argument("--samples", "-n", type=_positive_int, default=100_000, help="samples per angle (default %(default)s)")
    p.add_argument("--seed", type=_seed, default=0, help="random seed, a non-negative integer (default %(default)s)")
    p.add_argument("--significance", type=_open_unit, default=0.01,
                   help="significance level, in (0, 1) (default %(default)s)")
    p.set_defaults(run=_chi2)

    p = sub.add_parser("lut", help="albedo tables for renderers: E(mu, param) and E_avg(param) with errors",
                       description="Directional albedo E(mu, param) at mu = (j + 1/2)/N and its average "
                                   "E_avg = 2 int E mu dmu over a parameter, each cell with its error bound, "
                                   "and the model, parameters, tolerance and version as metadata "
                                   "(brdfs.lut).  The other parameters keep their defaults (GGX: F = 1).")
    p.add_argument("model", help="a model name (`brdfs models` lists them)")
    p.add_argument("--param", "-p", action="append", nargs="+", metavar="KEY=VALUE", default=[], required=True,
                   help="the swept parameter NAME=START:STOP:N (e.g. alpha=0.01:1:32), and any fixed ones KEY=VALUE")
    p.add_argument("--mu", type=_positive_int, default=32, help="cells in mu = cos theta (default %(default)s)")
    p.add_argument("--format", "-f", choices=("npy", "csv", "exr"), default=None,
                   help="npy (a NumPy archive), csv or exr (needs Mitsuba); default: from the file's suffix")
    p.add_argument("--output", "-o", required=True, metavar="FILE", help="the file to write")
    p.add_argument("--rtol", type=float, default=1e-10, help="relative tolerance of every value (default %(default)g)")
    p.set_defaults(run=_lut)

    p = sub.add_parser("compare", help="how many printed numbers reproduce, by chapter (from a build)")
    p.add_argument("--results", default="results", help="the build's results directory (default: %(default)s)")
    p.add_argument("--differing", action="store_true", help="list every number that differs, with its reason")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(run=_compare)

    # the explorer (brdfs.explore); its own --import, like the global one, goes through brdfs.user_models
    p = sub.add_parser("explore", help="an interactive BRDF explorer in the browser (localhost)",
                       description="Serve the BRDF explorer (brdfs.explore): parameters, lobe, certified "
                                   "albedo, lit sphere and (theta_h, theta_d) slice of any registered model.")
    p.add_argument("--port", type=int, default=8123, help="port (default %(default)s; 0: any free port)")
    p.add_argument("--host", default="127.0.0.1",
                   help="address to bind (default %(default)s; any other is your choice, and warned about)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.add_argument("--import", dest="imports", action="append", default=[], metavar="MODULE_OR_FILE",
                   help="a module or .py file registering your own models, repeatable")
    p.set_defaults(run=_explore)
    return parser


def _explore(args) -> int:
    from brdfs.explore import serve
    # main() has imported args.imports already (the global and the sub-command's --import share them)
    return serve(args.host, args.port, open_browser=not args.no_browser)


def _default_method() -> str:
    from brdfs.numerics.albedo import albedo
    return inspect.signature(albedo).parameters["method"].default


def _argument_type(convert, valid, expected: str):
    """An argparse ``type``: ``convert(text)`` where ``valid`` holds, else one line naming ``expected``
    (argparse puts the option's name before it)."""
    def parse(text: str):
        try:
            value = convert(text)
            if valid(value, text):
                return value
        except (ValueError, OverflowError):
            pass
        raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}")
    return parse


_positive_int = _argument_type(lambda t: int(float(t)), lambda v, t: v > 0 and v == float(t), "a positive integer")
_seed = _argument_type(int, lambda v, t: v >= 0, "a non-negative integer")
_open_unit = _argument_type(float, lambda v, t: 0.0 < v < 1.0, "a number in (0, 1)")


def _load_models(parser, imports) -> None:
    """The models of installed packages (entry points ``brdfs.models``), then each ``--import``."""
    from brdfs.user_models import import_models, load_entry_points
    try:
        load_entry_points()
        for spec in imports:
            import_models(spec)
    except ValueError as err:
        parser.error(str(err))


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    _load_models(parser, args.imports)
    try:
        if hasattr(args, "param") and args.command != "lut":
            args.param = _key_values(args.param, "--param")
        if hasattr(args, "option"):
            # 1e5 samples is an integer option's value: an integral number is passed as an int
            args.option = {k: int(v) if isinstance(v, float) and v.is_integer() else v
                           for k, v in _key_values(args.option, "--option").items()}
        return args.run(args)
    except (argparse.ArgumentTypeError, ValueError, TypeError) as err:
        message = str(err).splitlines()[0] if str(err) else type(err).__name__
        parser._subparsers._group_actions[0].choices[args.command].error(message)
    return EXIT_USAGE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
