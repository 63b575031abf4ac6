"""The ``brdfs`` command line: its answers are the front door's, and every bad call is refused with
argparse's usage line plus one ``error:`` line naming the argument and its value (status 2)."""
from __future__ import annotations

import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

import brdfs
from brdfs.cli import _key_values, main, parse_theta
from brdfs.physics.models import MODELS


def run(argv, capsys):
    """(exit status, stdout, stderr) of ``brdfs argv``."""
    try:
        status = main(argv)
    except SystemExit as exit_:
        status = exit_.code
    out = capsys.readouterr()
    return status, out.out, out.err


def test_albedo_json_gives_value_error_evaluations_and_status_of_the_front_door(capsys):
    status, out, _ = run(["albedo", "ggx", "--param", "alpha=0.3", "--theta", "60", "--json"], capsys)
    rows = json.loads(out)
    direct = brdfs.albedo(brdfs.model("ggx", alpha=0.3), 60.0)
    assert status == 0 and len(rows) == 1
    assert {"theta_deg", "value", "error", "evaluations", "status"} <= set(rows[0])
    assert rows[0]["value"] == float(direct.value) and rows[0]["error"] == float(direct.error)
    assert rows[0]["evaluations"] == direct.evaluations > 0 and rows[0]["status"] == "converged"


def test_theta_range_includes_its_stop_and_lists_are_taken_as_given():
    assert parse_theta("0:90:5").tolist() == [5.0 * k for k in range(19)]
    assert parse_theta("0:1:0.1")[-1] == pytest.approx(1.0) and parse_theta("0:1:0.1").size == 11
    assert parse_theta("10, 20,85").tolist() == [10.0, 20.0, 85.0]


def test_albedo_csv_has_one_row_per_angle_with_full_precision(capsys):
    status, out, _ = run(["albedo", "phong", "-p", "n=20", "-t", "0:60:30", "--csv"], capsys)
    rows = list(csv.DictReader(io.StringIO(out)))
    assert status == 0 and [float(r["theta_deg"]) for r in rows] == [0.0, 30.0, 60.0]
    assert float(rows[1]["value"]) == float(brdfs.albedo(brdfs.model("phong", n=20), 30.0).value)


def test_models_lists_every_registered_model_with_its_parameters(capsys):
    status, out, _ = run(["models", "--json"], capsys)
    rows = {r["model"]: r for r in json.loads(out)}
    assert status == 0 and set(rows) == set(MODELS)
    assert "n" in rows["phong"]["parameters"] and rows["phong"]["typical"] == MODELS["phong"].examples["typical"]
    # what a parameter takes in words, where it is neither a range nor a choice (the model's param_texts)
    assert all(rows[name]["described"] == dict(cls.param_texts) for name, cls in MODELS.items())
    status, out, _ = run(["models"], capsys)
    assert status == 0 and all(name in out for name in MODELS)
    assert all(f"{key}: {text}" in out for cls in MODELS.values() for key, text in cls.param_texts.items())


def test_chi2_passes_a_models_own_sampler_and_reports_the_statistic(capsys):
    status, out, _ = run(["chi2", "phong", "-p", "n=20", "-t", "30", "-n", "20000", "--json"], capsys)
    (row,) = json.loads(out)
    assert status == 0 and row["passes"] and row["dof"] > 0 and row["strategy"] == MODELS["phong"].strategies[0]


def test_compare_counts_the_verdicts_of_a_builds_comparison(tmp_path, capsys):
    (tmp_path / "checks").mkdir()
    header = "artifact,source,model,param,param_value,quantity,published,computed,computed_err,verdict,reason\n"
    body = ("a,Table 3.1,phong,n,1,C,0.35,0.3496,1e-15,reproduces,\n"
            "b,Table 3.2,ward,m,0.4,C,1.63,1.6205,1e-12,differs,rounding\n"
            "c,Table 4.1,patch,s,2,I,0.1,0.1,0,reproduces,\n")
    (tmp_path / "checks" / "published_comparison.csv").write_text(header + body)
    status, out, _ = run(["compare", "--results", str(tmp_path), "--json"], capsys)
    summary = json.loads(out)
    assert status == 0 and summary["total"] == {"reproduces": 2, "differs": 1}
    assert summary["chapters"] == {"chapter 3": {"reproduces": 1, "differs": 1}, "chapter 4": {"reproduces": 1}}
    assert [d["artifact"] for d in summary["differing"]] == ["b"]


BAD_CALLS = [
    # (argv, text the one error line must contain: the argument and its value)
    (["albedo", "no_such_model", "-t", "30"], "no_such_model"),
    (["albedo", "phong", "-p", "n=abc", "-t", "30"], "'abc'"),
    (["albedo", "phong", "-p", "n=-1", "-t", "30"], "-1"),
    (["albedo", "phong", "-p", "n=inf", "-t", "30"], "inf"),
    (["albedo", "phong", "-p", "n=nan", "-t", "30"], "nan"),
    (["albedo", "phong", "-p", "q=2", "-t", "30"], "q"),
    (["albedo", "phong", "-p", "n20", "-t", "30"], "'n20'"),
    (["albedo", "phong", "-p", "n=20", "-t", "95"], "95"),
    (["albedo", "phong", "-p", "n=20", "-t", "0:90:0"], "0:90:0"),
    (["albedo", "phong", "-p", "n=20", "-t", "ten"], "ten"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--method", "simpson"], "simpson"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--rtol", "-1"], "-1"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--atol", "0"], "atol"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--rtol", "x"], "'x'"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--method", "monte_carlo", "-o", "n_sample=10"], "n_sample"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--method", "engine", "-o", "n_samples=10"], "n_samples"),
    (["albedo", "phong", "-p", "n=20"], "--theta"),
    (["albedo", "cook_torrance", "-p", "m=0.1", "-p", "G=smiht", "-t", "30"], "smiht"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "--strategy", "magic"], "magic"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "-n", "0"], "'0'"),
    (["compare", "--results", "/nonexistent/results"], "/nonexistent/results"),
    (["render"], "render"),
    (["albedo", "phong", "-p", "n=20", "-p", "n=30", "-t", "30"], "n=20 and n=30"),
    (["albedo", "p_model", "-p", "n=20", "p=0.5", "n=4", "-t", "30"], "n=20 and n=4"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--json", "--csv"], "--json"),
    (["albedo", "phong", "-p", "n=20", "-t", "30", "--method", "monte_carlo", "-o", "n_samples=10", "-o",
      "n_samples=20"], "n_samples=10 and n_samples=20"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "--significance", "2"], "--significance"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "--significance", "0"], "'0'"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "--seed", "-1"], "--seed"),
    (["chi2", "phong", "-p", "n=20", "-t", "30", "--seed", "1.5"], "'1.5'"),
    (["--import", "/no/such/model.py", "models"], "/no/such/model.py"),
    (["--import", "no_such_module_43", "models"], "no_such_module_43"),
]


@pytest.mark.parametrize("argv, named", BAD_CALLS, ids=[" ".join(a) for a, _ in BAD_CALLS])
def test_a_bad_call_prints_usage_and_one_error_line_naming_it_and_exits_2(argv, named, capsys):
    status, out, err = run(argv, capsys)
    lines = [line for line in err.splitlines() if line.strip()]
    errors = [line for line in lines if "error:" in line]
    assert status == 2, (status, out, err)
    assert lines[0].startswith("usage: brdfs"), err
    assert len(errors) == 1 and named in errors[0], err
    assert out == ""


def test_python_dash_m_brdfs_is_the_command_line():
    # the reciprocal Phong at n = 0 is 1/pi on the half-space R.V > 0: albedo 1 at normal incidence
    done = subprocess.run([sys.executable, "-m", "brdfs", "albedo", "phong", "-p", "n=0", "-t", "0", "--json"],
                          capture_output=True, text=True, check=True)
    values = [row["value"] for row in json.loads(done.stdout)]
    assert np.allclose(values, 1.0, rtol=1e-12)


def test_help_names_every_subcommand_and_option(capsys):
    status, out, _ = run(["--help"], capsys)
    assert status == 0 and all(c in out for c in ("models", "albedo", "chi2", "compare"))
    status, out, _ = run(["albedo", "--help"], capsys)
    assert status == 0 and all(o in out for o in ("--param", "--theta", "--method", "--rtol", "--atol",
                                                  "--option", "--csv", "--json"))


def test_param_takes_several_pairs_after_one_option_as_the_models_listing_shows_them(capsys):
    status, out, _ = run(["albedo", "p_model", "--param", "n=20", "p=0.5", "--theta", "30", "--json"], capsys)
    direct = brdfs.albedo(brdfs.model("p_model", n=20, p=0.5), 30.0)
    assert status == 0 and json.loads(out)[0]["value"] == float(direct.value)
    status, out, _ = run(["models"], capsys)
    assert "e.g. --param n=20 p=0.5;" in out and "n=20.0" not in out
    rows = {r["model"]: r for r in json.loads(run(["models", "--json"], capsys)[1])}
    for name, row in rows.items():            # each listed example, read as --param reads it, builds the model
        if row["command_line"] and row["example_param"]:
            params = _key_values([row["example_param"].split()], "--param")
            assert brdfs.model(name, **params).params.items() >= MODELS[name].examples["typical"].items(), name


def test_a_model_the_command_line_cannot_build_is_listed_as_such_without_an_object_address(capsys):
    unbuildable = [n for n, c in MODELS.items() if any(callable(v) for e in c.examples.values() for v in e.values())]
    assert unbuildable                          # the patch mixture's weight is a Python function
    status, out, _ = run(["models"], capsys)
    assert status == 0 and " at 0x" not in out and "<function" not in out
    for name in unbuildable:
        line = out.split(name, 1)[1].splitlines()[1]
        assert "not buildable from the command line" in line, line
    rows = {r["model"]: r for r in json.loads(run(["models", "--json"], capsys)[1])}
    assert all(rows[n]["command_line"] is False and rows[n]["typical"] is None for n in unbuildable)


def test_version_is_the_packages_one(capsys):
    status, out, _ = run(["--version"], capsys)
    assert status == 0 and out.strip() == f"brdfs {brdfs.__version__}"
