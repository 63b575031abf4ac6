"""config.yaml against workflow/schemas/config.schema.yaml, in-process and through `snakemake -n`."""

import copy
import os
import shutil
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
import yaml

from brdfs.pipeline.config import CONFIG_YAML, load_config, validate_config
from brdfs.pipeline.io import REPO_ROOT

SNAKEMAKE = Path(sys.executable).with_name("snakemake")


def broken(config: dict, case: str) -> dict:
    """``config`` with one mistake; see BROKEN."""
    config = copy.deepcopy(config)
    if case == "wrong type":
        config["tolerance"]["rtol"] = "tight"
    elif case == "unknown key":
        config["metal_reflectance"]["colour"] = "red"
    elif case == "out of range":
        config["metal_reflectance"]["metals"][4]["ior_re"] = -2.97
    return config


# case -> what the error message must contain: the key and the bad value
BROKEN = {
    "wrong type": ["'tight' is not of type 'number'", "['tolerance']['rtol']"],
    "unknown key": ["'colour' was unexpected", "'red'"],
    "out of range": ["-2.97 is less than or equal to the minimum of 0", "['metal_reflectance']['metals'][4]['ior_re']"],
}


def raw_config() -> dict:
    return yaml.safe_load(CONFIG_YAML.read_text())


def test_config_is_valid_and_defaults_are_filled():
    config = raw_config()
    del config["tolerance"]
    assert validate_config(config)["tolerance"] == {"rtol": 1e-10, "atol": 1e-14}
    assert load_config()["tolerance"] == {"rtol": 1e-10, "atol": 1e-14}


@pytest.mark.parametrize("case", BROKEN)
def test_schema_rejects_in_process(case):
    with pytest.raises(jsonschema.ValidationError) as error:
        validate_config(broken(raw_config(), case))
    message = str(error.value)
    assert all(part in message for part in BROKEN[case]), message


def test_every_object_of_the_schema_forbids_unknown_keys():
    schema = yaml.safe_load((REPO_ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())

    def objects(node):
        if isinstance(node, dict):
            if node.get("type") == "object":
                yield node
            for value in node.values():
                yield from objects(value)

    found = list(objects(schema))
    assert len(found) >= 4 and all(o.get("additionalProperties") is False for o in found)


def dry_run(tmp_path: Path, config: dict) -> subprocess.CompletedProcess:
    """`snakemake -n` in a copy of the workflow with ``config`` as its config.yaml."""
    for name in ("Snakefile", "workflow"):
        (shutil.copytree if (REPO_ROOT / name).is_dir() else shutil.copy)(REPO_ROOT / name, tmp_path / name)
    for name in ("src", "data"):
        (tmp_path / name).symlink_to(REPO_ROOT / name)
    (tmp_path / "config.yaml").write_text(yaml.safe_dump(config))
    env = {**os.environ, "PATH": f"{SNAKEMAKE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    return subprocess.run(
        [str(SNAKEMAKE), "-n", "--cores", "1"], cwd=tmp_path, capture_output=True, text=True, env=env, timeout=120
    )


def test_dry_run_of_the_valid_config_plans_every_rule(tmp_path):
    run = dry_run(tmp_path, raw_config())
    assert run.returncode == 0, run.stderr
    assert "results/checks/published/metal_a0.csv" in run.stdout and "merge_comparison" in run.stdout
    assert "results/figures/fig_2_1_albedo_classical.png" in run.stdout
    assert not (tmp_path / "results").exists()


@pytest.mark.parametrize("case", BROKEN)
def test_dry_run_stops_on_a_broken_config(tmp_path, case):
    run = dry_run(tmp_path, broken(raw_config(), case))
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "Error validating config file" in output
    assert all(part in output for part in BROKEN[case]), output
    assert not (tmp_path / "results").exists()
