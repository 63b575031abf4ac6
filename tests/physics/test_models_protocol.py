"""The BRDF protocol: a model defined outside the package works through the public API alone."""
from dataclasses import dataclass

import numpy as np
import pytest
import yaml

from brdfs import albedo, model
from brdfs.numerics.grazing import asymptotic_law
from brdfs.physics.lobes import PowerCosine
from brdfs.physics.models import MODELS, BRDF, register
from brdfs.pipeline.config import CONFIG_YAML, ConfigError, check_config

ANGLES = np.linspace(0.0, 89.0, 10)


@dataclass(frozen=True)
class Lambert(BRDF):
    """f = ρ/π, defined here only: the package knows nothing of it."""

    rho: float = 1.0
    name = "lambert_in_a_test"

    def _eval(self, L, V, nl, nv):
        return np.full(np.broadcast_shapes(nl.shape, nv.shape), self.rho / np.pi)

    @property
    def lobe(self):
        return PowerCosine(0.0, "half")


@pytest.fixture
def lambert():
    register(Lambert)
    yield model(Lambert.name)
    del MODELS[Lambert.name]


def test_a_model_defined_in_a_test_has_albedo_one_at_ten_angles(lambert):
    est = albedo(lambert, ANGLES)
    assert np.all(np.abs(est.value - 1.0) <= est.error) and np.all(est.error < 1e-9)
    assert set(est.status.ravel()) == {"converged"} and est.evaluations > 0


def test_a_model_defined_in_a_test_has_a_grazing_limit_of_one(lambert):
    law = asymptotic_law(lambert)
    assert law.exponent == 0 and abs(law.constant.value - 1.0) <= law.constant.error + 1e-12


def test_the_config_schema_accepts_a_registered_model_and_rejects_an_unknown_one(lambert):
    config = yaml.safe_load(CONFIG_YAML.read_text())
    config["grazing"]["fig_2_1_models"].append({"model": Lambert.name})
    check_config(config)
    config["grazing"]["fig_2_1_models"].append({"model": "lambertt"})
    with pytest.raises(ConfigError, match="'lambertt'"):
        check_config(config)


def test_parameter_columns_come_from_the_dataclass_fields():
    assert Lambert.param_columns() == ("rho",)
    assert model("cook_torrance", m=0.1).param_columns() == ("m", "C", "G")
    assert model("phong", n=4).params == {"n": 4, "C": pytest.approx(6 / (2 * np.pi))}


@pytest.mark.parametrize("name, params", [("phong", {"n": 7}), ("blinn", {"n": 30}), ("ward", {"m": 0.2}),
                                          ("cook_torrance", {"m": 0.3}), ("patch_basic", {"R": 1.0})])
def test_default_cosine_sampling_has_weight_f_cos_over_pdf(name, params):
    brdf = model(name, **params)
    L = np.array([np.sin(0.6), 0.0, np.cos(0.6)])
    u = np.random.default_rng(5).random((1000, 2))
    V, weight, pdf = brdf.sample(L, u, strategy="cosine")
    assert np.allclose(np.linalg.norm(V, axis=-1), 1.0) and np.all(V[:, 2] >= 0)
    assert np.allclose(pdf, V[:, 2] / np.pi)
    assert np.allclose(weight, brdf(L, V) * V[:, 2] / pdf)


EXAMPLE_PARAMS = {"n": 10.0, "m": 0.2, "alpha": 0.3, "s": 2.0, "d": 0.5, "R": 1.0, "sigma0_um": 0.1, "tau_um": 1.7,
                  "b": 0.5, "ratio": 0.5, "weight": lambda R: np.exp(-R)}


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_answers_every_verb_of_the_protocol(name):
    cls = MODELS[name]
    brdf = cls(**{k: EXAMPLE_PARAMS[k] for k in cls.param_columns() if k in EXAMPLE_PARAMS})
    assert brdf.delta_albedo(np.array([0.0, 45.0])).value.shape == (2,)
    assert brdf.exact_albedo(np.array([10.0])).shape == (1,)
    law = brdf.grazing_law()
    assert law is None or (law.exponent >= 0 and np.isfinite(law.constant.value))
    assert isinstance(brdf.grazing_limit_model(), BRDF)
    assert set(brdf.params) == set(cls.param_columns())
