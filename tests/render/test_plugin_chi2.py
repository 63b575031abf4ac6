"""Every sampler of the Lambert, Phong-family and microfacet plugins, and of the generic plugin
``brdfs_model`` (the numpy p-model, in wavefront mode), passes Mitsuba's own chi-square test
(``mi.chi2.ChiSquareTest`` through ``mi.chi2.BSDFAdapter``, on the lobe chart of :mod:`_chi2`) at the
narrowest and the typical parameters of the model's examples, at two incidence angles each; and the
test rejects a pdf off by 5 % and a uniform sampler that claims the cosine pdf.

Significance 1 % per case, Šidák-corrected over the cases (``test_count``).  The lobe scale s of the
chart is the lobe's width in u = (1 − cos a)/2: 1/(2n) for a cosine power, m² (Ward, Cook–Torrance) and
4α² (GGX, Beckmann: heavier tails) for the microfacet lobes and 2/n for the Blinn lobes (δ ~ 1/√n, the
angle from R ~ 2δ), 1 for the cosine.
"""
from __future__ import annotations

import numpy as np
import pytest

from _chi2 import chi2_test, describe

# (plugin dict, lobe scale s, chart axis, incidence angles in degrees)
CASES = {
    "lambert": ({"type": "brdfs_lambert"}, 1.0, "normal", (10.0, 80.0)),
    "phong n=1e4": ({"type": "brdfs_phong", "n": 1e4}, 0.5e-4, "mirror", (30.0, 80.0)),
    "phong n=20": ({"type": "brdfs_phong", "n": 20}, 1 / 40, "mirror", (10.0, 60.0)),
    "phong_cosmin n=1e4": ({"type": "brdfs_phong_cosmin", "n": 1e4}, 0.5e-4, "mirror", (10.0, 85.0)),
    "phong_cosmin n=20": ({"type": "brdfs_phong_cosmin", "n": 20}, 1 / 40, "mirror", (45.0, 80.0)),
    "pumped phong g1 n=20": ({"type": "brdfs_phong", "n": 20, "pumping": "g1"}, 1 / 40, "mirror", (70.0,)),
    "phong n=20 + diffuse (one-sample MIS)": ({"type": "brdfs_phong", "n": 20, "diffuse_reflectance": 0.5},
                                              0.2, "mirror", (45.0,)),
    "blinn n=1e4": ({"type": "brdfs_blinn", "n": 1e4}, 2e-4, "mirror", (30.0, 80.0)),
    "blinn n=20": ({"type": "brdfs_blinn", "n": 20}, 0.1, "mirror", (45.0, 80.0)),
    "blinn_cosmin n=1e4": ({"type": "brdfs_blinn_cosmin", "n": 1e4}, 2e-4, "mirror", (10.0, 85.0)),
    "blinn_cosmin n=20": ({"type": "brdfs_blinn_cosmin", "n": 20}, 0.1, "mirror", (10.0, 60.0)),
    "ward m=0.005": ({"type": "brdfs_ward", "m": 0.005}, 0.005 ** 2, "mirror", (20.0, 70.0)),
    "ward m=0.1": ({"type": "brdfs_ward", "m": 0.1}, 0.01, "mirror", (30.0, 80.0)),
    "cook_torrance m=0.005": ({"type": "brdfs_cook_torrance", "m": 0.005}, 0.005 ** 2, "mirror", (10.0, 75.0)),
    "cook_torrance m=0.1": ({"type": "brdfs_cook_torrance", "m": 0.1, "G": "smith"}, 0.01, "mirror", (60.0,)),
    "ggx alpha=0.01": ({"type": "brdfs_ggx", "alpha": 0.01}, 4e-4, "mirror", (30.0, 75.0)),
    "ggx alpha=0.3": ({"type": "brdfs_ggx", "alpha": 0.3}, 0.36, "mirror", (10.0, 70.0)),
    "beckmann alpha=0.01": ({"type": "brdfs_beckmann", "alpha": 0.01}, 4e-4, "mirror", (30.0, 75.0)),
    "beckmann alpha=0.3": ({"type": "brdfs_beckmann", "alpha": 0.3}, 0.36, "mirror", (10.0, 70.0)),
    "generic p_model n=1e4": ({"type": "brdfs_model", "model": "p_model", "n": 1e4, "p": 0.5}, 0.5e-4, "mirror",
                              (30.0, 80.0)),
    "generic p_model n=20": ({"type": "brdfs_model", "model": "p_model", "n": 20, "p": 0.5}, 1 / 40, "mirror",
                             (10.0, 70.0)),
}
RUNS = [(case, theta) for case, (*_, angles) in CASES.items() for theta in angles]
SAMPLES = 100_000
#: The deliberate faults are tested with more samples: a 5 % pdf error gives p ~ 1e-4 at 10⁵ samples,
#: far below the level at 3·10⁵.
FAULT_SAMPLES = 300_000
#: p-values reached, printed by the last test (pytest -s) for the report.
P_VALUES: dict[str, float] = {}


@pytest.mark.parametrize("case, theta", RUNS, ids=[f"{c} theta={t:g}" for c, t in RUNS])
def test_plugin_sampler_passes_mitsubas_chi_square_test(mitsuba, case, theta):
    """Pumped Phong is run at n = 20 alone: its sampler and pdf are plain Phong's (the pumping divides
    eval by g > 0, never the sampled density), so plain Phong's n = 10⁴ covers its narrowest n, Fig. 2.8's
    5000 included; :func:`test_pumped_phong_samples_plain_phongs_density` holds that at n = 5000."""
    bsdf, scale, about, _ = CASES[case]
    test = chi2_test(bsdf, theta, scale, about, sample_count=SAMPLES)
    P_VALUES[f"{case} theta={theta:g}"] = test.p_value
    significance = 1.0 - (1.0 - 0.01) ** (1.0 / len(RUNS))
    assert not test.fail and test.p_value >= significance, describe(test)


@pytest.mark.parametrize("pumping", ["g1", "g2"])
def test_pumped_phong_samples_plain_phongs_density(mitsuba, pumping):
    """At Fig. 2.8's n = 5000 the pumped plugin draws the same directions as plain Phong from the same
    numbers, reports the same pdf, and zeroes the same sample weights (what ``BSDFAdapter`` reads): the
    chi-square test of the one is the other's."""
    import drjit as dr
    mi = mitsuba
    rng = np.random.default_rng(13)
    count = 4096
    theta = np.radians(rng.uniform(0.0, 89.0, count))
    si = dr.zeros(mi.SurfaceInteraction3f, count)
    si.wi = mi.Vector3f(np.stack([np.sin(theta), np.zeros(count), np.cos(theta)]).astype(np.float32))
    u = rng.random((3, count)).astype(np.float32)
    ctx = mi.BSDFContext()
    drawn = []
    for bsdf in (mi.load_dict({"type": "brdfs_phong", "n": 5000}),
                 mi.load_dict({"type": "brdfs_phong", "n": 5000, "pumping": pumping})):
        bs, weight = bsdf.sample(ctx, si, mi.Float(u[0]), mi.Point2f(u[1:]))
        drawn.append((np.array(bs.wo), np.array(bs.pdf), np.array(bsdf.pdf(ctx, si, bs.wo)),
                      np.all(np.array(weight) == 0, axis=0)))
    (wo, bs_pdf, pdf, zero), (pumped_wo, pumped_bs_pdf, pumped_pdf, pumped_zero) = drawn
    assert (bs_pdf > 0).mean() > 0.5
    assert np.array_equal(wo, pumped_wo) and np.array_equal(bs_pdf, pumped_bs_pdf)
    assert np.array_equal(pdf, pumped_pdf) and np.array_equal(zero, pumped_zero)


@pytest.mark.parametrize("case, theta", [("phong n=20", 30.0), ("ggx alpha=0.3", 45.0), ("lambert", 30.0)])
def test_chi_square_rejects_a_pdf_off_by_five_percent(mitsuba, monkeypatch, case, theta):
    from brdfs.render.mitsuba.plugins import _common
    monkeypatch.setattr(_common, "PDF_SCALE", 1.05)
    bsdf, scale, about, _ = CASES[case]
    test = chi2_test(bsdf, theta, scale, about, sample_count=FAULT_SAMPLES)
    assert not test.passed, describe(test)


@pytest.mark.parametrize("bsdf", [{"type": "brdfs_lambert"},
                                  {"type": "brdfs_phong", "n": 20, "diffuse_reflectance": 0.5}])
def test_chi_square_rejects_a_uniform_sampler_claiming_the_cosine_pdf(mitsuba, monkeypatch, bsdf):
    from brdfs.render.mitsuba.plugins import _common
    monkeypatch.setattr(_common, "UNIFORM_CLAIMS_COSINE", True)
    test = chi2_test(bsdf, 30.0, 1.0, "normal", sample_count=FAULT_SAMPLES)
    assert not test.passed, describe(test)


def test_print_p_values():
    """Not a claim: prints the p-values reached (pytest -s) for the report."""
    for case, p in P_VALUES.items():
        print(f"chi2 p-value {case}: {p:.3g}")
