"""Work against precision of the albedo methods on hard problems (:mod:`brdfs.artifacts._work_precision`):
true error against BRDF evaluations for the engine over a range of tolerances, product Gauss grids,
scipy's dblquad and Monte Carlo (uniform, cosine and the model's own importance sampling)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts._work_precision import work_precision
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

NAME = "extra_work_precision"
SECTION = "work_precision"
STYLE = {("engine", ""): ("o", "-"), ("product_grid", ""): ("s", "-"), ("dblquad", ""): ("^", "-"),
         ("monte_carlo", "uniform"): ("x", "--"), ("monte_carlo", "cosine"): ("+", "--"),
         ("monte_carlo", "model"): ("d", "--")}
FLOOR = 1e-17


@figure(NAME, config=(SECTION,), resources={"runtime": 5}, chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """``case, model, theta_deg, method, sampler, setting, evaluations, status, albedo, albedo_err,
    reference, reference_err, reference_kind, true_error, dishonest``."""
    return work_precision(cfg[SECTION], cfg["seed"])


def plot(df: pd.DataFrame, path) -> None:
    """One panel per case: true error against BRDF evaluations; a red ring marks a point whose
    reported error is below its true error."""
    cases = list(dict.fromkeys(df["case"]))
    cols = 4
    rows = -(-len(cases) // cols)
    fig, axes = plotting.plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), squeeze=False)
    for ax, case in zip(axes.ravel(), cases):
        sub = df[df["case"] == case]
        for (method, sampler), (marker, style) in STYLE.items():
            m = sub[(sub["method"] == method) & (sub["sampler"] == sampler)].sort_values("evaluations")
            if m.empty:
                continue
            label = method if not sampler else f"MC {sampler}"
            ax.loglog(m["evaluations"], np.maximum(m["true_error"], FLOOR), style, marker=marker, label=label)
            bad = m[m["dishonest"]]
            ax.loglog(bad["evaluations"], np.maximum(bad["true_error"], FLOOR), "o", mfc="none", mec="red", ms=10,
                      label="reported < true")
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("BRDF evaluations")
        ax.set_ylabel("true error of a(θ)")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.ravel()[len(cases):]:
        ax.set_axis_off()
    handles = {}
    for ax in axes.ravel():
        for h, l in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(l, h)
    fig.legend(list(handles.values()), list(handles), loc="upper center", bbox_to_anchor=(0.5, 0.0),
               ncol=len(handles), fontsize=8)
    fig.suptitle(f"Work against precision of the albedo methods (errors below {FLOOR:g} drawn at {FLOOR:g})")
    fig.tight_layout()
    plotting.savefig(fig, path)
