"""White-furnace comparison (F = 1): the thesis's remedies against today's microfacet practice, with the
random walk on the Smith microsurface as the physical reference.

Panel 1 (``quantity = albedo``): a(θ) of GGX and Beckmann single scattering (height-correlated G2) at the
roughness matched to the thesis's lobes (Phong n ↔ α = √(2/(4n + 2)), Blinn n ↔ α = √(2/(n + 2)),
:mod:`brdfs.artifacts._microfacet_energy`), the same with Kulla–Conty compensation, the random walk
(variant ``walk``: all bounces; ``walk_single``: its first bounce, an independent estimate of E), the
thesis's Phong and Blinn (n of the pumping tables) unpumped and pumped once and twice (g1, eq. 2.20, and
g2, eq. 2.21, from the deps' albedo tables) and the new model (phong_cosmin with c = (n+2)/2π;
blinn_cosmin with C = 1/max a, Table 3.1's constant, computed).

Panel 2 (``quantity = loss``): 1 − a against α at ``sweep_theta_deg`` for the models that cost one engine
call per point (microfacet single scattering, phong_cosmin, Phong), and at the α of panel 1 for the
compensated, pumped and Blinn models.

``quantity = max_albedo``: the new model's largest albedo on the θ grid per α of the sweep (above 1 where it
creates energy).  ``quantity = max_deviation_from_walk``: max over the walk's angles of |a − a_walk| per remedy (θ of the
maximum in ``theta_deg``); ``max_deviation_from_one``: max over the whole θ grid of |a − 1|, the walk's
value for F = 1 (no path lost, all energy leaves).  ``quantity = gold_albedo``: with a gold conductor (Fresnel from n, k) the walk,
the compensated model (Kulla–Conty's F_ms) and single scattering, a measured comparison.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from brdfs.artifacts import _microfacet_energy as mf
from brdfs.numerics.albedo import albedo
from brdfs.physics.geometry import cos_incidence
from brdfs.physics.models import MODELS, model
from brdfs.pipeline import plotting
from brdfs.pipeline.registry import figure

DEPS = (*mf.PUMPING_TABLES.values(), mf.ENERGY_TABLE)
#: The walk the thesis's models (which have no walk of their own) are compared with.
REFERENCE_WALK = "ggx"


def _theta_grid(c):
    step = float(c["theta_step_deg"])
    return np.unique(np.concatenate([np.arange(0.0, 90.0, step), [89.0, 90.0]]))


def _engine_rows(family, brdf, variant, theta, rtol, **columns):
    est = albedo(brdf, theta, rtol=rtol)
    extra = brdf.table_error() if hasattr(brdf, "table_error") else 0.0
    return mf.rows(family=family, variant=variant, quantity="albedo", theta_deg=theta,
                   value=est.value, value_err=est.error + extra, **columns)


def _thesis_rows(family, deps, theta, c, rtol):
    """Albedo of the thesis's model, pumped 0..levels times (tables), and of its new-model variant (engine)."""
    frames = []
    x = cos_incidence(theta)
    for correction in ("g1", "g2"):
        levels, n = mf.pumped_family(family, deps[mf.PUMPING_TABLES[family]], correction, c["pumping_levels"])
        for level, _, table in levels:
            if level == 0 and correction == "g2":
                continue
            a = table(x)
            frames.append(mf.rows(family=family, model=family, variant="pumped" if level else "original",
                                  pumping=correction if level else "none", level=level, n=n,
                                  alpha=mf.alpha_of_n(family, n), quantity="albedo", theta_deg=theta,
                                  value=a, value_err=table.error + a * table.model_rtol))
    new = mf.new_model(family, n)
    frames.append(_engine_rows(family, new, "new_model", theta, rtol, model=new.name, n=n,
                               alpha=mf.alpha_of_n(family, n)))
    return frames, n


def _microfacet_rows(family, alpha, theta, walk_theta, c, seed, family_index):
    frames = []
    for k, name in enumerate(("ggx", "beckmann")):
        for compensation in ("none", "kulla_conty"):
            brdf = mf.microfacet(name, alpha, compensation)
            variant = "single_scattering" if compensation == "none" else "kulla_conty"
            frames.append(_engine_rows(family, brdf, variant, theta, c["rtol"], model=name, alpha=alpha,
                                       G2="height_correlated"))
        for j, t in enumerate(walk_theta):
            w = mf.walk(name, alpha, t, c, seed, (1, family_index, k, j))
            for variant, orders in (("walk", None), ("walk_single", (1,))):
                value, err = w.albedo(orders)
                frames.append(mf.rows(family=family, model=name, variant=variant, alpha=alpha,
                                      G2="height_correlated", quantity="albedo", theta_deg=t,
                                      value=value, value_err=err))
    return frames


def _sweep_rows(family, first, c):
    """1 − a against α at the sweep angles (new model, original model; microfacet single scattering once,
    in the rows of the ``first`` family).  Only a family whose new model has a closed-form constant is
    swept (Phong's; blinn_cosmin's C_n needs a maximisation per n: panel 1 only)."""
    theta = np.asarray(c["sweep_theta_deg"], float)
    new_name = MODELS[family].corrected_by
    swept = not MODELS[new_name].constant_is_computed
    frames = []
    for alpha in c["sweep_alpha"]:
        n = float(mf.n_of_alpha(family, alpha))
        brdfs = [] if not first else [
            (name, mf.microfacet(name, alpha), "single_scattering", np.nan) for name in ("ggx", "beckmann")]
        if n > 0 and swept:
            brdfs += [(new_name, model(new_name, n=n), "new_model", n),
                      (family, model(family, n=n), "original", n)]
        for name, brdf, variant, n_col in brdfs:
            est = albedo(brdf, theta, rtol=c["rtol"])
            frames.append(mf.rows(family=family, model=name, variant=variant, n=n_col, alpha=alpha,
                                  G2="height_correlated" if variant == "single_scattering" else "",
                                  quantity="loss", theta_deg=theta, value=1.0 - est.value, value_err=est.error))
            if variant == "new_model":      # where it creates energy: the largest albedo on the θ grid
                grid = _theta_grid(c)
                full = albedo(brdf, grid, rtol=c["rtol"])
                k = int(np.argmax(full.value))
                frames.append(mf.rows(family=family, model=name, variant=variant, n=n_col, alpha=alpha,
                                      quantity="max_albedo", theta_deg=grid[k], value=full.value[k],
                                      value_err=full.error[k]))
    return frames


def _loss_at_tabulated(albedo_rows, theta):
    """1 − a of every curve of panel 1 at the sweep angles that lie on its grid."""
    picked = albedo_rows[albedo_rows["theta_deg"].isin(theta)].copy()
    picked["quantity"] = "loss"
    picked["value"] = 1.0 - picked["value"]
    return picked


def _deviation_from_one_rows(albedo_rows):
    """max_θ |a − 1| over the whole θ grid: the walk's value for F = 1 wherever it was run (every path
    leaves with all its energy, so a_walk = 1 with zero variance; ``walk`` rows and ``lost`` = 0)."""
    frames = []
    curves = albedo_rows[~albedo_rows["variant"].isin(["walk", "walk_single"])]
    for keys, g in curves.groupby(["family", "model", "variant", "pumping", "level"], dropna=False):
        dev = (g["value"] - 1.0).abs()
        row = g.loc[[dev.idxmax()]].copy()
        row["quantity"] = "max_deviation_from_one"
        row["value"] = float(dev.max())
        frames.append(row[mf.COLUMNS])
    return frames


def _deviation_rows(albedo_rows):
    """max_θ |a − a_walk| of every remedy against the walk of the same family and distribution
    (for the thesis's models: against the GGX walk; the Beckmann walk gives the same a = 1 for F = 1)."""
    frames = []
    for family, fam in albedo_rows.groupby("family"):
        walks = fam[fam["variant"] == "walk"]
        for keys, g in fam[~fam["variant"].isin(["walk", "walk_single"])].groupby(
                ["model", "variant", "pumping", "level"], dropna=False):
            name = keys[0]
            ref = walks[walks["model"] == (name if name in set(walks["model"]) else REFERENCE_WALK)]
            merged = g.merge(ref[["theta_deg", "value", "value_err"]], on="theta_deg", suffixes=("", "_walk"))
            if merged.empty:
                continue
            dev = (merged["value"] - merged["value_walk"]).abs()
            i = int(dev.to_numpy().argmax())
            row = merged.iloc[[i]].copy()
            row["quantity"] = "max_deviation_from_walk"
            row["value"] = dev.iloc[i]
            row["value_err"] = row["value_err"].to_numpy() + row["value_err_walk"].to_numpy()
            frames.append(row[mf.COLUMNS])
    return frames


def _gold_rows(alpha_by_family, c, seed):
    """Gold conductor: walk vs the compensated model (Kulla–Conty with F_ms) vs single scattering."""
    eta = mf.gold_index(c["gold"])
    theta = np.asarray(c["walk_theta_deg"], float)
    fresnel = mf.gold_fresnel(c["gold"])
    frames = []
    for f_index, (family, alpha) in enumerate(alpha_by_family.items()):
        for k, name in enumerate(("ggx", "beckmann")):
            for compensation in ("none", "kulla_conty"):
                brdf = mf.microfacet(name, alpha, compensation, ior_re=eta.real, ior_im=eta.imag)
                est = albedo(brdf, theta, rtol=c["rtol"])
                frames.append(mf.rows(family=family, model=name, alpha=alpha, G2="height_correlated",
                                      variant="single_scattering" if compensation == "none" else "kulla_conty",
                                      quantity="gold_albedo", theta_deg=theta, value=est.value,
                                      value_err=est.error + brdf.table_error()))
            for j, t in enumerate(theta):
                value, err = mf.walk(name, alpha, t, c, seed, (2, f_index, k, j), fresnel=fresnel).albedo()
                frames.append(mf.rows(family=family, model=name, alpha=alpha, G2="height_correlated",
                                      variant="walk", quantity="gold_albedo", theta_deg=t, value=value, value_err=err))
    return frames


@figure("extra_energy_compensation", deps=DEPS, config=("microfacet",), chapter=None)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Tidy rows ``family, model, variant, pumping, level, n, alpha, G2, quantity, theta_deg, value, value_err``."""
    c = cfg["microfacet"]
    mf.seed_energy_tables(deps[mf.ENERGY_TABLE])
    theta = _theta_grid(c)
    walk_theta = np.asarray(c["walk_theta_deg"], float)
    frames, alphas = [], {}
    for index, family in enumerate(("phong", "blinn")):
        thesis, n = _thesis_rows(family, deps, theta, c, c["rtol"])
        alphas[family] = float(mf.alpha_of_n(family, n))
        frames += thesis
        frames += _microfacet_rows(family, alphas[family], theta, walk_theta, c, cfg["seed"], index)
    albedo_rows = pd.concat(frames, ignore_index=True)
    out = [albedo_rows, _loss_at_tabulated(albedo_rows, c["sweep_theta_deg"])]
    for index, family in enumerate(("phong", "blinn")):
        out += _sweep_rows(family, index == 0, c)
    out += _deviation_rows(albedo_rows)
    out += _deviation_from_one_rows(albedo_rows)
    out += _gold_rows(alphas, c, cfg["seed"])
    return pd.concat(out, ignore_index=True)[mf.COLUMNS]


STYLES = {"single_scattering": "-", "kulla_conty": "--", "new_model": "-.", "original": ":", "pumped": "-"}
ANGLE_STYLES = {0.0: "-", 60.0: "--", 85.0: ":"}


def _label(r):
    if r.variant == "pumped":
        return f"{r.model} pumped {r.pumping} ×{int(r.level)}"
    if r.variant in ("new_model", "original"):
        return f"{r.model} ({r.variant.replace('_', ' ')}), n = {r.n:g}"
    return f"{r.model} α = {r.alpha:.3f} {r.variant.replace('_', ' ')}"


def plot(df: pd.DataFrame, path) -> None:
    """Left/middle: albedo against θ (Phong-matched, Blinn-matched); right: 1 − a against α."""
    fig, axes = plotting.plt.subplots(1, 3, figsize=(16, 6.2))
    fig.subplots_adjust(bottom=0.36, wspace=0.28)
    curves = df[df["quantity"] == "albedo"]
    for ax, family in zip(axes[:2], ("phong", "blinn")):
        fam = curves[curves["family"] == family]
        for keys, g in fam[~fam["variant"].isin(["walk", "walk_single"])].groupby(
                ["model", "variant", "pumping", "level"], sort=False, dropna=False):
            r = g.iloc[0]
            ax.plot(g["theta_deg"], g["value"], STYLES.get(r.variant, "-"), lw=1.0, label=_label(r))
        for name, marker in (("ggx", "o"), ("beckmann", "s")):
            for variant, fill in (("walk", "k"), ("walk_single", "none")):
                w = fam[(fam["variant"] == variant) & (fam["model"] == name)]
                ax.errorbar(w["theta_deg"], w["value"], yerr=w["value_err"], fmt=marker, ms=4, color="k",
                            mfc=fill, label=f"{name} random walk ({'all bounces' if variant == 'walk' else '1st bounce'})")
        ax.axhline(1.0, color="0.6", lw=0.6)
        ax.set(xlabel="incidence angle θ_L [deg]", ylabel="albedo a(θ_L), F = 1",
               title=f"{family}-matched roughness (α = {fam['alpha'].dropna().iloc[0]:.3f})")
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    ax = axes[2]
    loss = df[(df["quantity"] == "loss")]
    colours = {}
    for (name, variant, theta), g in loss.groupby(["model", "variant", "theta_deg"], sort=False):
        if variant in ("walk", "walk_single", "pumped", "kulla_conty") or len(g) < 2:
            continue
        g = g.sort_values("alpha")
        colour = colours.setdefault((name, variant), f"C{len(colours)}")
        ax.plot(g["alpha"], g["value"], ANGLE_STYLES.get(theta, "-"), color=colour, lw=1.0,
                label=f"{name} {variant.replace('_', ' ')}" if theta == 0.0 else None)
    for (name, variant, pump, level), g in loss[loss["variant"].isin(["pumped", "kulla_conty"])].groupby(
            ["model", "variant", "pumping", "level"], dropna=False):
        text = f"{name} pumped {pump} ×{int(level)}" if variant == "pumped" else f"{name} Kulla–Conty"
        ax.plot(g["alpha"], g["value"], "x" if variant == "pumped" else "+", ms=5, label=f"{text} (0°, 60°, 85°)")
    for theta, style in ANGLE_STYLES.items():
        ax.plot([], [], style, color="0.3", label=f"θ_L = {theta:g}°")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set(xlabel="roughness α (Phong n = (2/α² − 2)/4, Blinn n = 2/α² − 2)",
           ylabel="1 − a (energy lost > 0, created < 0)", title="energy lost or created", xscale="log")
    ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.suptitle("White furnace (F = 1): the thesis's remedies vs GGX/Beckmann + Kulla–Conty vs the Smith random walk",
                 fontsize=10)
    plotting.savefig(fig, path)
