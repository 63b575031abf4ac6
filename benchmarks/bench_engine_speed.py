"""Benchmark: the engine on one angle at a time and at loose tolerances, as ratios measured in one run.

Issue 24, "Fast on one angle and at loose tolerances".  For the five curves of the speed benchmark
(:mod:`bench_albedo_curves`: Phong n = 150, Ward m = 0.1, Cook–Torrance m = 0.1 with eq. 2.10's G,
phong_cosmin n = 128, blinn_cosmin n = 2) it measures, interleaved so that a change of the shared
machine's load hits all alike:

* ``curve_ms_per_point``: one ``albedo`` call on the 100-point curve θ = 0 … 89°, divided by 100;
* ``single_ms_1e-10`` / ``single_ms_1e-6``: the mean over 12 angles of one ``albedo`` call per angle;
* ``single_over_curve`` = single (1e-10) / per-point (target ≤ 5) and ``loose_over_tight`` =
  single (1e-6) / single (1e-10) (target ≤ ½);
* ``single_evals_1e-10`` / ``single_evals_1e-06``: the mean evaluations of those single calls,
  ``single_rounds_1e-10`` / ``single_rounds_1e-06`` their mean driver rounds and
  ``single_root_rounds_1e-10`` / ``single_root_rounds_1e-06`` their mean multisection rounds of the
  kink radii found numerically (exact counts);
* ``floor_ms_*``, ``kernel_ms_*``, ``floor_loose_over_tight``, ``floor_single_over_curve`` and
  ``kernel_loose_over_tight``: the part of a single call spent on its breakpoints and its
  integration, of that on the 1-D route's kernel, the ratios a call would reach with every other cost
  removed, and the kernel's own loose/tight ratio (:func:`_single_floor`).

``--models`` (also part of the default run; ``--only=ggx,phong`` for some) times every registered model at its ``typical`` example the
same way (issue 41, "per-call cost"): ``curve_ms_per_point`` and ``single_ms`` at rtol 1e-10 and 1e-6,
their ratio ``single_over_curve`` (target ≤ 3 for a model on an integral route), and the single call's
CPU ms (target ≤ 0.1 ms for a model whose single calls need no integration, ``closed_form``: its own
route is a closed form; the patch mixtures' own routes integrate, and have the ratio's target).  It
also times the curve points and single calls of commit ``e0ba585`` (:data:`BEFORE`; ``--before=REV``
another, ``--before=`` none) in a child process on that commit's ``src``, between its own timings
(:class:`_CurveAt`): ``curve_ms_before``, ``curve_vs_before`` and ``curve_not_slower`` (the target: no
curve point slower than at e0ba585, within :data:`SLOWER_BEYOND` for the machine's noise), and
``single_over_curve_before`` and ``single_vs_before`` (that commit's ratio, and our single call over
its: a change's before and after in one run, with ``--before=`` the commit it started from).

Each time is the best of ``ROUNDS`` rounds of CPU time (``time.process_time``); in ``--models`` each round's
sample repeats its call for at least :data:`MIN_SAMPLE` s (:func:`_per_call`).  For the Smith-masked models (GGX, Beckmann–Smith at
α = 0.3, Cook–Torrance with the thesis's Smith G at m = 0.3) it reports ``Estimate.evaluations``
(BRDF or kernel values) of single calls at 1e-10 at 12 angles from 0° to 89.9° — median and maximum
(target: median ≤ 5,000) — and the median time.  ``--polar`` (also part of the default run; printed,
not written to the CSV) splits a single call of the polar-route models (GGX, Beckmann) into its parts
(:func:`polar_parts`).  With ``--accuracy-grid`` it times instead the full
3,726-cell accuracy grid (engine and disk certifier apart, CPU seconds; minutes).  Evaluation counts are exact; times are ratios on a
shared machine, never absolute targets.  Writes results/benchmarks/engine_speed.csv.
"""
import contextlib
import sys
import time

import numpy as np
import pandas as pd

from brdfs.core import gauss_kronrod
from brdfs.numerics.integrate import azimuthal, hemisphere
from brdfs.numerics.albedo import albedo
from brdfs.pipeline.io import REPO_ROOT
from brdfs.physics.models import model

try:
    from brdfs.core.compiled import numpy_only
except ImportError:          # a baseline commit's src (:class:`_CurveAt`'s child) has no compiled routes
    numpy_only = contextlib.nullcontext

CURVES = [("phong", {"n": 150}), ("ward", {"m": 0.1}), ("cook_torrance", {"m": 0.1}),
          ("phong_cosmin", {"n": 128}), ("blinn_cosmin", {"n": 2})]
SMITH = [("ggx", {"alpha": 0.3}), ("beckmann", {"alpha": 0.3}), ("cook_torrance", {"m": 0.3, "G": "smith"})]
CURVE_THETA = np.linspace(0.0, 89.0, 100)
SINGLE_THETA = np.linspace(0.0, 89.0, 12)
SMITH_THETA = np.linspace(0.0, 89.9, 12)
ROUNDS = 7
TIGHT, LOOSE = 1e-10, 1e-6
SINGLE_TARGET, LOOSE_TARGET, EVALUATIONS_TARGET = 5.0, 0.5, 5000


def _label(name, params):
    return f"{name} " + " ".join(f"{k}={v}" for k, v in params.items())


def _seconds(fn):
    """CPU seconds of this process (``time.process_time``): on a shared machine the wall time also
    counts the other processes' share of the cores."""
    start = time.process_time()
    fn()
    return time.process_time() - start


def _curve_runs(brdf):
    """The three timed runs of one curve model: seconds per point, per single call at each rtol."""
    return {
        "curve_ms_per_point": lambda: _seconds(lambda: albedo(brdf, CURVE_THETA, rtol=TIGHT)) / CURVE_THETA.size,
        "single_ms_1e-10": lambda: _seconds(lambda: [albedo(brdf, float(t), rtol=TIGHT) for t in SINGLE_THETA])
        / SINGLE_THETA.size,
        "single_ms_1e-6": lambda: _seconds(lambda: [albedo(brdf, float(t), rtol=LOOSE) for t in SINGLE_THETA])
        / SINGLE_THETA.size,
    }


def _single_evaluations(brdf):
    """Mean ``Estimate.evaluations`` of the single calls at each rtol, their mean number of
    integrand evaluation rounds of the Gauss–Kronrod driver (its calls of ``_evaluate``) and of
    multisection rounds placing the kink radii found numerically (``hemisphere._multisection``'s
    calls of its function; the Torrance–Sparrow switches): the work the times measure, exact where
    the times are noisy (on a loaded machine a ratio of times can move by 20 % or more)."""
    rounds, sections = [0], [0]
    evaluate, multisection = gauss_kronrod._evaluate, hemisphere._multisection

    def counted(*args, **kwargs):
        rounds[0] += 1
        return evaluate(*args, **kwargs)

    def sectioned(fn, *args):
        def counted_fn(x):
            sections[0] += 1
            return fn(x)
        return multisection(counted_fn, *args)

    out = {}
    gauss_kronrod._evaluate, hemisphere._multisection = counted, sectioned
    try:
        for rtol in (TIGHT, LOOSE):
            rounds[0] = sections[0] = 0
            out[f"single_evals_{rtol:g}"] = float(np.mean([albedo(brdf, float(t), rtol=rtol).evaluations
                                                           for t in SINGLE_THETA]))
            out[f"single_rounds_{rtol:g}"] = rounds[0] / SINGLE_THETA.size
            out[f"single_root_rounds_{rtol:g}"] = sections[0] / SINGLE_THETA.size
    finally:
        gauss_kronrod._evaluate, hemisphere._multisection = evaluate, multisection
    return out


def _single_floor(brdf):
    """CPU ms per single call (best of ``ROUNDS``) spent on the work of the answer itself
    (``floor_ms_*``): the breakpoints (``radial_breakpoints_many``, the kink search included) and the
    integration (``gauss_kronrod.integrate``: the integrand at the nodes, the rule's sums, the
    driver's rounds); and, of that, on the 1-D route's radial kernel alone (``kernel_ms_*``).  What a
    call costs besides (checking its arguments, choosing the route, assembling the answer) is the same
    at both tolerances, so without any of it the loose/tight ratio would be ``floor_loose_over_tight``
    and the single/curve ratio ``floor_single_over_curve``: where those miss the targets, only cheaper
    breakpoints or integration can meet them.  ``kernel_loose_over_tight`` is the kernel's own ratio: a
    sum of parts is at least the smallest of their ratios, so where the kernel's and every other
    part's are above ½ the call's is too, whatever is reorganised around the kernel."""
    spent, kernel, depth = [0.0], [0.0], [0]

    def timed(fn, into, nested):
        def run(*args, **kwargs):
            nested[0] += 1
            start = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                nested[0] -= 1
                if nested[0] == 0:            # an integration inside another counts once
                    into[0] += time.process_time() - start
        return run

    patched = [(gauss_kronrod, "integrate", spent, depth), (azimuthal, "integrate", spent, depth),
               (hemisphere, "radial_breakpoints_many", spent, depth),
               (azimuthal, "radial_breakpoints_many", spent, depth),
               (azimuthal._RadialKernel, "__call__", kernel, [0])]
    originals = [getattr(owner, name) for owner, name, *_ in patched]
    for (owner, name, into, nested), fn in zip(patched, originals):
        setattr(owner, name, timed(fn, into, nested))
    out = {}
    try:
        for rtol in (TIGHT, LOOSE):
            best = (np.inf, np.inf)
            for _ in range(ROUNDS):
                spent[0] = kernel[0] = 0.0
                for t in SINGLE_THETA:
                    albedo(brdf, float(t), rtol=rtol)
                best = min(best, (spent[0] / SINGLE_THETA.size, kernel[0] / SINGLE_THETA.size))
            out[f"floor_ms_{rtol:g}"], out[f"kernel_ms_{rtol:g}"] = 1e3 * best[0], 1e3 * best[1]
    finally:
        for (owner, name, *_), fn in zip(patched, originals):
            setattr(owner, name, fn)
    return out


def curve_ratios():
    """Best-of-``ROUNDS`` times of every curve model, all models interleaved in each round."""
    brdfs = {_label(n, p): model(n, **p) for n, p in CURVES}
    for brdf in brdfs.values():                              # warm up (imports, caches)
        albedo(brdf, 30.0)
    runs = {label: _curve_runs(brdf) for label, brdf in brdfs.items()}
    best = {label: {k: np.inf for k in r} for label, r in runs.items()}
    for _ in range(ROUNDS):
        for label, r in runs.items():
            for key, run in r.items():
                best[label][key] = min(best[label][key], run())
    rows = []
    for label, b in best.items():
        row = {"case": label, **{k: 1e3 * v for k, v in b.items()}}
        row["single_over_curve"] = b["single_ms_1e-10"] / b["curve_ms_per_point"]
        row["loose_over_tight"] = b["single_ms_1e-6"] / b["single_ms_1e-10"]
        row["meets_targets"] = bool(row["single_over_curve"] <= SINGLE_TARGET and row["loose_over_tight"] <= LOOSE_TARGET)
        with numpy_only():          # the anatomy of the numpy path (a compiled call has no parts to time)
            row |= _single_evaluations(brdfs[label]) | _single_floor(brdfs[label])
        row["floor_loose_over_tight"] = row["floor_ms_1e-06"] / row["floor_ms_1e-10"]
        row["floor_single_over_curve"] = row["floor_ms_1e-10"] / row["curve_ms_per_point"]
        row["kernel_loose_over_tight"] = row["kernel_ms_1e-06"] / row["kernel_ms_1e-10"]
        rows.append(row)
    return pd.DataFrame(rows)


#: Issue 41's targets: a single angle at most this many curve points (integral routes), a single call
#: of a model's own route at most this many CPU ms.
RATIO_TARGET, OWN_MS_TARGET = 3.0, 0.1


#: The commit whose curve points no curve point may be slower than (issue 41: "with no curve point slower
#: than at e0ba585"), timed in the same run by :class:`_CurveAt`.
BEFORE = "e0ba585"
#: A curve point counts as slower than at :data:`BEFORE` beyond this ratio of the two best times (the
#: best of ``ROUNDS`` on a machine shared with other jobs still moves by a few per cent).
SLOWER_BEYOND = 1.10


#: A sample of :func:`_per_call` repeats its call for at least this many CPU seconds: one call of a fast
#: model's curve takes 0.1–5 ms, and the best of 7 such single calls still moved by ±13 % between runs
#: (a curve of Phong at 1e-6 read 12 % "slower" than at e0ba585 in one run, the same within 2 % in a
#: separate A/B of 50 ms samples).
MIN_SAMPLE = 0.02


def steady_allocator():
    """Put this process's allocator in the state a long-running one reaches: glibc serves an array above its
    mmap threshold (128 KB at start) by mmap, page faults on first touch included, until a freed mapped
    chunk raises the threshold to its size (and the trim threshold to twice that, so that freed heap memory
    stays for the next array).  A fresh process's patch_exponential curve at 1e-6 (2 MB
    arrays) took 0.041–0.044 ms a point, and 0.025–0.028 ms after any model had freed a larger array (the
    same code, in the same run): which models ran first decided a third of its ratio."""
    np.empty(1 << 21)              # 16 MB, mapped, freed at once: the threshold becomes 16 MB


def _per_call(fn, min_seconds=MIN_SAMPLE):
    """CPU seconds per call of ``fn``, called as many times as one sample of ``min_seconds`` needs (at least once)."""
    calls, start = 0, time.process_time()
    while True:
        fn()
        calls += 1
        spent = time.process_time() - start
        if spent >= min_seconds:
            return spent / calls


def _curve_seconds(brdf, rtol, rounds):
    """Best CPU seconds per point of the 100-angle curve over ``rounds`` samples (:func:`_per_call`; used
    here and in :class:`_CurveAt`'s child)."""
    return min(_per_call(lambda: albedo(brdf, CURVE_THETA, rtol=rtol)) for _ in range(rounds)) / CURVE_THETA.size


def _single_seconds(brdf, rtol, rounds):
    """Best CPU seconds per single call (the mean over ``SINGLE_THETA``, one call per angle) over ``rounds``
    samples (:func:`_per_call`; used here and in :class:`_CurveAt`'s child)."""
    single = lambda: [albedo(brdf, float(t), rtol=rtol) for t in SINGLE_THETA]  # noqa: E731
    return min(_per_call(single) for _ in range(rounds)) / SINGLE_THETA.size


class _CurveAt:
    """The curve points and single calls of another commit's code, timed by a child process on that
    commit's ``src`` (``git archive``) one request at a time, between this run's own timings, so that
    both see the same load: ``seconds(name, rtol, rounds)`` per point of the model's ``typical`` example
    (``kind="single"``: per single call), NaN where that commit has no such model (one without that
    example stops the run with the child's traceback)."""

    CHILD = (
        "import sys, warnings\n"
        "warnings.simplefilter('ignore')\n"
        "sys.path.insert(0, sys.argv[1])\n"
        "import bench_engine_speed as bench\n"
        "bench.steady_allocator()\n"
        "from brdfs.physics.models import MODELS\n"
        "for line in sys.stdin:\n"
        "    name, rtol, rounds, kind = line.split()\n"
        "    if name not in MODELS:\n"
        "        print('absent', flush=True)\n"
        "        continue\n"
        "    brdf = MODELS[name].example('typical')\n"
        "    bench.albedo(brdf, 30.0)\n"
        "    timed = bench._single_seconds if kind == 'single' else bench._curve_seconds\n"
        "    print(repr(timed(brdf, float(rtol), int(rounds))), flush=True)\n")

    def __init__(self, rev):
        """``rev`` a commit, or None: this working tree's own ``src`` (the same code as the parent's, timed
        in a child like the baseline's, so that the two compare child with child)."""
        import pathlib
        import subprocess
        import tempfile
        self.rev = rev or "this tree"
        self.dir = tempfile.TemporaryDirectory(prefix="bench-")
        if rev is None:
            src = REPO_ROOT / "src"
        else:
            archive = subprocess.run(["git", "-C", str(REPO_ROOT), "archive", rev, "src"], check=True,
                                     capture_output=True)
            subprocess.run(["tar", "-x", "-C", self.dir.name], input=archive.stdout, check=True)
            src = pathlib.Path(self.dir.name) / "src"
        env = {**__import__("os").environ, "PYTHONPATH": str(src)}
        self.child = subprocess.Popen([sys.executable, "-c", self.CHILD, str(pathlib.Path(__file__).parent)],
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)

    def seconds(self, name, rtol, rounds, kind="curve"):
        self.child.stdin.write(f"{name} {rtol!r} {rounds} {kind}\n")
        self.child.stdin.flush()
        answer = self.child.stdout.readline().strip()
        if answer == "absent":
            return float("nan")
        if not answer:
            raise RuntimeError(f"bench_engine_speed: the {self.rev} baseline failed on {name} at rtol {rtol!r} "
                               "(its traceback above)")
        return float(answer)

    def close(self):
        self.child.stdin.close()
        self.child.wait()
        self.dir.cleanup()


def model_ratios(rounds=ROUNDS, only=None, before=BEFORE):
    """Every registered model (or those named in ``only``) at its ``typical`` example: CPU ms per
    curve point (100 angles) and per single call (12 angles), best of ``rounds``, at both tolerances,
    interleaved model by model; with ``before`` (a commit; None: not timed), that commit's curve point
    and single call timed between them (:class:`_CurveAt`), ``curve_vs_before`` = ours / its,
    ``curve_not_slower`` (within :data:`SLOWER_BEYOND`), its ``single_over_curve_before`` and
    ``single_vs_before`` = ours / its.  ``meets_target``: the single call's target and, where timed, the
    curve's."""
    import warnings

    from brdfs.physics.models import MODELS
    rows = []
    other = _CurveAt(before) if before else None
    ours = _CurveAt(None) if before else None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for name, cls in MODELS.items():
                if not only or name in only:
                    rows += _model_rows(name, cls.example("typical"), rounds, other, ours)
    finally:
        for child in (other, ours):
            if child is not None:
                child.close()
    return pd.DataFrame(rows)


def _model_rows(name, brdf, rounds, other, ours=None):
    """:func:`model_ratios`' two rows of one model (rtol 1e-10 and 1e-6).  With a baseline, the curve points
    compared are both timed in child processes (``ours``: this tree's, interleaved with the baseline's):
    the parent's own timings ran 10–30 % apart from a child's, which flagged a different curve "slower" in
    every run."""
    route = str(np.ravel(albedo(brdf, 30.0).route)[0])
    rows = []
    for rtol in (TIGHT, LOOSE):
        best_curve = best_single = best_before = best_single_before = best_ours = np.inf
        for _ in range(rounds):
            best_curve = min(best_curve, _curve_seconds(brdf, rtol, 1))
            best_single = min(best_single, _single_seconds(brdf, rtol, 1))
            if other is not None:
                best_before = min(best_before, other.seconds(name, rtol, 1))
                best_ours = min(best_ours, ours.seconds(name, rtol, 1))
                best_single_before = min(best_single_before, other.seconds(name, rtol, 1, "single"))
        ratio = best_single / best_curve
        closed = _closed_form(brdf, rtol)
        meets = bool(1e3 * best_single <= OWN_MS_TARGET if closed else ratio <= RATIO_TARGET)
        row = {"model": name, "route": route, "rtol": rtol, "curve_ms_per_point": 1e3 * best_curve,
               "single_ms": 1e3 * best_single, "single_over_curve": ratio, "closed_form": closed}
        if other is not None:
            row["curve_ms_before"] = 1e3 * best_before
            row["curve_ms_child"] = 1e3 * best_ours
            row["curve_vs_before"] = best_ours / best_before
            row["single_over_curve_before"] = best_single_before / best_before
            row["single_vs_before"] = best_single / best_single_before
            row["curve_not_slower"] = bool(not best_ours > SLOWER_BEYOND * best_before)    # NaN: no such model at the baseline
            meets = meets and row["curve_not_slower"]
        rows.append(row | {"meets_target": meets})
    return rows


def _closed_form(brdf, rtol):
    """Whether single calls of ``brdf`` are answered without the adaptive driver (no call of
    ``gauss_kronrod._evaluate``, and no evaluations counted): a closed form, whose target is
    :data:`OWN_MS_TARGET`; a model's own route that integrates (the patch mixtures) has an integral
    route's target, :data:`RATIO_TARGET`.  Asked of the numpy routes (a compiled route integrates without
    ``_evaluate``)."""
    rounds, evaluate = [0], gauss_kronrod._evaluate

    def counted(*args, **kwargs):
        rounds[0] += 1
        return evaluate(*args, **kwargs)

    gauss_kronrod._evaluate = counted
    try:
        with numpy_only():
            evaluations = sum(albedo(brdf, float(t), rtol=rtol).evaluations for t in SINGLE_THETA)
    finally:
        gauss_kronrod._evaluate = evaluate
    return rounds[0] == 0 and evaluations == 0


def smith_evaluations():
    """Evaluations and time of single calls at 1e-10 for the Smith-masked models."""
    rows = []
    for name, params in SMITH:
        brdf = model(name, **params)
        albedo(brdf, 30.0)
        evaluations, seconds, statuses = [], [], []
        for t in SMITH_THETA:
            start = time.process_time()
            est = albedo(brdf, float(t), rtol=TIGHT)
            seconds.append(time.process_time() - start)
            evaluations.append(est.evaluations)
            statuses.append(str(est.status))
        rows.append({"case": _label(name, params), "median_evaluations": float(np.median(evaluations)),
                     "max_evaluations": int(max(evaluations)), "median_ms": 1e3 * float(np.median(seconds)),
                     "all_converged": all(s == "converged" for s in statuses),
                     "meets_targets": bool(np.median(evaluations) <= EVALUATIONS_TARGET)})
    return pd.DataFrame(rows)


#: The models of the polar route timed part by part (issue 41 (e)): their ``typical`` examples.
POLAR = ("ggx", "beckmann")


def polar_parts(rounds=ROUNDS):
    """Where a single call of a polar-route model goes (issue 41 (e)): CPU µs per call (mean over the
    12 angles of ``SINGLE_THETA``, best of ``rounds``, rtol 1e-10) of the whole call (``call_us``), of
    the route (``route_us``: ``polar.albedo_many`` of the one element), its breakpoints
    (``breakpoints_us``), the driver's integration (``integrate_us``) and, in it, the radial integrand
    at the nodes (``integrand_us``); the front door's share is call − route, the driver's own
    integrate − integrand; with numba, ``compiled_us`` is the compiled single angle's own call
    (breakpoints, integrand and driver; route − compiled is its Python glue).  ``curve_point_us`` is a point of the 100-angle curve (the same arithmetic
    on arrays of ~17,000 nodes instead of ~170), ``nodes`` the mean nodes of a single call.  The
    integrand's and the driver's numpy calls on ~170-element arrays cost their dispatch (~0.5 µs each)
    whatever the arithmetic: ``fixed_over_curve`` = (call − integrand) / curve point is the ratio a
    single call would keep with an integrand of no cost."""
    from brdfs.numerics import albedo as front_door
    from brdfs.numerics.integrate import polar
    from brdfs.physics.models import MODELS

    from brdfs.core import compiled

    spent = {k: [0.0] for k in ("route", "breakpoints", "integrate", "integrand", "compiled")}

    def timed(fn, into):
        def run(*args, **kwargs):
            start = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                into[0] += time.process_time() - start
        return run

    patched = [(front_door.ENGINE_ROUTES, "polar", "route"), (polar, "_breakpoints_of_one", "breakpoints"),
               (polar, "integrate", "integrate"), (polar, "radial_integrand", "integrand")]
    if compiled.available():                     # the compiled single angle: one call of its own
        from brdfs.numerics.integrate import polar_compiled
        patched.append((polar_compiled, "albedo_one", "compiled"))
    get = lambda owner, attr: owner[attr] if isinstance(owner, dict) else getattr(owner, attr)    # noqa: E731

    def put(owner, attr, fn):
        if isinstance(owner, dict):
            owner[attr] = fn
        else:
            setattr(owner, attr, fn)

    originals = [get(owner, name) for owner, name, _ in patched]
    rows = []
    try:
        for name in POLAR:
            brdf = MODELS[name].example("typical")
            albedo(brdf, 30.0)
            curve = min(_seconds(lambda: albedo(brdf, CURVE_THETA, rtol=TIGHT)) for _ in range(rounds))
            nodes = np.mean([albedo(brdf, float(t), rtol=TIGHT).evaluations for t in SINGLE_THETA])
            for (owner, attr, key), fn in zip(patched, originals):
                put(owner, attr, timed(fn, spent[key]))
            best = None
            for _ in range(rounds):
                for v in spent.values():
                    v[0] = 0.0
                call = _seconds(lambda: [albedo(brdf, float(t), rtol=TIGHT) for t in SINGLE_THETA])
                parts = {"call": call, **{k: v[0] for k, v in spent.items()}}
                best = parts if best is None or call < best["call"] else best
            for (owner, attr, _), fn in zip(patched, originals):
                put(owner, attr, fn)
            per = {f"{k}_us": 1e6 * v / SINGLE_THETA.size for k, v in best.items()}
            rows.append({"model": name, **per, "curve_point_us": 1e6 * curve / CURVE_THETA.size, "nodes": nodes,
                         "single_over_curve": per["call_us"] / (1e6 * curve / CURVE_THETA.size),
                         "fixed_over_curve": (per["call_us"] - per["integrand_us"] - per["compiled_us"])
                         / (1e6 * curve / CURVE_THETA.size)})
    finally:
        for (owner, attr, _), fn in zip(patched, originals):
            put(owner, attr, fn)
    return pd.DataFrame(rows)


def accuracy_grid_seconds():
    """CPU seconds of the full accuracy grid (``accuracy_map: {grid: full}``, 3,726 cells): the
    engine (with the pumped families' tables) and the disk certifier, measured apart."""
    import yaml

    from brdfs.artifacts import extra_accuracy_map as accuracy

    cfg = yaml.safe_load((REPO_ROOT / "config.yaml").read_text())
    sec, tol = dict(cfg[accuracy.SECTION], grid="full"), cfg["tolerance"]
    certifier, spent = accuracy.disk_albedo_many, {}

    def timed(*args, **kwargs):
        start = time.process_time()
        out = certifier(*args, **kwargs)
        spent["disk"] = time.process_time() - start
        return out

    accuracy.disk_albedo_many = timed
    try:
        total = _seconds(lambda: spent.setdefault("cells", len(accuracy.accuracy_map(sec, tol))))
    finally:
        accuracy.disk_albedo_many = certifier
    return pd.DataFrame([{"case": "accuracy grid (full)", "cells": spent["cells"], "total_s": total,
                          "engine_s": total - spent["disk"], "disk_s": spent["disk"]}])


def main():
    steady_allocator()
    if "--accuracy-grid" in sys.argv:
        print(accuracy_grid_seconds().to_string(index=False, float_format=lambda x: f"{x:.1f}"), flush=True)
        return
    if "--polar" in sys.argv:
        print(polar_parts().to_string(index=False, float_format=lambda x: f"{x:.3g}"), flush=True)
        return
    only = next((a.split("=", 1)[1].split(",") for a in sys.argv if a.startswith("--only=")), None)
    before = next((a.split("=", 1)[1] or None for a in sys.argv if a.startswith("--before=")), BEFORE)
    models = model_ratios(only=only, before=before)
    print(models.to_string(index=False, float_format=lambda x: f"{x:.3g}"), flush=True)
    out = REPO_ROOT / "results" / "benchmarks" / "engine_speed_models.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    models.to_csv(out, index=False, float_format="%.4g")
    if "--models" in sys.argv:
        return
    curves = curve_ratios()
    print(curves.to_string(index=False, float_format=lambda x: f"{x:.3g}"), flush=True)
    smith = smith_evaluations()
    print(smith.to_string(index=False, float_format=lambda x: f"{x:.4g}"), flush=True)
    print(polar_parts().to_string(index=False, float_format=lambda x: f"{x:.3g}"), flush=True)
    out = REPO_ROOT / "results" / "benchmarks" / "engine_speed.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    pd.concat([curves.assign(kind="curve"), smith.assign(kind="smith")]).to_csv(out, index=False, float_format="%.4g")


if __name__ == "__main__":
    main()
