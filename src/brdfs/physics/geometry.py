"""Directions on the hemisphere: N = (0, 0, 1), incidence in the x–z plane (notation of §1.2.2)."""
from __future__ import annotations

import numpy as np


def cos_incidence(theta_deg):
    """cos θ computed as sin(90° − θ), exact to rounding even at 89.9995°."""
    return np.sin(np.radians(90.0 - np.asarray(theta_deg, float)))


def sin_incidence(theta_deg):
    return np.sin(np.radians(np.asarray(theta_deg, float)))


def light_direction(theta_deg):
    """L = (sin θ, 0, cos θ) for incidence angles θ in degrees, shape (..., 3)."""
    return np.stack([sin_incidence(theta_deg), np.zeros_like(np.asarray(theta_deg, float)),
                     cos_incidence(theta_deg)], axis=-1)


def direction(theta_deg, phi_deg=0.0):
    """Unit vector at polar angle θ and azimuth φ (degrees)."""
    theta_deg, phi_deg = np.broadcast_arrays(np.asarray(theta_deg, float), np.asarray(phi_deg, float))
    s = sin_incidence(theta_deg)
    phi = np.radians(phi_deg)
    return np.stack([s * np.cos(phi), s * np.sin(phi), cos_incidence(theta_deg)], axis=-1)


def dot(a, b):
    return np.sum(a * b, axis=-1)


def mirror(L):
    """R = 2 (N·L) N − L  (eq. 3.8)."""
    R = -np.asarray(L, float).copy()
    R[..., 2] = L[..., 2]
    return R


def r_dot_v(L, V):
    """R·V = 2 (N·L)(N·V) − L·V  (eq. 3.9), without forming R."""
    return 2.0 * L[..., 2] * V[..., 2] - dot(L, V)


def half_vector(L, V):
    """H = (L + V)/|L + V|."""
    h = L + V
    return h / np.linalg.norm(h, axis=-1, keepdims=True)


def n_dot_h(L, V):
    """N·H = (N·L + N·V)/|L + V|  (§1.2.2)."""
    h = L + V
    return h[..., 2] / np.linalg.norm(h, axis=-1)
