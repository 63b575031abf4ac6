"""Integration engine: vectorised adaptive Gauss–Kronrod and lobe-following hemisphere coordinates."""
from brdfs.numerics.integrate.gauss_kronrod import Estimate, integrate

__all__ = ["Estimate", "integrate"]
