"""The value type every computation of the package returns: a value with its error estimate.

The bottom layer of the package: :mod:`brdfs.physics` (closed forms, the patch models' own
integrals) and :mod:`brdfs.numerics` (every albedo method) both return an :class:`Estimate`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: ``status`` of an element that met its tolerance.
CONVERGED = "converged"
#: ``status`` of an element left short of its tolerance when ``max_rounds`` or ``max_intervals`` ran out.
BUDGET_EXHAUSTED = "budget_exhausted"
#: ``status`` of an element short of its tolerance whose remaining error no split could reduce.
STALLED = "stalled"


@dataclass(frozen=True)
class Estimate:
    """A computed value with its absolute error estimate (arrays of equal shape).

    ``evaluations`` (how many integrand or BRDF values it cost) and ``status`` (per value:
    :data:`CONVERGED`, :data:`BUDGET_EXHAUSTED`, :data:`STALLED`) are filled where the method
    producing it knows them.  Unpacking gives ``(value, error)``.
    """

    value: np.ndarray
    error: np.ndarray
    evaluations: int | None = None
    status: np.ndarray | None = None

    def __iter__(self):
        return iter((self.value, self.error))

    def __getitem__(self, idx):
        status = None if self.status is None else np.asarray(self.status)[idx]
        return Estimate(np.asarray(self.value)[idx], np.asarray(self.error)[idx], self.evaluations, status)
