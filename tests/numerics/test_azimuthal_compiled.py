"""The compiled single-angle azimuthal route (issue 41, per-call cost) is a replica of the numpy one.

Every model the compiled route takes (read from its declarations: :func:`.azimuthal.compiled_spec`), at
its examples and the finite ends of its declared ranges, at angles from 0 through 1e-6° to 90° − 1e-9°
and 90°, at rtol 1e-3 … 1e-12: the same status, the same evaluations (but where a refinement decision
sits on a threshold, rare), a value within :data:`ULPS` ε |value| of the numpy path's and far inside
the reported error; a flipped decision still honest against the numpy value ± its error.  The numpy
path (:func:`brdfs.core.compiled.numpy_only`) is the reference; its own honesty is the sweep's."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from brdfs.core import compiled
from brdfs.core.gauss_kronrod import NODES, NodeValues
from brdfs.numerics.integrate import azimuthal, hemisphere
from brdfs.physics.models import MODELS, model

pytestmark = pytest.mark.skipif(not compiled.available(), reason="numba (the optional extra 'fast') is not installed")

ANGLES = (0.0, 1e-6, 1e-3, 30.0, 60.0, 89.0, 89.9999, 90.0 - 1e-9, 90.0)
RTOLS = (1e-3, 1e-6, 1e-8, 1e-10, 1e-12)
#: |compiled − numpy| ≤ ε |value| (ULPS + GRAZING / cos θ) where both took the same decisions: the
#: transcendental functions are libm's against numpy's SIMD ones and the sums loops against BLAS
#: (measured: at most 1.9 ulps at 0°–89°, 89.999999999° and 90°), and near grazing the max(N·L, N·V)
#: kernels divide a difference by cos θ, whose rounding they bound by ε / cos θ (measured: 3,817 ulps
#: at 89.9999°, 0.0067 ε / cos θ, on this grid; a reviewer's 26,000 random cells: at most 0.10 ε / cos θ,
#: corrected Blinn n = 0.32 at 89.9992°, 7,336 ulps for an error of 4.8e-9).
ULPS, GRAZING = 4, 0.25
#: ... and within this share of the reported error (measured: 0.017).
WITHIN_ERROR = 0.05
#: The two reported errors within this share of each other (measured 0.042: where a call converges,
#: Σ|K − G| is of the size of its nodes' rounding, which the two paths round apart).
ERRORS_APART = 0.1
#: Cells where a refinement decision sits on a threshold (other evaluations): at most this share
#: (measured: none in 900).
FLIPS = 0.01


def _declared(cls):
    """Parameters of ``cls``: its examples, and each finite closed end of a declared range (not C's)
    with the others typical."""
    out = [dict(p) for p in cls.examples.values()]
    for key, interval in cls.param_ranges.items():
        for bound, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open)):
            if np.isfinite(bound) and not is_open and key != "C":
                out.append({**cls.examples["typical"], key: bound})
    return out


def _covered():
    """The models the compiled route takes, with their parameters (none named here)."""
    models = [model(name, **params) for name, cls in sorted(MODELS.items()) if cls.closed_form_azimuth is not None
              for params in _declared(cls)]
    return [m for m in dict.fromkeys(models) if azimuthal.compiled_spec(m) is not None]    # an example may be an end


def _single(brdf, theta, rtol):
    return azimuthal.albedo_many([brdf], np.array([theta]), rtol=rtol)


def test_the_compiled_route_covers_both_lobes_and_every_kernel_it_replicates():
    specs = {(spec[0], spec[3]) for spec in map(azimuthal.compiled_spec, _covered())}
    kernels = {spec[1] for spec in specs}
    assert kernels == set(azimuthal.COMPILED_KERNELS.values())
    assert {spec[0] for spec in specs} == {azimuthal.COMPILED_POWER_COSINE, azimuthal.COMPILED_BECKMANN}


def test_a_single_angle_of_a_covered_model_is_answered_without_the_numpy_driver(monkeypatch):
    """The front door's single angle of every covered model takes the compiled route (the numpy driver
    of the 1-D route is never called), with the 1-D route's name, and a batch still takes numpy."""
    import brdfs

    def refused(*args, **kwargs):
        raise AssertionError("the numpy driver was called")
    monkeypatch.setattr(azimuthal, "integrate", refused)
    for brdf in _covered():
        est = brdfs.albedo(brdf, 30.0, rtol=1e-8)
        assert str(est.route) == "engine/azimuthal" and str(est.status) == "converged", brdf
    with pytest.raises(AssertionError, match="numpy driver"):
        azimuthal.albedo_many([brdf] * 2, np.array([30.0, 60.0]))


@pytest.mark.filterwarnings("ignore:invalid value encountered:RuntimeWarning")    # Ward at exactly 90°: NaN both ways
def test_the_compiled_route_gives_the_numpy_answer_over_the_grid():
    cells, flips, worst = 0, [], 0.0
    for brdf in _covered():
        for theta in ANGLES:
            for rtol in RTOLS:
                with compiled.numpy_only():
                    ref = _single(brdf, theta, rtol)
                got = _single(brdf, theta, rtol)
                cells += 1
                label = (brdf, theta, rtol)
                value, error, ref_value, ref_error = (float(x[0]) for x in (got.value, got.error, ref.value, ref.error))
                assert got.status[0] == ref.status[0], label
                if not math.isfinite(ref_value):     # Ward's route at exactly 90° (the front door declares +inf there)
                    assert not math.isfinite(value) and got.evaluations == ref.evaluations, label
                    continue
                assert math.isfinite(value) and math.isfinite(error), label
                if got.evaluations != ref.evaluations:
                    flips.append(label)
                    assert abs(value - ref_value) <= error + ref_error, label
                    continue
                delta = abs(value - ref_value)
                worst = max(worst, delta / (np.finfo(float).eps * abs(ref_value)) if delta else 0.0)
                mu = math.cos(math.radians(theta))
                ulps = ULPS + (GRAZING / mu if mu > 0 else 0.0)
                assert delta <= ulps * np.finfo(float).eps * abs(ref_value), (label, delta / abs(ref_value))
                assert delta <= WITHIN_ERROR * ref_error, (label, delta, ref_error)
                assert abs(error - ref_error) <= ERRORS_APART * ref_error, (label, error, ref_error)
    assert cells >= 500 and len(flips) <= FLIPS * cells, (cells, flips)
    print(f"{cells} cells, worst {worst:.1f} ulps, {len(flips)} decision flips")


def test_the_compiled_nodes_are_the_numpy_kernels_within_their_rounding():
    """Node by node, before the driver: the substituted onset, the lobe's angle, the frame kernel and
    the weight, each value within its own rounding bound plus ε of the largest."""
    from brdfs.numerics.integrate import azimuthal_compiled as compiled_route
    for brdf in _covered():
        spec = azimuthal.compiled_spec(brdf)
        kernel = azimuthal._RadialKernel.of(brdf)
        for theta in (0.0, 1e-3, 30.0, 89.0, 89.9999, 90.0):
            mu, st = np.array([math.cos(math.radians(theta))]), np.array([math.sin(math.radians(theta))])
            bp, t0 = hemisphere.radial_breakpoints_many([brdf], mu, st, np.array([theta]), touch=True)
            bp, lo, hi = hemisphere.horizon_onset(bp, t0, min_span=1.0)
            row = bp[0][np.isfinite(bp[0])]
            a, b = row[:-1], row[1:]
            x = 0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * NODES

            def integrand(t, elem):
                value, rounding = kernel(t, mu[:, None], st[:, None])
                return NodeValues(value, value, rounding)
            ref = hemisphere.square_root_onset(integrand, lo, hi)(x, np.zeros(a.size, np.intp))
            l, h = float(lo[0]), float(hi[0])
            scale = float(np.arcsinh(math.sqrt((h - l) / l))) / (h - l) if 0 < l < h else 0.0
            value, rounding = compiled_route.nodes(x, float(mu[0]), float(st[0]), *spec, l, h, scale)
            slack = np.abs(ref.extra_err) + np.finfo(float).eps * np.max(np.abs(ref.high))
            assert np.all(np.abs(value - ref.high) <= slack), (brdf, theta)
            np.testing.assert_allclose(np.abs(rounding), np.abs(ref.extra_err), rtol=0.1, atol=1e-300)


def test_the_compiled_frame_kernels_are_the_numpy_ones_with_the_same_rounding_bounds():
    """Each frame kernel (:data:`.azimuthal.KERNELS`) at the same cos β, sin β (from 0 to 1 − 1e-15 in t):
    the value within its rounding bound plus ε of the largest (measured: 0.27 of it), the bound itself
    the same but for the last ulps (measured: 6.5e-15 ε of the largest value)."""
    from brdfs.numerics.integrate import azimuthal_compiled as compiled_route
    t = np.concatenate([np.linspace(0.0, 1.0 - 1e-3, 100), 1.0 - np.logspace(-3, -15, 40)])
    for brdf in _covered():
        spec = azimuthal.compiled_spec(brdf)
        numpy_kernel = azimuthal.KERNELS[brdf.closed_form_azimuth[0]][brdf.closed_form_azimuth[1]]
        for theta in (0.0, 1e-3, 30.0, 89.0, 89.9999, 90.0 - 1e-9):
            mu, st = math.cos(math.radians(theta)), math.sin(math.radians(theta))
            with np.errstate(divide="ignore", invalid="ignore"):
                cb, sb = brdf.lobe.angle(t)
                value, bound = (x[0] for x in numpy_kernel(cb[None], sb[None], np.array([[mu]]), np.array([[st]])))
            got = np.array([compiled_route._kernel(spec[3], c, s, mu, st) for c, s in zip(cb.tolist(), sb.tolist())])
            scale = np.finfo(float).eps * np.max(np.abs(value))
            assert np.all(np.abs(got[:, 0] - value) <= np.abs(bound) + scale), (brdf, theta)
            assert np.all(np.abs(got[:, 1] - bound) <= 1e-6 * scale), (brdf, theta)


def test_the_compiled_carlson_rd_meets_the_relative_error_wards_bound_allows():
    """Ward's kernel (:mod:`.ward_azimuth`) bounds its rounding with R_D accurate to ``_RD_REL`` = 4ε
    (scipy's ``elliprd``: measured ≤ 2.6ε); the compiled duplication algorithm, on the complete arguments
    the moments use, (0, c, s) and (0, s, c) with s/c from 1e-199 to 10, against mpmath at 40 digits
    (measured over 6,000: ≤ 3.04ε)."""
    import mpmath as mp

    from brdfs.numerics.integrate import azimuthal_compiled as compiled_route
    from brdfs.numerics.integrate.ward_azimuth import _RD_REL
    rng = np.random.default_rng(41)
    worst = 0.0
    with mp.workdps(40):
        for k in range(150):
            c = 10.0 ** rng.uniform(-8, 1)
            s = c * 10.0 ** (rng.uniform(-199, 1) if k % 3 == 0 else rng.uniform(-6, 1))
            for args in ((0.0, c, s), (0.0, s, c)):
                exact = mp.elliprd(*args)
                worst = max(worst, float(abs(compiled_route._rd(*args) - exact) / exact))
    assert worst <= _RD_REL, worst / np.finfo(float).eps


def test_a_model_that_overrides_its_azimuth_weight_takes_the_numpy_route():
    """A user's subclass whose weight the compiled route cannot know (it overrides ``azimuth_weight``):
    numpy answers, with the user's weight."""
    typical = model("phong", n=20.0)

    class Doubled(type(typical)):
        def azimuth_weight(self, cos_beta):
            return 2 * super().azimuth_weight(cos_beta)

    doubled = Doubled(n=20.0, C=typical.C)
    assert azimuthal.compiled_spec(typical) is not None and azimuthal.compiled_spec(doubled) is None
    est = _single(doubled, 30.0, 1e-10)
    np.testing.assert_allclose(est.value, 2 * _single(typical, 30.0, 1e-10).value, rtol=1e-9)


def test_without_numba_every_route_is_numpy_to_the_bit():
    """``BRDFS_COMPILED=0``: the compiled routes are off for the process and a single angle is the
    numpy path's to the bit."""
    code = ("import numpy as np\n"
            "from brdfs.core import compiled\n"
            "from brdfs.numerics.integrate import azimuthal\n"
            "from brdfs.physics.models import model\n"
            "m = model('blinn_cosmin', n=2.0)\n"
            "assert not compiled.available() and azimuthal.compiled_spec(m) is None\n"
            "est = azimuthal.albedo_many([m], np.array([48.5]), rtol=1e-10)\n"
            "print(repr(float(est.value[0])), repr(float(est.error[0])), est.evaluations)\n")
    env = {**os.environ, "BRDFS_COMPILED": "0"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout.split()
    with compiled.numpy_only():
        ref = _single(model("blinn_cosmin", n=2.0), 48.5, 1e-10)
    assert out == [repr(float(ref.value[0])), repr(float(ref.error[0])), str(ref.evaluations)]


def test_only_the_exact_lobes_and_distributions_it_replicates_take_the_compiled_route():
    """A subclass of the lobe or of its distribution may change what t means: numpy answers.  A
    (frame, kernel) declared as a list is the same declaration."""
    import dataclasses
    from functools import cached_property

    covered = [cls.example("typical") for cls in MODELS.values()
               if azimuthal.compiled_spec(cls.example("typical")) is not None]
    assert len(covered) >= 5
    for brdf in covered:
        lobe = brdf.lobe
        if dataclasses.is_dataclass(lobe) and hasattr(lobe, "distribution"):
            distribution = type("Own", (type(lobe.distribution),), {})(**dataclasses.asdict(lobe.distribution))
            other = dataclasses.replace(lobe, distribution=distribution)
        else:
            other = type("Own", (type(lobe),), {})(**{f.name: getattr(lobe, f.name) for f in dataclasses.fields(lobe)})
        relobed = type("Relobed", (type(brdf),), {"lobe": cached_property(lambda self, other=other: other)})
        relobed.lobe.__set_name__(relobed, "lobe")
        params = {f.name: getattr(brdf, f.name) for f in dataclasses.fields(brdf) if f.init}
        assert azimuthal.compiled_spec(relobed(**params)) is None, brdf.name
        listed = type("Listed", (type(brdf),), {"closed_form_azimuth": list(brdf.closed_form_azimuth)})
        assert azimuthal.compiled_spec(listed(**params)) == azimuthal.compiled_spec(brdf), brdf.name


def test_the_compiled_breakpoints_are_the_numpy_ones_to_the_bit():
    """A single angle's breakpoint row and onset interval (:func:`.azimuthal_compiled.breakpoints_of_one`)
    are :func:`.hemisphere.radial_breakpoints_many` and :func:`.hemisphere.horizon_onset`'s, bit for bit
    (the sign of a zero included), for every covered model at its examples and range ends, at every
    angle of the grid and rtol 1e-3 … 1e-12 (the loose and the tight first partitions)."""
    from brdfs.numerics.integrate import azimuthal_compiled as compiled_route
    cells = 0
    for brdf in _covered():
        for theta in ANGLES:
            th = np.array([theta])
            mu, st = np.sin(np.radians(90.0 - th)), np.sin(np.radians(th))
            for rtol in RTOLS:
                tight, tail, root_rtol = azimuthal._single_angle_settings(rtol)
                min_span = azimuthal.TIGHT_ONSET_MIN_SPAN if tight else hemisphere.ONSET_MIN_SPAN
                bp, kinks, t0 = hemisphere.radial_breakpoints_many([brdf], mu, st, th, tail=tail, root_rtol=root_rtol,
                                                                   kinks=True, touch=True, graded=tight)
                bp, lo, hi = hemisphere.horizon_onset(bp, t0, min_span=min_span)
                row, got_lo, got_hi = compiled_route.breakpoints_of_one(brdf, mu, st, th, tail, tight, min_span)
                label = (brdf, theta, rtol)
                assert not kinks.element.size, label
                assert row.tobytes() == bp[0].tobytes(), (label, row, bp[0])
                assert np.array([got_lo, got_hi]).tobytes() == np.array([lo[0], hi[0]]).tobytes(), label
                cells += 1
    assert cells >= 500, cells
