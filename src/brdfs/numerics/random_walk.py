"""Random walk on the Smith microsurface (Heitz, Hanika, d'Eon, Dachsbacher 2016, "Multiple-scattering
microfacet BSDFs with the Smith model", ACM TOG 35(4); the walk of their reference implementation): the physical reference
for the energy a microfacet conductor reflects, all bounces included.

The microsurface is Smith's: microfacet normals distributed by D, heights independent of the normals
(uniform on [−1, 1]: the walk's result does not depend on the height distribution).  A ray at height h
travelling along w:

* **next height** — above the horizon (w·N > 0) it leaves with probability G1(w, h) = C1(h)^Λ(w), else
  it meets the surface at h' = C1⁻¹(C1(h) / (1 − U)^{1/Λ(w)}); below the horizon it always meets the
  surface, the same formula with Λ(w) = −1 − Λ(−w) (Heitz et al. 2016, the height sampling of the
  microsurface's free path);
* **scattering** — the microfacet normal H is drawn from the visible normals seen from −w
  (:meth:`~brdfs.physics.distributions.GGX.sample_visible_normal`), the ray reflected about it
  and its energy multiplied by F(−w·H).

Every path starts above the surface along −L.  A path still on the surface after ``max_order``
scatterings is counted as lost (its number is returned; with F ≤ 1 the energy lost that way is at
most that fraction).  The single-scattering part (order 1) of the albedo is, in expectation, the
albedo of f_ss with the height-correlated G2 (Heitz et al. 2016) — a test of both.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from brdfs.physics.geometry import light_direction


@dataclass(frozen=True)
class Walk:
    """Exit directions ``V`` (n, 3; NaN where lost), ``weight`` (energy, 0 where lost) and
    ``order`` (number of scatterings; 0 where lost) of ``n`` paths from incidence ``theta_deg``."""

    theta_deg: float
    V: np.ndarray
    weight: np.ndarray
    order: np.ndarray
    lost: int

    def albedo(self, orders=None):
        """(mean, standard error) of the energy leaving after the given numbers of scatterings
        (all by default; e.g. ``orders=(1,)`` for single scattering)."""
        w = self.weight if orders is None else np.where(np.isin(self.order, orders), self.weight, 0.0)
        return float(w.mean()), float(w.std(ddof=1) / np.sqrt(w.size))

    def plane_lobe(self, theta_v_edges_deg, phi_halfwidth_deg, orders=None):
        """f(L, V) cos θ_V in the plane of incidence, estimated by binning: per θ_V bin and side
        (φ = 180° mirror side, φ = 0° light side) the energy leaving per unit solid angle of the wedge
        |φ − φ_side| < ``phi_halfwidth_deg``.  Returns (θ_V centres, φ, value, standard error) as arrays."""
        V = self.V
        keep = self.order > 0 if orders is None else np.isin(self.order, orders)
        w = np.where(keep, self.weight, 0.0)
        theta_v = np.degrees(np.arccos(np.clip(np.nan_to_num(V[:, 2], nan=-1.0), -1.0, 1.0)))
        phi = np.degrees(np.arctan2(np.nan_to_num(V[:, 1]), np.nan_to_num(V[:, 0]))) % 360.0
        edges = np.asarray(theta_v_edges_deg, float)
        centres = 0.5 * (edges[1:] + edges[:-1])
        dphi = np.radians(2.0 * phi_halfwidth_deg)
        solid = dphi * (np.cos(np.radians(edges[:-1])) - np.cos(np.radians(edges[1:])))
        rows = []
        for side in (0.0, 180.0):
            distance = np.abs((phi - side + 180.0) % 360.0 - 180.0)
            in_wedge = distance < phi_halfwidth_deg
            bin_index = np.digitize(theta_v, edges) - 1
            for b in range(centres.size):
                x = np.where(in_wedge & (bin_index == b), w, 0.0) / solid[b]
                rows.append((centres[b], side, x.mean(), x.std(ddof=1) / np.sqrt(x.size)))
        return tuple(np.array(c) for c in zip(*rows))


def _c1(h):
    """Cumulative distribution of the uniform height on [−1, 1]."""
    return np.clip(0.5 * (h + 1.0), 0.0, 1.0)


def random_walk(distribution, theta_deg, n_paths, rng, fresnel=None, max_order=100):
    """Walk ``n_paths`` paths from incidence ``theta_deg`` on the Smith microsurface of ``distribution``
    (a :class:`~brdfs.physics.distributions.GGX` or :class:`~brdfs.physics.distributions.Beckmann`);
    ``fresnel(cos)`` multiplies the energy at every reflection (None: F = 1)."""
    L = light_direction(theta_deg)
    w = np.tile(-L, (n_paths, 1))
    h = np.full(n_paths, np.inf)
    energy = np.ones(n_paths)
    V = np.full((n_paths, 3), np.nan)
    weight = np.zeros(n_paths)
    order = np.zeros(n_paths, dtype=int)
    active = np.arange(n_paths)
    for scatterings in range(max_order + 1):
        if active.size == 0:
            break
        wa, ha = w[active], h[active]
        z = wa[:, 2]
        u = rng.random(active.size)
        lam = distribution.smith_lambda_signed(z)
        c1 = _c1(ha)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            leaves = (z > 0) & (u > 1.0 - c1 ** lam)
            new_h = np.where(np.isfinite(lam) & (lam != 0),
                             2.0 * c1 / (1.0 - u) ** (1.0 / lam) - 1.0, ha)
        out = active[leaves]
        V[out], weight[out], order[out] = wa[leaves], energy[out], scatterings
        stay = ~leaves
        if scatterings == max_order:
            break
        active, wa, ha = active[stay], wa[stay], np.clip(new_h[stay], -1.0, 1.0)
        wi = -wa
        H = distribution.sample_visible_normal(wi, rng.random(active.size), rng.random(active.size))
        cos_ih = np.sum(wi * H, axis=-1)
        if fresnel is not None:
            energy[active] *= fresnel(np.clip(cos_ih, 0.0, 1.0))
        w[active] = -wi + 2.0 * cos_ih[:, None] * H
        h[active] = ha
    lost = int(np.sum(order == 0))
    return Walk(float(theta_deg), V, weight, order, lost)
