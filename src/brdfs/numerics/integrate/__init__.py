"""Integration engine: lobe-following hemisphere coordinates over the adaptive Gauss–Kronrod driver
(:mod:`brdfs.core.gauss_kronrod`)."""
from brdfs.core.estimate import Estimate
from brdfs.core.gauss_kronrod import integrate

__all__ = ["Estimate", "integrate"]
