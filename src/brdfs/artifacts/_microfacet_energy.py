"""Shared parts of the white-furnace comparison (issue 18): the thesis's remedies (pumping, sec. 2.3;
the new model, chapter 3) beside today's microfacet practice (GGX/Beckmann with Smith's G2,
Kulla–Conty compensation) and the random walk on the Smith microsurface as the physical reference.

Roughness mapping (a choice, stated in the captions).  Walter et al. (2007), sec. 5.2, match the
Blinn–Phong normal distribution cos^n δ to Beckmann by n = 2/α² − 2; the same α is used for GGX
(their suggestion too).  The thesis's Phong is a mirror lobe (R·V)^n: at normal incidence the angle
between R and V is 2δ and cos^n 2δ ≈ exp(−2nδ²) ≈ cos^{4n} δ, so Phong n ↔ Blinn 4n ↔
α = √(2/(4n + 2)).  Thus Phong n = 20 ↔ α = 0.156 and Blinn n = 20 ↔ α = 0.302.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _pumping_figures as pumping_figures
from brdfs.physics.optical_constants import complex_index
from brdfs.numerics import pumping, tables
from brdfs.numerics.quantities import maximal_constant
from brdfs.numerics.random_walk import random_walk
from brdfs.physics.fresnel import unpolarised_reflectance
from brdfs.physics.models import MODELS, model

#: The table artifact holding the Kulla–Conty E tables (read by the figures instead of recomputing).
ENERGY_TABLE = "extra_microfacet_albedo"
PUMPING_TABLES = {"phong": "extra_pumping_albedo_phong", "blinn": "extra_pumping_albedo_blinn"}
COLUMNS = ["family", "model", "variant", "pumping", "level", "n", "alpha", "G2", "quantity",
           "theta_deg", "value", "value_err"]


def alpha_of_n(family: str, n):
    """α matched to the exponent n of the cosine-lobe model ``family`` (Phong: mirror lobe, Blinn:
    half-vector lobe; the model's :attr:`~brdfs.physics.models.base.BRDF.half_angle_exponent_factor`,
    module docstring)."""
    n = np.asarray(n, float)
    return np.sqrt(2.0 / (MODELS[family].half_angle_exponent_factor * n + 2.0))


def n_of_alpha(family: str, alpha):
    """Inverse of :func:`alpha_of_n`."""
    blinn = 2.0 / np.asarray(alpha, float) ** 2 - 2.0
    return blinn / MODELS[family].half_angle_exponent_factor


def pumped_family(family: str, table_df: pd.DataFrame, correction: str, levels: int):
    """[(level, model, table)] of ``family`` pumped 0 … ``levels`` times from the deps' tables (no integration)."""
    name, n, C = table_df[["model", "n", "C"]].iloc[0]
    tables = pumping.tables_from_frame(table_df, correction)
    models = pumping.pumped_models(pumping_figures.base_model(name, n, C), tables[:-1], correction)
    return [(k, models[k], tables[k]) for k in range(min(levels, len(models) - 1) + 1)], float(n)


def new_model(family: str, n: float):
    """The thesis's new model of the family (:attr:`~brdfs.physics.models.base.BRDF.corrected_by`):
    phong_cosmin with c = (n+2)/2π (eq. 3.10), or blinn_cosmin (eq. 3.34) with C = 1/max a (its
    Table 3.1 constant, computed: :attr:`~brdfs.physics.models.base.BRDF.constant_is_computed`)."""
    name = MODELS[family].corrected_by
    if not MODELS[name].constant_is_computed:
        return model(name, n=n)
    C = float(maximal_constant([model(name, n=n)], rtol=1e-9)[0].value[0])
    return model(name, n=n, C=C)


def microfacet(name: str, alpha: float, compensation: str = "none", G2: str = "height_correlated", **fresnel):
    """A Smith microfacet model with the tables it needs (:func:`brdfs.numerics.tables.build`: the E
    table of Kulla–Conty's compensation, seeded from :data:`ENERGY_TABLE` by :func:`seed_energy_tables`)."""
    return tables.build(name, alpha=float(alpha), G2=G2, compensation=compensation, **fresnel)


def energy_table(name: str, alpha: float, G2: str):
    """(E table, E_avg) of Smith microfacet model ``name`` at ``alpha`` and ``G2`` (F = 1), the table
    its compensated version is built with, and E_avg = 2 ∫₀¹ E(μ) μ dμ integrated from it exactly."""
    return microfacet(name, alpha, "kulla_conty", G2).energy_table()


def energy_table_frame(name: str, alpha: float, G2: str):
    """The E table's nodes as tidy rows (``mu`` = node, ``albedo``, ``albedo_err`` = the table's bound,
    with ``piece, x_lo, x_hi, node``), for :func:`seed_energy_tables`."""
    table = energy_table(name, alpha, G2)[0]
    rows = table.to_frame().rename(columns={"cos_theta": "mu"}).drop(columns=["model_rtol"])
    return rows.assign(model=name, G2=G2, alpha=float(alpha))


def seed_energy_tables(frame) -> int:
    """Put the E tables stored by :func:`energy_table_frame` (rows with a ``piece``) into the factory's
    cache (:func:`brdfs.numerics.tables.seed`), so that the compensated models of the figures are built
    with the tables of :data:`ENERGY_TABLE` instead of recomputing them; returns how many."""
    nodes = frame.dropna(subset=["piece"])
    count = 0
    for (name, alpha, G2), g in nodes.groupby(["model", "alpha", "G2"]):
        table = pumping.AlbedoTable.from_frame(g.rename(columns={"mu": "cos_theta"}).assign(
            model_rtol=0.0, piece=g["piece"].astype(int), node=g["node"].astype(int)))
        tables.seed(MODELS[name].energy_request(float(alpha), G2), table)
        count += 1
    return count


def gold_index(cfg_gold: dict) -> complex:
    """The measured complex index n + ik of gold at the configured wavelength and data set
    (:func:`brdfs.physics.optical_constants.complex_index`)."""
    return complex(complex_index("gold", cfg_gold["wavelength_nm"], cfg_gold["dataset"]))


def gold_fresnel(cfg_gold: dict):
    eta = gold_index(cfg_gold)
    return lambda c: unpolarised_reflectance(c, eta.real, eta.imag)


def distribution(name: str, alpha: float):
    """The microfacet distribution of Smith model ``name`` at roughness ``alpha`` (the model's own)."""
    return microfacet(name, alpha).distribution


def walk_paths(cfg: dict) -> int:
    """Paths per walk: the small default, or the full run behind the config switch ``walk_full``."""
    return int(cfg["walk_paths_full"] if cfg["walk_full"] else cfg["walk_paths"])


def walk(name: str, alpha: float, theta_deg: float, cfg: dict, seed: int, key: tuple, fresnel=None):
    """One seeded random walk; the stream is seeded by ``[seed, *key]`` (independent per curve/angle)."""
    rng = np.random.default_rng([int(seed), *[int(k) for k in key]])
    return random_walk(distribution(name, alpha), theta_deg, walk_paths(cfg), rng, fresnel=fresnel,
                       max_order=int(cfg["walk_max_order"]))


def rows(**columns) -> pd.DataFrame:
    """A tidy frame with every column of :data:`COLUMNS` (missing ones empty)."""
    length = max(np.size(v) for v in columns.values())
    data = {c: np.broadcast_to(np.asarray(columns.get(c, "" if c in ("variant", "pumping", "G2") else np.nan),
                                          dtype=object if c in ("family", "model", "variant", "pumping", "G2",
                                                                "quantity") else float), (length,))
            for c in COLUMNS}
    return pd.DataFrame(data)
