"""Numerics: hemispherical integration, albedo and derived quantities, pumping, patch geometry."""
