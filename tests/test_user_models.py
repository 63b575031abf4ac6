"""A user's own model, written from the guide's recipe in a file outside the package: the command line
imports it (``brdfs --import``), an installed package registers it (entry-point group
``brdfs.models``), and the package's generic model tests pass on it (run in this process on
their own test functions, collected afresh from their files)."""
from __future__ import annotations

import importlib.util
import inspect
import json
import re
import shlex
import sys
from pathlib import Path

import numpy as np
import pytest

import brdfs
from brdfs.cli import main
from brdfs.physics.models import MODELS
from brdfs.user_models import ENTRY_POINT_GROUP, import_models, load_entry_points

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "guide" / "own_model.rst"
RECIPE = ROOT / "docs" / "guide" / "my_model.py"
NAME = "my_model"


def _guide_commands():
    """The ``$ brdfs --import ...`` lines of the guide, as argument lists."""
    return [shlex.split(line.split("$", 1)[1])[1:] for line in GUIDE.read_text().splitlines()
            if re.match(r"\s*\$ brdfs --import", line)]


@pytest.fixture
def forget_my_model():
    """Leave the registry and ``sys.modules`` as they were (other tests list every registered model)."""
    yield
    MODELS.pop(NAME, None)
    sys.modules.pop(NAME, None)


def test_the_guides_commands_run_from_a_directory_outside_the_package(tmp_path, forget_my_model, capsys,
                                                                     monkeypatch):
    """``brdfs --import my_model.py albedo my_model --param n=20 --theta 0,60 --json`` in the temporary
    directory (the albedo is the front door's: a(0) of the normalised Blinn–Phong is 1.0607 at
    n = 20), then the guide's chi2 and models calls."""
    (tmp_path / "my_model.py").write_text(RECIPE.read_text())
    commands = _guide_commands()
    assert [c[2] for c in commands] == ["albedo", "chi2", "models"], commands
    monkeypatch.chdir(tmp_path)
    assert NAME not in MODELS
    assert main(commands[0]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["theta_deg"] for r in rows] == [0.0, 60.0] and {r["status"] for r in rows} == {"converged"}
    assert Path(sys.modules[NAME].__file__).parent == tmp_path and ROOT not in tmp_path.parents
    direct = brdfs.albedo(brdfs.model(NAME, n=20), [0.0, 60.0])
    assert [r["value"] for r in rows] == pytest.approx(list(direct.value), rel=1e-12)
    assert abs(rows[0]["value"] - 1.0607) < 1e-4
    assert main(commands[1]) == 0                              # chi2: its own sampler passes
    assert "half_vector" in capsys.readouterr().out
    assert main(commands[2]) == 0 and NAME in capsys.readouterr().out


def test_import_by_module_name_from_the_current_directory_and_one_line_errors(tmp_path, forget_my_model,
                                                                              monkeypatch):
    (tmp_path / "my_model.py").write_text(RECIPE.read_text())
    (tmp_path / "broken_model.py").write_text("import numpy\nraise RuntimeError('half written\\nsecond line')\n")
    monkeypatch.chdir(tmp_path)
    assert import_models("my_model") == [NAME]
    assert import_models("my_model") == []                     # imported once, registered once
    with pytest.raises(ValueError, match=r"^--import 'broken_model.py': RuntimeError: half written$"):
        import_models("broken_model.py")
    assert "broken_model" not in sys.modules


def test_an_installed_package_registers_its_models_through_the_entry_point_group(tmp_path, forget_my_model,
                                                                                monkeypatch):
    """A distribution on sys.path whose ``entry_points.txt`` names the module in ``brdfs.models``."""
    (tmp_path / "my_model.py").write_text(RECIPE.read_text())
    info = tmp_path / "my_models_pkg-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: my-models-pkg\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(f"[{ENTRY_POINT_GROUP}]\nmine = my_model\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    assert NAME not in MODELS
    assert load_entry_points() == [NAME]
    assert float(brdfs.albedo(brdfs.model(NAME, n=0.0), 0.0).value) == pytest.approx(1.0, rel=1e-10)


#: The generic model tests: every test function of these files parametrized by a model ``name``.
GENERIC = ("tests/physics/test_model_properties.py", "tests/physics/test_model_declarations.py",
           "tests/physics/test_models_protocol.py", "tests/numerics/test_chi2_sampling.py")


def _fresh_module(path: Path):
    """The test module at ``path`` imported afresh, so that its parametrization (``list(MODELS)``) is
    taken with the models registered now."""
    name = f"_generic_{path.stem}_for_a_user_model"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[name]
    return module


def _generic_cases(module, model_name):
    """(test name, function, arguments) of every case of ``module`` that pytest would run for
    ``model_name``: the functions parametrized by ``name``, crossed with their other parametrizations."""
    for attr, func in vars(module).items():
        marks = [m for m in getattr(func, "pytestmark", []) if m.name == "parametrize"]
        if not attr.startswith("test_") or not marks:
            continue
        combos = [{}]
        for mark in marks:
            names = [a.strip() for a in mark.args[0].split(",")] if isinstance(mark.args[0], str) else list(mark.args[0])
            values = [v if len(names) > 1 else (v,) for v in mark.args[1]]
            combos = [{**c, **dict(zip(names, v))} for c in combos for v in values]
        for combo in combos:
            if combo.get("name") == model_name:
                yield attr, func, combo


def test_the_generic_model_tests_pass_on_a_model_added_from_a_file_in_a_temporary_directory(
        tmp_path, forget_my_model, monkeypatch):
    """The recipe does not break the suite: the model written from the guide, imported from a file in a
    temporary directory, passes every case of the generic tests (properties, declarations, protocol,
    chi-square) that pytest runs for each registered model, collected from their files afresh."""
    (tmp_path / "my_model.py").write_text(RECIPE.read_text())
    monkeypatch.chdir(tmp_path)
    assert import_models("my_model.py") == [NAME]
    ran = []
    for path in GENERIC:
        for test, func, arguments in _generic_cases(_fresh_module(ROOT / path), NAME):
            assert set(inspect.signature(func).parameters) <= set(arguments), (test, "needs a fixture")
            func(**arguments)
            ran.append(test)
    assert len(ran) >= 15 and {
        "test_every_model_is_finite_and_non_negative_over_its_ranges",
        "test_every_model_that_claims_reciprocity_is_reciprocal",
        "test_every_sampler_agrees_with_its_pdf",
        "test_every_model_sampler_passes_chi_square_at_its_narrowest_lobe_at_89_99_deg",
        "test_the_model_rejects_a_value_just_outside_each_declared_range_and_accepts_the_closed_bounds",
        "test_every_numeric_parameter_has_a_bounded_test_range_inside_its_declared_range",
        "test_every_models_closed_forms_agree_with_its_integrated_albedo",
    } <= set(ran), sorted(ran)
