"""Direction proposals of the Monte Carlo renderer: the models' own samplers, in the local frame N = (0, 0, 1).

A proposal draws the unknown direction ``w`` of a BRDF given the known one ``k`` (the renderer
walks from the eye, so ``k`` is the viewing direction and ``w`` the light direction; every model
rendered is reciprocal, so a sampler of V given L serves for L given V) and states its
solid-angle density ``pdf(k, w)``. A material mixes proposals (one-sample mixture, i.e.
defensive importance sampling): weight = f(w, k) cos θ_w / Σ_j p_j pdf_j(k, w), which is an
unbiased estimator whatever the proposals, as long as their mixture covers the BRDF's support.

There is one kind of proposal, :class:`Proposal`: a model's strategy of
:meth:`~brdfs.physics.models.base.BRDF.sample_direction` / :meth:`~brdfs.physics.models.base.BRDF.pdf`
(its default, the first of its ``strategies``, unless told). The samplers themselves live with the
models (:mod:`brdfs.physics.sampling` holds the pieces they share); a sampler that rejects (a
direction below the horizon, a Russian-roulette miss) returns −N with pdf 0, which the material
weighs 0 — its sub-probability density is what the mixture's pdf sums, so the estimator stays
unbiased. The cosine strategy every model has (cos θ / π) is the mixture's defensive share.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: The strategy every model accepts: cos θ / π (the defensive share of a mixture).
COSINE = "cosine"


@dataclass(frozen=True)
class Proposal:
    """``model``'s sampler ``strategy``: directions from :meth:`sample` (``u`` (…, ≥ :attr:`dimension`))
    with density :meth:`pdf` per solid angle."""

    model: object
    strategy: str

    @classmethod
    def of(cls, model, strategy=None) -> "Proposal":
        """The model's ``strategy``, its default (the first of ``model.strategies``) if None."""
        return cls(model, model.strategies[0] if strategy is None else strategy)

    @property
    def dimension(self) -> int:
        """Uniform numbers one sample consumes."""
        return self.model.sample_dimension(self.strategy)

    @property
    def is_cosine(self) -> bool:
        return self.strategy == COSINE

    def sample(self, k, u):
        """Directions w given k from ``u`` (its first :attr:`dimension` numbers); −N where rejected."""
        return np.asarray(self.model.sample_direction(k, u[..., :self.dimension], self.strategy), float)

    def pdf(self, k, w):
        """Density of :meth:`sample`'s directions w given k (a sub-probability where it rejects)."""
        return np.asarray(self.model.pdf(k, w, self.strategy), float)
