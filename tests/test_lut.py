"""Tables for renderers (``brdfs lut``): E(μ, p) cells are the engine's albedos with their errors, E_avg
agrees with an independent integration of E(μ) over μ and with a Monte Carlo estimate, and the files
carry the metadata a renderer's build needs."""
from __future__ import annotations

import json

import numpy as np
import pytest

import brdfs
from brdfs import lut
from brdfs.cli import main


@pytest.fixture(scope="module")
def small():
    """GGX with F = 1 at α = 0.1, 0.3, 0.5 on 8 cells of μ."""
    return lut.albedo_lut("ggx", "alpha", [0.1, 0.3, 0.5], n_mu=8)


def test_the_cells_are_the_engines_albedos_at_the_cell_centres(small):
    assert small.mu.tolist() == [(j + 0.5) / 8 for j in range(8)] and small.converged
    direct = brdfs.albedo(brdfs.model("ggx", alpha=0.3), lut.theta_of_mu(small.mu))
    np.testing.assert_allclose(small.E[1], direct.value, rtol=1e-12)
    assert np.all(small.E_error <= 1e-10 * small.E + 1e-14) and np.all(small.E_error > 0)


def test_e_avg_agrees_with_a_direct_integration_of_e_over_mu(small):
    """2 ∫ E(μ) μ dμ by Gauss–Legendre in μ on 24 and 48 nodes (engine albedos at each): the two
    rules agree to 1e-9, and E_avg lies within its error plus that difference of the finer one."""
    estimates = []
    for n in (24, 48):
        x, w = np.polynomial.legendre.leggauss(n)
        mu, wmu = 0.5 * (x + 1), 0.5 * w
        E = brdfs.albedo_table([brdfs.model("ggx", alpha=a) for a in small.param_values], lut.theta_of_mu(mu))
        estimates.append(2 * (E.value * mu) @ wmu)
    quadrature = np.abs(estimates[1] - estimates[0])
    assert np.all(quadrature < 1e-8), quadrature
    assert np.all(np.abs(small.E_avg - estimates[1]) <= small.E_avg_error + quadrature + 1e-12), (
        small.E_avg - estimates[1], small.E_avg_error, quadrature)


def test_e_avg_agrees_with_a_million_sample_monte_carlo_within_four_standard_errors(small):
    """E_avg = (1/π) ∬ f cos θ_L cos θ_V: L cosine-distributed (μ_L = √u, density 2μ_L over μ_L), V from
    the model's own sampler; the mean weight is E_avg, 10⁶ samples, seed fixed."""
    rng = np.random.default_rng(20010101)
    f = brdfs.model("ggx", alpha=0.3)
    n = 1_000_000
    u = rng.random((n, 4))
    mu_l, phi = np.sqrt(u[:, 0]), 2 * np.pi * u[:, 1]
    s = np.sqrt(1 - mu_l ** 2)
    L = np.stack([s * np.cos(phi), s * np.sin(phi), mu_l], -1)
    _, weight, _ = f.sample(L, u[:, 2:])
    mean, standard_error = weight.mean(), weight.std(ddof=1) / np.sqrt(n)
    assert standard_error < 1e-3
    assert abs(mean - small.E_avg[1]) <= 4 * standard_error, (mean, small.E_avg[1], standard_error)


def test_a_wrong_e_avg_would_fail_the_monte_carlo_check(small):
    """The check above can fail: E_avg of α = 0.1 or 0.5 is many standard errors (~3e-4) from α = 0.3's."""
    assert abs(small.E_avg[0] - small.E_avg[1]) > 40 * 3e-4 and abs(small.E_avg[2] - small.E_avg[1]) > 40 * 3e-4


@pytest.mark.parametrize("fmt", ["npy", "csv"])
def test_the_file_holds_every_cell_its_error_and_the_metadata(small, tmp_path, fmt):
    path = lut.write(small, tmp_path / f"ggx.{fmt}")
    back = lut.read(path)
    for key in ("E", "E_error", "E_avg", "E_avg_error", "mu", "param_values"):
        np.testing.assert_array_equal(back[key], getattr(small, key))
    meta = back["metadata"]
    assert meta["model"] == "ggx" and meta["param"] == "alpha" and meta["rtol"] == 1e-10
    assert meta["version"] == brdfs.__version__ and meta["fixed_params"] == {} and meta["converged"] is True


def test_the_command_writes_the_table_and_refuses_a_bad_sweep_with_one_line(tmp_path, capsys):
    out = tmp_path / "ggx.npy"
    assert main(["lut", "ggx", "--param", "alpha=0.2:0.4:2", "--mu", "4", "-o", str(out)]) == 0
    table = np.load(out)
    assert table["E"].shape == (2, 4) and json.loads(str(table["metadata"]))["n_mu"] == 4
    assert "largest error" in capsys.readouterr().out
    for argv, named in ((["--param", "alpha=0.2"], "exactly one swept parameter"),
                        (["--param", "alpha=0.4:0.2:3"], "alpha=0.4:0.2:3"),
                        (["--param", "alpha=0.1:0.2:3", "ior_re=1:2:2"], "got 2"),
                        (["--param", "alpha=0:0.2:3"], "alpha"),
                        (["--param", "alpha=0.1:0.2:3", "--format", "tiff"], "tiff")):
        with pytest.raises(SystemExit) as exit_:
            main(["lut", "ggx", *argv, "-o", str(tmp_path / "x.npy")])
        err = capsys.readouterr().err
        assert exit_.value.code == 2 and [line for line in err.splitlines() if "error:" in line][0].count(named), err
