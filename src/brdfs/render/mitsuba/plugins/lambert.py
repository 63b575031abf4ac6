"""Lambert's BRDF f = ρ/π as a Mitsuba plugin (``brdfs_lambert``), sampled by the cosine distribution
(every model's baseline strategy), which is exact for it (weight ρ).  Its sampler is the one the mutation ``UNIFORM_CLAIMS_COSINE`` of :mod:`._common` breaks.
"""
from __future__ import annotations

from brdfs.render.mitsuba.plugins._common import INV_PI, ModelBSDF, cosine_pdf, sample_cosine

import mitsuba as mi


class LambertBSDF(ModelBSDF):
    """f = ρ/π (``reflectance``: texture, default 1, the white-furnace material)."""

    name = "lambert"
    weight_name = "reflectance"
    lobe_flag = mi.BSDFFlags.DiffuseReflection

    def lobe_eval(self, L, V, active):
        return mi.Float(INV_PI)

    def own_pdf(self, L, V, active):
        return cosine_pdf(V)

    def own_sample(self, L, u, active):
        return sample_cosine(u)

    def describe(self):
        return {}
PLUGINS = {cls.name: cls for cls in (LambertBSDF,)}
