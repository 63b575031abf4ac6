"""A mixture whose weight p(R) is not smooth declares where (``weight_points``), and its albedo, f itself and
its sampling tables are then honest: a box of width 1e-5 at R = 0.37, undeclared, gave 0 ± 0 "converged"
by every route for an albedo of about 1.

The references share no code with the package's mixture integrals: the lens area of eq. 4.9 written again
here (the textbook arccos form) and integrated by scipy's ``quad`` over the box alone, and f = h ∫ c(R) dR
over the box in closed form, h (1/max(m, a) − 1/b)/π (eqs. 4.7, 4.21)."""
import numpy as np
import pytest
from scipy.integrate import quad

import brdfs
from brdfs.physics.models import MODELS

CENTRE, WIDTH = 0.37, 1e-5
LO, HI = CENTRE - WIDTH / 2, CENTRE + WIDTH / 2
HEIGHT = 1.0 / (HI - LO)                     # normalised: ∫ p = 1


def narrow_box(R):
    """p(R) = 1/(b − a) on [a, b] = 0.37 ∓ 5e-6, 0 elsewhere: jumps at a and b."""
    R = np.asarray(R, float)
    return np.where((R >= LO) & (R <= HI), HEIGHT, 0.0)


def _lens_albedo(d, R):
    """a_R at |L'_P| = d: Area(C(L'_P, R) ∩ unit disk)/(π min(1, R²)) (eqs. 4.8, 4.9), the circles'
    intersection by the textbook arccos form (R < 1 here, so the patch is never the whole disk)."""
    if d + R <= 1.0:
        return 1.0
    alpha = np.arccos((d * d + 1.0 - R * R) / (2.0 * d))
    beta = np.arccos((d * d + R * R - 1.0) / (2.0 * d * R))
    kite = 0.5 * np.sqrt((-d + R + 1.0) * (d + R - 1.0) * (d - R + 1.0) * (d + R + 1.0))
    return (alpha + R * R * beta - kite) / (np.pi * min(1.0, R * R))


def reference_albedo(theta_deg):
    """h ∫_a^b a_R dR by ``quad`` with the box's ends as its only interval: (value, bound on its error)."""
    d = np.sin(np.radians(theta_deg))
    value, error = quad(lambda R: _lens_albedo(d, R), LO, HI, epsabs=0.0, epsrel=1e-13)
    return HEIGHT * value, HEIGHT * error + 1e-15     # + a_R's own rounding (a few ε of values ≤ 1)


def declared(**kwargs):
    return brdfs.model("patch_mixture", weight=narrow_box, weight_points=(LO, HI), **kwargs)


ANGLES = np.array([0.0, 45.0, 60.0, 89.0, 90.0 - 1e-9])


@pytest.mark.parametrize("method, angles", [("auto", ANGLES), ("engine", ANGLES), ("disk", np.array([60.0]))])
def test_a_narrow_box_weight_with_its_points_declared_gives_an_honest_and_tight_albedo_by_every_route(method, angles):
    """Every route within its reported error of the reference, and the error not absurdly loose (≤ 1e3 × the
    true error or ≤ 1e-9).  A single angle (its own graded partition) and a batch both."""
    brdf = declared()
    reference = np.array([reference_albedo(t) for t in angles])
    batch = brdfs.albedo(brdf, angles, method=method, rtol=1e-10)
    singles = [brdfs.albedo(brdf, float(t), method=method, rtol=1e-10) for t in angles[:2]] if angles.size > 1 else []
    for est, (truth, truth_err) in [*zip(zip(batch.value, batch.error, batch.status), reference),
                                    *((( float(s.value), float(s.error), str(s.status)), r)
                                      for s, r in zip(singles, reference))]:
        value, error, status = est
        true_error = abs(value - truth)
        assert status == "converged"
        assert true_error <= error + truth_err, (method, value, error, truth)
        assert error <= max(1e3 * true_error, 1e-9), (method, error, true_error)
    assert np.all(reference[:, 0] > 0.46)       # the box's mass is all there: a ≈ a_0.37(θ), not 0


def narrow_triangle(R):
    """p(R) = h (1 − |R − c|/(w/2)) on [a, b] (h = 2/w, normalised): kinks at a, c and b, and a slope
    4/w² = 4e10 that turns the nodes' rounding (a few ε R) into ~1e-11 of the albedo."""
    R = np.asarray(R, float)
    return np.where((R >= LO) & (R <= HI), 2.0 / (HI - LO) * (1.0 - np.abs(R - CENTRE) / ((HI - LO) / 2)), 0.0)


def _triangle_reference(theta_deg):
    """∫ p a_R dR of :func:`narrow_triangle` in mpmath (30 digits; the lens of eq. 4.9 again, the same
    doubles a, c, b): free of the rounding of R that the package's nodes carry."""
    import mpmath as mp
    with mp.workdps(30):
        d, lo, c, hi = mp.sin(mp.radians(mp.mpf(theta_deg))), mp.mpf(LO), mp.mpf(CENTRE), mp.mpf(HI)

        def integrand(R):
            lens = 1 if d + R <= 1 else (mp.acos((d * d + 1 - R * R) / (2 * d)) + R * R * mp.acos((d * d + R * R - 1) / (2 * d * R))
                                         - mp.sqrt((-d + R + 1) * (d + R - 1) * (d - R + 1) * (d + R + 1)) / 2) / (mp.pi * R * R)
            return 2 / (hi - lo) * (1 - abs(R - c) / ((hi - lo) / 2)) * lens
        return float(mp.quad(integrand, [lo, c, hi]))


@pytest.mark.parametrize("rtol, status", [(1e-8, "converged"), (1e-10, "stalled")])
def test_a_narrow_triangle_reports_the_rounding_of_its_own_nodes(rtol, status):
    """Declared at its kinks, the triangle is resolved, but p at a node R stands for p a few ε R away: its
    albedo moves by ~1.1e-11 where the quadrature's error was 1.2e-14.  Every route adds a bound of that
    (``evaluation_error``, 2.7e-10 here): honest and not absurdly loose, ``stalled`` below it."""
    brdf = brdfs.model("patch_mixture", weight=narrow_triangle, weight_points=(LO, CENTRE, HI))
    angles = np.array([0.0, 60.0, 89.0])
    truth = np.array([_triangle_reference(t) for t in angles])
    est = brdfs.albedo(brdf, angles, rtol=rtol, warn=False)
    true_error = np.abs(est.value - truth)
    assert list(est.status) == [status] * 3
    assert np.all(true_error <= est.error) and np.all(est.error <= np.maximum(1e3 * true_error, 1e-9)), (true_error, est.error)


def test_a_stalled_mixture_is_told_what_its_own_error_is_and_not_to_build_finer_tables():
    """The warning names the model's own source of error (:attr:`BRDF.evaluation_error_source`)."""
    brdf = brdfs.model("patch_mixture", weight=narrow_triangle, weight_points=(LO, CENTRE, HI))
    with pytest.warns(brdfs.NotConvergedWarning, match="p's own rounding") as caught:
        brdfs.albedo(brdf, 30.0, rtol=1e-10)
    assert "finer tables" not in str(caught[0].message)


@pytest.mark.parametrize("m", [0.2, LO + 0.3 * WIDTH, HI + 1e-4])
def test_f_itself_integrates_the_declared_box_below_inside_and_beyond_it(m):
    """f = ∫_m² p(R) c(R) dR (eq. 4.21) at projected distances m below the peak (the whole box), inside it,
    and beyond it (0): h (1/max(m, a) − 1/b)/π, to the model's own rtol."""
    brdf = declared()
    L = np.array([0.0, 0.0, 1.0])
    V = np.array([m, 0.0, np.sqrt(1.0 - m * m)])           # m(L, V) = |L_xy + V_xy| = m (eq. 4.1)
    f = float(brdf(L, V))
    exact = HEIGHT * (1.0 / max(m, LO) - 1.0 / HI) / np.pi if m < HI else 0.0
    assert abs(f - exact) <= 1e-11 * max(exact, 1.0), (m, f, exact)


def test_the_sampling_tables_hold_the_declared_box():
    """The table of F (eq. 4.27) has edges at the declared points: W = ∫ p = 1, every radius drawn lies in
    the box, and the pdf's tabulated f agrees with f itself."""
    brdf = declared()
    assert abs(brdf.total_weight - 1.0) <= 1e-12
    R = brdf.radius_of_cdf(np.linspace(0.01, 0.99, 9))
    assert np.all((R >= LO) & (R <= HI)), R
    L = np.tile([0.0, 0.0, 1.0], (3, 1))
    V = np.array([[m, 0.0, np.sqrt(1.0 - m * m)] for m in (0.2, CENTRE, 0.5)])
    pdf = brdf.pdf(L, V, "russian_roulette")
    np.testing.assert_allclose(pdf, brdf(L, V) * V[:, 2], rtol=1e-9, atol=0.0)


@pytest.mark.parametrize("bad", [("x",), (float("nan"),), (-0.1,), (2.5,), 0.3, "0.3", (None,)])
def test_a_bad_weight_point_is_refused_in_one_line_naming_the_key_and_the_value(bad):
    with pytest.raises(ValueError) as caught:
        brdfs.model("patch_mixture", weight=narrow_box, weight_points=bad)
    message = str(caught.value)
    shown = bad if not isinstance(bad, tuple) else bad[0]
    assert "\n" not in message and "weight_points" in message and repr(shown) in message, message


def test_declared_points_are_a_value_of_the_model_sorted_and_hashable():
    """The model is a frozen value (a cache key): points given in any order and kind compare and hash alike;
    none declared is the default, as every model built before the field."""
    a = brdfs.model("patch_mixture", weight=narrow_box, weight_points=[HI, np.float64(LO), HI])
    b = declared()
    assert a == b and hash(a) == hash(b) and a.weight_points == (LO, HI)
    assert not b.has_evaluation_error          # p constant between its points: no rounding of its own to bound
    assert MODELS["patch_mixture"](weight=narrow_box).weight_points == ()


@pytest.mark.parametrize("points", [(1.0,), ()])
def test_a_weight_that_is_not_finite_somewhere_is_refused_in_one_line_when_the_model_is_built(points):
    """p(R) NaN beyond R = 1.5: refused at once, with or without points (without, the albedo was NaN ± NaN
    after 63,756 evaluations, and with points the rounding bound would have dropped to NaN)."""
    def weight(R):
        return np.where(np.asarray(R) > 1.5, np.nan, 1.0)

    with pytest.raises(ValueError, match=r"weight p\(R\) must be finite on \[0, 2\], got nan at R = 1.50") as error:
        brdfs.model("patch_mixture", weight=weight, weight_points=points)
    assert "\n" not in str(error.value)
