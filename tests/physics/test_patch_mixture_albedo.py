"""The mixture of basic patches (eqs. 4.20–4.24) answers its albedo by its own route, ∫ p(R) a_R(L) dR +
p_Diffuse over the basic patches' lens areas, with an honest error up to grazing incidence."""
import numpy as np
import pytest

from brdfs import albedo, model
from brdfs.core import gauss_kronrod
from brdfs.core.compiled import numpy_only
from brdfs.physics.models import MODELS

#: The sweep's truths (``tests/data/sweep_truths.csv``, family patch_mixture, p(R) = 1/2, p_Diffuse = 0):
#: the projected disk of the closed-form ξ(m) of ``sweep/independent.py`` (no brdfs.numerics), θ, a, error.
UNIFORM_TRUTHS = [(36.710537000000002, 0.8915665515466602, 7.0e-14),
                  (89.900000000000006, 0.58741142555224313, 2.2e-14),
                  (89.989999999999995, 0.58740430152455703, 2.2e-14)]


def _uniform(R):
    return np.full(np.shape(R), 0.5)


@pytest.mark.parametrize("rtol", [1e-4, 1e-10])
def test_the_mixture_albedo_is_its_own_route_and_honest_up_to_grazing_incidence(rtol):
    """At 89.9° (rtol 1e-4) it was 3.3e-6 off at a reported 2.4e-6 before the cuts above the lens
    kink R = 1 − sin θ (``patch_geometry.LENS_LAYER_GRADING``): a weight that does not vanish at R → 0
    weighs the layer where a_R falls from 1 to ~1/2 in full."""
    theta = np.array([t for t, _, _ in UNIFORM_TRUTHS])
    truth = np.array([a for _, a, _ in UNIFORM_TRUTHS])
    truth_err = np.array([e for _, _, e in UNIFORM_TRUTHS])
    est = albedo(model("patch_mixture", weight=_uniform), theta, rtol=rtol)
    assert set(est.route) == {"engine/own"} and set(est.status) == {"converged"}
    assert np.all(np.abs(est.value - truth) <= est.error + truth_err), np.abs(est.value - truth) / est.error


def test_a_dirac_diffuse_part_adds_its_weight_to_the_albedo():
    """a_2 = 1 (the patch of radius 2 covers the unit disk): p_Diffuse adds p_Diffuse (eq. 4.24)."""
    theta = np.array([0.0, 50.0, 89.0])
    plain = albedo(model("patch_mixture", weight=_uniform), theta, rtol=1e-12)
    diffuse = albedo(model("patch_mixture", weight=_uniform, p_diffuse=0.5), theta, rtol=1e-12)
    assert np.all(np.abs(diffuse.value - plain.value - 0.5) <= diffuse.error + plain.error)


@pytest.mark.parametrize("rtol", [1e-4, 1e-10])
def test_a_single_angle_is_honest_against_the_sweeps_truths_up_to_grazing_incidence(rtol):
    """One angle per call starts from its own graded partition (``patch_geometry._single_element_partition``),
    not the batch's: it too holds the truths within its reported error."""
    brdf = model("patch_mixture", weight=_uniform)
    for theta, truth, truth_err in UNIFORM_TRUTHS:
        est = albedo(brdf, theta, rtol=rtol)
        assert str(est.status) == "converged" and abs(float(est.value) - truth) <= float(est.error) + truth_err


@pytest.mark.parametrize("name", ["patch_mixture", "patch_exponential", "generalized_lambertian"])
def test_a_single_angle_of_a_mixture_meets_its_tolerance_on_its_first_evaluation_and_agrees_with_the_batch(name):
    """Graded by halves toward the lens's kinks R = 1 ∓ sin θ and, from below, toward the weight's own
    points (a generalized Lambertian's clip m_clip), a single angle's first partition meets its rtol
    on one evaluation of the lens areas (the rough pass's, which the final pass reuses, or the final answer
    where it is within a quarter of the target): one or two rounds of the driver, where bisecting those
    kinks level by level took 6–9 at 1e-10.  A looser rtol grades fewer levels
    (:func:`~brdfs.physics.patch_geometry.lens_kink_levels`), on fewer nodes.  Its value agrees with the
    batch's (another partition, bisected) within the two reported errors, at 1e-10, 1e-8, 1e-6 and 1e-4."""
    brdf = MODELS[name].example("typical")
    theta = np.linspace(0.0, 89.0, 12)
    rounds, nodes, evaluate = [0], [0], gauss_kronrod._evaluate

    def counted(integrand, elem, lo, hi, *args, **kwargs):
        rounds[0] += 1
        nodes[0] += 21 * np.size(lo)
        return evaluate(integrand, elem, lo, hi, *args, **kwargs)

    first_nodes = {}
    for rtol in (1e-10, 1e-8, 1e-6, 1e-4):
        batch = albedo(brdf, theta, rtol=rtol)
        nodes[0] = 0
        for k, t in enumerate(theta):
            rounds[0] = 0
            gauss_kronrod._evaluate = counted
            try:
                with numpy_only():     # the numpy driver's rounds (the compiled route's nodes are the same: its tests)
                    one = albedo(brdf, float(t), rtol=rtol)
            finally:
                gauss_kronrod._evaluate = evaluate
            assert str(one.status) == "converged" and str(one.route) == "engine/own"
            assert abs(float(one.value) - batch.value[k]) <= float(one.error) + batch.error[k]
            assert rounds[0] in (1, 2), (t, rtol, rounds[0])
        first_nodes[rtol] = nodes[0]
    assert first_nodes[1e-10] > first_nodes[1e-8] > first_nodes[1e-6] >= first_nodes[1e-4], first_nodes


def test_a_looser_tolerance_grades_one_level_fewer_per_factor_2_to_the_5_halves_down_to_two():
    """Each level halves the interval next to a kink where a_R starts as (R − R₀)^{3/2}: its error falls by
    2^{5/2}.  All 8 levels at 1e-10 and tighter (and rtol 0, and a float32 1e-10); 7 just above; 2 at 1e-6
    and, the floor, looser."""
    from brdfs.physics.patch_geometry import LENS_KINK_GRADING, lens_kink_levels

    assert len(LENS_KINK_GRADING) == 8
    step = 2.0 ** 2.5
    assert [lens_kink_levels(r) for r in (0.0, 1e-13, 1e-10, np.float32(1e-10), 1.01e-10, 1e-10 * step,
                                          1e-10 * step * 1.01, 1e-10 * step ** 3, 1e-8, 1e-6, 1e-4, 1.0, 1e300)] \
        == [8, 8, 8, 8, 7, 7, 6, 5, 5, 2, 2, 2, 2]


@pytest.mark.parametrize("points", [(2.5,), (-0.5, 1.3), (0.0, 2.0)])
def test_a_single_angle_grades_only_toward_weight_points_inside_the_range_of_R(points):
    """A weight's point outside (0, 2] is no feature of ∫₀² p(R) a_R dR: the batch's partition drops it
    (``patch_geometry._r_breakpoints``), and a single angle's graded partition drops it too.  Grading
    toward R = 2.5 once put cuts past 2 into the single angle's partition (a uniform weight at 30°:
    1.1613 ± 4e-13 where the batch gives 0.92695 ± 1e-11)."""
    from brdfs.physics import patch_geometry as patch

    theta = np.array([30.0, 75.0])
    batch = patch.weighted_mixture_albedo(_uniform, 0.0, theta, 1e-10, 1e-14, points)
    for k, t in enumerate(theta):
        one = patch.weighted_mixture_albedo(_uniform, 0.0, [t], 1e-10, 1e-14, points, single_graded=True)
        partition = patch._single_element_partition(points, float(np.sin(np.radians(t))))
        assert partition.min() == 0.0 and partition.max() == 2.0
        assert abs(one.value[0] - batch.value[k]) <= one.error[0] + batch.error[k]
