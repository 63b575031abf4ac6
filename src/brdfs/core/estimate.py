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
#: ``status`` of an element whose integral diverges (the model declares it, e.g. Ward at θ = 90°):
#: ``value`` is +inf and ``error`` 0, an exact answer rather than a failure.
DIVERGED = "diverged"
#: Every status, in order from the best answer to the worst.
STATUSES = (CONVERGED, DIVERGED, BUDGET_EXHAUSTED, STALLED)


@dataclass(frozen=True)
class Estimate:
    """A computed value with its absolute error estimate (arrays of equal shape).

    ``evaluations`` (how many integrand or BRDF values it cost), ``status`` (per value:
    :data:`CONVERGED`, :data:`DIVERGED`, :data:`BUDGET_EXHAUSTED`, :data:`STALLED`) and ``route``
    (per value: which method and route produced it, e.g. ``"engine/azimuthal"``, ``"disk"``; see
    :mod:`brdfs.numerics.albedo`) are filled where the method producing it knows them.  Unpacking
    gives ``(value, error)``; indexing indexes ``value``, ``error``, ``status`` and ``route`` alike.

    >>> e = Estimate([1.0, 2.0], [1e-12, 2e-12], 42, ["converged", "stalled"], ["engine/azimuthal", "disk"])
    >>> value, error = e
    >>> str(e[1].status), str(e[1].route)
    ('stalled', 'disk')
    """

    value: np.ndarray
    error: np.ndarray
    evaluations: int | None = None
    status: np.ndarray | None = None
    route: np.ndarray | None = None

    def __iter__(self):
        return iter((self.value, self.error))

    def __getitem__(self, idx):
        status = None if self.status is None else np.asarray(self.status)[idx]
        route = None if self.route is None else np.asarray(self.route)[idx]
        return Estimate(np.asarray(self.value)[idx], np.asarray(self.error)[idx], self.evaluations, status, route)

    @property
    def converged(self) -> np.ndarray:
        """Per value: whether the error met the tolerance asked for (``status == "converged"``);
        all True where no status is known."""
        if self.status is None:
            return np.ones(np.shape(self.value), bool)
        return np.asarray(self.status) == CONVERGED
