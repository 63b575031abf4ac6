"""The model factory above the physics layer (brdfs.numerics.tables): a model that needs tables is
built with them, each tabulated once per process or seeded from an artifact's CSV, and the
package's front door brdfs.model is this factory."""
from __future__ import annotations

import numpy as np
import pytest

import brdfs
from brdfs.artifacts import _microfacet_energy as mf
from brdfs.numerics import pumping, tables
from brdfs.physics.models import MODELS
from brdfs.physics.models import model as physics_model
from brdfs.physics.models.pumped import Pumped
from brdfs.physics.tables import MissingTable, TableRequest


def test_the_front_door_is_the_factory_and_builds_plain_models_as_physics_does():
    assert brdfs.model is tables.build
    assert tables.build("phong", n=20) == physics_model("phong", n=20)
    with pytest.raises(ValueError, match="name = 'phongg': unknown model"):
        tables.build("phongg", n=20)


def test_a_compensated_model_is_built_with_the_e_table_it_requests_once_per_process():
    request = MODELS["beckmann"].energy_request(0.4)
    built = tables.build("beckmann", alpha=0.4, compensation="kulla_conty")
    again = tables.build("beckmann", alpha=0.4, compensation="kulla_conty", ior_re=0.3, ior_im=2.0)
    assert built.energy is tables.tabulate(request) and again.energy is built.energy
    assert request.model == physics_model("beckmann", alpha=0.4) and request.degree == 4
    # the table is the engine's E: compensation brings the albedo to 1 within its error
    est = brdfs.albedo(built, np.array([0.0, 60.0, 89.0]), rtol=1e-8)
    assert np.all(np.abs(est.value - 1.0) <= est.error + built.table_error())


def test_a_table_seeded_from_the_artifacts_rows_is_used_instead_of_a_new_one(monkeypatch):
    """extra_microfacet_albedo's node rows read back give the same table, and the figures' models are
    built from it without an engine call."""
    frame = mf.energy_table_frame("ggx", 0.35, "separable").assign(quantity="E_table_node")
    original = mf.energy_table("ggx", 0.35, "separable")[0]
    monkeypatch.setattr(tables, "_TABLES", {})
    monkeypatch.setattr(tables, "tabulate_albedo", lambda *a, **k: pytest.fail("tabulated again"))
    assert mf.seed_energy_tables(frame) == 1
    seeded = mf.microfacet("ggx", 0.35, "kulla_conty", "separable")
    np.testing.assert_array_equal(seeded.energy.values, original.values)
    assert seeded.energy.error == original.error
    np.testing.assert_array_equal(seeded.energy_table()[1].value, mf.energy_table("ggx", 0.35, "separable")[1].value)


def test_pump_divides_by_the_tabulated_albedo_of_its_base():
    base = physics_model("phong", n=8)
    pumped = tables.pump(base, "g2", target_rtol=1e-6, engine_rtol=1e-9)
    assert isinstance(pumped, Pumped) and pumped.base == base and pumped.correction == "g2"
    direct = pumping.tabulate_albedo(base, target_rtol=1e-6, engine_rtol=1e-9)
    np.testing.assert_array_equal(pumped.table.values, direct.values)
    assert tables.tabulate(TableRequest(base, target_rtol=1e-6, engine_rtol=1e-9)) is pumped.table


def test_the_physics_factory_refuses_a_table_needing_model_the_numerics_factory_builds():
    with pytest.raises(MissingTable):
        physics_model("ggx", alpha=0.2, compensation="kulla_conty")
    assert tables.build("ggx", alpha=0.2, compensation="kulla_conty").energy is not None
