"""my_model.py: a model written from the user guide's recipe ("Writing your own model").

The normalised Blinn–Phong lobe f = (n + 8)/(8π) (N·H)^n, with its own half-vector sampler.  Use it
from the command line with ``brdfs --import my_model.py albedo my_model --param n=20 --theta 0,60``.
"""
from dataclasses import dataclass

import numpy as np

from brdfs.physics import sampling
from brdfs.physics.geometry import n_dot_h
from brdfs.physics.lobes import HALF, PowerCosine
from brdfs.physics.models import BRDF, register
from brdfs.physics.models.base import log_range, non_negative, positive_power


@register
@dataclass(frozen=True)
class MyModel(BRDF):
    """Normalised Blinn–Phong, f = (n + 8)/(8π) (N·H)^n."""

    n: float = 20.0
    name = "my_model"
    param_ranges = {"n": non_negative()}                     # the constructor refuses n < 0
    test_ranges = {"n": log_range(1e-2, 1e4, zero=True)}     # where the generic tests draw n
    examples = {"typical": {"n": 20.0}, "narrowest": {"n": 1e4}}
    # conserves_energy = False: (n + 8)/(8π) only approximates the normalisation (a(0) = 1.061 at n = 20)
    strategies = ("half_vector", "cosine")                   # its own sampler first

    def _eval(self, L, V, nl, nv):
        return (self.n + 8) / (8 * np.pi) * positive_power(n_dot_h(L, V), self.n)

    @property
    def lobe(self):
        return PowerCosine(self.n, HALF)                      # the engine follows (N·H)^n

    def _sample_direction(self, L, u, strategy):
        return sampling.half_vector_sample(L, u, self.n)

    def _pdf(self, L, V, strategy):
        return sampling.half_vector_pdf(L, V, self.n)
