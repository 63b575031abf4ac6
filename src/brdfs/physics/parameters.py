"""Checks of model parameters, shared by the models and the pieces they are built from
(microfacet distributions): a module of its own, below both, so that importing
:mod:`brdfs.physics.distributions` alone does not go through the models package."""
from __future__ import annotations

import numpy as np


def check_positive(name, value, allow_zero=False):
    """Reject bad parameters with a message that names them."""
    value = float(value)
    if not np.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        raise ValueError(f"{name} must be {'non-negative' if allow_zero else 'positive'}, got {value!r}")
    return value
