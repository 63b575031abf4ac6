"""brdfs — recomputing Neumann (2001), *Constructions of Bidirectional Reflection Distribution Functions*.

Public API: :func:`albedo`, :func:`albedo_table`, :func:`model`, :data:`MODELS`, :class:`Estimate`.
"""
from brdfs.numerics.albedo import albedo, albedo_table
from brdfs.numerics.integrate import Estimate
from brdfs.physics.models import MODELS, model

__all__ = ["albedo", "albedo_table", "model", "MODELS", "Estimate"]
