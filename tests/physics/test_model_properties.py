"""Property tests of every registered model (issue 26), with ``hypothesis`` over each model's declared
parameter ranges (``param_ranges``, ``param_choices``) and over random directions:

* f(L, V) is finite and non-negative;
* f(L, V) = f(V, L) for every model that claims reciprocity (``reciprocal``); the non-reciprocal
  ones are listed in :data:`NOT_RECIPROCAL` with the reason, and shown to be non-reciprocal;
* a(θ) ≤ 1 + its reported error (``brdfs.albedo`` at rtol 1e-6) for every model that claims energy
  conservation (``conserves_energy``), built by the front door ``brdfs.model``;
* ``sample`` and ``pdf`` agree: the reported pdf and weight of a sampled direction are ``pdf(L, V)``
  and f cos θ_V / pdf, samples lie in the upper hemisphere or are the rejected marker V = −N with
  weight and pdf 0, and ∫ pdf dω (a quadrature that never calls the sampler) equals the accepted
  fraction of a scrambled Sobol set of 2^15 uniform points within 1e-3.

Parameters are drawn from the test range each model class declares (``test_ranges``, bounded and
inside the declared range, the thesis's narrowest lobes included: n = 1e4, m = 0.005, α = 0.01,
s = 512, R = 0.2 and below; :meth:`~brdfs.physics.models.base.BRDF.test_range`), log-uniformly or
uniformly as it says; nothing here is keyed by a model's or a parameter's name.

The quadrature of ∫ pdf dω follows the lobe, so that the narrowest lobes are resolved:

* sphere-domain samplers: polar coordinates (β, ψ) about the mirror direction R of L, with
  dω = sin β dβ dψ; β on geometric Gauss–Legendre panels (2^k · 1e-6 rad up to π, graded the same
  way about the angles β = π/2 ∓ θ_L where the horizon starts and ends cutting the circles) and ψ
  on the exact arc above the horizon, |ψ| < arccos(−cos β cos θ_L / (sin β sin θ_L));
* disk-domain samplers (chapter 4) and He–Torrance (whose lobe is a Gaussian on the base plane):
  polar coordinates about V'_P = −L_P on the projected disk, dω = dA / cos θ_V, radial panels
  geometric from the centre, split at the radii where the density jumps (``disk_boundaries``:
  circles, and the ellipse's radius along each ray) and ending exactly on the unit circle.

The quadrature itself is checked on the baseline strategies (``cosine``, ``uniform``: ∫ = 1).
"""
from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.stats import qmc

import brdfs
from brdfs.physics.models import MODELS
from brdfs.physics.models.base import UNIFORM
from brdfs.physics.tables import MissingTable

NAMES = list(MODELS)

#: The models that do not claim reciprocity, each with the reason (the class's own comment).
NOT_RECIPROCAL = {
    "phong_original": "f = c (R·V)^n / cos θ_L divides by cos θ_L alone (eq. 2.5)",
    "blinn_original": "f = C (N·H)^n / cos θ_L divides by cos θ_L alone (eq. 2.5)",
}

#: Examples per (model, property) run; see the module docstring for what each example draws.
EXAMPLES = {"finite": 25, "reciprocal": 25, "energy": 4, "compensated": 2, "sample": 5, "baseline": 1}
#: Fewer for the models whose evaluation is itself an integral (the mixture: ∫ p(R) f*_R dR).
FEWER = {("patch_mixture", "sample"): 2}


def _settings(kind, name=None):
    return settings(derandomize=True, max_examples=FEWER.get((name, kind), EXAMPLES[kind]), deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


# --- parameters ---------------------------------------------------------------------------------
def _log_uniform(lo, hi):
    return st.floats(math.log(lo), math.log(hi)).map(math.exp).map(lambda x: min(max(x, lo), hi))


def _linear(lo, hi):
    return st.floats(lo, hi)


def _draw_value(cls, key, energy):
    """A strategy of values of parameter ``key`` of ``cls``: its test range (:meth:`BRDF.test_range`),
    clipped to the open bounds of its declared range; 0 itself and None where the test range adds them."""
    draw = cls.test_range(key, energy=energy)
    interval = cls.param_ranges.get(key)
    lo, hi = draw.lo, draw.hi
    if interval is not None and interval.hi_open and hi >= interval.hi:
        hi = np.nextafter(interval.hi, -np.inf)
    if interval is not None and interval.lo_open and lo <= interval.lo:
        lo = np.nextafter(interval.lo, np.inf)
    base = _log_uniform(lo, hi) if draw.log else _linear(lo, hi)
    if draw.zero and (interval is None or interval.contains(0.0)):
        base = st.one_of(st.just(0.0), base)
    if draw.none:                  # the feature switched off (F = 1 without an index)
        base = st.one_of(st.none(), base)
    return base.filter(lambda x: x is None or interval is None or interval.contains(x))


def _builds(cls, params):
    """Whether ``cls`` accepts ``params`` (parameters drawn apart that go together, such as an index's
    real and imaginary parts or neither); a model that needs a table is built by :func:`build`."""
    try:
        cls(**params)
    except MissingTable:
        return True
    except ValueError:
        return False
    return True


def params_of(cls, *, with_constant=False, energy=False, fixed=None):
    """A strategy of parameter dicts of ``cls`` inside its declared ranges and choices, drawn from its
    test ranges (the energy property's own where it declares them); its constant factor
    (``scale_parameter``) at its default unless ``with_constant``."""
    fixed = fixed or {}
    parts = {}
    for key in cls.param_columns():
        if key in fixed:
            parts[key] = st.just(fixed[key])
        elif key in cls.param_choices:
            parts[key] = st.sampled_from(cls.param_choices[key])
        elif key == cls.scale_parameter and not with_constant:
            continue
        elif cls.test_range(key, energy=energy) is not None:
            parts[key] = _draw_value(cls, key, energy)
        elif any(callable(ex.get(key)) for ex in cls.examples.values()):       # the mixture's weight
            parts[key] = st.sampled_from([ex[key] for ex in cls.examples.values()])
    strategy = st.fixed_dictionaries(parts)
    if any(cls.test_range(key, energy=energy) is not None and cls.test_range(key, energy=energy).none
           for key in parts if key not in fixed):
        strategy = strategy.filter(lambda params: _builds(cls, params))
    return strategy


def _plain(cls, params):
    """Without table-needing choices (Kulla–Conty): those go through :func:`test_compensated_...`."""
    return {k: v for k, v in params.items() if not (k == "compensation")} | (
        {"compensation": "none"} if "compensation" in cls.param_columns() else {})


def build(name, params):
    return brdfs.model(name, **params)


# --- directions -----------------------------------------------------------------------------------
def _directions(rng, n, grazing=True):
    """n directions of the upper hemisphere, a quarter of them within 1e-6 … 1e-2 of the horizon."""
    mu = rng.random(n)
    if grazing:
        k = n // 4
        mu[:k] = 10.0 ** rng.uniform(-6, -2, k)
    phi = 2 * np.pi * rng.random(n)
    s = np.sqrt((1 - mu) * (1 + mu))
    return np.stack([s * np.cos(phi), s * np.sin(phi), mu], -1)


SEEDS = st.integers(0, 2 ** 32 - 1)


def _drawn_model_and_directions(name, data, seed, n=256):
    """A model at drawn parameters (its constant C too) and ``n`` random pairs (L, V)."""
    cls = MODELS[name]
    params = data.draw(params_of(cls, with_constant=True).map(lambda p: _plain(cls, p)), label="params")
    rng = np.random.default_rng(seed)
    return params, build(name, params), _directions(rng, n), _directions(rng, n)


# --- finite, non-negative, reciprocal ---------------------------------------------------------------
@pytest.mark.parametrize("name", NAMES)
@_settings("finite")
@given(data=st.data(), seed=SEEDS)
def test_every_model_is_finite_and_non_negative_over_its_ranges(name, data, seed):
    params, f, L, V = _drawn_model_and_directions(name, data, seed)
    V[:8] = L[:8]                                          # the mirror/retro peaks of the lobes
    V[8:16] = L[8:16] * [-1, -1, 1]
    values = f(L, V)
    assert np.all(np.isfinite(values)), (params, L[~np.isfinite(values)][:3], V[~np.isfinite(values)][:3])
    assert np.all(values >= 0.0), (params, values.min())


@pytest.mark.parametrize("name", [n for n in NAMES if MODELS[n].reciprocal])
@_settings("reciprocal")
@given(data=st.data(), seed=SEEDS)
def test_every_model_that_claims_reciprocity_is_reciprocal(name, data, seed):
    params, f, L, V = _drawn_model_and_directions(name, data, seed)
    forward, backward = f(L, V), f(V, L)
    # rounding: 1e-12 relative, and 1e-12 of the batch's largest value absolute (the Fresnel factor of
    # n = 1 is 0 up to cancellation, ~1e-33, in L·H and V·H rounded differently); plus a series' truncation
    reference = f
    if getattr(f, "ior_re", None) is not None:              # F rounds to ~1e-16 of the F = 1 value
        reference = dataclasses.replace(f, ior_re=None, ior_im=type(f).__dataclass_fields__["ior_im"].default)
    scale = max(float(np.max(reference(L, V))), float(np.max(reference(V, L))))
    allowed = (1e-12 * np.maximum(abs(forward), abs(backward)) + 1e-12 * scale
               + f.truncation_error(L, V) + f.truncation_error(V, L))
    bad = abs(forward - backward) > allowed
    assert not bad.any(), (params, L[bad][:2], V[bad][:2], forward[bad][:2], backward[bad][:2])


def test_the_non_reciprocal_models_are_the_listed_ones_and_are_not_reciprocal():
    assert {n for n in NAMES if not MODELS[n].reciprocal} == set(NOT_RECIPROCAL)
    rng = np.random.default_rng(1)
    L, V = _directions(rng, 64, grazing=False), _directions(rng, 64, grazing=False)
    for name in NOT_RECIPROCAL:
        f = MODELS[name].example()
        assert np.max(abs(f(L, V) - f(V, L)) / (f(L, V) + f(V, L) + 1e-300)) > 0.1, name


# --- energy -----------------------------------------------------------------------------------------
ENERGY = [n for n in NAMES if MODELS[n].conserves_energy]
ANGLES = st.lists(st.floats(0.0, 90.0), min_size=2, max_size=2).map(lambda t: [0.0, 89.9] + t)


def _assert_conserves(f, theta, params):
    # the engine, or where a model has neither a lobe nor its own route (the elliptical patch, not
    # symmetric about the plane of incidence) the projected-disk integration the engine points to
    own = f.lobe is not None or f.albedo_estimate(np.zeros(1), 1e-6, 1e-14) is not None
    est = brdfs.albedo(f, np.asarray(theta), method="engine" if own else "disk", rtol=1e-6)
    over = ~(est.value <= 1.0 + est.error)           # NaN fails too
    assert not over.any(), (params, np.asarray(theta)[over], est.value[over] - 1, est.error[over],
                            [str(s) for s in np.asarray(est.status)[over]])


@pytest.mark.parametrize("name", ENERGY)
@_settings("energy")
@given(data=st.data(), theta=ANGLES)
def test_every_model_that_claims_energy_conservation_has_albedo_at_most_one(name, data, theta):
    cls = MODELS[name]
    params = data.draw(params_of(cls, energy=True).map(lambda p: _plain(cls, p)), label="params")
    _assert_conserves(build(name, params), theta, params)


#: Compensated (Kulla–Conty) models need an E table (about 1 s each, cached per process by
#: ``brdfs.model``): one roughness per family, every other parameter drawn.
COMPENSATED = {"ggx": 0.3, "beckmann": 0.5}


@pytest.mark.parametrize("name", [n for n in COMPENSATED if n in ENERGY])
@_settings("compensated")
@given(data=st.data(), theta=ANGLES)
def test_compensated_microfacet_models_have_albedo_at_most_one(name, data, theta):
    cls = MODELS[name]
    params = data.draw(params_of(cls, fixed={"alpha": COMPENSATED[name], "compensation": "kulla_conty",
                                             "G2": "height_correlated"}), label="params")
    _assert_conserves(build(name, params), theta, params)


def test_beckmann_narrowest_conserves_energy():
    theta = np.linspace(0.0, 89.9, 40)
    _assert_conserves(brdfs.model("beckmann", alpha=0.01), theta, {"alpha": 0.01})


# --- sampling -------------------------------------------------------------------------------------
_GL = {k: np.polynomial.legendre.leggauss(k) for k in (8, 12)}


def _gauss_panels(edges, k):
    """Nodes and weights of k-point Gauss–Legendre on the panels between sorted ``edges`` (…, m)."""
    x, w = _GL[k]
    a, b = edges[..., :-1, None], edges[..., 1:, None]
    nodes = 0.5 * (a + b) + 0.5 * (b - a) * x
    weights = 0.5 * (b - a) * w
    return nodes.reshape(edges.shape[:-1] + (-1,)), weights.reshape(edges.shape[:-1] + (-1,))


def _graded(centre, lo, hi, smallest=1e-6):
    """Geometric edges 2^k · smallest on both sides of ``centre``, clipped to [lo, hi]."""
    steps = smallest * 4.0 ** np.arange(0, 20)
    steps = steps[steps < 2 * np.pi]
    return np.clip(np.concatenate([centre - steps, [centre], centre + steps]), lo, hi)


def integrate_pdf_sphere(pdf, L):
    """∫ pdf(V) dω over the hemisphere, polar about the mirror direction R of L (module docstring)."""
    R = np.array([-L[0], -L[1], L[2]])
    mu = L[2]
    horizontal = np.hypot(L[0], L[1])
    e1 = (np.array([0.0, 0.0, 1.0]) - mu * R) / horizontal if horizontal > 1e-14 else np.array([1.0, 0.0, 0.0])
    e2 = np.cross(R, e1)
    theta = math.acos(min(mu, 1.0))
    b_top = min(math.pi, math.pi / 2 + theta)
    edges = np.unique(np.concatenate([_graded(0.0, 0.0, b_top), _graded(math.pi / 2 - theta, 0.0, b_top),
                                      _graded(b_top, 0.0, b_top), [b_top]]))
    beta, wb = _gauss_panels(edges, 12)
    sb, cb = np.sin(beta), np.cos(beta)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(sb * e1[2] > 0, -cb * mu / (sb * e1[2]), np.where(cb > 0, -np.inf, np.inf))
    psi_max = np.arccos(np.clip(q, -1.0, 1.0))
    # ψ/ψm on panels graded geometrically toward 0 (the plane of incidence, where a half-vector lobe at
    # grazing incidence is squeezed to a width ~cos θ_L) and toward the ends ±1 (the horizon)
    k = 2.0 ** -np.arange(1, 15)
    frac = np.unique(np.concatenate([[0.0, 1.0], k, 1 - k]))
    frac = np.concatenate([-frac[::-1], frac[1:]])
    x, w = _gauss_panels(frac, 8)
    psi = psi_max[:, None] * x                                   # [−ψm, ψm]
    wpsi = psi_max[:, None] * w
    V = (cb[:, None, None] * R + sb[:, None, None] * (np.cos(psi)[..., None] * e1 + np.sin(psi)[..., None] * e2))
    V[..., 2] = np.maximum(V[..., 2], 0.0)
    V /= np.linalg.norm(V, axis=-1, keepdims=True)
    values = pdf(V)
    return float(np.sum(values * wpsi * (wb * sb)[:, None]))


def integrate_pdf_disk(pdf, L, circles=(), ellipse=None, n_psi=512):
    """∫ pdf(V) dω = ∫ pdf / cos θ_V dA on the projected disk, polar about V'_P = −L_P."""
    c = np.array([-L[0], -L[1]])
    psi = 2 * np.pi * (np.arange(n_psi) + 0.5) / n_psi           # periodic: the midpoint rule
    d = np.stack([np.cos(psi), np.sin(psi)], -1)
    cd = d @ c
    r_max = -cd + np.sqrt(np.maximum(cd ** 2 + 1.0 - c @ c, 0.0))
    radii = [np.broadcast_to(r, psi.shape) for r in circles]
    if ellipse is not None:
        b, ratio, angle = ellipse
        a = b / ratio
        radii.append(1.0 / np.hypot(np.cos(psi - angle) / a, np.sin(psi - angle) / b))
    steps = 1e-6 * 2.0 ** np.arange(0, 22)
    edges = np.concatenate([np.zeros((n_psi, 1)), np.broadcast_to(steps, (n_psi, steps.size))]
                           + [r[:, None] for r in radii] + [r_max[:, None]], axis=1)
    edges = np.sort(np.minimum(edges, r_max[:, None]), axis=1)
    r, wr = _gauss_panels(edges, 12)
    x = c[0] + r * d[:, None, 0]
    y = c[1] + r * d[:, None, 1]
    nv = np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    V = np.stack([x, y, nv], -1)
    with np.errstate(divide="ignore", invalid="ignore"):
        density = np.where(nv > 0, pdf(V) / nv, 0.0)
    return float(np.sum(density * r * wr) * 2 * np.pi / n_psi)


def integrate_pdf(f, L, strategy):
    """∫ pdf dω by the quadrature that follows the model's sampler (module docstring)."""
    pdf = functools.partial(f.pdf, L, strategy=strategy)
    if strategy in ("cosine", UNIFORM):          # the baselines, smooth on the sphere
        return integrate_pdf_sphere(pdf, L)
    if f.sampling_domain == "disk" or f.name == "he_torrance":
        circles, ellipse = f.disk_boundaries() if f.sampling_domain == "disk" else ((), None)
        return integrate_pdf_disk(pdf, L, circles, ellipse)
    return integrate_pdf_sphere(pdf, L)


N_SOBOL = 2 ** 15


def check_sampler(f, L, strategy, seed, marker=True, n=N_SOBOL):
    """The sampling properties of ``f`` at ``L`` for ``strategy``; returns (∫ pdf dω, accepted fraction)."""
    dim = f.sample_dimension(strategy)
    u = qmc.Sobol(dim, scramble=True, seed=seed).random(n)
    V, weight, pdf = f.sample(L, u, strategy)
    accepted = V[:, 2] > 0
    # a rejected sample (below the horizon) has weight and pdf 0, and is the marker V = −N
    assert np.all(weight[~accepted] == 0) and np.all(pdf[~accepted] == 0)
    if marker:
        assert np.array_equal(V[~accepted], np.broadcast_to([0.0, 0.0, -1.0], V[~accepted].shape)), V[~accepted][:3]
    Va = V[accepted]
    assert np.allclose(np.linalg.norm(Va, axis=-1), 1.0, rtol=0, atol=1e-12)
    assert np.all(np.isfinite(weight)) and np.all(weight >= 0)
    # the reported pdf is the pdf of the sampled direction, and the weight is f cos θ_V / pdf
    assert np.all(pdf[accepted] > 0)
    again = f.pdf(L, Va, strategy)
    np.testing.assert_allclose(pdf[accepted], again, rtol=1e-12, atol=0)
    np.testing.assert_allclose(weight[accepted], f(L, Va) * Va[:, 2] / again, rtol=1e-12, atol=0)
    # ∫ pdf dω = the accepted fraction
    total = integrate_pdf(f, L, strategy)
    fraction = accepted.mean()
    assert abs(total - fraction) <= 1e-3, (strategy, total, fraction)
    return total, fraction


def _light(theta_deg, phi):
    t = math.radians(theta_deg)
    return np.array([math.sin(t) * math.cos(phi), math.sin(t) * math.sin(phi), math.cos(t)])


THETA_L = st.one_of(st.just(0.0), st.floats(0.0, 89.5))
PHI_L = st.floats(0.0, 2 * math.pi)
SAMPLED = [(n, s) for n in NAMES for s in MODELS[n].strategies if s != "cosine"]


#: Samplers that return a reflected direction below the horizon instead of the rejected marker
#: V = −N that ``BRDF.sample`` documents (none since the visible-normal samplers were fixed:
#: :func:`test_smith_samplers_return_the_rejected_marker`).
NO_MARKER: set = set()


@pytest.mark.parametrize("name, strategy", SAMPLED)
def test_every_sampler_agrees_with_its_pdf(name, strategy):
    cls = MODELS[name]

    @_settings("sample", name)
    @given(params=params_of(cls).map(lambda p: _plain(cls, p)), theta=THETA_L, phi=PHI_L, seed=st.integers(0, 2 ** 16))
    def run(params, theta, phi, seed):
        check_sampler(build(name, params), _light(theta, phi), strategy, seed, marker=(name, strategy) not in NO_MARKER)

    run()


@pytest.mark.parametrize("name, strategy", [("ggx", "visible_normals"), ("beckmann", "visible_normals")])
def test_smith_samplers_return_the_rejected_marker(name, strategy):
    # refuted before: V = 2(L·H)H − L was returned below the horizon (weight 0, pdf 0)
    check_sampler(MODELS[name].example("typical"), _light(60.0, 0.3), strategy, 1)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("strategy", ["cosine", UNIFORM])
@_settings("baseline")
@given(data=st.data(), theta=THETA_L, phi=PHI_L, seed=st.integers(0, 2 ** 16))
def test_the_baseline_samplers_agree_with_their_pdf_and_the_quadrature_integrates_them_to_one(
        name, strategy, data, theta, phi, seed):
    cls = MODELS[name]
    params = data.draw(params_of(cls).map(lambda p: _plain(cls, p)), label="params")
    total, fraction = check_sampler(build(name, params), _light(theta, phi), strategy, seed, n=2 ** 12)
    assert fraction == 1.0 and abs(total - 1.0) < 1e-6, total
