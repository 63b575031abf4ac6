"""A user's own Mitsuba scene can load the package's BRDFs: ``register_plugins()`` registers every plugin
under its documented name (idempotently), the README's snippet renders, the generic plugin renders a
model the user registers, and bad input says in one line which key is wrong."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

def readme_snippet() -> str:
    """The README's snippet ("Rendering the models in your own Mitsuba scene"), run as the user would."""
    from brdfs.pipeline.io import REPO_ROOT
    text = (REPO_ROOT / "README.md").read_text()
    section = text[text.index("## Rendering the models in your own Mitsuba scene"):]
    start = section.index("```python\n") + len("```python\n")
    return section[start:section.index("```", start)]


#: The names the plugins' docstring (``brdfs.render.mitsuba.plugins``) documents for R1a's plugins.
DOCUMENTED = ("brdfs_lambert", "brdfs_phong", "brdfs_phong_cosmin", "brdfs_blinn", "brdfs_blinn_cosmin", "brdfs_ward", "brdfs_cook_torrance",
              "brdfs_ggx", "brdfs_beckmann", "brdfs_model")


def test_register_plugins_is_idempotent_and_registers_the_documented_names(mitsuba):
    from brdfs.render.mitsuba import plugins, register_plugins
    first = register_plugins()
    assert register_plugins() == first
    assert set(DOCUMENTED) <= set(first)
    assert all(name.startswith(plugins.PREFIX) for name in first)
    for name in DOCUMENTED:
        assert f"``{name}``" in plugins.__doc__, f"{name} is registered but not documented"


@pytest.mark.parametrize("name, params", [
    ("brdfs_lambert", {"reflectance": {"type": "rgb", "value": [0.8, 0.5, 0.2]}}),
    ("brdfs_phong", {"n": 20, "pumping": "g1"}), ("brdfs_phong_cosmin", {"n": 20, "strategy": "cosine"}),
    ("brdfs_ward", {"m": 0.1}), ("brdfs_cook_torrance", {"m": 0.1, "G": "smith"}),
    ("brdfs_ggx", {"alpha": 0.3, "ior_re": 0.2, "ior_im": 3.0}), ("brdfs_beckmann", {"alpha": 0.3}),
    ("brdfs_model", {"model": "he_torrance", "sigma0_um": 0.1, "tau_um": 1.7}),
])
def test_every_documented_plugin_loads_from_a_scene_dict(mitsuba, name, params):
    bsdf = mitsuba.load_dict({"type": name, **params})
    assert bsdf.flags() & int(mitsuba.BSDFFlags.Reflection)
    assert not bsdf.flags() & int(mitsuba.BSDFFlags.Transmission)


def test_readme_snippet_renders_a_users_own_scene(mitsuba, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(readme_snippet(), "README", "exec"), namespace)
    image = np.asarray(namespace["image"])
    assert image.shape == (48, 64, 3)
    assert np.all(np.isfinite(image)) and image.min() >= 0
    centre = image[20:28, 28:36]                       # the gold ball: red above blue, as gold is
    assert centre[..., 0].mean() > 1.2 * centre[..., 2].mean()
    assert (tmp_path / "ball.exr").stat().st_size > 0


def _users_model_class():
    """A user's own model, f = 1/π, built in the test (registered as ``users_white_lambert``)."""
    from brdfs.physics.models.base import BRDF

    @dataclass(frozen=True)
    class UsersWhiteLambert(BRDF):
        name = "users_white_lambert"
        lobe = None

        def _eval(self, L, V, nl, nv):
            return np.full(np.shape(nl), 1.0 / np.pi)

    return UsersWhiteLambert


@pytest.fixture
def users_model():
    from brdfs.physics.models import MODELS, register
    cls = register(_users_model_class())
    yield cls
    MODELS.pop(cls.name, None)


def _furnace(mi, bsdf):
    return mi.load_dict({
        "type": "scene", "integrator": {"type": "path", "max_depth": 64, "rr_depth": 64},
        "sensor": {"type": "perspective", "fov": 20,
                   "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": 16, "height": 16, "rfilter": {"type": "box"}},
                   "sampler": {"type": "independent", "sample_count": 16}},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}},
        "ball": {"type": "sphere", "bsdf": bsdf},
    })


def test_generic_plugin_renders_a_users_own_model_as_mitsuba_renders_its_own_lambert(mitsuba, users_model):
    """A white sphere of the user's model f = 1/π under a sky of radiance 1, through ``brdfs_model`` with
    Mitsuba's own path integrator in wavefront mode: the same image as Mitsuba's ``diffuse`` BSDF gives
    with the same random numbers (same sampler, same pdf), and 1 on the ball (a white furnace)."""
    from brdfs.render.mitsuba.integrator import wavefront
    with wavefront():
        image = np.asarray(mitsuba.render(_furnace(mitsuba, {"type": "brdfs_model", "model": users_model.name}),
                                          seed=1))
    reference = np.asarray(mitsuba.render(_furnace(mitsuba, {"type": "diffuse",
                                                              "reflectance": {"type": "rgb", "value": 1.0}}), seed=1))
    ball = (slice(4, 12), slice(4, 12))
    assert np.allclose(image, reference, rtol=1e-4, atol=1e-6)
    assert abs(image[ball].mean() - 1.0) < 0.03, image[ball].mean()


@pytest.mark.parametrize("params, line", [
    ({"type": "brdfs_phong"}, "brdfs_phong: parameter 'n' is required"),
    ({"type": "brdfs_phong", "n": -1}, "brdfs_phong: n = -1.0 must be >= 0"),
    ({"type": "brdfs_phong", "n": 20, "strategy": "half"}, "brdfs_phong: strategy = 'half'"),
    ({"type": "brdfs_phong", "n": 20, "pumping": "g3"}, "brdfs_phong: pumping = 'g3'"),
    ({"type": "brdfs_ward", "m": 0.0}, "brdfs_ward: m = 0.0 must be > 0"),
    ({"type": "brdfs_cook_torrance", "m": 0.1, "G": "beckmann"}, "brdfs_cook_torrance: G = 'beckmann'"),
    ({"type": "brdfs_ggx", "alpha": 0.3, "compensation": "kulla_conty"}, "render it through brdfs_model"),
    ({"type": "brdfs_model", "model": "no_such_model"}, "brdfs_model: model(): name = 'no_such_model'"),
    ({"type": "brdfs_patch_exponential", "s": 10.0, "mis_density": "cheap"},
     "brdfs_patch_exponential: mis_density = 'cheap'; choose one of ('exact', 'lobe')"),
    # two Fresnel factors on one lobe, or half an index: no meaning
    ({"type": "brdfs_ggx", "alpha": 0.3, "ior_re": 1.5, "eta": 1.5}, "brdfs_ggx: eta given beside ior_re = 1.5"),
    ({"type": "brdfs_model", "model": "ggx", "alpha": 0.3, "ior_re": 1.5, "eta": 1.5, "k": 0.0},
     "brdfs_model: eta given beside ior_re = 1.5"),
    ({"type": "brdfs_beckmann", "alpha": 0.3, "ior_im": 3.0}, "brdfs_beckmann: ior_im = 3.0 given without ior_re"),
    ({"type": "brdfs_ggx", "alpha": 0.3, "ior_re": 0.0}, "brdfs_ggx: ior_re = 0.0 must be > 0"),
    ({"type": "brdfs_ggx", "alpha": 0.3, "ior_re": 1.5, "ior_im": -1.0}, "brdfs_ggx: ior_im = -1.0 must be >= 0"),
    ({"type": "brdfs_phong_cosmin", "n": 20, "k": 3.0}, "brdfs_phong_cosmin: k given without eta"),
])
def test_bad_plugin_parameters_are_named_in_one_line(mitsuba, params, line):
    with pytest.raises(RuntimeError) as error:
        mitsuba.load_dict(params)
    assert line in str(error.value).strip().splitlines()[-1]


def test_use_variant_says_what_to_run_without_libllvm19(monkeypatch):
    from brdfs.render.mitsuba import MISSING_LLVM, MissingLLVM, use_variant
    monkeypatch.delenv("DRJIT_LIBLLVM_PATH", raising=False)
    with pytest.raises(MissingLLVM) as error:
        use_variant("llvm_ad_rgb", candidates=("/nonexistent/libLLVM-19.so",))
    assert str(error.value) == MISSING_LLVM
    assert "make llvm" in MISSING_LLVM and "\n" not in MISSING_LLVM


def test_generic_plugin_refuses_symbolic_mode_in_one_line(mitsuba):
    """Inside a symbolic loop the numpy model cannot see the values: the plugin says so."""
    import drjit as dr
    from brdfs.render.mitsuba.plugins.generic import WAVEFRONT_ONLY
    bsdf = mitsuba.load_dict({"type": "brdfs_model", "model": "phong", "n": 20})
    ctx = mitsuba.BSDFContext()

    def body(i, total):
        si = dr.zeros(mitsuba.SurfaceInteraction3f)
        si.wi = mitsuba.Vector3f(0, 0, 1)
        total += bsdf.eval(ctx, si, mitsuba.Vector3f(0, 0, 1))[0]
        return i + 1, total

    with pytest.raises(Exception) as error:
        dr.while_loop((mitsuba.UInt32(0), mitsuba.Float(0)), lambda i, total: i < 2, body)
    chain, exc = [], error.value
    while exc is not None:
        chain.append(str(exc))
        exc = exc.__cause__ or exc.__context__
    assert any(WAVEFRONT_ONLY in message for message in chain), chain
