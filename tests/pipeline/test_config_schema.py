"""config.yaml against workflow/schemas/config.schema.yaml, in-process and through `snakemake -n`.

Every malformed configuration must stop with ONE line that names the key and the value,
before any rule runs and without writing anything under results/.
"""

import copy
import functools
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

from dataclasses import dataclass

import numpy as np
import pytest
import yaml

from brdfs.physics.models import BRDF, MODELS, register
from brdfs.physics.models.base import Interval
from brdfs.pipeline.config import (CONFIG_SCHEMA, CONFIG_YAML, ConfigError, load_config, load_schema, validate_config,
                                   yaml12_scalar)
from brdfs.pipeline.io import REPO_ROOT

SNAKEMAKE = Path(sys.executable).with_name("snakemake")
NAN, INF = float("nan"), float("inf")


@functools.lru_cache(maxsize=None)
def _parsed(path: Path) -> dict:
    return yaml.safe_load(path.read_text())


def raw_config() -> dict:
    """config.yaml as PyYAML reads it (a fresh copy each call)."""
    return copy.deepcopy(_parsed(CONFIG_YAML))


def schema() -> dict:
    """The schema file as PyYAML reads it (read only: no copy)."""
    return _parsed(CONFIG_SCHEMA)


def set_key(config: dict, path: str, value) -> dict:
    """``config`` with the dotted ``path`` (integers index lists) set to ``value``."""
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    node = config
    for part in parents:
        node = node[part]
    node[last] = value
    return config


def delete_key(config: dict, path: str) -> dict:
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    node = config
    for part in parents:
        node = node[part]
    del node[last]
    return config


# (dotted key, bad value): unknown keys, wrong types, negative exponents, angles outside
# [0, 90], tolerances <= 0, unknown model names, empty lists, other out-of-range values.
MALFORMED = [
    # unknown keys, at the top and nested
    ("colour", "red"),
    ("metal_reflectance.colour", "red"),
    ("grazing.readings.ward_mm", 0.1),
    ("grazing.fig_2_1_models.0.nn", 150),
    ("patch.fig_4_10_ellipses.0.c", 0.3),
    ("he_torrance.fig_3_3.phong.m", 0.1),
    # wrong types
    ("seed", "twenty"),
    ("seed", 1.5),
    ("tolerance", -1),
    ("tolerance.rtol", "tight"),
    ("pumping.levels", 2.5),
    ("blinn_cn.n", 8),
    ("metal_reflectance.metals.0.lambda_nm", "578nm"),
    ("patch.fig_4_10_grid", True),
    # negative exponents
    ("blinn_cn.n.0", -1),
    ("mean_albedo.n.2", -4),
    ("pumping.n", -20),
    ("grazing.fig_2_1_models.0.n", -150),
    ("new_model_albedo.radiance_n", -100),
    ("grazing.stability.n_values.1", -8),
    # angles outside [0, 90]
    ("grazing.readings.ward_theta_deg.0", 90.5),
    ("grazing.readings.cook_torrance_theta_deg.1", -1.0),
    ("new_model_lobes.slice_theta_deg.1", 95.0),
    ("p_model_ratio.theta_l_deg.0", 90.0),
    ("patch.fig_4_3_theta_deg.0", -10.0),
    ("patch.fig_4_10_theta_deg", 91.0),
    ("he_torrance.fig_3_3.theta_deg", 120.0),
    ("grazing.ward_in_range.theta_max_deg", 90.0),
    # tolerances <= 0
    ("tolerance.rtol", 0.0),
    ("tolerance.rtol", -1.0e-10),
    ("tolerance.atol", 0.0),
    ("mean_albedo.rtol", -1.0e-9),
    ("pumping.engine_rtol", 0.0),
    # unknown model names
    ("grazing.fig_2_1_models.1.model", "torrance"),
    ("grazing.divergence_models.0.model", "Phong"),
    ("grazing.stability.models.0", "lambert"),
    ("work_precision.cases.0.model", "blinn_at_90"),
    # empty lists
    ("blinn_cn.n", []),
    ("ward_cmax.m", []),
    ("grazing.fig_3_4_models", []),
    ("metal_reflectance.metals", []),
    ("patch.fig_s", []),
    ("new_model_albedo.fig_3_1_n", []),
    # other ranges and enums
    ("seed", -5),
    ("ward_cmax.m.0", 0.0),
    ("metal_reflectance.metals.4.ior_re", -2.97),
    ("patch.m_clip", 2.0),
    ("grazing.fig_2_1_models.2.G", "beckmann"),
    ("he_torrance.fig_3_3.quantity", "radiance"),
    # NaN and +-inf, in every kind of numeric field (integer, number, list item, oneOf, model parameter)
    ("seed", NAN),
    ("seed", INF),
    ("tolerance.rtol", NAN),
    ("tolerance.atol", INF),
    ("tolerance.rtol", -INF),
    ("mean_albedo.rtol", NAN),
    ("pumping.levels", NAN),
    ("ward_cmax.m.0", NAN),
    ("blinn_cn.n.1", INF),
    ("grazing.readings.ward_theta_deg.0", NAN),
    ("grazing.readings.cook_torrance_theta_deg.1", -INF),
    ("grazing.fig_2_1_models.0.n", INF),
    ("metal_reflectance.metals.4.ior_re", NAN),
    ("patch.m_clip", INF),
    ("work_precision.cases.0.theta_deg", NAN),
    ("work_precision.cases.3.m", NAN),
    ("accuracy_map.reduced.families.cook_torrance_ts.0", INF),
    # strings that are no YAML 1.2 number where the schema wants one
    ("tolerance.rtol", "1e-10x"),
    ("tolerance.atol", "nan"),
    ("tolerance.rtol", ".nan.0"),
    ("ward_cmax.m.0", "0.1 "),
    ("pumping.levels", "true"),
]

# Strings that YAML 1.2 reads as a number: refused by the number's own range, and the message names
# the number as read (key, string, the value the message shows).
MALFORMED_YAML12 = [
    ("tolerance.rtol", "-1e-10", "tolerance.rtol = -1e-10: must be >= 1e-15"),
    ("tolerance.rtol", ".nan", "tolerance.rtol = nan: must be a finite number"),
    ("tolerance.atol", "-.inf", "tolerance.atol = -inf: must be a finite number"),
    ("ward_cmax.m.0", "+.INF", "ward_cmax.m[0] = inf: must be a finite number"),
    ("seed", "-5", "seed = -5: must be >= 0"),
]

# `--config` entries as Snakemake parses and merges them (nested scalars are strings, merged into
# the file's sections): (entry, the line's start up to and including the value).
MALFORMED_OVERRIDES = [
    ("seed=nan", "seed = nan: must be a finite number"),
    ("seed=inf", "seed = inf: must be a finite number"),
    ("seed=-inf", "seed = -inf: must be a finite number"),
    ("tolerance={rtol: .nan}", "tolerance.rtol = nan: must be a finite number"),
    ("tolerance={atol: .inf}", "tolerance.atol = inf: must be a finite number"),
    ("tolerance={rtol: -.Inf, atol: 1e-14}", "tolerance.rtol = -inf: must be a finite number"),
    ("tolerance={rtol: -1e-8}", "tolerance.rtol = -1e-08: must be >= 1e-15"),
    ("tolerance={rtol: tight}", "tolerance.rtol = 'tight': must be of type number"),
    ("tolerance={rtol: null}", "tolerance.rtol = 'null': must be of type number"),
    ("tolerance={rtol: nan}", "tolerance.rtol = 'nan': must be of type number"),
    ("tolerance={rtol: [1.0e-8]}", "tolerance.rtol = ['1.0e-8']: must be of type number"),
    ("tolerance={rtol: 1e-8, colour: red}", "tolerance.colour = 'red': unknown key"),
    ("tolerance={rtol: 1e-8", "tolerance = '{rtol: 1e-8': must be of type object"),
    ("ward_cmax={m: []}", "ward_cmax.m = []: must not be empty"),
    ("ward_cmax={m: [0.1, .nan]}", "ward_cmax.m[1] = nan: must be a finite number"),
    ("ward_cmax={m: [0.1, 0]}", "ward_cmax.m[1] = 0: must be > 0"),
    ("blinn_cn={n: [2, -8]}", "blinn_cn.n[1] = -8: must be > 0"),
    ("pumping={levels: 2.5}", "pumping.levels = 2.5: must be of type integer"),
    ("pumping={levels: true}", "pumping.levels = 'true': must be of type integer"),
    ("grazing={readings: {ward_theta_deg: [90.5]}}", "grazing.readings.ward_theta_deg[0] = 90.5: must be < 90"),
    ("grazing={readings: {ward_mm: 0.1}}", "grazing.readings.ward_mm = '0.1': unknown key"),
    ("patch={m_clip: .inf}", "patch.m_clip = inf: must be a finite number"),
    ("work_precision={cases: [{label: a, model: phong, n: 10, theta_deg: .nan}]}",
     "work_precision.cases[0].theta_deg = nan: must be a finite number"),
    ("work_precision={cases: [{label: a, model: torrance, theta_deg: 45}]}",
     "work_precision.cases[0].model = 'torrance': must be one of"),
]


def override(*entries: str) -> dict:
    """The shipped config updated by ``--config`` entries, as Snakemake parses and merges them."""
    from snakemake.cli import parse_config
    from snakemake.utils import update_config

    config = raw_config()
    update_config(config, parse_config(list(entries)))
    return config


def test_at_least_sixty_malformed_configs_are_tried():
    assert len(MALFORMED) + len(MALFORMED_YAML12) + len(MALFORMED_OVERRIDES) >= 60
    assert sum(isinstance(v, float) and not math.isfinite(v) for _, v in MALFORMED) >= 10


def test_the_shipped_config_is_valid_and_defaults_are_filled():
    config = raw_config()
    del config["tolerance"]
    assert validate_config(config)["tolerance"] == {"rtol": 1e-10, "atol": 1e-14}
    assert load_config()["tolerance"] == {"rtol": 1e-10, "atol": 1e-14}


@pytest.mark.parametrize(("key", "value"), MALFORMED, ids=[f"{k}={v!r}" for k, v in MALFORMED])
def test_malformed_config_stops_with_one_line_naming_key_and_value(key, value):
    with pytest.raises(ConfigError) as error:
        validate_config(set_key(raw_config(), key, value))
    message = str(error.value)
    shown = key.split(".")
    # the key as printed: a.b[0].c
    printed = shown[0] + "".join(f"[{p}]" if p.isdigit() else f".{p}" for p in shown[1:])
    assert "\n" not in message and len(message) < 400, message
    assert f"{printed} = {value!r}" in message, message


@pytest.mark.parametrize(("key", "value", "line"), MALFORMED_YAML12, ids=[f"{k}={v!r}" for k, v, _ in MALFORMED_YAML12])
def test_a_string_read_as_a_yaml_12_number_is_checked_as_that_number(key, value, line):
    with pytest.raises(ConfigError) as error:
        validate_config(set_key(raw_config(), key, value))
    assert str(error.value) == f"Error validating config file: {line}"


@pytest.mark.parametrize(("entry", "line"), MALFORMED_OVERRIDES, ids=[e for e, _ in MALFORMED_OVERRIDES])
def test_a_malformed_command_line_override_stops_with_one_line_naming_key_and_value(entry, line):
    with pytest.raises(ConfigError) as error:
        validate_config(override(entry))
    message = str(error.value)
    assert "\n" not in message and message.startswith(f"Error validating config file: {line}"), message


def test_nested_overrides_are_read_as_yaml_and_merged_into_the_files_sections():
    config = validate_config(override("tolerance={rtol: 1.0e-8, atol: 1.0e-15}"))
    assert config["tolerance"] == {"rtol": 1e-8, "atol": 1e-15}
    # deep merge: the keys not given keep the file's values
    config = validate_config(override("tolerance={rtol: 1e-8}", "grazing={readings: {ward_theta_deg: [89.9, 8e1]}}"))
    assert config["tolerance"] == {"rtol": 1e-8, "atol": 1e-14}
    assert config["grazing"]["readings"]["ward_theta_deg"] == [89.9, 80.0]
    assert config["grazing"]["readings"]["grids"] == raw_config()["grazing"]["readings"]["grids"]
    assert config["seed"] == raw_config()["seed"]
    # integers, booleans and strings as the schema wants them; a list replaces the file's list
    config = validate_config(override("seed=7", "pumping={levels: 3}", "work_precision={cases: "
                                      "[{label: '1e-10', model: blinn_cosmin, n: 2, theta_deg: max}, "
                                      "{label: b, model: ward, m: 1e-1, theta_deg: 60}]}"))
    assert config["seed"] == 7 and config["pumping"]["levels"] == 3 and type(config["pumping"]["levels"]) is int
    assert config["work_precision"]["cases"] == [
        {"label": "1e-10", "model": "blinn_cosmin", "n": 2, "theta_deg": "max"},
        {"label": "b", "model": "ward", "m": 0.1, "theta_deg": 60},
    ]


def test_yaml_12_numbers_in_the_config_file_are_numbers(tmp_path):
    text = CONFIG_YAML.read_text().replace("rtol: 1.0e-10", "rtol: 1e-10").replace("atol: 1.0e-14", "atol: 1E-14")
    assert yaml.safe_load(text)["tolerance"] == {"rtol": "1e-10", "atol": "1E-14"}   # PyYAML: YAML 1.1 strings
    (tmp_path / "config.yaml").write_text(text)
    config = load_config(tmp_path / "config.yaml")
    assert config["tolerance"] == {"rtol": 1e-10, "atol": 1e-14} and type(config["tolerance"]["rtol"]) is float
    assert config == load_config()
    for text, value in [("1e-10", 1e-10), ("-2.5E+3", -2500.0), (".5", 0.5), ("1.", 1.0), ("0x1f", 31), ("0o17", 15),
                        ("+.inf", INF), ("true", True), ("~", None), ("1e", "1e"), ("max", "max"), ("1_000", "1_000")]:
        assert yaml12_scalar(text) == value and type(yaml12_scalar(text)) is type(value), text


def test_a_missing_required_key_is_named():
    with pytest.raises(ConfigError, match=r"^Error validating config file: grazing\.readings\.grids is missing"):
        validate_config(delete_key(raw_config(), "grazing.readings.grids"))


def test_every_key_of_the_schema_has_a_description_and_every_number_a_range():
    def resolve(node):
        ref = node.get("$ref", "")
        return {**schema()["$defs"][ref.rsplit("/", 1)[1]], **node} if ref else node

    def check(name, node):
        node = resolve(node)
        assert node.get("description"), f"{name}: no description"
        if node.get("type") in ("number", "integer"):
            assert {"minimum", "exclusiveMinimum"} & set(node) and {"maximum", "exclusiveMaximum"} & set(node), name
        assert "type" in node or "enum" in node or "const" in node, f"{name}: no type"
        walk(name, node)

    def walk(name, node):
        if node.get("type") == "object" or "properties" in node:
            # keysAre: keys the schema cannot list (a figure's object labels), refused by a named check
            # with the whole config (test_config_meaning holds that check to refusing an unknown key);
            # propertyNames: keys from an enum the schema is filled in with (the render figures)
            closed = node.get("additionalProperties") is False or "keysAre" in node
            ref = node.get("propertyNames", {}).get("$ref", "#/").rsplit("/", 1)[1]
            named = "enum" in load_schema()["$defs"].get(ref, {})
            assert closed or named, f"{name}: admits unknown keys"
            for key, sub in node.get("properties", {}).items():
                check(f"{name}.{key}", sub)
            if isinstance(node.get("additionalProperties"), dict):
                check(f"{name}.<key>", node["additionalProperties"])
        items = resolve(node.get("items", {})) if "items" in node else None
        if items:
            if items.get("type") in ("number", "integer"):
                assert {"minimum", "exclusiveMinimum"} & set(items) and {"maximum", "exclusiveMaximum"} & set(items), name
            walk(f"{name}[]", items)

    walk("config", schema())
    assert set(schema()["properties"]) >= set(raw_config())


def test_the_schemas_model_names_are_the_registered_models():
    assert load_schema()["$defs"]["model_name"]["enum"] == sorted(MODELS)


def test_the_schemas_render_figures_are_the_registered_artifacts_that_render():
    """One list of the render figures, the registry's: every per-figure mapping of a preset takes them."""
    from brdfs.pipeline import registry

    rendering = sorted(name for name, artifact in registry.artifacts().items() if artifact.renders)
    assert load_schema()["$defs"]["render_figure"]["enum"] == rendering and len(rendering) == 12
    preset = load_schema()["properties"]["renders"]["properties"]["preview"]["properties"]
    for key in ("figure_spp", "crop_spp", "object_spp", "adaptive", "clamp"):
        assert preset[key]["propertyNames"] == {"$ref": "#/$defs/render_figure"}, key


@dataclass(frozen=True)
class TintedLambert(BRDF):
    """f = ρ/π, ρ ∈ [0, 1], and a categorical tint: defined here only, the schema knows nothing of it."""

    rho: float = 1.0
    tint: str = "grey"
    name = "tinted_lambert_in_a_test"
    param_ranges = {"rho": Interval(0.0, 1.0)}
    param_choices = {"tint": ("grey", "warm")}
    examples = {"typical": {"rho": 0.5}, "narrowest": {"rho": 1.0}}
    accuracy_families = {"tinted_lambert_rho": ("rho", {})}

    def _eval(self, L, V, nl, nv):
        return np.full(np.broadcast_shapes(nl.shape, nv.shape), self.rho / np.pi)


@pytest.fixture
def tinted_lambert():
    register(TintedLambert)
    yield TintedLambert
    del MODELS[TintedLambert.name]


def test_a_model_registered_in_a_test_is_accepted_wherever_models_are_named(tinted_lambert):
    """Its name, its parameters (with their declared range and choices) beside every ``model`` key,
    and its accuracy-map family, all taken from the class."""
    config = raw_config()
    entry = {"model": TintedLambert.name, "rho": 0.25, "tint": "warm"}
    config["grazing"]["fig_2_1_models"].append(dict(entry))
    config["grazing"]["stability"]["models"].append(TintedLambert.name)
    config["work_precision"]["cases"].append({"label": "tinted", "theta_deg": 30.0, **entry})
    config["accuracy_map"]["reduced"]["families"]["tinted_lambert_rho"] = [0.5, 1.0]
    validate_config(config)


@pytest.mark.parametrize(("key", "value"), [
    ("grazing.fig_2_1_models.3.rho", 1.5),
    ("grazing.fig_2_1_models.3.tint", "blue"),
    ("work_precision.cases.0.rho", -0.1),
    ("accuracy_map.reduced.families.tinted_lambert_rho.0", 2.0),
])
def test_a_registered_models_parameters_are_bounded_by_its_declared_ranges(tinted_lambert, key, value):
    config = raw_config()
    config["grazing"]["fig_2_1_models"].append({"model": TintedLambert.name, "rho": 0.5})
    config["accuracy_map"]["reduced"]["families"]["tinted_lambert_rho"] = [0.5]
    with pytest.raises(ConfigError) as error:
        validate_config(set_key(config, key, value))
    assert repr(value) in str(error.value)


def test_an_unregistered_models_family_and_parameters_are_unknown_keys():
    config = raw_config()
    config["accuracy_map"]["reduced"]["families"]["tinted_lambert_rho"] = [0.5]
    with pytest.raises(ConfigError, match="tinted_lambert_rho"):
        validate_config(config)
    config = raw_config()
    config["grazing"]["fig_2_1_models"].append({"model": "phong", "tint_in_a_test": 0.5})   # (oren_nayar has rho)
    with pytest.raises(ConfigError, match="tint_in_a_test"):
        validate_config(config)


def test_the_accuracy_map_families_are_the_models_declared_families():
    families = load_schema()["properties"]["accuracy_map"]["properties"]["reduced"]["properties"]["families"]
    declared = {f for cls in MODELS.values() for f in cls.accuracy_families}
    assert set(families["properties"]) == declared


def dry_run(tmp_path: Path, *config_args: str) -> subprocess.CompletedProcess:
    """`snakemake -n --config ...` in a copy of the workflow."""
    for name in ("Snakefile", "workflow", "config.yaml"):
        (shutil.copytree if (REPO_ROOT / name).is_dir() else shutil.copy)(REPO_ROOT / name, tmp_path / name)
    for name in ("src", "data"):
        (tmp_path / name).symlink_to(REPO_ROOT / name)
    env = {**os.environ, "PATH": f"{SNAKEMAKE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    args = [str(SNAKEMAKE), "-n", "--cores", "1", *(["--config", *config_args] if config_args else [])]
    return subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, env=env, timeout=120)


# The valid configuration through `snakemake -n` (with `1e-10` in config.yaml and nested `--config`
# values): tests/pipeline/test_workflow_e2e.py plans the whole workflow so, once for its claims and these.


# `--config` entries and the whole line each stops the run with. All are read in process as Snakemake's
# command line reads and merges them (the workflow calls the same validate_config on the result); the
# last also goes through `snakemake -n`, for the wiring: one line, no traceback, before any job.
COMMAND_LINE_STOPS = [
    ("tolerance=-1", "Error validating config file: tolerance = -1: must be of type object"),
    ("seed=-5", "Error validating config file: seed = -5: must be >= 0"),
    ("colour=red", "Error validating config file: colour = 'red': unknown key"),
    ("tolerance={rtol: .nan}", "Error validating config file: tolerance.rtol = nan: must be a finite number"),
]


@pytest.mark.parametrize(("argument", "line"), COMMAND_LINE_STOPS, ids=[a for a, _ in COMMAND_LINE_STOPS])
def test_a_malformed_command_line_config_stops_with_exactly_its_line(argument, line):
    with pytest.raises(ConfigError) as error:
        validate_config(override(argument))
    assert str(error.value) == line


def test_snakemake_stops_on_a_malformed_command_line_config(tmp_path):
    argument, line = COMMAND_LINE_STOPS[-1]
    run = dry_run(tmp_path, argument)
    assert run.returncode != 0
    output = run.stdout + run.stderr
    assert line in output.splitlines(), output
    assert "Traceback" not in output and "Building DAG" not in output, output
    assert not (tmp_path / "results").exists()
