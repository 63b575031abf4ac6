"""The sweep's cells: (family, parameters, θ), drawn from each model's declared parameter ranges,
and for each cell the integrand the third route integrates (:mod:`sweep.third_route`).

A family is a model with its categorical choices fixed (Cook–Torrance's G, the Smith models' G2
and compensation, He–Torrance's term, a pumped model's correction).  Its parameters are drawn
(seeded) from the model class's ``param_ranges`` intersected with the finite bounds below (the
declared ranges are open-ended; the bounds are the widest the package's documentation and issues
treat: n to 1e4, m to 0.005, α to 0.01), plus the class's ``examples``.  Angles: random in
[0°, 90°) and 90° − 10⁻ᵏ, k = 1 … 9.

The BRDF the truth integrates is written again in :mod:`sweep.independent` for every family
(He–Torrance's too, on the projected disk); ``pointwise_agreement`` holds each rewrite to the package's
model at random directions.  Where a sharper route exists (:mod:`sweep.sharp`: the patch models at 40
digits, Kulla–Conty's closed form, He–Torrance's vectorised disk, the hemisphere families in long
double) :func:`truth` takes it.  Oren–Nayar (and Lambert, its σ = 0) has a closed-form albedo, derived from the
rewrite (:func:`sweep.independent.oren_nayar_albedo`; ``tests/numerics/test_sweep_subset.py`` holds it
to a nested quadrature).  Models
built with a table (pumped, Kulla–Conty) are built from the table stored in
``tests/data/sweep_tables.json`` (computed once by :mod:`sweep.tables`), so the truths do not move
when the engine that tabulated it changes.

Nothing here imports :mod:`brdfs.numerics`.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from brdfs.physics.models import MODELS
from brdfs.physics.models.base import ALPHA_MAX, ALPHA_MIN
from brdfs.physics.models.pumped import Pumped
from brdfs.physics.tables import AlbedoTable

from sweep import independent as ind
from sweep.third_route import Integrand, Truth, disk_albedo, disk_rho_max, hemisphere_albedo, incidence

ROOT = Path(__file__).resolve().parents[1]
TABLES = ROOT / "tests" / "data" / "sweep_tables.json"
TRUTHS = ROOT / "tests" / "data" / "sweep_truths.csv"

#: Finite bounds of the sweep for parameters whose declared range is open-ended (by parameter
#: name; a draw is log-uniform where the bound's ratio exceeds 10, else uniform).
SWEEP_BOUNDS = {"n": (0.5, 1.0e4), "m": (0.005, 1.0), "alpha": (0.01, 1.0), "p": (0.0, 1.0),
                "R": (0.01, 2.0), "s": (0.1, 512.0), "d": (0.0, 1.0), "b": (0.02, 2.0),
                "ratio": (0.1, 1.0), "u_angle_deg": (0.0, 180.0), "sigma0_um": (0.05, 0.3),
                "tau_um": (1.0, 5.0), "ior_re": (0.2, 3.0), "ior_im": (0.0, 5.0),
                "rho": (0.0, 1.0), "sigma": (0.0, 0.5 * np.pi)}
#: 90° − 10⁻ᵏ.
GRAZING = tuple(90.0 - 10.0 ** -k for k in range(1, 10))


class OrenNayarIntegrated(MODELS["oren_nayar"]):
    """Oren–Nayar without its closed-form albedo route, as a user writes it: the engine integrates its
    BRDF and honours its kinks (the family ``oren_nayar_integrated``'s model, and the tests' of the
    engine on those kinks)."""

    def albedo_estimate(self, theta_deg, rtol, atol):
        return None


def mixture_feature_params(cls) -> list[dict]:
    """The parameter sets (JSON) of a mixture class's declared ``feature_examples`` whose weight is a box:
    ``["box", a, b]`` (rewritten by :func:`sweep.independent.box_weight`), its declared points, no Dirac part."""
    return [{"weight": ["box", float(ex["weight"].lo), float(ex["weight"].hi)], "p_diffuse": 0.0,
             "weight_points": [float(r) for r in ex["weight_points"]]}
            for ex in cls.feature_examples.values() if hasattr(ex["weight"], "lo")]


@dataclass(frozen=True)
class Family:
    """A model with its choices fixed: ``swept`` parameters drawn, ``fixed`` ones set."""

    name: str
    model: str
    swept: tuple
    fixed: tuple = ()
    pumped: str | None = None          # 'g1' or 'g2': the model pumped once with that correction
    n_params: int = 8
    n_random_angles: int = 6
    grazing: tuple = GRAZING            # the angles 90° − 10⁻ᵏ of every parameter set
    #: The package's class of the cell's model where it is not ``MODELS[model]`` (a model without its
    #: own albedo route, as a user writes it, so that the engine integrates its BRDF)
    model_class: type | None = None
    #: The parameter sets where they are given rather than drawn (the ends of a declared range)
    param_sets: tuple = ()

    @property
    def fixed_dict(self):
        return dict(self.fixed)


FAMILIES = (
    Family("phong", "phong", ("n",)),
    Family("phong_original", "phong_original", ("n",)),
    Family("phong_cosmin", "phong_cosmin", ("n",)),
    Family("p_model", "p_model", ("n", "p")),
    Family("blinn", "blinn", ("n",)),
    Family("blinn_original", "blinn_original", ("n",)),
    Family("blinn_cosmin", "blinn_cosmin", ("n",)),
    Family("ward", "ward", ("m",)),
    Family("ward_cosmin", "ward_cosmin", ("m",)),
    Family("cook_torrance_ts", "cook_torrance", ("m",), (("G", "torrance_sparrow"),)),
    Family("cook_torrance_smith", "cook_torrance", ("m",), (("G", "smith"),)),
    Family("cook_torrance_none", "cook_torrance", ("m",), (("G", "none"),)),
    Family("patch_basic", "patch_basic", ("R",)),
    Family("patch_mixture", "patch_mixture", ("weight", "p_diffuse"), n_params=4),
    Family("patch_exponential", "patch_exponential", ("s",)),
    Family("patch_elliptical", "patch_elliptical", ("b", "ratio", "u_angle_deg")),
    Family("generalized_lambertian", "generalized_lambertian", ("d",)),
    Family("ggx_height_correlated", "ggx", ("alpha",), (("G2", "height_correlated"),)),
    Family("ggx_separable", "ggx", ("alpha",), (("G2", "separable"),)),
    Family("ggx_fresnel", "ggx", ("alpha", "ior_re", "ior_im"), (("G2", "height_correlated"),), n_params=4),
    Family("ggx_kulla_conty", "ggx", ("alpha",), (("G2", "height_correlated"), ("compensation", "kulla_conty")), n_params=5),
    Family("beckmann_height_correlated", "beckmann", ("alpha",), (("G2", "height_correlated"),)),
    Family("beckmann_separable", "beckmann", ("alpha",), (("G2", "separable"),)),
    Family("beckmann_kulla_conty", "beckmann", ("alpha",), (("G2", "height_correlated"), ("compensation", "kulla_conty")), n_params=5),
    Family("pumped_phong_g1", "phong", ("n",), pumped="g1", n_params=6),
    Family("pumped_phong_g2", "phong", ("n",), pumped="g2", n_params=6),
    Family("pumped_blinn_g1", "blinn", ("n",), pumped="g1", n_params=6),
    Family("pumped_blinn_g2", "blinn", ("n",), pumped="g2", n_params=6),
    # Lambert is Oren–Nayar at σ = 0 (bit for bit, the model's own claim): a(θ) = ρ
    Family("lambert", "oren_nayar", ("rho",), (("sigma", 0.0),), n_params=3, n_random_angles=3,
           grazing=GRAZING[::4]),
    Family("oren_nayar", "oren_nayar", ("rho", "sigma")),
    # He–Torrance (the directional-diffuse density integrated, plus the specular delta's closed form),
    # rewritten and integrated by :mod:`sweep.he_torrance` (vectorised disk quadrature, ~0.03–1.2 CPU-s a
    # cell; H4, session 5): its two examples and four draws, at four random angles and 90° − 10⁻ᵏ
    Family("he_torrance_total", "he_torrance", ("sigma0_um", "tau_um"), (("term", "total"),), n_params=6,
           n_random_angles=4),
    # Oren–Nayar answers with its closed form; integrated, it is the engine's test of azimuthal kinks
    # (the half-planes Δφ = ±90°) in a user's model.  Last, so that the cells before it stay as drawn.
    Family("oren_nayar_integrated", "oren_nayar", ("rho", "sigma"), model_class=OrenNayarIntegrated),
    # The edges of issue 41, after the others so that their cells stay as drawn: a user's 2-D model next
    # to the pole (the kink θ_V = θ_L 1e-6° from it), n = 0 (the declared end) at grazing, and the Smith
    # models at the ends of their declared α
    Family("oren_nayar_integrated_pole", "oren_nayar", ("rho", "sigma"), model_class=OrenNayarIntegrated,
           n_params=4, n_random_angles=0, grazing=(1e-6, 1e-5, 1e-4, 1e-3)),
    Family("phong_n0", "phong", ("n",), param_sets=({"n": 0.0},), n_random_angles=4),
    Family("phong_original_n0", "phong_original", ("n",), param_sets=({"n": 0.0},), n_random_angles=4),
    Family("ggx_alpha_ends", "ggx", ("alpha",), (("G2", "height_correlated"),),
           param_sets=({"alpha": ALPHA_MIN}, {"alpha": ALPHA_MAX})),
    Family("ggx_separable_alpha_ends", "ggx", ("alpha",), (("G2", "separable"),),
           param_sets=({"alpha": ALPHA_MIN}, {"alpha": ALPHA_MAX})),
    Family("beckmann_alpha_ends", "beckmann", ("alpha",), (("G2", "height_correlated"),),
           param_sets=({"alpha": ALPHA_MIN}, {"alpha": ALPHA_MAX})),
    # the generalized Lambertian with its clip next to the weight's pole R = 2, at grazing incidence, where
    # the clip and the lens's kink 1 + sin θ meet the pole's layer (issue 41: up to 3.4× dishonest before
    # patch_geometry.WEIGHT_LAYER_GRADING)
    Family("generalized_lambertian_clip_near_2", "generalized_lambertian", ("d", "m_clip"),
           param_sets=({"d": 1.0, "m_clip": 2.0 - 1e-7}, {"d": 1.0, "m_clip": 2.0 - 1e-9},
                       {"d": 0.5, "m_clip": 2.0 - 1e-9}),
           n_random_angles=0, grazing=(89.9, 89.97, 89.99, 89.995, 89.999)),
    # a mixture's weight with features of its own, declared with its points (the class's feature_examples:
    # a box of width 1e-5 at R = 0.37, undeclared 0 ± 0 "converged" by every route)
    Family("patch_mixture_narrow_box", "patch_mixture", ("weight", "p_diffuse", "weight_points"),
           param_sets=tuple(mixture_feature_params(MODELS["patch_mixture"])), n_random_angles=4),
)
#: Families declared but left out of the committed sweep: He–Torrance's density alone (term 'dd'),
#: the same integral as ``he_torrance_total`` without the delta's closed form.
SLOW_FAMILIES = (
    Family("he_torrance_dd", "he_torrance", ("sigma0_um", "tau_um"), (("term", "dd"),), n_params=2,
           n_random_angles=1, grazing=(GRAZING[0], GRAZING[-1])),
)
FAMILY = {f.name: f for f in FAMILIES + SLOW_FAMILIES}


# --- parameters and angles ---------------------------------------------------------------

def _draw(rng, name, interval):
    lo, hi = SWEEP_BOUNDS[name]
    lo, hi = max(lo, interval.lo), min(hi, interval.hi)
    if lo > 0 and hi / lo > 10:
        return float(np.exp(rng.uniform(np.log(lo), np.log(hi))))
    return float(rng.uniform(lo, hi))


def family_parameters(family: Family, rng) -> list[dict]:
    """The family's parameter sets: the class's examples first, then draws from its ranges."""
    cls = MODELS[family.model]
    if family.param_sets:
        return [dict(p) for p in family.param_sets]
    if family.model == cls.name and "weight" in family.swept:      # the mixture: its two example weights
        return [{"weight": w, "p_diffuse": p} for w in ("uniform", "falling") for p in (0.0, 0.5)]
    out = []
    for kind in ("narrowest", "typical"):
        ex = {k: v for k, v in cls.examples.get(kind, {}).items() if k in family.swept}
        if len(ex) == len(family.swept):
            out.append(ex)
    if "R" in family.swept:                   # R = 1: the unit patch, where the lens geometry degenerates
        out.append({"R": 1.0})
    if family.model == "oren_nayar":        # its two examples differ in σ only: one Lambert point
        out = [dict(t) for t in dict.fromkeys(tuple(sorted(e.items())) for e in out)]
    while len(out) < family.n_params:
        out.append({k: _draw(rng, k, cls.param_ranges[k]) for k in family.swept})
    return [{k: (round(v, 6) if isinstance(v, float) else v) for k, v in p.items()} for p in out]


def cells(seed: int, families=FAMILIES) -> list[tuple[str, dict, float]]:
    """Every (family, parameters, θ) of the sweep, seeded."""
    rng = np.random.default_rng(seed)
    out = []
    for family in families:
        for params in family_parameters(family, rng):
            angles = list(np.round(rng.uniform(0.0, 90.0, family.n_random_angles), 6)) + list(family.grazing)
            out += [(family.name, params, float(t)) for t in angles]
    return out


# --- the model of a cell --------------------------------------------------------------------

def load_tables(path=TABLES) -> dict:
    if not Path(path).exists():
        return {}
    return json.loads(Path(path).read_text())


def table_key(family: Family, params: dict) -> str:
    return json.dumps({"family": family.name, **params}, sort_keys=True)


def table_from_json(entry) -> AlbedoTable:
    return AlbedoTable(np.array(entry["edges"]), np.array(entry["values"]), float(entry["error"]),
                       float(entry.get("model_rtol", 0.0)))


def table_to_json(table: AlbedoTable) -> dict:
    return {"edges": list(map(float, table.edges)), "values": np.asarray(table.values).tolist(),
            "error": float(table.error), "model_rtol": float(table.model_rtol)}


def needs_table(family: Family) -> bool:
    return family.pumped is not None or family.fixed_dict.get("compensation") == "kulla_conty"


def build(family_name: str, params: dict, tables: dict | None = None):
    """The package's model of a cell (with its stored table, where it needs one)."""
    family = FAMILY[family_name]
    cls = family.model_class or MODELS[family.model]
    kwargs = {**family.fixed_dict, **params}
    if family.model == "patch_mixture":
        weight = {"uniform": lambda R: np.full(np.shape(R), 0.5), "falling": lambda R: 1.0 - 0.5 * np.asarray(R, float)}
        kwargs = {"weight": ind.box_weight(params["weight"]) if ind.box_ends(params["weight"]) else weight[params["weight"]],
                  "p_diffuse": params["p_diffuse"], "weight_points": tuple(params.get("weight_points", ()))}
    if needs_table(family):
        tables = load_tables() if tables is None else tables
        table = table_from_json(tables[table_key(family, params)])
        if family.pumped is not None:
            return Pumped(cls(**kwargs), table, family.pumped)
        return cls(**kwargs, energy=table)
    return cls(**kwargs)


# --- the integrand of a cell -----------------------------------------------------------------

def _cos_points(n):
    w = 1.0 / np.sqrt(n + 1.0)
    return [w * k for k in (0.25, 0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 13, 16, 20, 25, 32)] + [0.5 * np.pi]


def _atan_points(scale, ks):
    return [float(np.arctan(scale * k)) for k in ks]


_BECKMANN_KS = (0.25, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 5, 6, 7, 8)
_GGX_KS = tuple(np.geomspace(0.1, 1e4, 26))


def _independent(family: Family, params: dict, model) -> Integrand:
    """The rewritten BRDF of the family in its lobe's frame, with the kinks as levels."""
    p, name = {**family.fixed_dict, **params}, family.model
    base_nv = lambda nl: ()
    if name.startswith("phong") or name == "p_model":
        divide = {"phong": "none", "phong_original": "nl", "phong_cosmin": "max", "p_model": "max"}[name]
        f = ind.phong(p["n"], model.C if not isinstance(model, Pumped) else model.base.C, divide, p.get("p", 1.0))
        frame, pts = "mirror", _cos_points(p["n"])
        if divide == "max":
            base_nv = lambda nl: (nl,)
    elif name.startswith("blinn"):
        divide = {"blinn": "none", "blinn_original": "nl", "blinn_cosmin": "max"}[name]
        f = ind.blinn(p["n"], 1.0, divide)
        frame, pts = "half", _cos_points(p["n"])
        if divide == "max":
            base_nv = lambda nl: (nl,)
    elif name in ("ward", "ward_cosmin"):
        f = ind.ward(p["m"], 1.0, corrected=name == "ward_cosmin")
        frame, pts = "half", _atan_points(p["m"], _BECKMANN_KS)
        if name == "ward_cosmin":
            base_nv = lambda nl: (nl,)
    elif name == "cook_torrance":
        f = ind.cook_torrance(p["m"], p["G"])
        frame, pts = "half", _atan_points(p["m"], _BECKMANN_KS)
        if p["G"] == "torrance_sparrow":
            integ = Integrand(f, frame, pts, nv_levels=lambda nl: (nl,), lh_levels=ind.torrance_sparrow_lh_levels)
            return integ
        if p["G"] == "smith":
            return Integrand(f, frame, pts, normal_kink=True)
    elif name in ("ggx", "beckmann"):
        multiple = None
        nv = lambda nl: tuple(k * p["alpha"] for k in (1 / 16, 1 / 4, 1.0, 4.0) if k * p["alpha"] < 1)
        if p.get("compensation") == "kulla_conty":
            multiple = model.multiple_scattering           # the table's term, through the physics layer
            edges = tuple(float(e) for e in model.energy.edges[1:-1])
            nv = (lambda nv0: (lambda nl: nv0(nl) + edges))(nv)
        f = ind.smith_microfacet(name, p["alpha"], p["G2"], p.get("ior_re"), p.get("ior_im", 0.0), multiple)
        ks = _GGX_KS if name == "ggx" else _BECKMANN_KS + (10, 14, 20, 40, 100)
        return Integrand(f, "half", _atan_points(p["alpha"], ks), nv_levels=nv)
    else:
        raise KeyError(family.name)
    if isinstance(model, Pumped):
        base_f, table, g2 = f, model.table, model.correction == "g2"

        def f(L, V, nl, nv, geo=None):
            g = np.maximum(table(nl), table(nv))
            if g2:
                g = np.maximum(g, np.maximum(nl, nv))
            return base_f(L, V, nl, nv, geo) / g
        levels = lambda nl: tuple(float(x) for x in np.ravel(model.nv_levels(nl)))
        return Integrand(f, frame, pts, nv_levels=levels)
    return Integrand(f, frame, pts, nv_levels=base_nv)


def _patch_truth(family: Family, params: dict, model, theta: float) -> Truth:
    name = family.model
    if name == "patch_basic":
        xi = ind.patch_basic_xi(params["R"], model.C)
        return disk_albedo(lambda rho, psi: xi(rho), theta, radial_kinks=(params["R"],))
    if name == "patch_exponential":
        xi = ind.patch_exponential_xi(params["s"], model.C)
        scales = [k / max(params["s"], 1e-9) for k in (0.5, 1, 2, 4, 8, 16, 32, 64)]
        return disk_albedo(lambda rho, psi: xi(rho), theta, radial_scales=[x for x in scales if x < 2])
    if name == "generalized_lambertian":
        xi = ind.generalized_lambert_xi(params["d"], model.m_clip, model.C)
        return disk_albedo(lambda rho, psi: xi(rho), theta, radial_kinks=(model.m_clip,))
    if name == "patch_mixture":
        xi = ind.patch_mixture_xi(params["weight"], params["p_diffuse"])
        # ξ ~ 1/m + ln(m)/2 at m → 0: ρ ξ(ρ) has a ρ ln ρ end, taken by cuts geometric toward 0
        return disk_albedo(lambda rho, psi: xi(rho), theta, radial_kinks=(1.0, *(ind.box_ends(params["weight"]) or ())),
                           radial_scales=tuple(10.0 ** -np.arange(1, 13)))
    if name == "patch_elliptical":
        rho_e = ind.ellipse_radius(params["b"], params["ratio"], params["u_angle_deg"])
        C = model.C
        return disk_albedo(lambda rho, psi: np.where(rho <= rho_e(psi), C, 0.0), theta,
                           ellipse_radius=rho_e, symmetric=False)
    raise KeyError(family.name)


def truth(family_name: str, params: dict, theta: float, tables: dict | None = None) -> Truth:
    """The third route's a(θ) of a cell."""
    family = FAMILY[family_name]
    model = build(family_name, params, tables)
    from sweep.sharp import sharp_truth         # H4, session 5: sharper routes where they exist (None: none)
    sharp = sharp_truth(family, {**family.fixed_dict, **params}, theta, model)
    if sharp is not None:
        return sharp
    if family.model.startswith("patch") or family.model == "generalized_lambertian":
        t = _patch_truth(family, params, model, theta)
        t.route += "+independent"
        return t
    if family.model == "oren_nayar":
        p = {**family.fixed_dict, **params}
        value = ind.oren_nayar_albedo(p["rho"], p["sigma"], theta)
        exact = p["sigma"] == 0.0               # B = 0 and A = 1 exactly: a = ρ, to the bit
        return Truth(value, 0.0 if exact else 16 * np.finfo(float).eps * abs(value), "closed_form+independent")
    t = hemisphere_albedo(_independent(family, params, model), theta)
    t.route += "+independent" + ("+table" if needs_table(family) else "")
    return t


def pointwise_agreement(family_name: str, params: dict, n: int = 2000, seed: int = 0, tables=None) -> float:
    """max |f_independent − f_model| / max |f_model| over random direction pairs (the rewrite of the
    family against the package's model)."""
    family = FAMILY[family_name]
    model = build(family_name, params, tables)
    rng = np.random.default_rng(seed)
    def dirs(k):
        u = rng.uniform(size=(k, 2))
        z = u[:, 0]
        r = np.sqrt(1 - z * z)
        return np.stack([r * np.cos(2 * np.pi * u[:, 1]), r * np.sin(2 * np.pi * u[:, 1]), z], -1)
    L, V = dirs(n), dirs(n)
    ref = model(L, V)
    if family.model.startswith("patch") or family.model == "generalized_lambertian":
        m = np.hypot(L[:, 0] + V[:, 0], L[:, 1] + V[:, 1])
        if family.model == "patch_elliptical":
            psi = np.arctan2(L[:, 1] + V[:, 1], L[:, 0] + V[:, 0])
            rho_e = ind.ellipse_radius(params["b"], params["ratio"], params["u_angle_deg"])
            mine = np.where(m <= rho_e(psi), model.C, 0.0)
        else:
            xi = {"patch_basic": lambda: ind.patch_basic_xi(params["R"], model.C),
                  "patch_exponential": lambda: ind.patch_exponential_xi(params["s"], model.C),
                  "generalized_lambertian": lambda: ind.generalized_lambert_xi(params["d"], model.m_clip, model.C),
                  "patch_mixture": lambda: ind.patch_mixture_xi(params["weight"], params["p_diffuse"])}[family.model]()
            mine = xi(m)
    elif family.model == "he_torrance":             # H4, session 5: the rewrite on the projected disk
        from sweep.sharp import he_torrance_pointwise
        return he_torrance_pointwise(model, rng)
    elif family.model == "oren_nayar":
        p = {**family.fixed_dict, **params}
        mine = np.where((L[:, 2] >= 0) & (V[:, 2] > 0), ind.oren_nayar(p["rho"], p["sigma"])(L, V), 0.0)
    else:
        integ = _independent(family, params, model)
        with np.errstate(all="ignore"):
            mine = integ.f(L, V, L[:, 2], V[:, 2], None)
        mine = np.where((L[:, 2] >= 0) & (V[:, 2] > 0), mine, 0.0)
    scale = float(np.max(np.abs(ref))) or 1.0
    return float(np.max(np.abs(mine - ref)) / scale)
