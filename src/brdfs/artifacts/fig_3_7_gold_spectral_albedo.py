"""Figure 3.7: albedo of gold over incidence angle and wavelength, the new model for metals
(eq. 3.29, Fresnel reflectance at Θ_min) with measured optical constants.

The exponent n, the data set of gold's optical constants and the grids are choices of config
section ``gold_spectral`` (the thesis states none of them for this figure). The albedo integral
(eq. 1.13) of eq. 3.29 is computed by the package's engine for each wavelength: F(Θ_min) varies
with V, so it does not factor out of the integral. Beside the plot: the colour (D65, CIE 1931 2°,
sRGB) of the albedo spectra at normal and at grazing incidence, i.e. of a gold sphere's centre
and rim under uniform daylight (eq. 3.32). The CSV also holds gold's n, k and a0 at the
comparison wavelength for the chosen and the other data sets (the caption compares them with
Table 1.2).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.numerics.albedo import albedo_table
from brdfs.physics import optical_constants, spectral_colour
from brdfs.physics.fresnel import normal_incidence_reflectance
from brdfs.physics.models.metal import PhongCosminMetal
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

NAME = "fig_3_7_gold_spectral_albedo"
SECTION = "gold_spectral"
COLUMNS = ["quantity", "metal", "dataset", "n", "wavelength_nm", "theta_deg", "ior_re", "ior_im", "value", "value_err"]


def _grid(spec: dict) -> np.ndarray:
    start, stop, step = float(spec["start"]), float(spec["stop"]), float(spec["step"])
    return np.linspace(start, stop, int(round((stop - start) / step)) + 1)


def spectral_albedo(metal, dataset, n, wavelength_nm, theta_deg, rtol, atol):
    """a(θ, λ) of eq. 3.29: Estimate of shape (len(wavelength_nm), len(theta_deg)), and the indices."""
    eta = optical_constants.complex_index(metal, wavelength_nm, dataset)
    models = [PhongCosminMetal(n, ior_re=float(e.real), ior_im=float(e.imag)) for e in eta]
    return albedo_table(models, theta_deg, rtol=rtol, atol=atol), eta


def _colour_rows(metal, dataset, n, wl, theta, est):
    """Linear sRGB of the albedo spectra at the first and last angle, with an error bound.

    The map spectrum → XYZ has non-negative weights, so an error ≤ e at every wavelength moves
    XYZ by at most e · XYZ(white); the sRGB error is bounded through |M_XYZ→RGB|.
    """
    rows = []
    white_xyz = spectral_colour.reflectance_to_xyz(wl, np.ones(wl.size))
    m_abs = np.abs(spectral_colour.xyz_to_linear_srgb(np.eye(3)).T)  # columns = images of X, Y, Z
    for j in (0, theta.size - 1):
        rgb = spectral_colour.reflectance_to_linear_srgb(wl, est.value[:, j])
        err = m_abs @ (white_xyz * est.error[:, j].max())
        for channel, v, e in zip("rgb", rgb, err):
            rows.append({"quantity": f"albedo_linear_srgb_{channel}", "metal": metal, "dataset": dataset, "n": n,
                         "theta_deg": theta[j], "value": v, "value_err": e})
    return rows


@figure(NAME, config=(SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Rows ``quantity`` = ``albedo`` (per λ, θ), ``albedo_linear_srgb_{r,g,b}`` (θ = first/last),
    ``a0`` (eq. 1.40 at the comparison wavelength, per data set, with n, k)."""
    c = cfg[SECTION]
    metal, dataset, n = c["metal"], c["dataset"], float(c["n"])
    wl, theta = _grid(c["wavelength_nm"]), _grid(c["theta_deg"])
    est, eta = spectral_albedo(metal, dataset, n, wl, theta, c["rtol"], cfg["tolerance"]["atol"])
    W, T = np.meshgrid(wl, theta, indexing="ij")
    rows = pd.DataFrame({"quantity": "albedo", "metal": metal, "dataset": dataset, "n": n,
                         "wavelength_nm": W.ravel(), "theta_deg": T.ravel(),
                         "ior_re": np.repeat(eta.real, theta.size), "ior_im": np.repeat(eta.imag, theta.size),
                         "value": est.value.ravel(), "value_err": est.error.ravel()})
    colour_rows = pd.DataFrame(_colour_rows(metal, dataset, n, wl, theta, est))
    lam = float(c["compare_wavelength_nm"])
    compare = []
    for ds in [dataset, *[d for d in c["compare_datasets"] if d != dataset]]:
        e = complex(optical_constants.complex_index(metal, lam, ds))
        a0 = float(normal_incidence_reflectance(e.real, e.imag))
        compare.append({"quantity": "a0", "metal": metal, "dataset": ds, "wavelength_nm": lam, "theta_deg": 0.0,
                        "ior_re": e.real, "ior_im": e.imag, "value": a0, "value_err": 4 * np.finfo(float).eps * a0})
    return pd.concat([rows, colour_rows, pd.DataFrame(compare)], ignore_index=True)[COLUMNS]


def plot(df: pd.DataFrame, path) -> None:
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors

    a = df[df["quantity"] == "albedo"]
    fig = plt.figure(figsize=(7.6, 4.2))
    ax = fig.add_axes([0.08, 0.12, 0.58, 0.78])
    wl = np.sort(a["wavelength_nm"].unique())
    norm = colors.Normalize(wl[0], wl[-1])
    cmap = plt.get_cmap("turbo")
    for lam, g in a.groupby("wavelength_nm"):
        ax.plot(g["theta_deg"], g["value"], color=cmap(norm(lam)), lw=1.0)
    n = a["n"].iloc[0]
    ax.set(xlabel="incidence angle θ [deg]", ylabel="albedo a(θ, λ)", xlim=(0, 90),
           title=f"Fig. 3.7: albedo of gold, eq. 3.29 (n = {n:g}; {a['dataset'].iloc[0]})")
    bar = fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, pad=0.02)
    bar.set_label("wavelength λ [nm]")
    rgb = df[df["quantity"].str.startswith("albedo_linear_srgb_")]
    for i, (theta, g) in enumerate(rgb.groupby("theta_deg")):
        lin = g.set_index("quantity").loc[[f"albedo_linear_srgb_{c}" for c in "rgb"], "value"].to_numpy()
        sw = fig.add_axes([0.80, 0.55 - 0.4 * i, 0.13, 0.3])
        sw.imshow(spectral_colour.encode_srgb(lin).reshape(1, 1, 3), aspect="auto")
        sw.set_xticks([]), sw.set_yticks([])
        sw.set_title(f"θ = {theta:g}°\nlin. sRGB {lin[0]:.2f} {lin[1]:.2f} {lin[2]:.2f}", fontsize=7)
        sw.grid(False)
        for spine in sw.spines.values():
            spine.set_visible(True)
    fig.text(0.80, 0.03, "albedo colour,\nD65, CIE 1931 2°", fontsize=7)
    plotting.savefig(fig, path)
