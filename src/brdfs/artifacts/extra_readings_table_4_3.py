"""How Table 4.3 was computed: eq. 4.22 evaluated as a sum, searched over a declared family.

The thesis (after eq. 4.42): for a ξ with increasing parts, "the computation of the maximal albedo
and of the normalizing factor ... can be accomplished by numerical methods using formula (4.22)".
For the clipped generalized Lambertian ξ (eq. 4.59), p(R) = −C ξ'(R) π min(1, R²) (eq. 4.41) and
a_R(L) = Area(C(L'_P, R))/(π min(1, R²)) (eq. 4.8), so

    a^ξ(θ) = π ξ_max − ∫₀² ξ'(R) Area(C(L'_P, R)) dR,        C_max = 1/a^ξ(90°),
    a_diffuse = a^ξ(0°)/a^ξ(90°)  (Area = π min(1, R²) at θ = 0),

ξ' = 0 above the clip m_clip = 1.9, where ξ' itself is largest. The family evaluates the integral
as a sum: every rule (left, right, midpoint, trapezoid, Simpson, two-point Gauss per step) × step
h (``patch.readings_steps``) × range end (m_clip or 2) × the clip node (a node exactly at m_clip
takes ξ' = 0, ``clipped``, or its value from below, ``unclipped``). The lens areas, which do not
depend on d, are computed once per node set and angle. One reading is applied unchanged to the
22 numeric prints of the C_max and a_diffuse columns.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import patch_geometry as patch
from brdfs.pipeline import plotting
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import table

NAME = "extra_readings_table_4_3"
ARTIFACT = "patch_generalized_lambert"
GROUP = "Table 4.3 C_max and a_diffuse"
QUANTITIES = ("C_max", "a_diffuse")
RULES = ("left", "right", "midpoint", "trapezoid", "simpson", "gauss2")
ENDS = ("m_clip", "2")
CLIP_NODES = ("clipped", "unclipped")
PROCEDURE = ("eq. 4.22 as a sum, 'by numerical methods using formula (4.22)' (Sec. 4.6, after eq. 4.42)")


def _slopes(ds, R: np.ndarray, m_clip: float) -> np.ndarray:
    """ξ'(R) of every d (rows): the formula below m_clip, 0 from m_clip on."""
    below = np.minimum(R, m_clip)
    log_w = np.log1p(-0.25 * below * below)
    d = np.asarray(ds, float)[:, None]
    value = 0.25 * d * below * np.exp((-0.5 * d - 1.0) * log_w)
    return np.where(R < m_clip, value, 0.0)


def reading_values(ds, m_clip: float, steps, rules=RULES) -> tuple[pd.DataFrame, dict]:
    """The family's readings and, per reading, (C_max, a_diffuse) for every d.

    Per step, the products ξ'(R) Area(C(L'_P, R)) are formed once on the grid R = i h of [0, 2]
    (the range ending at m_clip is its prefix), at the midpoints and at the Gauss nodes; every
    reading is then one weighted sum of them.
    """
    rows, out = [], {}
    xi_max = np.array([patch.GeneralizedLambertProfile(d, m_clip).xi_max for d in ds])
    for h in steps:
        n2 = int(round(2.0 / h))
        grid = np.arange(n2 + 1) * h
        clip_index = int(round(m_clip / h))
        on_grid = abs(clip_index * h - m_clip) <= 1e-9 * h
        centres = grid[:-1] + h / 2
        gauss = np.sort(np.concatenate([centres - h / (2 * np.sqrt(3.0)), centres + h / (2 * np.sqrt(3.0))]))
        products = {}
        for nodes_name, R in (("grid", grid), ("midpoint", centres), ("gauss2", gauss)):
            if nodes_name != "grid" and nodes_name not in rules:
                continue
            areas = np.stack([_lens_areas(R, theta) for theta in (0.0, 90.0)])          # (2, nodes)
            slope = _slopes(ds, R, m_clip)                                             # (d, nodes)
            products[nodes_name] = slope[:, None, :] * areas[None, :, :]               # (d, θ, nodes)
        clipped = products["grid"].copy()
        clipped[..., clip_index] = 0.0            # the node at the clip (or the first beyond it)
        unclipped = clipped.copy()
        if on_grid:                               # its derivative from below: ξ'(m_clip⁻)
            at_clip = _slopes(ds, np.array([m_clip * (1 - 1e-16)]), m_clip)[:, 0]
            unclipped[..., clip_index] = at_clip[:, None] * np.stack(
                [_lens_areas(np.array([m_clip]), theta)[0] for theta in (0.0, 90.0)])[None, :]
        for rule in rules:
            for end_name in ENDS:
                n = clip_index if end_name == "m_clip" else n2
                for clip_node, P in (("clipped", clipped), ("unclipped", unclipped)):
                    if rule in ("midpoint", "gauss2"):
                        k = n if rule == "midpoint" else 2 * n
                        total = products[rule][..., :k].sum(axis=-1) * (h if rule == "midpoint" else h / 2)
                    else:
                        total = readings.grid_rule_sum(rule, P, h, n)
                    a = np.pi * xi_max[:, None] - total                                # (d, θ)
                    end_label = f"m_clip = {m_clip:g}" if end_name == "m_clip" else "2"
                    name = f"{rule}, h = {h:g}, to {end_label}, clip node {clip_node}"
                    rows.append({"reading": name, "rule": rule, "step": h, "end": end_name, "clip_node": clip_node})
                    out[name] = list(zip(1.0 / a[:, 1], a[:, 0] / a[:, 1]))
    return pd.DataFrame(rows), out


def _lens_areas(R: np.ndarray, theta: float) -> np.ndarray:
    """Area(C(L'_P, R) ∩ unit disk) at incidence θ (π min(1, R²) a_R(θ) of eq. 4.8); 0 at R = 0;
    π min(1, R²) at θ = 0, where the disk is centred."""
    if theta == 0.0:
        return np.pi * np.minimum(1.0, R * R)
    d = np.sin(np.radians(theta))
    mu = 0.0 if theta == 90.0 else np.cos(np.radians(theta))
    area = np.zeros_like(R)
    positive = R > 0
    area[positive] = patch.circle_intersection(np.full(positive.sum(), d), R[positive],
                                               np.full(positive.sum(), mu)).area
    return area


def group_entries() -> pd.DataFrame:
    """The numeric prints of Table 4.3's C_max and a_diffuse columns, in file order."""
    rows = published.published_rows(ARTIFACT)
    rows = rows[rows["quantity"].isin(QUANTITIES)]
    return rows[[published.print_kind(p) == "numeric" for p in rows["published"]]].reset_index(drop=True)


def run_search(cfg: dict) -> readings.Search:
    """Table 4.3's search: every reading of the family on every numeric print of the group."""
    entries = group_entries()
    ds = sorted({float(v) for v in entries["param_value"]})
    family, values = reading_values(ds, float(cfg["patch"]["m_clip"]), cfg["readings"]["table_4_3"]["steps"])
    column = {q: i for i, q in enumerate(QUANTITIES)}
    matrix = np.array([[values[name][ds.index(float(e.param_value))][column[e.quantity]]
                        for e in entries.itertuples()] for name in family["reading"]])
    return readings.search(GROUP, entries, family, matrix, seed=cfg["seed"], draws=cfg["readings"]["placebo_draws"],
                           axes=("step", "rule", "end", "clip_node"), procedure=PROCEDURE)


@table(NAME, config=("patch", "readings", "seed"), chapter=4)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """One row per (reading, entry): the value each reading prints for each entry of Table 4.3."""
    return run_search(cfg).tidy()


def plot(df: pd.DataFrame, path) -> None:
    """Entries reproduced against the step, one line per rule and edge treatment, with the placebo."""
    readings.plot_groups(df, path, [dict(group=GROUP, x="step", lines=("rule", "end", "clip_node"),
                                         title="Table 4.3: eq. 4.22 as a sum", xlabel="step h in R", log_x=True)])
