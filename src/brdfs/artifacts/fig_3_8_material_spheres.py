"""Figure 3.8: the material editor — a diffuse gray reference sphere and golden spheres n = 2, 8, 16.

Rendered the way the thesis's material editor did it (section 3.6): direct light from two point
lights (delta emitters, each rendered alone: no light sampling, so no noise but the pixel jitter's)
plus the daylight term S·a(θ_V) (eq. 3.32) read from the tabulated albedo of each sphere's material
(gold: eq. 3.29 at the eight wavelengths, :func:`brdfs.numerics.albedo.albedo_table`; gray: ρ) at the
pixel's cos θ_V (the integrator's ``cos_v`` AOV). The display scale puts the gray sphere's median at
0.5 (section 3.6).
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd

from brdfs.artifacts import _render_figures as rf
from brdfs.numerics.albedo import albedo_table
from brdfs.physics import optical_constants
from brdfs.physics.models.metal import PhongCosminMetal
from brdfs.pipeline.registry import figure
from brdfs.render import spectrum

#: θ_V grid of the editor's albedo tables (interpolated linearly in cos θ_V) and their accuracy.
TABLE_COS = np.linspace(0.0, 1.0, 17)
TABLE_RTOL = 1e-4
TABLE_ATOL = 1e-12
#: Samples per pixel of the noise-free editor image (one per pass: they only antialias the edges).
EDITOR_SPP = 8

NAME = "fig_3_8_material_spheres"


def panels(cfg: dict) -> list:
    section = cfg[rf.SECTION]
    objects = [("gray", rf.sphere(-3.3, 0.0, 1.0), {"diffuse": section["diffuse_reflectance"]})]
    for k, n in enumerate(section["material_spheres"]["gold_n"]):
        objects.append((f"gold n={n:g}", rf.sphere(-1.1 + 2.2 * k, 0.0, 1.0),
                        {"metal": "gold", "model": "phong_cosmin", "n": n}))
    camera = {"eye": (0.0, -14.0, 1.0), "target": (0.0, 0.0, 1.0), "fov_deg": 13.0}   # the outer spheres clear of the edges
    return [rf.Panel("gray (Lambert) and gold n = " + ", ".join(f"{n:g}" for n in section["material_spheres"]["gold_n"]),
                     objects, rf.TWO_LIGHTS, camera, sky=False, background=0.08, reference=("gray",), aspect=3.0,
                     max_depth=1, point_lights=True, spp=EDITOR_SPP)]


def albedo_spectrum(spec: dict, cos_v: np.ndarray) -> np.ndarray:
    """a(θ_V) per wavelength (…, 8) of a material entry at ``cos_v``, from its table on TABLE_COS."""
    if "diffuse" in spec:
        return np.full(cos_v.shape + (rf.SPECTRAL,), float(spec["diffuse"]))
    theta = np.degrees(np.arccos(np.clip(TABLE_COS, 1e-6, 1.0)))
    eta = optical_constants.complex_index(spec["metal"], spectrum.WAVELENGTHS_NM)
    models = [PhongCosminMetal(float(spec["n"]), ior_re=float(e.real), ior_im=float(abs(e.imag))) for e in eta]
    table = albedo_table(models, theta, rtol=TABLE_RTOL, atol=TABLE_ATOL).value          # (8, len(TABLE_COS))
    return np.stack([np.interp(cos_v, TABLE_COS, row) for row in table], axis=-1)


def with_daylight(cfg: dict):
    """The ``post`` hook: add S·a(θ_V) to every pass (the same noise-free term in each)."""
    sky = float(cfg[rf.SECTION]["sky_radiance"])

    def post(panel, rendered):
        specs = {label: spec for label, _, spec in panel.objects}
        ambient = np.zeros(rendered.passes.shape[1:])
        # the spheres stand apart on the background (ID 0), so a pixel's ID is coverage × its
        # sphere's ID, and its averaged cos θ_V is coverage × the sphere's mean cos θ_V there
        sphere = np.ceil(rendered.ids)
        coverage = np.where(sphere > 0, rendered.ids / np.maximum(sphere, 1.0), 0.0)
        for k, label in rendered.labels.items():
            sel = (sphere == k) & (coverage > 0)
            if label in specs and sel.any():
                cos_v = rendered.cos_v[sel] / coverage[sel]
                ambient[sel] = sky * coverage[sel, None] * albedo_spectrum(specs[label], cos_v)
        return dataclasses.replace(rendered, passes=rendered.passes + ambient)

    return post


@figure(NAME, config=(rf.SECTION,), resources={"runtime": 2})
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    return rf.compute_panels(cfg, NAME, panels(cfg), post=with_daylight(cfg))


def plot(df: pd.DataFrame, path) -> None:
    rf.plot_panels(df, path, "Fig. 3.8: gray reference sphere and gold spheres (new model)")
