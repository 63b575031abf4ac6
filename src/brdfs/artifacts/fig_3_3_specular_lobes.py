"""Figure 3.3: specular lobes at 42° incidence, in the plane of incidence, of Phong (n = 20), the new
model (eq. 3.10, n = 20), Cook–Torrance (m = 0.1, "n = 5") and He–Torrance (σ0 = 0.1, τ = 1.4,
n = 0.8 + 6i) (Sec. 3.2.4).

Choices the thesis leaves open (config section ``he_torrance.fig_3_3``): the calibration ("calibrated
to provide similar response for perpendicular illumination", constants not given), the plotted
quantity, the wavelength of He–Torrance, and the reading of Cook–Torrance's "n = 5" as its refractive
index, with the unpolarised Fresnel factor F(L·H) of eqs. 1.41–1.43 multiplying eq. 2.9.
He–Torrance's specular term is a delta at the mirror direction: it has no lobe, only its albedo ρ_s,
given in the CSV (quantity ``specular_albedo``) and marked in the figure.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure
from brdfs.physics.geometry import direction, light_direction
from brdfs.physics.models import model
from brdfs.physics.models.he_torrance import EVAL_RTOL
from brdfs.physics.models.microfacet import CookTorranceFresnel

PARAM_COLUMNS = ("n", "m", "G", "sigma0_um", "tau_um", "lambda_um", "ior_re", "ior_im", "term")
NORMAL = np.array([0.0, 0.0, 1.0])


def lobe_models(fig_cfg: dict, lambda_um: float) -> list[tuple[str, dict, object]]:
    """(name, parameter columns, BRDF callable) of the four models of the caption."""
    ct, ht = fig_cfg["cook_torrance"], fig_cfg["he_torrance"]
    he = model("he_torrance", **ht, lambda_um=lambda_um, term="dd")
    return [
        ("phong", {"n": fig_cfg["phong"]["n"]}, model("phong", n=fig_cfg["phong"]["n"])),
        ("phong_cosmin", {"n": fig_cfg["phong_cosmin"]["n"]}, model("phong_cosmin", n=fig_cfg["phong_cosmin"]["n"])),
        ("cook_torrance", dict(ct), CookTorranceFresnel(m=ct["m"], G=ct["G"], ior_re=ct["ior_re"], ior_im=ct["ior_im"])),
        ("he_torrance", dict(ht, lambda_um=lambda_um, term="dd"), he),
    ]


def evaluation_error(brdf, L, V, value):
    """Absolute error of a closed-form BRDF value: :data:`EVAL_RTOL` of it, plus the model's own
    truncation error (He–Torrance's series tail; zero for a closed form)."""
    return EVAL_RTOL * np.abs(value) + brdf.truncation_error(L, V)


@figure("fig_3_3_specular_lobes", config=("he_torrance",))
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """The lobes in the plane of incidence (φ = 180° the mirror side, φ = 0° the side of the light).

    Returns
    -------
    pandas.DataFrame
        Columns ``model`` and the parameter columns, ``calibration, scale, scale_err, quantity,
        theta_deg, theta_v_deg, phi_deg, brdf, brdf_err, value, value_err`` where ``value`` is the
        plotted, calibrated quantity; He–Torrance's delta is one row with ``quantity = specular_albedo``.
    """
    fig_cfg = cfg["he_torrance"]["fig_3_3"]
    theta = fig_cfg["theta_deg"]
    step = fig_cfg["theta_v_step_deg"]
    theta_v = np.linspace(0.0, 90.0, int(round(90.0 / step)) + 1)[:-1]       # the horizon itself excluded
    L = light_direction(theta)
    models = lobe_models(fig_cfg, cfg["he_torrance"]["lambda_um"])
    reference = float(models[0][2](NORMAL, NORMAL))
    frames = []
    for name, params, brdf in models:
        scale, scale_err = calibration(fig_cfg["calibration"], brdf, reference)
        for phi in (0.0, 180.0):
            V = direction(theta_v, phi)
            f = brdf(L, V)
            f_err = evaluation_error(brdf, L, V, f)
            weight = np.cos(np.radians(theta_v)) if fig_cfg["quantity"] == "intensity" else 1.0
            value = scale * f * weight
            value_err = scale * weight * f_err + scale_err * np.abs(f * weight) + EVAL_RTOL * np.abs(value)
            frames.append(_rows(name, params, fig_cfg, scale, scale_err, theta, theta_v, phi, f, f_err,
                                value, value_err))
        rho = brdf.mirror_albedo(theta)        # He–Torrance's specular delta: an albedo, no lobe
        if rho is not None:
            frames.append(_rows(name, {**params, "term": "specular"}, fig_cfg, scale, scale_err, theta,
                                np.array([theta]), 180.0, np.nan, np.nan, scale * rho.value,
                                scale * rho.error + scale_err * rho.value, quantity="specular_albedo"))
    return pd.concat(frames, ignore_index=True)


def calibration(kind: str, brdf, reference: float) -> tuple[float, float]:
    """Scale making f(N, N) equal to Phong's (``mirror_brdf_at_normal``), or 1 (``none``); with its error."""
    if kind == "none":
        return 1.0, 0.0
    own = float(brdf(NORMAL, NORMAL))
    scale = reference / own
    return scale, 3 * EVAL_RTOL * scale


def _rows(name, params, fig_cfg, scale, scale_err, theta, theta_v, phi, f, f_err, value, value_err,
          quantity=None):
    columns = {c: params.get(c, "") for c in PARAM_COLUMNS}
    return pd.DataFrame({
        "model": name, **columns, "calibration": fig_cfg["calibration"], "scale": scale, "scale_err": scale_err,
        "quantity": quantity or fig_cfg["quantity"], "theta_deg": theta, "theta_v_deg": theta_v, "phi_deg": phi,
        "brdf": f, "brdf_err": f_err, "value": value, "value_err": value_err})


def plot(df: pd.DataFrame, path) -> None:
    """Polar lobes: the normal up, the mirror side (φ = 180°) to the right, the light to the left."""
    fig = plotting.plt.figure(figsize=(7.5, 5.2))
    ax = fig.add_subplot(projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    lobes = df[df["quantity"] != "specular_albedo"]
    for name, g in lobes.groupby("model", sort=False):
        signed = np.where(g["phi_deg"] == 180.0, 1.0, -1.0) * g["theta_v_deg"]
        order = np.argsort(signed.to_numpy())
        ax.plot(np.radians(signed.to_numpy()[order]), g["value"].to_numpy()[order], label=name)
    theta = df["theta_deg"].iloc[0]
    top = lobes["value"].max()
    ax.annotate("", xy=(np.radians(-theta), 0.0), xytext=(np.radians(-theta), 0.9 * top),
                arrowprops={"arrowstyle": "->", "color": "0.4"})
    delta = df[df["quantity"] == "specular_albedo"].iloc[0]
    ax.plot([np.radians(theta)] * 2, [0, top], color="0.3", ls="--", lw=0.8,
            label=f"He–Torrance specular delta (albedo ρ_s = {delta['value']:.4f}, scaled)")
    ax.set_title(f"Figure 3.3: specular lobes at θ_L = {theta:g}° ({lobes['quantity'].iloc[0]})", fontsize=10)
    ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(-0.1, -0.15))
    plotting.savefig(fig, path)
