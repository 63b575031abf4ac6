"""A seeded subset of the independent sweep (``sweep/``, issue 24) in the suite: the engine, the
certifier (``method="disk"``) and the single-angle path (``single``: the default method one angle per
call, compiled where numba is) against truths computed once by a third route that shares no code with
:mod:`brdfs.numerics` (``tests/data/sweep_truths.csv``; ``make sweep`` runs all of them).

The subset: :data:`N_CELLS` cells drawn with config.yaml's seed, spread over the families (one per
family first, then grazing cells 90° − 10⁻ᵏ), among the cells whose truth is accurate enough to judge
an error bound at :data:`RTOL` (truth_err ≤ 1e-12 |truth|).
"""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from sweep.cells import TRUTHS
from sweep.check import classify, run_group
from sweep.config import config_seed

N_CELLS = 40
RTOL = 1e-8
#: Families the engine refuses (no lobe of its own and no albedo route, or not symmetric about
#: the plane of incidence): only the disk and the single calls (the default method) are held to them.
METHODS = ("engine", "disk", "single")
#: Dishonest cells found by the sweep and still open, each held by a strict xfail reproducer in
#: ``test_honesty_families.py``: (method, family, params) at the grazing angles 90° − 1e-7 and beyond.
KNOWN_OPEN = {("engine", "ggx_height_correlated", '{"alpha": 0.700492}'):
              "test_ggx_polar_route_is_honest_at_grazing_incidence"}


def subset(truths: pd.DataFrame, n: int = N_CELLS, seed: int | None = None) -> pd.DataFrame:
    """``n`` judgeable cells: one per family first, then the rest, grazing ones preferred, seeded."""
    rng = np.random.default_rng(config_seed() if seed is None else seed)
    ok = truths[np.isfinite(truths["truth"]) & (truths["truth_err"] <= 1e-12 * truths["truth"].abs())]
    picks = [g.index[rng.integers(len(g))] for _, g in ok.groupby("family", sort=True)]
    rest = ok.drop(index=picks)
    grazing = rest[rest["theta_deg"] > 89.9]
    more = rng.choice(grazing.index, size=min(max(n - len(picks), 0) // 2, len(grazing)), replace=False)
    rest = rest.drop(index=more)
    fill = rng.choice(rest.index, size=max(n - len(picks) - len(more), 0), replace=False)
    return ok.loc[sorted([*picks, *more, *fill])]


def sweep_rows(cells: pd.DataFrame) -> pd.DataFrame:
    groups = [(fam, par, list(g["theta_deg"]), METHODS, (RTOL,)) for (fam, par), g in cells.groupby(["family", "params"])]
    rows = pd.DataFrame([row for g in groups for row in run_group(g)])
    merged = rows.merge(cells[["family", "params", "theta_deg", "truth", "truth_err"]],
                        on=["family", "params", "theta_deg"])
    return classify(merged)


@pytest.fixture(scope="module")
def cells():
    if not TRUTHS.exists():
        pytest.skip("tests/data/sweep_truths.csv not computed (python -m sweep.compute_truths)")
    return subset(pd.read_csv(TRUTHS))


def test_the_subset_spreads_over_every_family_and_reaches_grazing_angles(cells):
    truths = pd.read_csv(TRUTHS)
    assert len(cells) == N_CELLS
    assert set(cells["family"]) == set(truths[truths["truth_err"] <= 1e-12 * truths["truth"].abs()]["family"])
    assert (cells["theta_deg"] > 90 - 1e-6).sum() >= 5


def test_engine_disk_and_single_calls_are_honest_on_a_seeded_subset_of_the_independent_sweep(cells):
    rows = sweep_rows(cells)
    answered = rows[rows["verdict"] != "refused"]
    assert len(answered[answered["method"] == "disk"]) >= 0.9 * N_CELLS
    assert len(answered[answered["method"] == "single"]) == N_CELLS       # the default method answers every cell
    known = [(m, f, p) in KNOWN_OPEN and t >= 90 - 1e-7 for m, f, p, t in
             zip(rows["method"], rows["family"], rows["params"], rows["theta_deg"])]
    bad = rows[rows["dishonest"] & ~np.array(known, bool)]
    assert bad.empty, "dishonest (true error above reported error + truth error):\n" + bad[
        ["method", "family", "params", "theta_deg", "value", "error", "truth", "truth_err", "ratio"]].to_string()


def test_every_rewritten_brdf_of_the_sweep_agrees_with_the_package_model_at_random_directions():
    from sweep.cells import FAMILIES, family_parameters, load_tables, pointwise_agreement, needs_table, table_key
    tables = load_tables()
    rng = np.random.default_rng(config_seed())
    worst = {}
    for family in FAMILIES:
        params = [p for p in family_parameters(family, rng)
                  if not needs_table(family) or table_key(family, p) in tables][:1]
        worst[family.name] = max(pointwise_agreement(family.name, p, n=200, tables=tables) for p in params)
    assert max(worst.values()) < 1e-11, {k: v for k, v in worst.items() if v >= 1e-11}


def test_the_third_route_reproduces_closed_form_albedos_in_both_frames_and_on_the_disk():
    from sweep import independent as ind
    from sweep.third_route import Integrand, disk_albedo, hemisphere_albedo
    n = 20.0
    phong = Integrand(ind.phong(n), "mirror", [0.25, 0.5, 1.0, 0.5 * np.pi])
    new_model = Integrand(ind.phong(n, divide="max"), "mirror", [0.25, 0.5, 1.0, 0.5 * np.pi], nv_levels=lambda nl: (nl,))
    lambert = Integrand(lambda L, V, nl, nv, geo: np.full(nv.shape, 1 / np.pi), "half")
    cases = [(hemisphere_albedo(phong, 0.0), 1.0),                                    # eq. 3.6
             (hemisphere_albedo(new_model, 90 - 1e-9), (n + 2) / (2 * (n + 1))),      # eq. 3.27, up to O(cos θ)
             (hemisphere_albedo(lambert, 37.0), 1.0),
             (disk_albedo(lambda rho, psi: np.full(rho.shape, 1 / np.pi), 63.0), 1.0)]
    for truth, exact in cases:
        assert abs(truth.value - exact) <= truth.error + 1e-9 * (exact == (n + 2) / (2 * (n + 1))), (truth, exact)
    assert all(t.error < 1e-12 for t, _ in cases)


def test_the_oren_nayar_closed_form_truth_agrees_with_a_nested_quad_of_its_rewrite():
    """The sweep's Oren–Nayar truths are a closed form (``independent.oren_nayar_albedo``); here it is
    held to scipy's dblquad of the rewritten BRDF, split at its kinks θ_V = θ and Δφ = π/2."""
    from scipy.integrate import dblquad
    from sweep import independent as ind
    rho, sigma, theta = 0.8, 1.1, 70.0
    f, t = ind.oren_nayar(rho, sigma), np.radians(theta)
    L = np.array([np.sin(t), 0.0, np.cos(t)])

    def g(phi, tv):
        V = np.array([np.sin(tv) * np.cos(phi), np.sin(tv) * np.sin(phi), np.cos(tv)])
        return float(f(L, V)) * np.cos(tv) * np.sin(tv)
    value = sum(2.0 * dblquad(g, a, b, pa, pb, epsabs=1e-13, epsrel=1e-11)[0]
                for a, b in ((0.0, t), (t, np.pi / 2)) for pa, pb in ((0.0, np.pi / 2), (np.pi / 2, np.pi)))
    assert abs(value - ind.oren_nayar_albedo(rho, sigma, theta)) < 1e-11
    assert ind.oren_nayar_albedo(rho, 0.0, theta) == rho                       # σ = 0: Lambert


def test_the_third_routes_disk_is_honest_in_the_square_root_layer_at_grazing_incidence():
    """Near 90° the disk's rim ρ_max(ψ) has a √ layer of width cos θ about ψ = π/2, and the basic patch
    R = 1 a jump at ρ = 1 that meets the rim: the truth within its own error of the lens area
    (eqs. 4.7–4.9) in mpmath at 50 digits.  (The committed truth of this cell was 9.4e-13 off at a
    reported 2.2e-14, computed by an earlier state of the route: the sweep called the package
    dishonest there; the grazing disk truths are recomputed.)"""
    import mpmath as mp
    from sweep.cells import FAMILY, _patch_truth, build
    mp.mp.dps = 50
    d = mp.sin(mp.mpf(89.99) * mp.pi / 180)
    a = mp.acos(d / 2)                           # R = 1: both arccos terms are acos(d/2)
    exact = float((2 * a - d * mp.sqrt(4 - d * d) / 2) / mp.pi)
    # the disk route itself (the committed truths of the basic patch now come from a closed form)
    t = _patch_truth(FAMILY["patch_basic"], {"R": 1.0}, build("patch_basic", {"R": 1.0}), 89.99)
    assert abs(t.value - exact) <= t.error, (t.value, exact, t.error)


def test_rows_the_default_call_answers_are_the_rows_of_that_methods_own_call():
    """``auto`` calls the engine on the same angles, and the disk on all of them where the engine
    refuses: the check takes those answers for the engine's (Phong) or the disk's (the elliptical
    patch, not symmetric about the plane of incidence) rows instead of calling again; a direct call
    gives the same bits."""
    import json
    from brdfs import albedo
    from sweep.cells import build
    groups = {("phong", '{"n": 20.0}'): "engine",
              ("patch_elliptical", '{"b": 0.307268, "ratio": 0.489933, "u_angle_deg": 44.116697}'): "disk"}
    for (family, params), method in groups.items():
        rows = pd.DataFrame(run_group((family, params, [40.0, 89.9], ("default", "engine", "disk"), (1e-6,))))
        derived = rows[rows["method"] == method]
        assert set(derived["source"]) == {"default"}
        assert set(rows[rows["method"] == ({"engine", "disk"} - {method}).pop()]["source"]) == {"call"}
        direct = albedo(build(family, json.loads(params)), np.array([40.0, 89.9]), method=method, rtol=1e-6)
        assert np.array_equal(derived["value"].to_numpy(), direct.value)
        assert np.array_equal(derived["error"].to_numpy(), direct.error)


def test_a_resumed_check_keeps_only_the_groups_it_finished(tmp_path):
    """An interrupted check leaves whole groups (and perhaps none of a group) in its partial file;
    ``--resume`` keeps the whole ones (every angle × method × rtol) and runs the others again."""
    from sweep.check import completed_groups
    whole = [dict(family="phong", params='{"n": 2.0}', theta_deg=t, method=m, rtol=r, value=1.0)
             for t in (10.0, 20.0) for m in ("engine", "disk") for r in (1e-4, 1e-8)]
    cut = [dict(row, family="ward") for row in whole[:5]]
    partial = tmp_path / "sweep_rows.partial.csv"
    pd.DataFrame(whole + cut).to_csv(partial, index=False)
    kept = completed_groups(partial, methods=("engine", "disk"), rtols=(1e-4, 1e-8))
    assert set(kept["family"]) == {"phong"} and len(kept) == len(whole)
