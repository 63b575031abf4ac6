"""Elements of a vectorised integration that share one model object are evaluated together: one
call of the model (or of its kernel) per distinct object and round, on all of its elements."""
from __future__ import annotations

import numpy as np


def indices_by_model(models) -> list[list[int]]:
    """The element indices of each distinct model object, in order of first appearance."""
    groups: dict[int, list[int]] = {}
    for i, m in enumerate(models):
        groups.setdefault(id(m), []).append(i)
    return list(groups.values())


def first_of_model(models) -> np.ndarray:
    """For every element, the index of the first element with the same model object."""
    first = np.empty(len(models), int)
    for members in indices_by_model(models):
        first[members] = members[0]
    return first
