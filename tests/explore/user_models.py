"""A user's own models for the explorer's tests, registered by ``brdfs explore --import`` (in the
server's process only: the test process's MODELS stays the package's)."""
import time
from dataclasses import dataclass

import numpy as np

from brdfs.core.estimate import Estimate
from brdfs.physics.lobes import HALF, PowerCosine
from brdfs.physics.models import BRDF, register
from brdfs.physics.models.base import Interval


@register
@dataclass(frozen=True)
class ExploreLambert(BRDF):
    """Lambert, f = rho / pi: albedo rho at every angle."""

    rho: float = 0.8
    name = "explore_lambert"
    param_ranges = {"rho": Interval(0.0, 1.0)}
    examples = {"typical": {"rho": 0.8}}

    def _eval(self, L, V, nl, nv):
        return np.full(np.broadcast_shapes(nl.shape, nv.shape), self.rho / np.pi)

    @property
    def lobe(self):
        return PowerCosine(0.0, HALF)


@register
@dataclass(frozen=True)
class ExploreFailing(ExploreLambert):
    """A model that fails on purpose where k > 5 (its evaluation raises)."""

    k: float = 1.0
    name = "explore_failing"
    param_ranges = {"rho": Interval(0.0, 1.0), "k": Interval(0.0, 10.0)}

    def _eval(self, L, V, nl, nv):
        if self.k > 5:
            raise ArithmeticError(f"k = {self.k:g} > 5 breaks this model on purpose")
        return super()._eval(L, V, nl, nv)


@register
@dataclass(frozen=True)
class ExploreSlow(ExploreLambert):
    """Lambert whose albedo takes `seconds` of waiting (no CPU): a slow model for the page's tests."""

    seconds: float = 1.0
    name = "explore_slow"
    param_ranges = {"rho": Interval(0.0, 1.0), "seconds": Interval(0.0, 5.0)}

    def albedo_estimate(self, theta_deg, rtol, atol):
        time.sleep(self.seconds)
        value = np.full(np.shape(theta_deg), self.rho)
        return Estimate(value, np.zeros_like(value))


@register
@dataclass(frozen=True)
class ExploreCoarse(ExploreLambert):
    """Lambert as if evaluated from a coarse table (relative error 1e-3): its albedo cannot meet rtol 1e-6."""

    name = "explore_coarse"
    evaluation_rtol = 1e-3
