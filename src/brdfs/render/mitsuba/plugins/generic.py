"""``brdfs_model``: any model of the package, by name and parameters, rendered through its numpy code.

A model without a Dr.Jit twin — a user's own (registered with :func:`brdfs.physics.models.register`),
He–Torrance, the Blinn family, p_model, Kulla–Conty's compensated microfacet models — renders through
this plugin: ``{"type": "brdfs_model", "model": "he_torrance", "sigma0_um": 0.1, "tau_um": 1.7}``.  Its
eval, pdf and sample are the model's own (``model(L, V)``, ``model.pdf(L, V, strategy)``,
``model.sample_direction(L, u, strategy)``), evaluated in float64 on the directions Dr.Jit hands over
and returned as float32; ``strategy`` is any of the model's :attr:`~brdfs.physics.models.base.BRDF.strategies`
(its own by default) or ``"uniform"``; ``pumping = "g1"``/``"g2"`` divides the model by its albedo
(:func:`brdfs.numerics.tables.pump`).  The material's other keys (``specular``, ``diffuse_reflectance``,
``eta``, ``k``) are :class:`~brdfs.render.mitsuba.plugins._common.ModelBSDF`'s.

Slower, and wavefront only.  Each call converts Dr.Jit arrays to numpy, which needs evaluated arrays:
Dr.Jit must run in wavefront mode (:func:`brdfs.render.mitsuba.integrator.wavefront`: ``dr.set_flag(dr.JitFlag.SymbolicCalls, False)``,
``dr.set_flag(dr.JitFlag.SymbolicLoops, False)``) under an integrator that evaluates every bounce
(``brdfs_path``); inside a symbolic loop or call the plugin raises one line saying so.
"""
from __future__ import annotations

import mitsuba as mi
import drjit as dr
import numpy as np

from brdfs.render.mitsuba.plugins._common import ModelBSDF

#: Scene keys that are the material's, not the model's parameters.
MATERIAL_KEYS = ("type", "model", "strategy", "pumping", "specular", "diffuse_reflectance", "eta", "k")
WAVEFRONT_ONLY = ("brdfs_model evaluates the package's numpy model and runs in wavefront mode only: "
                  "render inside `with brdfs.render.mitsuba.integrator.wavefront():` (symbolic calls and "
                  "loops off), with an integrator that evaluates each bounce (brdfs_path)")


def build_model(props):
    """The package's model of ``props``: ``model`` (its name) and its parameters (every key but
    :data:`MATERIAL_KEYS`), built by the front door :func:`brdfs.model` (tables included), pumped if asked."""
    from brdfs.numerics import tables
    if "model" not in props:
        raise ValueError("brdfs_model: parameter 'model' (a model name) is required")
    params = {}
    for key in props.keys():
        if key in MATERIAL_KEYS:
            continue
        value = props[key]
        params[key] = value if isinstance(value, (str, bool)) else float(value)
    try:
        brdf = tables.build(str(props["model"]), **params)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"brdfs_model: {exc}") from None
    pumping = props.get("pumping", "none")
    if pumping != "none":
        brdf = tables.pump(brdf, pumping, target_rtol=1e-6, engine_rtol=1e-8)
    return brdf


def to_numpy(v):
    """A Dr.Jit Float or Vector3f as a numpy float64 array ((N,) or (N, 3)); one line outside wavefront mode."""
    try:
        dr.eval(v)
        array = np.asarray(v.numpy() if hasattr(v, "numpy") else np.array(v), float)
    except RuntimeError as exc:
        raise RuntimeError(f"{WAVEFRONT_ONLY} ({exc})") from None
    return array.T if array.ndim == 2 else array


def _broadcast(*arrays):
    width = max(a.shape[0] if a.ndim else 1 for a in arrays)
    return [np.broadcast_to(a, (width,) + a.shape[1:]) if a.ndim and a.shape[0] == 1 else a for a in arrays]


class ModelPluginBSDF(ModelBSDF):
    """The package's model ``model`` (by name) with its numpy eval, pdf and sampler (module docstring)."""

    name = "model"
    extra_parameters = {"model": ("string", "required", "a registered model's name (``brdfs models`` lists them); "
                                                        "its parameters are further keys"),
                        "pumping": ("string", "none", "``g1`` or ``g2``: divided by its albedo (eq. 2.20 / 2.21)")}

    def __init__(self, props):
        brdf = build_model(props)
        self.strategies = (*brdf.strategies, "uniform")
        super().__init__(props)
        self.brdf = brdf

    def lobe_eval(self, L, V, active):
        L, V = _broadcast(to_numpy(L), to_numpy(V))
        return mi.Float(self.brdf.unchecked(L, V))

    def own_pdf(self, L, V, active):
        L, V = _broadcast(to_numpy(L), to_numpy(V))
        return mi.Float(self.brdf.pdf(L, V, self.strategy))

    def lobe_pdf(self, L, V, active):
        if self.strategy == "cosine":                 # the protocol's cosine, drawn in Dr.Jit
            return super().lobe_pdf(L, V, active)
        return self.own_pdf(L, V, active)

    def lobe_sample(self, L, u, active):
        if self.strategy == "cosine":
            return super().lobe_sample(L, u, active)
        L = to_numpy(L)
        u = to_numpy(mi.Vector2f(u))
        dimension = self.brdf.sample_dimension(self.strategy)
        if dimension > 2:          # further numbers from a hash of the two (the strategy's 3rd, e.g. a pick)
            extra = to_numpy(mi.sample_tea_float32(mi.UInt32(u[:, 0] * 2 ** 24), mi.UInt32(u[:, 1] * 2 ** 24)))
            u = np.concatenate([u, np.broadcast_to(extra[:, None], (len(u), dimension - 2))], -1)
        L, u = _broadcast(L, u)
        V = self.brdf.sample_direction(L, u, self.strategy)
        return mi.Vector3f(np.ascontiguousarray(V.T, np.float32))

    def fresnel_cosine(self, L, V):
        L, V = _broadcast(to_numpy(L), to_numpy(V))
        return mi.Float(self.brdf.fresnel_cosine(L, V))

    def describe(self):
        return {"model": self.brdf.name, **{k: v for k, v in self.brdf.params.items() if not callable(v)},
                "strategy": self.strategy}


PLUGINS = {cls.name: cls for cls in (ModelPluginBSDF,)}
