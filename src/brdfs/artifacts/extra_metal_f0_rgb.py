"""Linear-sRGB normal-incidence reflectance F0 of gold, silver, copper and aluminium.

F0(λ) = a0 of eq. 1.40 from each metal's measured n(λ), k(λ) (config section ``metal_f0_rgb``
names the data sets), integrated against D65 and the CIE 1931 2° observer and converted to
linear sRGB with colour-science (:mod:`brdfs.physics.spectral_colour`). The error column bounds
the floating-point error of eq. 1.40 carried through the (non-negative) colour integration;
the interpolation of the tables and the spread between measurements are far larger and are
not in it (see the caption).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.physics import optical_constants, spectral_colour
from brdfs.physics.fresnel import normal_incidence_reflectance, normal_incidence_reflectance_err
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import table

NAME = "extra_metal_f0_rgb"
SECTION = "metal_f0_rgb"


def f0_linear_srgb(metal: str, dataset: str | None = None):
    """(linear sRGB of F0, error bound) for one metal."""
    wl = spectral_colour.VISIBLE_NM
    eta = optical_constants.complex_index(metal, wl, dataset)
    f0 = normal_incidence_reflectance(eta.real, eta.imag)
    err = normal_incidence_reflectance_err(eta.real, eta.imag).max()
    m_abs = np.abs(spectral_colour.xyz_to_linear_srgb(np.eye(3)).T)
    white = spectral_colour.reflectance_to_xyz(wl, np.ones(wl.size))
    return spectral_colour.reflectance_to_linear_srgb(wl, f0), m_abs @ (white * err)


@table(NAME, config=(SECTION,), resources={"runtime": 1}, chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Columns ``metal, r, g, b, r_err, g_err, b_err, dataset, citation``."""
    rows = []
    for metal, dataset in cfg[SECTION]["datasets"].items():
        rgb, err = f0_linear_srgb(metal, dataset)
        rows.append({"metal": metal, "r": rgb[0], "g": rgb[1], "b": rgb[2],
                     "r_err": err[0], "g_err": err[1], "b_err": err[2], "dataset": dataset,
                     "citation": optical_constants.citation(metal, dataset)})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path) -> None:
    shown = df[["metal", "r", "g", "b", "dataset"]].copy()
    for c in "rgb":
        shown[c] = [f"{v:.4f}" for v in df[c]]
    plotting.save_table_png(shown, path, "Linear-sRGB F0 (eq. 1.40; D65, CIE 1931 2°)")
