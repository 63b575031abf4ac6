"""The BRDF protocol: the verbs every model of the package answers, with their defaults.

A model is a small frozen value type.  Calling it, ``f(L, V)``, evaluates the BRDF on arrays of
unit vectors (…, 3) with N = (0, 0, 1); directions below the horizon give 0.  A subclass
implements ``_eval`` and ``lobe`` and overrides whichever other verbs it knows more about:

Shape of the integrand (read by the integration engine, :mod:`brdfs.numerics.integrate`):

* ``lobe``: the change of variables that follows the lobe (:mod:`brdfs.physics.lobes`):
  which frame (around the mirror direction R, around N for the half vector H, or the scattering
  vector) and which radial distribution (cosine power, a microfacet distribution).
* ``nv_levels(nl)``: values of N·V where the integrand has a kink (e.g. N·V = N·L for the
  max(N·L, N·V) of the new model).  The horizon N·V = 0 is always added by the engine.
* ``lh_levels(nl, cos_delta)``: kinks given as levels of L·H (half-vector frame only).
* ``albedo_estimate(theta_deg, rtol, atol)``: the model's own route to its albedo where it has
  one (the patch models integrate lens areas, ch. 4), which the albedo engine takes instead.
* ``delta_albedo(theta_deg)``: the albedo of a Dirac part of the BRDF (zero by default), which
  the albedo adds to the integral of the density (He–Torrance's specular term).

What is known in closed form (``None`` where nothing is):

* ``grazing_law()``: the law of a(θ) as cos θ → 0 (:class:`GrazingLaw`).
* ``limit_cos_power``: k with lim_{n→∞} a(θ) = cos^k θ for θ < 90° (cosine-lobe models).
* ``limit_albedo_90``: lim_{n→∞} a(90°).
* ``exact_albedo(theta_deg)``: a(θ) in closed form at the angles where one exists, else NaN.

Sampling (for Monte Carlo and rendering): ``sample(L, u) -> (V, weight, pdf)`` and ``pdf(L, V)``;
the default draws V from the cosine distribution, which every model accepts.

Parameters: ``params`` (the values, as ``data/published_values.csv`` names them) and
``param_columns()`` (the names, from the dataclass fields).
"""
from __future__ import annotations

import contextlib
import dataclasses
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from brdfs.core.estimate import Estimate


@dataclass(frozen=True)
class GrazingLaw:
    """a(θ) ~ constant · (cos θ_L)^(−exponent) as cos θ_L → 0; exponent 0 is a finite limit a(90°)."""

    exponent: float
    constant: Estimate
    derivation: str

    def __call__(self, mu):
        return self.constant.value * np.asarray(mu, float) ** -self.exponent


def exact(value) -> Estimate:
    """A closed-form value with its rounding error (4 ulps)."""
    value = float(value)
    return Estimate(value, 4 * np.finfo(float).eps * abs(value))


_COUNTERS: list[list[int]] = []


@contextlib.contextmanager
def counting_evaluations():
    """Count the BRDF values computed inside the block (every model, every method).

    >>> from brdfs import model
    >>> with counting_evaluations() as count:
    ...     _ = model("phong", n=2)([0, 0, 1.0], [[0, 0, 1.0]] * 5)
    >>> count[0]
    5
    """
    box = [0]
    _COUNTERS.append(box)
    try:
        yield box
    finally:
        # by identity: nested counters hold equal lists
        del _COUNTERS[next(i for i, b in enumerate(_COUNTERS) if b is box)]


@dataclass(frozen=True)
class BRDF:
    """Base class: subclasses implement ``_eval(L, V, nl, nv)`` and ``lobe``."""

    reciprocal: ClassVar[bool] = True
    name: ClassVar[str] = "brdf"
    #: Integrand ~ sqrt(N·V) at the horizon (Ward): the engine clusters nodes there.
    sqrt_at_horizon: ClassVar[bool] = False
    #: lim_{n→∞} a(θ) = cos^k θ (θ < 90°), None where not derived.
    limit_cos_power: ClassVar[int | None] = None
    #: lim_{n→∞} a(90°), None where not derived.
    limit_albedo_90: ClassVar[float | None] = None
    #: Integrand with a cone-shaped kink at V = N (1 − c|V − N|), e.g. the thesis's Smith G* (eq. 1.38).
    kink_at_normal: ClassVar[bool] = False
    #: (frame, kernel) of a model whose azimuthal integral is known in closed form
    #: (:mod:`brdfs.numerics.integrate.azimuthal`, with :meth:`azimuth_weight`), None otherwise.
    closed_form_azimuth: ClassVar[tuple[str, str] | None] = None

    def __call__(self, L, V):
        L = np.asarray(L, float)
        V = np.asarray(V, float)
        nl, nv = L[..., 2], V[..., 2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            f = self._eval(L, V, nl, nv)
        f = np.where((nl >= 0) & (nv > 0), f, 0.0)
        for box in _COUNTERS:
            box[0] += f.size
        return f

    def _eval(self, L, V, nl, nv):
        raise NotImplementedError

    # --- the integrand's shape ---------------------------------------------------------------
    @property
    def lobe(self):
        raise NotImplementedError

    def nv_levels(self, nl):
        return ()

    def lh_levels(self, nl, cos_delta):
        return ()

    def azimuth_weight(self, cos_beta):
        """The radial weight w(β) per unit of the lobe variable t that multiplies the closed-form
        azimuthal kernel named by :attr:`closed_form_azimuth` (:mod:`brdfs.numerics.integrate.azimuthal`):
        by default C times the lobe's own weight per unit t (a cosine power: C/(n+1))."""
        weight_per_t = getattr(self.lobe, "weight_per_t", None)
        if self.closed_form_azimuth is None or weight_per_t is None:
            raise NotImplementedError(f"{self.name} declares no closed-form azimuth weight")
        return weight_per_t(cos_beta, self.C)

    def delta_albedo(self, theta_deg) -> Estimate:
        """Albedo of the Dirac part of the BRDF: none by default."""
        zero = np.zeros(np.shape(theta_deg))
        return Estimate(zero, zero)

    def albedo_estimate(self, theta_deg, rtol, atol) -> Estimate | None:
        """The model's own route to its albedo, where it has one cheaper than integrating the BRDF
        over the hemisphere (the patch models: areas of lenses, ch. 4); None by default."""
        return None

    # --- closed forms -------------------------------------------------------------------------
    def grazing_law(self) -> GrazingLaw | None:
        """The law of a(θ) as cos θ → 0 where it is known in closed form; None otherwise."""
        return None

    def grazing_limit_model(self) -> "BRDF":
        """The integrand whose albedo at 90° is lim a(θ), θ → 90°: the model itself by default."""
        return self

    def exact_albedo(self, theta_deg) -> np.ndarray:
        """a(θ) in closed form where one exists, NaN elsewhere."""
        return np.full(np.shape(theta_deg), np.nan)

    # --- sampling ------------------------------------------------------------------------------
    #: Sampling strategies of :meth:`sample`/:meth:`pdf`; the first is the model's default and
    #: ``"cosine"`` (the baseline every model accepts) is always among them.
    strategies: ClassVar[tuple[str, ...]] = ("cosine",)
    #: Uniform numbers per sample a strategy consumes (2 unless listed).
    sample_dimensions: ClassVar[dict[str, int]] = {}

    def _strategy(self, strategy):
        strategy = self.strategies[0] if strategy is None else strategy
        if strategy not in self.strategies:
            raise ValueError(f"{self.name}: unknown sampling strategy {strategy!r}; choose one of {self.strategies}")
        return strategy

    def sample_dimension(self, strategy=None) -> int:
        """How many uniform numbers one sample of ``strategy`` consumes (the last axis of ``u``)."""
        return self.sample_dimensions.get(self._strategy(strategy), 2)

    def pdf(self, L, V, strategy=None):
        """Density (per solid angle of V) of :meth:`sample`'s directions; cos θ_V / π for ``"cosine"``.

        A sub-probability where the strategy can reject (its integral is 1 − P(rejected))."""
        strategy = self._strategy(strategy)
        V = np.asarray(V, float)
        if strategy == "cosine":
            nv = V[..., 2]
            return np.where(nv > 0, nv / np.pi, 0.0)
        L = np.broadcast_to(np.asarray(L, float), V.shape)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            p = self._pdf(L, V, strategy)
        return np.where(V[..., 2] > 0, np.nan_to_num(p, nan=0.0, posinf=0.0), 0.0)

    def sample(self, L, u, strategy=None):
        """Directions V from uniform numbers ``u`` (…, :meth:`sample_dimension`), with the weight
        f cos θ_V / pdf and the pdf (both 0 for a rejected sample, returned as V = −N).

        ``"cosine"`` draws the cosine distribution (Malley's method); the other strategies are the
        model's (:attr:`strategies`, the first the default).
        """
        strategy = self._strategy(strategy)
        u = np.asarray(u, float)
        if u.shape[-1] < self.sample_dimension(strategy):
            raise ValueError(f"{self.name}: strategy {strategy!r} needs u of shape (..., "
                             f"{self.sample_dimension(strategy)}), got {u.shape}")
        L = np.broadcast_to(np.asarray(L, float), u.shape[:-1] + (3,))
        if strategy == "cosine":
            r, phi = np.sqrt(u[..., 0]), 2.0 * np.pi * u[..., 1]
            nv = np.sqrt(np.maximum(1.0 - u[..., 0], 0.0))
            V = np.stack([r * np.cos(phi), r * np.sin(phi), nv], -1)
        else:
            with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
                V = self._sample_direction(L, u, strategy)
        pdf = self.pdf(L, V, strategy)
        with np.errstate(divide="ignore", invalid="ignore"):
            weight = np.where(pdf > 0, self(L, V) * V[..., 2] / pdf, 0.0)
        return V, weight, pdf

    def _sample_direction(self, L, u, strategy):
        raise NotImplementedError(f"{self.name}: no sampler {strategy!r}")

    def _pdf(self, L, V, strategy):
        raise NotImplementedError(f"{self.name}: no pdf for {strategy!r}")

    # --- parameters ---------------------------------------------------------------------------
    @property
    def params(self) -> dict:
        """Parameters as the published-values file names them (n, m, C, ...)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    @classmethod
    def param_columns(cls) -> tuple[str, ...]:
        """The names of the model's parameters (its CSV columns)."""
        return tuple(f.name for f in dataclasses.fields(cls))


def positive_power(x, n):
    """((x)^+)^n with 0^0 = 1 only for x > 0."""
    return np.where(x > 0, np.maximum(x, 0.0) ** n, 0.0)


def check_positive(name, value, allow_zero=False):
    """Reject bad parameters with a message that names them."""
    value = float(value)
    if not np.isfinite(value) or value < 0 or (value == 0 and not allow_zero):
        raise ValueError(f"{name} must be {'non-negative' if allow_zero else 'positive'}, got {value!r}")
    return value
