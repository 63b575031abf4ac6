"""Chi-square harness for the Mitsuba plugins: Mitsuba's own ``mi.chi2.ChiSquareTest`` through its
``mi.chi2.BSDFAdapter``, on a chart that resolves lobes of any width.

Mitsuba's ``SphericalDomain`` bins (φ, cos θ) about N uniformly: a lobe of width 0.01 rad (Phong
n = 10⁴, Ward m = 0.005) falls into one or two of its cells, and the test has no degrees of freedom.
:class:`LobeDomain` is polar about the lobe's axis A (the mirror direction of ``wi``, or N) with the
radial coordinate t = u / (u + s), u = (1 − cos a)/2 the cap's area fraction and s the lobe's scale in
u (≈ 1/(2n) for a cosine power, ≈ m² for a microfacet lobe): the lobe fills the middle of [0, 1/(1 + s)]
and the whole sphere is covered, so nothing lands outside.  The test integrates the density per unit
of the chart, so the pdf is multiplied by the Jacobian dω/(dφ dt) = 2 s/(1 − t)² (:func:`chart_pdf`).

R1b's patch-model tests reuse :func:`chi2_test` (a ``"disk"`` sampler is a direction sampler too).
The generic plugin ``brdfs_model`` (the package's numpy model) runs in Dr.Jit's wavefront mode only:
:func:`chi2_test` switches to it for that plugin and restores the flags afterwards
(:func:`brdfs.render.mitsuba.integrator.wavefront`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def incidence(theta_deg):
    """wi = (sin θ, 0, cos θ) in the local frame (the package's L of incidence θ)."""
    t = np.radians(theta_deg)
    return [float(np.sin(t)), 0.0, float(np.cos(t))]


@dataclass(frozen=True)
class LobeDomain:
    """(φ, t) ∈ [−π, π] × [0, 1/(1 + s)] ↔ directions a about ``axis``: u = (1 − cos a)/2 = s t/(1 − t)."""

    axis: tuple
    scale: float

    def bounds(self):
        import mitsuba as mi
        return mi.ScalarBoundingBox2f([-np.pi, 0.0], [np.pi, 1.0 / (1.0 + self.scale)])

    def aspect(self):
        return 1.0

    def _frame(self):
        import drjit as dr
        import mitsuba as mi
        return mi.Frame3f(dr.opaque(mi.Vector3f, self.axis))

    @property
    def _scale(self):
        import drjit as dr
        import mitsuba as mi
        return dr.opaque(mi.Float, self.scale)

    def map_forward(self, p):
        import drjit as dr
        import mitsuba as mi
        s = self._scale
        t = dr.minimum(p.y, 1.0 / (1.0 + s))
        u = dr.minimum(s * t / (1.0 - t), 1.0)
        cos_a = 1.0 - 2.0 * u
        sin_a = 2.0 * dr.safe_sqrt(u * (1.0 - u))
        sin_phi, cos_phi = dr.sincos(p.x)
        return self._frame().to_world(mi.Vector3f(sin_a * cos_phi, sin_a * sin_phi, cos_a))

    def map_backward(self, v):
        import drjit as dr
        import mitsuba as mi
        local = self._frame().to_local(v)
        rho2 = local.x * local.x + local.y * local.y
        u = dr.select(local.z > 0, rho2 / (2.0 * (1.0 + local.z)), 0.5 * (1.0 - local.z))
        return mi.Vector2f(dr.atan2(local.y, local.x), u / (u + self._scale))

    def jacobian(self, p):
        """dω / (dφ dt) = 2 du/dt = 2 s/(1 − t)² (t clipped to the chart, as :meth:`map_forward`)."""
        import drjit as dr
        s = self._scale
        t = dr.minimum(p.y, 1.0 / (1.0 + s))
        return 2.0 * s / (1.0 - t) ** 2


def chart_pdf(domain, pdf_func):
    """The pdf per unit of ``domain``'s chart from a pdf per solid angle (``ChiSquareTest`` calls it on
    the directions ``domain.map_forward`` gives)."""
    def pdf(v):
        return pdf_func(v) * domain.jacobian(domain.map_backward(v))
    return pdf


def lobe_axis(wi, about="mirror"):
    """The lobe's axis: the mirror direction of ``wi`` (``"mirror"``), N (``"normal"``), or a given 3-vector."""
    if about == "mirror":
        return (-wi[0], -wi[1], wi[2])
    if about == "normal":
        return (0.0, 0.0, 1.0)
    return tuple(float(c) for c in about)


def chi2_test(bsdf: dict, theta_deg: float, scale: float, about="mirror", sample_count: int = 200_000,
              res: int = 40, ires: int = 6, seed: int = 0):
    """Run ``mi.chi2.ChiSquareTest`` on the sampler of the plugin ``bsdf`` (a ``mi.load_dict`` dict) at
    incidence ``theta_deg``, on the :class:`LobeDomain` about ``about`` with lobe scale ``scale``.
    Returns the test after ``run`` (``test.p_value``, ``test.messages``, ``test.passed``)."""
    import drjit as dr
    import mitsuba as mi

    wi = incidence(theta_deg)
    # opaque, not a literal: the kernels of one plugin compile once for every angle and parameter
    sample_func, pdf_func = mi.chi2.BSDFAdapter(bsdf["type"], bsdf, wi=dr.opaque(mi.Vector3f, wi))
    domain = LobeDomain(lobe_axis(wi, about), float(scale))
    test = mi.chi2.ChiSquareTest(domain=domain, sample_func=sample_func, pdf_func=chart_pdf(domain, pdf_func),
                                 sample_dim=3, sample_count=sample_count, res=res, ires=ires, seed=seed)
    from brdfs.render.mitsuba.integrator import wavefront
    with wavefront(bsdf["type"] == "brdfs_model"):
        test.passed = bool(test.run(0.01, quiet=True))
    return test


def describe(test) -> str:
    """One line for an assertion message: p-value and Mitsuba's log."""
    return f"p = {test.p_value}: " + " | ".join(line for line in test.messages.splitlines() if line)
