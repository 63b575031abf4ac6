"""Chi-square goodness-of-fit tests of the models' samplers (``BRDF.sample`` against ``BRDF.pdf``).

As Mitsuba 3 (``mitsuba.chi2.ChiSquareTest``) and pbrt-v4 (``src/pbrt/bsdfs_test.cpp``) run them:
many samples are histogrammed on a grid of cells; the expected count of a cell is N times the
integral of the pdf over the cell (adaptive Gauss–Kronrod, :func:`brdfs.numerics.integrate.integrate`,
nested: azimuth inside, polar outside — not a point value); cells expecting fewer than 5 samples
are pooled; the statistic Σ (observed − expected)²/expected has (cells − 1) degrees of freedom.

Differences from those harnesses, and why:

* The grid follows the lobe.  A global (cos θ, φ) grid puts a lobe of n = 512 or m = 0.005 into one
  or two cells and tests nothing, so the cells are polar about the lobe: a *sphere chart* — polar
  angle α about an axis A (the mean sampled direction of an independent pilot run) and azimuth φ
  about A — or, for the patch models whose sampler draws points of the base plane (chapter 4), a
  *disk chart* — polar radius r and azimuth about the patch centre V'_P = −L_P on the unit disk
  (the model declares which: ``sampling_domain``).
  The radial and azimuthal edges are quantiles of the pilot's coordinates (roughly equal expected
  counts, also when the horizon cuts the lobe in half).  The horizon (the unit circle) is a closed-form level of φ at every radius and is
  passed to the inner integral as a breakpoint, as are the circles and the ellipse about V'_P where a
  model's density jumps (disk chart; the model declares them: ``disk_boundaries``).
* Samplers may reject (a sub-probability pdf, see :mod:`brdfs.physics.sampling`): the rejected
  samples form one more cell, expecting N (1 − ∫pdf), so the test also checks the pdf's mass.
* A sample in a cell whose pdf integral is zero fails the test outright (p = 0), as in Mitsuba.

Significance: a test passes when p ≥ 1 − (1 − α)^{1/T} (Šidák, T tests, α = 0.01).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from brdfs.core.gauss_kronrod import NodeValues, integrate
from brdfs.physics.geometry import light_direction

#: Cells expecting fewer samples are pooled (Mitsuba's and pbrt's ``min_exp_frequency``).
MIN_EXPECTED = 5.0
#: Breakpoints of the azimuth integral at π 2^{−k}, k = 2 … GRADING + 1, from φ = 0 and π.
GRADING = 20
SIGNIFICANCE = 0.01


def sidak_level(n_tests: int, significance: float = SIGNIFICANCE) -> float:
    """The per-test level 1 − (1 − α)^{1/T} that keeps the family-wise level at α."""
    return 1.0 - (1.0 - significance) ** (1.0 / max(int(n_tests), 1))


@dataclass(frozen=True)
class Chart:
    """Polar cells: ``radial_edges`` × ``phi_edges`` (both ascending; φ from 0 to 2π) about a centre.

    ``kind`` 'sphere': radius = angle α from the unit ``axis``; the frame's first axis points
    towards N.  ``kind`` 'disk': radius = distance on the base plane from ``centre`` (2-vector);
    the first axis points away from the origin.
    """

    kind: str
    axis: np.ndarray
    radial_edges: np.ndarray
    phi_edges: np.ndarray
    breaks: tuple = ()
    #: (b, ratio, major-axis angle [rad]) of an elliptic patch centred at the chart's centre (disk chart):
    #: its boundary enters the integrals as breakpoints.
    ellipse: tuple | None = None

    def ellipse_phi(self, radius):
        """Azimuths where the ellipse's boundary crosses the circle of ``radius`` (NaN where none)."""
        if self.ellipse is None:
            return []
        b, ratio, phi_u = self.ellipse
        e1, _ = self.frame()
        shift = phi_u - np.arctan2(e1[1], e1[0])
        with np.errstate(divide="ignore", invalid="ignore"):
            # r² (ratio² cos²ψ + sin²ψ) = b²  ⇔  cos²ψ = (b²/r² − 1)/(ratio² − 1)
            cos2 = (b * b / (radius * radius) - 1.0) / (ratio * ratio - 1.0)
        psi = np.where((cos2 >= 0) & (cos2 <= 1), np.arccos(np.sqrt(np.clip(cos2, 0, 1))), np.nan)
        return [np.mod(shift + sign * psi + k * np.pi, 2 * np.pi) for sign in (-1, 1) for k in (0, 1)]

    # --- coordinates ---------------------------------------------------------------------------
    def frame(self):
        if self.kind == "sphere":
            A = self.axis
            perp = np.array([0.0, 0.0, 1.0]) - A[2] * A
            norm = np.linalg.norm(perp)
            e1 = perp / norm if norm > 1e-12 else np.array([1.0, 0.0, 0.0]) - A[0] * A
            e1 = e1 / np.linalg.norm(e1)
            return e1, np.cross(A, e1)
        c = self.axis[:2]
        d = np.linalg.norm(c)
        e1 = c / d if d > 1e-12 else np.array([1.0, 0.0])
        return e1, np.array([-e1[1], e1[0]])

    def coordinates(self, V):
        """(radius, φ ∈ [0, 2π)) of directions V (…, 3)."""
        e1, e2 = self.frame()
        if self.kind == "sphere":
            radius = np.arctan2(np.linalg.norm(np.cross(V, self.axis), axis=-1), V @ self.axis)
            phi = np.arctan2(V @ e2, V @ e1)
        else:
            z = V[..., :2] - self.axis[:2]
            radius = np.hypot(z[..., 0], z[..., 1])
            phi = np.arctan2(z @ e2, z @ e1)
        return radius, np.mod(phi, 2.0 * np.pi)

    def directions(self, radius, phi):
        """Directions at (radius, φ) and the area element (sin α, or r / cos θ_V per unit of dω)."""
        e1, e2 = self.frame()
        if self.kind == "sphere":
            s, c = np.sin(radius), np.cos(radius)
            V = (s * np.cos(phi))[..., None] * e1 + (s * np.sin(phi))[..., None] * e2 + c[..., None] * self.axis
            return V, s
        xy = self.axis[:2] + (radius * np.cos(phi))[..., None] * e1 + (radius * np.sin(phi))[..., None] * e2
        nv2 = 1.0 - np.sum(xy * xy, axis=-1)
        nv = np.sqrt(np.maximum(nv2, 0.0))
        V = np.concatenate([xy, nv[..., None]], -1)
        with np.errstate(divide="ignore", invalid="ignore"):
            jac = np.where(nv > 0, radius / nv, 0.0)      # dω = dA / cos θ_V, dA = r dr dφ
        return V, jac

    def horizon_phi(self, radius):
        """φ_h(radius) ∈ [0, π]: the cell is above the horizon for |φ| < φ_h (sphere) or |φ| > π − … ;
        returned as the level where N·V = 0 (sphere) or |V_P| = 1 (disk), NaN if none."""
        if self.kind == "sphere":
            a = self.axis[2]
            b = np.sqrt(max(1.0 - a * a, 0.0))
            with np.errstate(divide="ignore", invalid="ignore"):
                cos_phi = -a * np.cos(radius) / (b * np.sin(radius))
        else:
            d = np.linalg.norm(self.axis[:2])
            with np.errstate(divide="ignore", invalid="ignore"):
                cos_phi = (1.0 - d * d - radius * radius) / (2.0 * d * radius)
        return np.where(np.abs(cos_phi) < 1.0, np.arccos(np.clip(cos_phi, -1.0, 1.0)), np.nan)


    def horizon_radius(self, phi):
        """The radius where the ray at azimuth φ crosses the horizon (NaN if it does not)."""
        phi = np.asarray(phi, float)
        if self.kind == "sphere":
            a = self.axis[2]
            b = np.sqrt(max(1.0 - a * a, 0.0))
            return np.arctan2(a, -b * np.cos(phi))
        d = np.linalg.norm(self.axis[:2])
        c = np.cos(phi)
        return -d * c + np.sqrt(np.maximum(d * d * c * c - d * d + 1.0, 0.0))


def _pilot_chart(model, L, strategy, kind, rng, n_pilot, n_radial, n_phi, breaks, ellipse=None):
    u = rng.random((n_pilot, model.sample_dimension(strategy)))
    V, _, _ = model.sample(L, u, strategy)
    V = V[V[:, 2] > 0]
    if kind == "sphere":
        mean = V.mean(axis=0) if V.size else np.array([0.0, 0.0, 1.0])
        axis = mean / np.linalg.norm(mean)
        top = np.pi
    else:
        axis = np.array([-L[0], -L[1], 0.0])
        top = 1.0 + np.hypot(L[0], L[1])
    chart = Chart(kind, axis, np.array([0.0, top]), np.array([0.0, 2.0 * np.pi]), breaks, ellipse)
    radius, phi = chart.coordinates(V)
    inner = np.quantile(radius, np.arange(1, n_radial) / n_radial) if radius.size else np.array([])
    edges = np.unique(np.concatenate([[0.0], inner, [top]]))
    # Azimuth edges: quantiles of the pilot's φ (a lobe cut by the horizon fills half the circle, so
    # equal bins would leave half the cells empty); 0 and 2π stay edges.
    inner_phi = np.quantile(phi, np.arange(1, n_phi) / n_phi) if phi.size else np.array([])
    phi_edges = np.unique(np.concatenate([[0.0], inner_phi, [2.0 * np.pi]]))
    return Chart(kind, axis, edges, phi_edges, breaks, ellipse)


def cell_probabilities(model, L, strategy, chart, rtol=1e-7, atol=1e-11):
    """∫ pdf over every cell (radial × azimuth), nested adaptive Gauss–Kronrod; shape (n_r, n_phi)."""
    edges = chart.radial_edges
    phi_edges = chart.phi_edges
    n_r, n_phi = edges.size - 1, phi_edges.size - 1
    r_lo = np.repeat(edges[:-1], n_phi)
    r_hi = np.repeat(edges[1:], n_phi)
    p_lo = np.tile(phi_edges[:-1], n_r)
    p_hi = np.tile(phi_edges[1:], n_r)
    # The horizon enters a cell through its azimuth edges and, where φ = 0 or π lies inside, at its
    # nearest and farthest radii: those radii split the radial integral (a sliver of a cell above
    # the horizon would otherwise fall between the Kronrod nodes).
    crossings = [chart.horizon_radius(p_lo), chart.horizon_radius(p_hi),
                 np.where((p_lo <= np.pi) & (np.pi <= p_hi), chart.horizon_radius(np.pi), np.nan),
                 np.where(p_lo == 0.0, chart.horizon_radius(0.0), np.nan)]
    radial_bp = [r_lo, *[np.where((r_lo < b) & (b < r_hi), b, np.nan)
                         for b in (*chart.breaks, *crossings)], r_hi]

    def outer(radius, cell):
        m = radius.shape
        rad, cells = radius.ravel(), np.repeat(cell, radius.shape[1])
        h = chart.horizon_phi(rad)
        lo, hi = p_lo[cells], p_hi[cells]
        # Lobes are symmetric about the plane of N and the axis (φ = 0, π), and at grazing incidence
        # squeezed onto it (a Beckmann lobe of m = 0.005 at 89.99° is 1e-6 rad wide across it):
        # breakpoints graded geometrically towards φ = 0, π, 2π let the Kronrod nodes find it.
        graded = [p0 + sign * np.pi * 0.5 ** k for p0 in (0.0, np.pi, 2.0 * np.pi) for sign in (-1.0, 1.0)
                  for k in range(2, 2 + GRADING)]
        cuts = [np.where((lo < c) & (c < hi), c, np.nan)
                for c in (h, 2.0 * np.pi - h, *graded, *chart.ellipse_phi(rad))]
        bp = np.sort(np.stack([lo, *cuts, hi], 1), axis=1)

        def inner(phi, elem):
            V, jac = chart.directions(np.broadcast_to(rad[elem][:, None], phi.shape), phi)
            return model.pdf(L, V, strategy) * jac

        est = integrate(inner, bp, rtol=rtol, atol=atol * 1e-2)
        return NodeValues(est.value.reshape(m), est.value.reshape(m), est.error.reshape(m))

    bp = np.sort(np.stack(radial_bp, 1), axis=1)
    est = integrate(outer, bp, rtol=rtol, atol=atol)
    return est.value.reshape(n_r, n_phi), est.error.reshape(n_r, n_phi)


def pooled_statistic(observed, expected, min_expected=MIN_EXPECTED):
    """Σ (O − E)²/E after pooling the cells expecting fewer than ``min_expected`` (smallest first,
    until the pool expects at least ``min_expected``); returns (statistic, dof, zero_pdf_hits)."""
    observed, expected = np.ravel(observed).astype(float), np.ravel(expected).astype(float)
    zero_hits = int(observed[expected <= 0].sum())
    order = np.argsort(expected)
    e, o = expected[order], observed[order]
    small = np.cumsum(e) < min_expected
    small |= e < min_expected
    k = int(small.sum())
    if k < e.size and e[:k].sum() < min_expected and k > 0:
        k += 1                                             # the pool absorbs the next cell
    cells_e = np.concatenate([[e[:k].sum()] if k else [], e[k:]])
    cells_o = np.concatenate([[o[:k].sum()] if k else [], o[k:]])
    keep = cells_e > 0
    stat = float(np.sum((cells_o[keep] - cells_e[keep]) ** 2 / cells_e[keep]))
    return stat, int(keep.sum()) - 1, zero_hits


@dataclass(frozen=True)
class Chi2Result:
    statistic: float
    dof: int
    p_value: float
    pdf_mass: float
    accepted_fraction: float
    weight_error: float
    n_samples: int


def chi2_test(model, theta_deg, strategy=None, n_samples=100_000, seed=0, n_radial=10, n_phi=10,
              n_pilot=20_000, kind=None, rtol=1e-6):
    """Run one chi-square test of ``model.sample(·, strategy)`` at incidence ``theta_deg``.

    The chart is the model's :attr:`~brdfs.physics.models.base.BRDF.sampling_domain` unless ``kind``
    is given; on the disk chart the integrals split at the model's
    :meth:`~brdfs.physics.models.base.BRDF.disk_boundaries`.

    Returns
    -------
    Chi2Result
        The statistic, its degrees of freedom and p-value, the pdf's mass ∫pdf dω (1 for a sampler
        that never rejects), the fraction of accepted samples, and the largest relative deviation of
        the returned weights from f cos θ_V / pdf and of the returned pdf from ``model.pdf``.
    """
    L = light_direction(theta_deg)
    rng_pilot, rng = (np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(2))
    kind = kind or model.sampling_domain
    # the circles and the ellipse about V'_P where the density jumps (the patch models declare them)
    breaks, ellipse = model.disk_boundaries() if kind == "disk" else ((), None)
    chart = _pilot_chart(model, L, strategy, kind, rng_pilot, n_pilot, n_radial, n_phi, breaks, ellipse)
    probs, _ = cell_probabilities(model, L, strategy, chart, rtol=rtol)

    u = rng.random((n_samples, model.sample_dimension(strategy)))
    V, weight, pdf = model.sample(L, u, strategy)
    accepted = V[:, 2] > 0
    radius, phi = chart.coordinates(V[accepted])
    i = np.clip(np.searchsorted(chart.radial_edges, radius, side="right") - 1, 0, probs.shape[0] - 1)
    j = np.clip(np.searchsorted(chart.phi_edges, phi, side="right") - 1, 0, probs.shape[1] - 1)
    observed = np.zeros(probs.shape)
    np.add.at(observed, (i, j), 1.0)
    mass = float(probs.sum())
    observed_all = np.concatenate([observed.ravel(), [n_samples - accepted.sum()]])
    expected_all = np.concatenate([probs.ravel() * n_samples, [max(1.0 - mass, 0.0) * n_samples]])
    stat, dof, zero_hits = pooled_statistic(observed_all, expected_all)
    p_value = 0.0 if zero_hits else float(chi2_distribution.sf(stat, dof))
    return Chi2Result(stat, dof, p_value, mass, float(accepted.mean()),
                      _weight_error(model, L, V, weight, pdf, strategy), n_samples)


def _weight_error(model, L, V, weight, pdf, strategy):
    """max |w − f cos θ_V / pdf| / (f cos θ_V / pdf) and max |pdf − model.pdf| / pdf over samples with pdf > 0."""
    ok = pdf > 0
    if not ok.any():
        return 0.0
    Vk = V[ok]
    again = model.pdf(L, Vk, strategy)
    expected = model(L, Vk) * Vk[:, 2] / again
    scale = np.maximum(np.abs(expected), np.finfo(float).tiny)
    return float(max(np.max(np.abs(weight[ok] - expected) / scale), np.max(np.abs(pdf[ok] - again) / again)))
