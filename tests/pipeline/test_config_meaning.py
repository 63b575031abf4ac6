"""A configuration is checked by meaning before any job (issue 40): everything a job would later reject
is refused while the workflow plans, with one line naming the key path and its value.

The cases call the validator in process (brdfs.pipeline.config); two go through `snakemake -n`
and check also that nothing under results/ changed.
"""

import copy
import functools
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from brdfs.pipeline.config import (CONFIG_YAML, ConfigError, load_config, load_schema, read_config_file,
                                   validate_config)
from brdfs.pipeline.io import REPO_ROOT
from brdfs.pipeline.registry import artifacts

SNAKEMAKE = Path(sys.executable).with_name("snakemake")
class _Delete:
    def __repr__(self) -> str:   # the same test id in every pytest-xdist worker
        return "<deleted>"


DELETE = _Delete()


@functools.lru_cache(maxsize=None)
def _shipped() -> dict:
    return yaml.safe_load(CONFIG_YAML.read_text())


def edited(path: str, value) -> dict:
    """The shipped config with the dotted ``path`` (integers index lists) set to ``value`` (or deleted)."""
    config = copy.deepcopy(_shipped())
    *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
    node = config
    for part in parents:
        node = node[part]
    if value is DELETE:
        del node[last]
    else:
        node[last] = value
    return config


def printed(path: str) -> str:
    """``a.b[0].c`` for ``a.b.0.c``."""
    first, *rest = path.split(".")
    return first + "".join(f"[{p}]" if p.isdigit() else f".{p}" for p in rest)


# (dotted key set, value, the key path and value the line must show, a word of the reason)
MEANING = [
    # a model entry holds its own model's parameters, each in the range or among the choices its class declares
    ("grazing.fig_2_1_models.0", {"model": "phong", "m": 0.1}, "grazing.fig_2_1_models[0].m = 0.1", "unknown parameter"),
    ("grazing.fig_2_1_models.3", {"model": "ward", "n": 150}, "grazing.fig_2_1_models[3].n = 150", "unknown parameter"),
    ("grazing.fig_3_4_models.0", {"model": "phong"}, "grazing.fig_3_4_models[0].n is missing", "required"),
    ("grazing.divergence_models.9", {"model": "he_torrance", "tau_um": 1.7}, "grazing.divergence_models[9].sigma0_um is missing", "required"),
    ("grazing.divergence_models.6.G", "beckmann", "grazing.divergence_models[6].G = 'beckmann'", "one of"),
    ("grazing.stability.disk_points.0", {"model": "ward", "s": 4.0, "theta_deg": 89.0}, "grazing.stability.disk_points[0].s = 4.0", "unknown parameter"),
    ("work_precision.cases.0", {"label": "x", "model": "blinn", "m": 0.1, "theta_deg": 30.0}, "work_precision.cases[0].m = 0.1", "unknown parameter"),
    ("work_precision.cases.7", {"label": "x", "model": "patch_exponential", "theta_deg": 30.0}, "work_precision.cases[7].s is missing", "required"),
    ("work_precision.cases.6.term", "diffuse", "work_precision.cases[6].term = 'diffuse'", "one of"),
    # optical-constants data sets, of the metal they are read for
    ("gold_spectral.dataset", "palik_1985", "gold_spectral.dataset = 'palik_1985'", "no data set of gold"),
    ("gold_spectral.dataset", "rakic_1995", "gold_spectral.dataset = 'rakic_1995'", "no data set of gold"),
    ("gold_spectral.compare_datasets.2", "cheng_2016", "gold_spectral.compare_datasets[2] = 'cheng_2016'", "no data set"),
    ("metal_f0_rgb.datasets.aluminium", "johnson_christy_1972", "metal_f0_rgb.datasets.aluminium = 'johnson_christy_1972'", "no data set of aluminium"),
    ("metal_f0_rgb.datasets.copper", "werner_2009", "metal_f0_rgb.datasets.copper = 'werner_2009'", "no data set of copper"),
    ("microfacet.gold.dataset", "mcpeak", "microfacet.gold.dataset = 'mcpeak'", "no data set of gold"),
    # ordered ranges
    ("gold_spectral.wavelength_nm.start", 800.0, "gold_spectral.wavelength_nm.stop = 780.0", "larger than start"),
    ("gold_spectral.wavelength_nm.stop", 380.0, "gold_spectral.wavelength_nm.stop = 380.0", "larger than start"),
    ("gold_spectral.theta_deg.start", 90.0, "gold_spectral.theta_deg.stop = 90.0", "larger than start"),
    ("grazing.approach_from", 4.5, "grazing.approach_to = 4.0", "larger than approach_from"),
    ("grazing.approach_to", -1.0, "grazing.approach_to = -1.0", "larger than approach_from"),
    ("accuracy_map.full.approach_to", -2.0, "accuracy_map.full.approach_to = -2.0", "larger than approach_from"),
    # samples per pixel split into passes
    ("renders.preview.spp", 100, "renders.preview.spp = 100", "multiple of passes"),
    ("renders.final.spp", 1530, "renders.final.spp = 1530", "multiple of passes"),
    ("renders.preview.figure_spp.fig_4_16_patch_metals", 250, "renders.preview.figure_spp.fig_4_16_patch_metals = 250", "multiple of passes"),
    ("renders.preview.figure_spp.fig_2_8_pumping_render", [48, 36, 48, 48], "renders.preview.figure_spp.fig_2_8_pumping_render[1] = 36", "multiple of passes"),
    # samples per object: the figure's own objects, multiples of passes, not beside a crop_spp
    ("renders.preview.object_spp.fig_4_9_sampling_efficiency", {"platinum s=3": 96},
     "renders.preview.object_spp.fig_4_9_sampling_efficiency.platinum s=3 = 96", "not an object of fig_4_9"),
    ("renders.preview.object_spp.fig_4_9_sampling_efficiency", {"gold s=10": 100},
     "renders.preview.object_spp.fig_4_9_sampling_efficiency.gold s=10 = 100", "multiple of passes"),
    ("renders.preview.object_spp.fig_2_8_pumping_render", {"tank": 4.5},
     "renders.preview.object_spp.fig_2_8_pumping_render.tank = 4.5", "integer"),
    ("renders.preview.crop_spp.fig_4_9_sampling_efficiency", 128,
     "renders.preview.object_spp.fig_4_9_sampling_efficiency: the figure also has", "give one of them"),
    ("renders.preview.adaptive.fig_3_9_metals_new_model", 0.05,
     "renders.preview.adaptive.fig_3_9_metals_new_model: the figure also has renders.preview.object_spp", "give one of them"),
    ("renders.preview.object_spp.fig_4_9_sampling_efficiency", {"gold s=10": 16},
     "renders.preview.object_spp.fig_4_9_sampling_efficiency.gold s=10 = 16", "below the figure's spp (32)"),
    ("renders.preview.figure_spp.fig_2_8_pumping_render", [48, 48, 128, 48],
     "renders.preview.object_spp.fig_2_8_pumping_render.tank = 120", "below the figure's spp (128)"),
    # a per-figure mapping takes the render figures only (one list: the registry's), a per-panel list one per panel
    ("renders.preview.clamp.fig_3_9_metals_new_mode", 2.0,
     "renders.preview.clamp.fig_3_9_metals_new_mode: unknown key", "did you mean fig_3_9_metals_new_model?"),
    ("renders.final.figure_spp.fig_2_1_models", 64,
     "renders.final.figure_spp.fig_2_1_models: unknown key", "must be one of fig_2_8_pumping_render, "),
    ("renders.preview.figure_spp.fig_3_9_metals_new_model", [32, 32],
     "renders.preview.figure_spp.fig_3_9_metals_new_model = [32, 32]", "one entry per panel (1 panel)"),
    ("renders.final.figure_spp.fig_2_8_pumping_render", [2584, 2584],
     "renders.final.figure_spp.fig_2_8_pumping_render = [2584, 2584]", "one entry per panel (4 panels)"),
    ("renders.clamp", {"fig_3_9_metals_new_model": 2.0}, "renders.clamp = ", "unknown key; it moved to renders.<preset>.clamp"),
    ("renders.preview.clamp.3", 2.0, "renders.preview.clamp.3: unknown key", "the keys are names (strings)"),
    ("renders.preview.clamp.Fig_3_9_metals_new_model", 2.0,
     "renders.preview.clamp.Fig_3_9_metals_new_model: unknown key", "did you mean fig_3_9_metals_new_model?"),
    # a setting the figure's panels would ignore: sampling on noise-free panels, a clamp on direct light only
    ("renders.final.clamp.fig_3_8_material_spheres", 2.0,
     "renders.final.clamp.fig_3_8_material_spheres = 2.0: fig_3_8_material_spheres does not use it", "direct light only"),
    ("renders.preview.figure_spp.fig_4_18_generalized_lambert", 800,
     "renders.preview.figure_spp.fig_4_18_generalized_lambert = 800: fig_4_18_generalized_lambert does not use it",
     "their own samples per pixel"),
    ("renders.preview.adaptive.fig_3_8_material_spheres", 0.01,
     "renders.preview.adaptive.fig_3_8_material_spheres = 0.01: fig_3_8_material_spheres does not use it",
     "their own samples per pixel"),
    # an integer is an int
    ("patch.fig_4_10_grid", 121.0, "patch.fig_4_10_grid = 121.0", "integer"),
    ("grazing.per_decade", 10.0, "grazing.per_decade = 10.0", "integer"),
    ("renders.preview.passes", 8.0, "renders.preview.passes = 8.0", "integer"),
    ("diagrams.fig_2_2.grid", 161.0, "diagrams.fig_2_2.grid = 161.0", "integer"),
    ("seed", 20010101.0, "seed = 20010101.0", "integer"),
    # the plastics' own constraint, a_s + max(r, g, b) <= 1
    ("renders.plastics.spheres.0.a_s", 0.3, "renders.plastics.spheres[0].a_s = 0.3", "a_s + max(rgb) = 1.05"),
    ("renders.plastics.plate.rgb", [0.55, 0.97, 0.6], "renders.plastics.plate.a_s = 0.04", "must be <= 1"),
    ("renders.ceramics.objects.0.a_s", 0.2, "renders.ceramics.objects[0].a_s = 0.2", "must be <= 1"),
    # non-empty, increasing lists
    ("mean_albedo.limit_check_n", [], "mean_albedo.limit_check_n = []", "empty"),
    ("mean_albedo.limit_check_n", [4096, 2048], "mean_albedo.limit_check_n[1] = 2048", "larger than the item before"),
    ("chapter3_claims.limit_check_n", [], "chapter3_claims.limit_check_n = []", "empty"),
    ("chapter3_claims.limit_check_n", [100, 100], "chapter3_claims.limit_check_n[1] = 100", "larger than the item before"),
    # boolean switches accept only booleans
    ("renders.caustics", "maybe", "renders.caustics = 'maybe'", "boolean"),
    ("renders.caustics", 1, "renders.caustics = 1", "boolean"),
    ("microfacet.walk_full", "yes", "microfacet.walk_full = 'yes'", "boolean"),
    ("sampling.full", 0, "sampling.full = 0", "boolean"),
    # a section an artifact reads is there (tolerance and sampling have defaults)
    ("gold_spectral", DELETE, "gold_spectral is missing", "required"),
    ("diagrams", DELETE, "diagrams is missing", "required"),
    ("microfacet", DELETE, "microfacet is missing", "required"),
]


@pytest.mark.parametrize(("path", "value", "shown", "reason"), MEANING, ids=[f"{p}={v!r}" for p, v, _, _ in MEANING])
def test_a_config_a_job_would_reject_is_refused_with_one_line_naming_key_and_value(path, value, shown, reason):
    with pytest.raises(ConfigError) as error:
        validate_config(edited(path, value))
    message = str(error.value)
    assert "\n" not in message and len(message) < 300, message
    assert message.startswith(f"Error validating config file: {shown}") and reason in message, message


def test_a_figure_with_a_crop_spp_and_an_adaptive_target_is_refused_with_one_line():
    config = edited("renders.final.crop_spp", {"fig_3_12_plastics": 64})
    config["renders"]["final"]["adaptive"] = {"fig_3_12_plastics": 0.05}
    with pytest.raises(ConfigError) as error:
        validate_config(config)
    assert str(error.value) == ("Error validating config file: renders.final.adaptive.fig_3_12_plastics: the figure "
                                "also has renders.final.crop_spp.fig_3_12_plastics = 64; give one of them")


def test_the_shipped_values_of_those_keys_are_valid_and_sections_with_defaults_may_be_left_out():
    config = validate_config(edited("sampling", DELETE))
    assert config["sampling"]["full"] is False and config["tolerance"]["rtol"] == 1e-10
    # a plastic exactly at the bound, and a single limit check, are fine
    validate_config(edited("renders.plastics.plate", {"a_s": 0.25, "n": 30, "rgb": [0.75, 0.5, 0.5]}))
    validate_config(edited("mean_albedo.limit_check_n", [1024]))


def test_every_section_an_artifact_reads_is_required_or_has_a_default():
    schema = load_schema()
    read = {s for a in artifacts().values() for s in a.config}
    defaulted = {k for k, v in schema["properties"].items() if "default" in v}
    assert read <= set(schema["required"]) | defaulted


# (file text, the start of the line, what else it names)
MALFORMED_FILES = [
    ("seed: 1\ntolerance: {rtol: 1.0e-8}\nseed: 2\n", "{path}:3: duplicate key 'seed' (lines 1 and 3)", ""),
    ("tolerance:\n  rtol: 1.0e-8\n  atol: 1.0e-15\n  rtol: 1.0e-9\n", "{path}:4: duplicate key 'rtol' (lines 2 and 4)", ""),
    ("grazing:\n  readings: {ward_m: 0.1, ward_m: 0.2}\n", "{path}:2: duplicate key 'ward_m' (lines 2 and 2)", ""),
    ("seed: [1\ntolerance: {}\n", "{path}:2:10: YAML syntax error:", "line 1, column 7"),
    ("seed: 1\n  tolerance: 2\n", "{path}:2:12: YAML syntax error:", ""),
    ("seed: 1\n\tgrazing: {}\n", "{path}:2:1: YAML syntax error:", "'\\t'"),
    ("", "config file {path} is empty", ""),
    ("# only a comment\n", "config file {path} is empty", ""),
    ("- seed\n- grazing\n", "config file {path} is a list, not a mapping", ""),
    ("20010101\n", "config file {path} is a int, not a mapping", ""),
]


@pytest.mark.parametrize(("text", "line", "also"), MALFORMED_FILES, ids=[repr(t[:24]) for t, _, _ in MALFORMED_FILES])
def test_a_malformed_file_is_refused_with_one_line_naming_the_file_and_where(tmp_path, text, line, also):
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as error:
        read_config_file(path)
    message = str(error.value)
    assert "\n" not in message and message.startswith(line.format(path=path)) and also in message, message


def test_a_missing_config_file_is_one_line(tmp_path):
    with pytest.raises(ConfigError, match=r"^config file .*nowhere\.yaml: cannot be read \(No such file"):
        load_config(overrides=(tmp_path / "nowhere.yaml",))


def test_the_command_line_check_of_make_all_configfile_prints_one_line(tmp_path, capsys):
    from brdfs.pipeline import config

    (tmp_path / "bad.yaml").write_text("patch: {fig_4_10_grid: 121.0}\n")
    assert config.main([str(tmp_path / "bad.yaml")]) == 1
    assert capsys.readouterr().err == "Error validating config file: patch.fig_4_10_grid = 121.0: must be of type integer\n"
    (tmp_path / "good.yaml").write_text("seed: 7\n")
    assert config.main([str(tmp_path / "good.yaml")]) == 0


def _dry_run(tree: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PATH": f"{SNAKEMAKE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    return subprocess.run([str(SNAKEMAKE), "-n", "--cores", "1", *args], cwd=tree, capture_output=True, text=True,
                          env=env, timeout=120)


def _results(tree: Path) -> dict:
    return {p.relative_to(tree).as_posix(): (p.stat().st_size, p.stat().st_mtime_ns)
            for p in (tree / "results").rglob("*")}


@pytest.mark.parametrize(("edit", "args", "line"), [
    (lambda text: text.replace("seed: 20010101\n", "seed: 20010101\nseed: 7\n"), (),
     "config.yaml:8: duplicate key 'seed' (lines 7 and 8); give each key once"),
    (None, ("--configfile", "mine.yaml"),
     "Error validating config file: grazing.fig_2_1_models[0].m = 0.1: unknown parameter; phong takes n, C (model phong)"),
], ids=["duplicate-key-in-config.yaml", "another-models-parameter-in-a-configfile"])
def test_snakemake_refuses_before_any_job_and_leaves_results_as_they_were(tmp_path, edit, args, line):
    for name in ("Snakefile", "workflow", "config.yaml"):
        (shutil.copytree if (REPO_ROOT / name).is_dir() else shutil.copy)(REPO_ROOT / name, tmp_path / name)
    for name in ("src", "data"):
        (tmp_path / name).symlink_to(REPO_ROOT / name)
    (tmp_path / "results" / "tables").mkdir(parents=True)
    (tmp_path / "results" / "tables" / "table_3_2_ward_cmax.csv").write_text("m,C\n0.1,1.0\n")
    (tmp_path / "mine.yaml").write_text("grazing:\n  fig_2_1_models:\n    - {model: phong, m: 0.1}\n")
    if edit is not None:
        (tmp_path / "config.yaml").write_text(edit((tmp_path / "config.yaml").read_text()))
    before = _results(tmp_path)
    run = _dry_run(tmp_path, *args)
    output = (run.stdout + run.stderr).strip().splitlines()
    assert run.returncode != 0 and line in output, output
    assert "Traceback" not in run.stderr and "Building DAG" not in run.stdout + run.stderr
    assert _results(tmp_path) == before
