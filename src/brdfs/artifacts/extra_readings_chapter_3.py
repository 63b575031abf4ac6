"""How chapter 3's tables were computed: declared families for Tables 3.1, 3.2, 3.3 and Sec. 3.7.4.

Each group is searched over a family fixed in ``readings.chapter_3`` before any reading is scored
(:mod:`brdfs.pipeline.readings`):

* **Tables 3.1 and 3.2** (C = 1/max_θ a(θ); the maximum is at normal incidence for every row): the
  maximum over a θ grid of each step of ``grid_steps_deg`` (0: the true maximum), and a(0) as a
  sum in θ_V of each rule with each count of ``a0_steps`` (at normal incidence the integrand
  depends on θ_V alone: a(0) = 2π ∫ f cos θ_V sin θ_V dθ_V), each rounded or truncated;
* **Table 3.3** (eq. 3.37, a_mean = ∫₀¹ a(θ) d(cos²θ)): the outer integral as a sum of each rule
  with each count of ``mean_steps`` in each variable (θ, cos θ or cos²θ), a(θ) from the engine at
  the nodes; the Blinn columns with Table 3.1's computed C_n;
* **Sec. 3.7.4** (the albedo at 90° of Blinn and corrected Blinn, n = 128): the albedo at
  90° − δ for each δ of ``near_grazing_deg``, with C_n computed or as printed in Table 3.1 — a group
  of two prints, too small for a placebo.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.numerics.albedo import albedo
from brdfs.physics.geometry import direction, light_direction
from brdfs.physics.models import model
from brdfs.pipeline import published
from brdfs.pipeline import readings
from brdfs.pipeline.registry import table

NAME = "extra_readings_chapter_3"
CONSTANTS = "table_3_1_blinn_constants"
GROUPS = {"blinn_cn": "Table 3.1 C_n", "ward_cmax": "Table 3.2 C_max", "mean_albedo": "Table 3.3 mean albedo",
          "blinn_90deg": "Sec. 3.7.4 albedo at 90 deg"}
RULES = ("left", "right", "midpoint", "trapezoid", "simpson")
PRINTING = ("round", "truncate")
#: The engine's tolerance for the albedo at the nodes (the prints have 3–4 digits).
NODE_RTOL = 1e-8


def _curves(models, theta_deg) -> np.ndarray:
    """a(θ) of every model on a grid, one engine call per model (a curve at a time: the batch door
    sends a large set of (model, θ) pairs to its slow fallback)."""
    return np.array([albedo(m, theta_deg, rtol=NODE_RTOL).value for m in models])


def _entries(artifact: str, numeric_only: bool = True) -> pd.DataFrame:
    rows = published.published_rows(artifact)
    if numeric_only:
        rows = rows[[published.print_kind(p) == "numeric" for p in rows["published"]]]
    return rows.reset_index(drop=True)


def _build(model_name: str, param: str, value: float, C=None):
    kwargs = {param: float(value)}
    return model(model_name, **kwargs) if C is None else model(model_name, C=float(C), **kwargs)


def _a0_by_rule(brdf, rule: str, n: int) -> float:
    """a(0) = 2π ∫₀^{π/2} f(N, V(θ_V)) cos θ_V sin θ_V dθ_V as a sum (NaN where the rule cannot)."""
    x, w = readings.rule_weights(rule, 0.0, np.pi / 2, n)
    if x.size == 0:
        return np.nan
    theta_v = np.degrees(x)
    f = brdf(light_direction(np.zeros_like(theta_v)), direction(theta_v, np.zeros_like(theta_v)))
    return float(2 * np.pi * np.sum(w * f * np.cos(x) * np.sin(x)))


def constant_search(cfg: dict, artifact: str, constants: pd.DataFrame) -> readings.Search:
    """Tables 3.1 / 3.2: C = 1/max a under a θ grid, or 1/a(0) under a rule in θ_V, each printed
    by rounding or truncation."""
    family = cfg["readings"]["chapter_3"]
    entries = _entries(artifact)
    models = [_build(e.model, e.param, e.param_value, C=1.0) for e in entries.itertuples()]
    steps = family["grid_steps_deg"]
    grid = np.unique(np.concatenate([np.arange(0.0, 90.0 + 1e-9, s) for s in steps if s > 0] + [[0.0]]))
    curve = _curves(models, grid)
    computed = []                       # (row without its printing rule, value): each computed once
    for step in steps:
        if step == 0:
            value, label = [_true_constant(constants, e) for e in entries.itertuples()], "1/max a(theta)"
        else:
            on = np.isclose(np.mod(grid + 1e-9, step), 0.0, atol=1e-6)
            value, label = 1.0 / curve[:, on].max(axis=1), f"1/max a over a {step:g} deg grid of theta"
        computed.append(({"reading": label, "method": "theta_grid", "rule": "",
                          "steps": step if step > 0 else np.nan}, value))
    for rule in RULES:
        for n in family["a0_steps"]:
            computed.append(({"reading": f"1/a(0), a(0) by the {rule} rule with {n} steps in theta_V",
                              "method": "a0_rule", "rule": rule, "steps": n},
                             [1.0 / _a0_by_rule(m, rule, n) for m in models]))
    rows, values, rules = [], [], []
    for printing in PRINTING:
        for row, value in computed:
            rows.append(row | {"reading": f"{row['reading']}, {readings.PRINTED_AS[printing]}", "printing": printing})
            values.append(value)
            rules.append(printing)
    group = GROUPS[artifact]
    return readings.search(group, entries, pd.DataFrame(rows), np.array(values, float), rules=rules,
                           seed=cfg["seed"], draws=cfg["readings"]["placebo_draws"],
                           axes=("steps", "rule", "method", "printing"), procedure="C = 1/max a(theta)")


def _true_constant(constants: pd.DataFrame, e) -> float:
    """This project's C (Table 3.1's or 3.2's computed value) for an entry."""
    column = "n" if "n" in constants.columns else "m"
    row = constants[(constants["model"] == e.model) & np.isclose(constants[column], float(e.param_value))]
    return float(row["C"].iloc[0])


def mean_search(cfg: dict, constants: pd.DataFrame) -> readings.Search:
    """Table 3.3: eq. 3.37 as a sum of each rule and count in each variable."""
    family = cfg["readings"]["chapter_3"]
    entries = _entries("mean_albedo")
    entries = entries[entries["param_value"] != "inf"].reset_index(drop=True)
    blinn_c = {(r.model, float(r.n)): r.C for r in constants.itertuples()}
    models = [_build(e.model, "n", e.param_value, C=blinn_c.get((e.model, float(e.param_value))))
              for e in entries.itertuples()]
    variables = {"theta": lambda t: t, "cos_theta": lambda mu: np.degrees(np.arccos(mu)),
                 "cos2_theta": lambda u: np.degrees(np.arccos(np.sqrt(u)))}
    integrands = {  # a_mean = ∫ g(x) a(θ(x)) dx over the variable's range
        "theta": (0.0, np.pi / 2, lambda x: np.sin(2 * x)),
        "cos_theta": (0.0, 1.0, lambda x: 2 * x),
        "cos2_theta": (0.0, 1.0, lambda x: np.ones_like(x)),
    }
    plan, nodes = [], []
    for variable, (a, b, _) in integrands.items():
        for rule in RULES:
            for n in family["mean_steps"]:
                x, w = readings.rule_weights(rule, a, b, n)
                if x.size:
                    plan.append((variable, rule, n, x, w))
                    angles = variables[variable](x) if variable != "theta" else np.degrees(x)
                    nodes.append(np.clip(angles, 0.0, 90.0))
    grid = np.unique(np.round(np.concatenate(nodes), 12))
    curve = _curves(models, grid)
    rows, values = [], []
    for variable, rule, n, x, w in plan:
        angles = np.clip(variables[variable](x) if variable != "theta" else np.degrees(x), 0.0, 90.0)
        columns = np.searchsorted(grid, np.round(angles, 12))
        g = integrands[variable][2](x)
        rows.append({"reading": f"eq. 3.37 by the {rule} rule with {n} steps in {variable.replace('_', ' ')}",
                     "variable": variable, "rule": rule, "steps": n})
        values.append(curve[:, columns] @ (w * g))
    return readings.search(GROUPS["mean_albedo"], entries, pd.DataFrame(rows), np.array(values), seed=cfg["seed"],
                           draws=cfg["readings"]["placebo_draws"], axes=("steps", "rule", "variable"),
                           procedure="eq. 3.37's outer integral as a sum")


def near_grazing_search(cfg: dict, constants: pd.DataFrame) -> readings.Search:
    """Sec. 3.7.4: the albedo at 90° − δ, with C_n computed or as printed in Table 3.1."""
    family = cfg["readings"]["chapter_3"]
    entries = _entries("blinn_90deg")
    printed_c = published.printed_lookup("blinn_cn")
    rows, values = [], []
    deltas = family["near_grazing_deg"]
    for source in ("computed", "printed"):
        models = []
        for e in entries.itertuples():
            blinn_c = _true_constant(constants, e) if source == "computed" else float(
                printed_c(e.param_value, "C_max", e.model))
            models.append(_build(e.model, "n", e.param_value, C=blinn_c))
        curve = _curves(models, np.array([90.0 - d for d in deltas]))
        for j, d in enumerate(deltas):
            rows.append({"reading": f"albedo at {90 - d:g} deg with C_n {source} (Table 3.1)", "delta_deg": d,
                         "constant": source})
            values.append(curve[:, j])
    return readings.search(GROUPS["blinn_90deg"], entries, pd.DataFrame(rows), np.array(values), seed=cfg["seed"],
                           draws=cfg["readings"]["placebo_draws"], axes=("delta_deg", "constant"),
                           procedure="the albedo at 90 deg")


@table(NAME, deps=(CONSTANTS, "table_3_2_ward_cmax"), config=("readings", "seed"), chapter=3)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """One row per (group, reading, entry) of chapter 3's four searches."""
    blinn, ward = deps[CONSTANTS], deps["table_3_2_ward_cmax"]
    return pd.concat([constant_search(cfg, "blinn_cn", blinn).tidy(), constant_search(cfg, "ward_cmax", ward).tidy(),
                      mean_search(cfg, blinn).tidy(), near_grazing_search(cfg, blinn).tidy()], ignore_index=True)


def plot(df: pd.DataFrame, path) -> None:
    """Entries reproduced per group against the step or count of its readings."""
    readings.plot_groups(df, path, [
        dict(group=GROUPS["blinn_cn"], x="steps", lines=("method", "rule", "printing"), title="Table 3.1",
             xlabel="theta grid step (deg) or steps in theta_V", log_x=True),
        dict(group=GROUPS["ward_cmax"], x="steps", lines=("method", "rule", "printing"), title="Table 3.2",
             xlabel="theta grid step (deg) or steps in theta_V", log_x=True),
        dict(group=GROUPS["mean_albedo"], x="steps", lines=("variable", "rule"), title="Table 3.3",
             xlabel="steps of the outer sum", log_x=True),
        dict(group=GROUPS["blinn_90deg"], x="delta_deg", lines=("constant",), title="Sec. 3.7.4",
             xlabel="90 deg minus the angle (deg)"),
    ])
