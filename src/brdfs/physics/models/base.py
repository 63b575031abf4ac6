"""The BRDF protocol: the verbs every model of the package answers, with their defaults.

A model is a small frozen value type.  Calling it, ``f(L, V)``, evaluates the BRDF on arrays of
unit vectors (…, 3) with N = (0, 0, 1); directions below the horizon give 0.  The horizon, one
convention for L and V alike: a direction exactly on it (N·L = 0 or N·V = 0) gives f's limit as
that direction rises to the horizon, finite or +inf (Ward's 1/√(N·L N·V), Cook–Torrance with G = 1),
never NaN; with both on it, where the limit depends on the approach, f = 0 (the disk's rays start
there at 90°).  A reciprocal model stays reciprocal there (at e0ba585 V on the horizon gave 0 and
L on it the formula: 16 of 17 reciprocal models broke f(L, V) = f(V, L) at exactly 90°).  The
integrators evaluate f with L on the horizon for the albedo at θ = 90°; the limit is what they need.  A subclass
implements ``_eval`` and ``lobe`` and overrides whichever other verbs it knows more about:

Shape of the integrand (read by the integration engine, :mod:`brdfs.numerics.integrate`):

* ``lobe``: the change of variables that follows the lobe (:mod:`brdfs.physics.lobes`):
  which :class:`~brdfs.physics.lobes.Frame` (around the mirror direction R, around N for the half
  vector H, or the scattering vector) and which radial distribution (cosine power, a microfacet
  distribution); ``None`` for a model without one (the patch models, whose albedo is their own).
* ``nv_levels(nl)``: values of N·V where the integrand has a kink (e.g. N·V = N·L for the
  max(N·L, N·V) of the new model).  The horizon N·V = 0 is always added by the engine.
* ``lh_levels(nl, cos_delta)``: kinks given as levels of L·H (half-vector frame only).
* ``azimuth_levels(nl)``: azimuths φ_V of V about N (L in the plane φ = 0) where the integrand
  has a kink: half-planes through N (none by default).
* ``scattering_radius_levels()`` and ``scattering_radius_kinks(cos_psi, sin_psi)``: kinks at radii
  r = |L_xy + V_xy| of the horizontal scattering vector — the same radius for every direction
  (the patch radii, He–Torrance's scales), or along the direction (cos ψ, sin ψ) of L_xy + V_xy
  (an elliptical patch).
* ``scattering_radius_steep_layer()``: (end, pole) where f grows as a power of 1/(pole − r) in
  r = |L_xy + V_xy| up to r = end (a generalized Lambertian: (m_clip, 2)), or None.
* ``torrance_sparrow_switches``: the integrand carries the min of eq. 2.10, whose masking and
  shadowing switches are kinks; ``symmetric_about_incidence_plane``: f(L, V) is even in V_y.
* ``albedo_estimate(theta_deg, rtol, atol)``: the model's own route to its albedo where it has
  one (the patch models integrate lens areas, ch. 4), which the albedo engine takes instead.
* ``delta_albedo(theta_deg)``: the albedo of a Dirac part of the BRDF (zero by default), which
  the albedo adds to the integral of the density (He–Torrance's specular term).

What is known in closed form (``None`` where nothing is):

* ``exact_mean_albedo()``: the mean albedo A (eq. 1.20 / 3.37).
* ``truncation_error(L, V)``: a bound of the error of an evaluation of f beyond its rounding
  (a series' truncation); zero by default.
* ``scattering_azimuth_kernel()``: for a lobe in the scattering frame, ∫ f cos θ_V sin θ_V dφ_V at
  polar angles (θ_L, θ_V) with a bound of its error (He–Torrance with F ≡ 1), which makes the albedo
  a 1-D integral over θ_V.

* ``grazing_law()``: the law of a(θ) as cos θ → 0 (:class:`GrazingLaw`); ``diverges_at_grazing``:
  a(θ) → ∞ there; ``grazing_limit_model()``: the integrand whose albedo is a(90°), which every
  albedo method integrates at exactly 90° (the model itself unless it is singular at N·L = 0).
* ``limit_cos_power``: k with lim_{n→∞} a(θ) = cos^k θ for θ < 90° (cosine-lobe models).
* ``limit_albedo_90``: lim_{n→∞} a(90°).
* ``exact_albedo(theta_deg)``: a(θ) in closed form at the angles where one exists, else NaN.

Sampling — the one home of the package's samplers; Monte Carlo albedo, the chi-square tests, the
renderer and Figure 4.9 all draw from it:

* ``sample(L, u, strategy) -> (V, weight, pdf)``, ``sample_direction(L, u, strategy)`` (V alone)
  and ``pdf(L, V, strategy)``; a model declares ``strategies`` (its own first: the default; then
  ``"cosine"``, which every model accepts, as it accepts ``"uniform"``), ``sample_dimensions``
  (numbers per sample, 2 unless listed) and implements ``_sample_direction``/``_pdf`` from the
  pieces of :mod:`brdfs.physics.sampling`;
* for its chi-square tests: ``sampling_domain`` (``"sphere"``, or ``"disk"`` for samplers of
  base-plane points), ``disk_boundaries()`` (where the density jumps), ``chi2_cases`` and
  ``chi2_example(params)`` (the parameters tested, narrowest first, else the ``examples``);
* ``fresnel_cosine(L, V)``: the angle at which a metal of the model reads its Fresnel factor
  (Θ_min of eq. 3.29 by default, θ' of eq. 4.53 for the patch models, L·H for the microfacet models).

Parameters: ``params`` (the values, as ``data/published_values.csv`` names them) and
``param_columns()`` (the names, from the dataclass fields; tables a model is built with are not
parameters).

What the model says about itself (class attributes, defaults here), read by sweeps, tests, the
config schema and the artifacts instead of lists keyed by model name:

* ``param_ranges`` (name -> :class:`Interval`, the ranges the constructor accepts: the base class
  refuses a value outside them, :meth:`BRDF.check_declared_parameters`), ``param_choices`` (the
  values of categorical parameters) and ``param_texts`` (what any other parameter takes, in words);
* ``test_ranges`` (name -> :class:`DrawRange`, bounded and inside ``param_ranges``): where the
  generic tests draw each numeric parameter (an infinite range needs one), and ``energy_test_ranges``
  (narrower ones for the energy-conservation property, where a wide draw costs too much);
  ``scale_parameter``: the name of f's constant factor (``C``), which claims hold at its default;
* ``examples`` (``"typical"`` and ``"narrowest"`` parameters) and :meth:`BRDF.example`;
* ``reciprocal`` and ``conserves_energy``: the model's claims (a model that declares False says why);
* ``chapter``: the thesis chapter that defines it (None beyond the thesis);
* ``accuracy_families``, ``pumping_reducible``, ``half_angle_exponent_factor``, ``corrected_by``,
  ``constant_is_computed``: what the accuracy map, the pumping tables and the white-furnace
  comparison need to know of it;
* ``table_requests(**params)``: the tables (:class:`brdfs.physics.tables.TableRequest`) a model
  needs, which a factory above the physics layer computes and hands to it when it is built
  (:func:`brdfs.numerics.tables.build`); the physics layer computes none.
"""
from __future__ import annotations

import dataclasses
import math
import numbers
import threading
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np

from brdfs.core.estimate import Estimate
from brdfs.physics.parameters import check_positive  # noqa: F401  (re-exported to the models)
from brdfs.physics.lobes import Frame
from brdfs.physics import fresnel


#: Every model class by its published name (``data/published_values.csv``), in the order the
#: modules of :mod:`brdfs.physics.models` register them (the thesis's order: chapters 2–4, then
#: today's Smith microfacet models); a model module registers its own classes with :func:`register`.
MODELS: dict[str, type] = {}


def register(cls):
    """Add a model class (with a unique ``name``) to :data:`MODELS`; usable as a decorator."""
    MODELS[cls.name] = cls
    return cls


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


#: How far from 1 the length of a direction passed to a model's public call may be.
UNIT_TOLERANCE = 1e-6


def check_directions(where: str, **directions) -> None:
    """Refuse, with one ``ValueError`` line naming ``where`` and the argument, a direction array that
    is not (…, 3), not finite, not of unit length within :data:`UNIT_TOLERANCE`, or that does not
    broadcast against the others.  One pass over |d|² when all is well (NaN and inf fail it too);
    the diagnosis only when not."""
    for arg, d in directions.items():
        if d.ndim == 0 or d.shape[-1] != 3:
            raise ValueError(f"{where}: {arg} must have shape (..., 3) (unit vectors), got shape {d.shape}")
        x, y, z = d[..., 0], d[..., 1], d[..., 2]
        off = np.abs(x * x + y * y + z * z - 1.0)
        if not off.max(initial=0.0) <= 2.0 * UNIT_TOLERANCE:        # NaN compares False: diagnosed below
            _refuse_direction(where, arg, d)
    try:
        np.broadcast_shapes(*(d.shape[:-1] for d in directions.values()))
    except ValueError:
        shapes = ", ".join(f"{arg} {d.shape}" for arg, d in directions.items())
        raise ValueError(f"{where}: directions of shapes {shapes} do not broadcast") from None


def _refuse_direction(where, arg, d):
    """The one line for the first direction of ``d`` that is not finite or not of unit length."""
    finite = np.isfinite(d).all(axis=-1)
    length = np.sqrt(np.sum(np.where(np.isfinite(d), d, 0.0) ** 2, axis=-1))
    bad = ~finite | ~(np.abs(length - 1.0) <= UNIT_TOLERANCE)
    if not bad.any():                     # within the tolerance of |d| though not of |d|²
        return
    index = tuple(int(i) for i in np.argwhere(bad)[0]) if d.ndim > 1 else ()
    at = f" at index {index}" if index else ""
    if not finite[index]:
        raise ValueError(f"{where}: {arg} must be finite, got {d[index].tolist()}{at}")
    raise ValueError(f"{where}: {arg} must be a unit vector (|{arg}| = 1 within {UNIT_TOLERANCE:g}), got "
                     f"|{arg}| = {float(length[index]):.9g}{at}")


def check_uniform_numbers(where: str, u) -> None:
    """Refuse sampler numbers outside [0, 1) (or not finite) with one line: one above 1 would
    silently give rejected samples."""
    bad = ~((u >= 0.0) & (u < 1.0))
    if bad.any():
        raise ValueError(f"{where}: random numbers u must lie in [0, 1), got {float(u[bad].flat[0])!r}")


#: The strategy every model accepts besides its own: directions uniform in solid angle, pdf 1/(2π).
UNIFORM = "uniform"

class _ThreadCounters(threading.local):
    """The open counters of the current thread: a call in one thread counts none of another's."""

    def __init__(self):
        self.boxes: list[list[int]] = []


_COUNTERS = _ThreadCounters()


class counting_evaluations:
    """Count the BRDF values computed inside the block (every model, every method).

    >>> from brdfs import model
    >>> with counting_evaluations() as count:
    ...     _ = model("phong", n=2)([0, 0, 1.0], [[0, 0, 1.0]] * 5)
    >>> count[0]
    5

    A class rather than a generator-based context manager: a single-angle albedo call enters one,
    and the generator's machinery cost it a microsecond more.  One instance may be entered again
    inside its own block: each entry counts in a box of its own.  Counters are per thread: calls in
    other threads at the same time count in their own (four threads give the serial counts)."""

    def __init__(self):
        self._boxes = []

    def __enter__(self):
        box = [0]
        _COUNTERS.boxes.append(box)
        self._boxes.append(box)
        return box

    def __exit__(self, *exc):
        box = self._boxes.pop()
        # by identity: nested counters hold equal lists
        boxes = _COUNTERS.boxes
        del boxes[next(i for i, b in enumerate(boxes) if b is box)]
        return False


def count_evaluations(n: int) -> None:
    """Add ``n`` to the open :class:`counting_evaluations` counters of this thread: the nodes of a
    closed-form kernel that a route evaluates in place of the BRDF (each node counts as one value)."""
    for box in _COUNTERS.boxes:
        box[0] += n


def _python_number(value):
    """``value`` as a Python float (an int stays an int): a float32 n kept float32 in ``n + 1.0`` (NEP 50)
    and the routes mixed the precisions differently, each answer 1e6 of its reported errors off (Phong,
    n = float32(0.1)); a long double reached the compiled routes as a type they cannot take."""
    if type(value) in (float, int):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    return float(value)


@dataclass(frozen=True)
class BRDF:
    """Base class: subclasses implement ``_eval(L, V, nl, nv)`` and ``lobe``.

    Every subclass's constructor starts with :meth:`check_declared_parameters` (then runs its own
    ``__post_init__``, if it has one): a parameter outside its declared range or choices is refused
    with one line naming it before any work, whether or not the subclass checks it itself."""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("__post_init__")
        if own is None or getattr(own, "_checks_declared", False):
            return

        def __post_init__(self):
            if type(self).__post_init__ is __post_init__:     # the outermost wrapper checks once
                self.check_declared_parameters()
            own(self)

        __post_init__._checks_declared = True
        __post_init__.__doc__ = own.__doc__
        __post_init__.__wrapped__ = own
        cls.__post_init__ = __post_init__

    def __post_init__(self):
        self.check_declared_parameters()

    def check_declared_parameters(self):
        """Refuse a parameter outside its :attr:`param_ranges` (None: the field's own default, a
        feature switched off or a constant computed) or its :attr:`param_choices`; keep a declared number
        given as a numpy scalar or 0-d array as a Python number (:func:`_python_number`)."""
        cls = type(self)
        for key, interval in cls.param_ranges.items():
            value = getattr(self, key, None)
            if value is None or isinstance(value, bool):
                continue
            try:
                inside = interval.contains(value)
            except (TypeError, ValueError):
                raise ValueError(f"{cls.name}: {key} must be a real number, got {value!r}") from None
            if not inside:
                raise ValueError(f"{cls.name}: {key} must lie in {interval.text()}, got {value!r}")
            number = _python_number(value)
            if number is not value:
                object.__setattr__(self, key, number)
        for key, choices in cls.param_choices.items():
            value = getattr(self, key, None)
            if value not in choices:
                raise ValueError(f"{cls.name}: {key} must be one of {tuple(choices)}, got {value!r}")

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
    #: f = 0 wherever the lobe's coordinates do not reach (``lobe.reaches_hemisphere`` False: a
    #: cosine-power lobe about R maps only R·V ≥ 0, where (R·V)⁺ⁿ lives).  The engine integrates only
    #: where the lobe reaches, so it refuses a model whose lobe stops short of the hemisphere unless the
    #: model declares this (``auto`` then takes the disk): an exponent-0 lobe about R on a Lambertian f
    #: came back converged at 0.75 at 60° (the cap R·V ≥ 0 only), for an albedo of 1.
    zero_beyond_lobe: ClassVar[bool] = False
    #: (frame, kernel) of a model whose azimuthal integral is known in closed form
    #: (:mod:`brdfs.numerics.integrate.azimuthal`, with :meth:`azimuth_weight`), None otherwise.
    closed_form_azimuth: ClassVar[tuple[Frame, str] | None] = None
    #: f(L, V) = f(L, V') with V' = V mirrored in the plane of incidence (V_y → −V_y): the integrators
    #: integrate one half of the hemisphere and double it.  False for an anisotropic model.
    symmetric_about_incidence_plane: ClassVar[bool] = True
    #: The integrand carries the min of eq. 2.10 (Torrance–Sparrow's G): its masking and shadowing
    #: switches are kinks (the disk reference finds them along its rays in closed form).
    torrance_sparrow_switches: ClassVar[bool] = False
    #: a(θ_L) → ∞ as θ_L → 90° (Ward, the original Phong and Blinn, Cook–Torrance with G = 1): at
    #: exactly 90° every albedo method answers +inf with error 0 and status ``"diverged"``.
    diverges_at_grazing: ClassVar[bool] = False
    #: Bound of |f as evaluated / f of the exact model − 1| (a model built from tables: the pumped
    #: models' ε, :mod:`brdfs.numerics.pumping`): :func:`brdfs.albedo` adds it × |a| to every error.
    evaluation_rtol: ClassVar[float] = 0.0
    #: Where :meth:`evaluation_error` comes from and what lowers it, in words (the not-converged warning's
    #: advice where that error exceeds the tolerance asked for).
    evaluation_error_source: ClassVar[str] = "its tables"
    evaluation_error_remedy: ClassVar[str] = "build it with finer tables"

    def __call__(self, L, V):
        """f(L, V) on unit vectors L, V (…, 3) (broadcast against each other), N = (0, 0, 1); 0 below
        the horizon.  Refuses, with one line, directions of another shape, not finite, or not of unit
        length within :data:`UNIT_TOLERANCE` (an unnormalised V would silently scale f)."""
        L = np.asarray(L, float)
        V = np.asarray(V, float)
        check_directions(self.name, L=L, V=V)
        return self.unchecked(L, V)

    def unchecked(self, L, V):
        """f(L, V) without the check of the directions: for the integrators, the samplers and the
        renderers, which build unit vectors themselves (``benchmarks/bench_checked_calls.py``)."""
        L = np.asarray(L, float)
        V = np.asarray(V, float)
        nl, nv = L[..., 2], V[..., 2]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            f = self._eval(L, V, nl, nv)
        f = np.where((nl >= 0) & (nv >= 0), f, 0.0)       # the horizon convention (module docstring)
        if np.any(nl == 0):                                # both on it: no limit (it depends on the approach)
            f = np.where((nl == 0) & (nv == 0), 0.0, f)
        for box in _COUNTERS.boxes:
            box[0] += f.size
        return f

    def _eval(self, L, V, nl, nv):
        raise NotImplementedError

    # --- the integrand's shape ---------------------------------------------------------------
    @property
    def lobe(self):
        """The lobe's coordinates (:mod:`brdfs.physics.lobes`), or None: every model declares it."""
        raise NotImplementedError(f"{self.name} declares no lobe (None for a model without one)")

    def nv_levels(self, nl):
        return ()

    def lh_levels(self, nl, cos_delta):
        return ()

    def azimuth_levels(self, nl):
        """Azimuths φ_V ∈ [0, 2π) of V about N, with L in the plane φ = 0 (as
        :func:`~brdfs.physics.geometry.light_direction`), where the integrand has a kink: the
        half-planes φ_V = const through N.  None by default."""
        return ()

    def scattering_radius_levels(self):
        """Radii r = |L_xy + V_xy| where the integrand has a kink or a jump, the same in every
        direction of L_xy + V_xy (chapter 4's patch radii).  None by default."""
        return ()

    def scattering_radius_kinks(self, cos_psi, sin_psi):
        """Radii r = |L_xy + V_xy| of the kinks along the direction (cos ψ, sin ψ) of L_xy + V_xy,
        one array (of the shape of ``cos_psi``) per kink: by default the constant radii of
        :meth:`scattering_radius_levels`."""
        return [np.full(np.shape(cos_psi), r) for r in self.scattering_radius_levels()]

    def scattering_radius_steep_layer(self):
        """(end, pole): f grows as a power of 1/(pole − r) in r = |L_xy + V_xy| up to r = end, or None (the
        default): the rays of the disk route whose end comes near the pole are graded toward it."""
        return None

    def scattering_azimuth_kernel(self):
        """``kernel(cos θ_L, sin θ_L, cos θ_V, sin θ_V) -> (value, error)``: ∫₀^{2π} f cos θ_V sin θ_V dφ_V
        in closed form (with a bound of its error), for a lobe in the scattering frame, so that the
        albedo is a 1-D integral over θ_V (:mod:`brdfs.numerics.integrate.scattering`).  None by default."""
        return None

    def half_vector_factors(self):
        """``(distribution, S)`` where f(L, V) = D(H) S(N·L, N·V): D the distribution's density of
        the half vector (it integrates D over the azimuth about N in closed form,
        ``azimuthal_integral``) and S any function of the polar angles (Smith's masking), so that the
        albedo is a 1-D integral over θ_V (:mod:`brdfs.numerics.integrate.polar`).  None by default.
        An S that is one of the declared forms of :mod:`brdfs.physics.masking` (its family, roughness and
        scale as fields) runs compiled where numba is; any other callable on numpy."""
        return None

    @property
    def azimuth_weight_form(self) -> tuple[float, float, float] | None:
        """The radial weight w(β) per unit of the lobe variable t that multiplies the closed-form
        azimuthal kernel named by :attr:`closed_form_azimuth` (:mod:`brdfs.numerics.integrate.azimuthal`),
        as the form (c, k, d) of w = c cos^k β / d, or None: by default C times the lobe's own weight
        per unit t (a cosine power: (C, 0, n+1), C/(n+1)).  :meth:`azimuth_weight` evaluates it, and
        the compiled single-angle route reads it (a model that overrides :meth:`azimuth_weight` takes
        the numpy route)."""
        form = getattr(self.lobe, "weight_per_t_form", None)
        if self.closed_form_azimuth is None or form is None:
            return None
        return form(self.C)

    def azimuth_weight(self, cos_beta):
        """w(β) of :attr:`azimuth_weight_form` at cos β: c/d where k = 0 (a number), else c cos^k β / d."""
        form = self.azimuth_weight_form
        if form is None:
            raise NotImplementedError(f"{self.name} declares no closed-form azimuth weight")
        c, k, d = form
        return c / d if k == 0 else c * cos_beta ** k / d

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

    def exact_mean_albedo(self) -> Estimate | None:
        """The mean albedo A = (1/π) ∫ a(L) cos θ_L dω_L (eq. 1.20 / 3.37) in closed form; None by default."""
        return None

    def mirror_albedo(self, theta_deg) -> Estimate | None:
        """The albedo of the surface's mirror (Dirac) reflection, whichever part of the BRDF this model
        evaluates (He–Torrance's ρ_s also for its term 'dd'); None for a model that describes none."""
        return None

    @property
    def has_evaluation_error(self) -> bool:
        """Whether :meth:`evaluation_error` can be nonzero (a model built from tables)."""
        return bool(self.evaluation_rtol)

    def evaluation_error(self, theta_deg, albedo):
        """Bound of |a as evaluated − a of the exact model| at ``theta_deg``, given the albedo ``albedo``
        of f as evaluated: ``evaluation_rtol`` × |a| (the pumped models' tables); a model whose
        tables enter its albedo otherwise (Kulla–Conty's E) bounds their share itself."""
        return self.evaluation_rtol * np.abs(np.asarray(albedo, float))

    def truncation_error(self, L, V):
        """Bound of the error of ``f(L, V)`` beyond rounding (a truncated series): zero by default."""
        return np.zeros(np.broadcast_shapes(np.shape(L), np.shape(V))[:-1])

    # --- sampling ------------------------------------------------------------------------------
    #: Sampling strategies of :meth:`sample`/:meth:`pdf`; the first is the model's default and
    #: ``"cosine"`` (the baseline every model accepts) is always among them.
    strategies: ClassVar[tuple[str, ...]] = ("cosine",)
    #: Uniform numbers per sample a strategy consumes (2 unless listed).
    sample_dimensions: ClassVar[dict[str, int]] = {}
    #: Every model also accepts ``"uniform"`` (1/(2π) on the hemisphere, not listed in
    #: :attr:`strategies`: the reference a Monte Carlo albedo compares the model's samplers with).
    #: The chart on which the sampler's density is smooth, for its chi-square test
    #: (:mod:`brdfs.numerics.chi2`): ``"sphere"`` (directions, polar about the lobe) or ``"disk"``
    #: (points of the base plane about V'_P = −L_P: the projected-disk samplers of chapter 4).
    sampling_domain: ClassVar[str] = "sphere"
    #: Parameters of the sampler's chi-square tests (artifact ``sampling_chi2``), narrowest lobe
    #: first (the reduced run tests the first only); () takes the model's examples.
    chi2_cases: ClassVar[tuple[dict, ...]] = ()

    @classmethod
    def chi2_parameters(cls) -> tuple[dict, ...]:
        """:attr:`chi2_cases`, or where a model declares none its :attr:`examples` (narrowest, typical)."""
        return cls.chi2_cases or tuple(cls.examples[k] for k in ("narrowest", "typical") if k in cls.examples)

    @classmethod
    def chi2_example(cls, params: dict) -> "BRDF":
        """The model of one entry of :meth:`chi2_parameters`: ``cls(**params)`` by default."""
        return cls(**params)

    def disk_boundaries(self) -> tuple[tuple[float, ...], tuple[float, float, float] | None]:
        """Where the sampler's density jumps on the base plane (``sampling_domain = "disk"``): radii
        of circles about V'_P, and an ellipse (b, ratio, major-axis angle [rad]) centred at V'_P or
        None.  The chi-square test's integrals split there.  None by default."""
        return (), None

    def fresnel_cosine(self, L, V):
        """cos of the angle at which a metal of this model reads its Fresnel factor:
        Θ_min, cos Θ_min = max(N·L, N·V) (eq. 3.29), by default (:mod:`brdfs.physics.fresnel`)."""
        return fresnel.cos_theta_min(L, V)

    def _strategy(self, strategy):
        strategy = self.strategies[0] if strategy is None else strategy
        if strategy not in self.strategies and strategy != UNIFORM:
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
        if strategy == UNIFORM:
            return np.where(V[..., 2] > 0, 1 / (2 * np.pi), 0.0)
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
        V = self.sample_direction(L, u, strategy)
        L = np.broadcast_to(np.asarray(L, float), V.shape)
        pdf = self.pdf(L, V, strategy)
        with np.errstate(divide="ignore", invalid="ignore"):
            weight = np.where(pdf > 0, self.unchecked(L, V) * V[..., 2] / pdf, 0.0)
        return V, weight, pdf

    def sample_direction(self, L, u, strategy=None):
        """The directions V of :meth:`sample` alone (no weight, no pdf): what a mixture of proposals
        draws (the renderer, :mod:`brdfs.render.materials`), which weighs by the mixture's pdf."""
        strategy = self._strategy(strategy)
        u = np.asarray(u, float)
        if u.ndim == 0 or u.shape[-1] < self.sample_dimension(strategy):
            raise ValueError(f"{self.name}: strategy {strategy!r} needs u of shape (..., "
                             f"{self.sample_dimension(strategy)}), got {u.shape}")
        check_uniform_numbers(f"{self.name}.sample", u)
        L = np.broadcast_to(np.asarray(L, float), u.shape[:-1] + (3,))
        if strategy == "cosine":
            r, phi = np.sqrt(u[..., 0]), 2.0 * np.pi * u[..., 1]
            nv = np.sqrt(np.maximum(1.0 - u[..., 0], 0.0))
            return np.stack([r * np.cos(phi), r * np.sin(phi), nv], -1)
        if strategy == UNIFORM:                      # cos θ_V = u₀: uniform in solid angle
            cos_v = u[..., 0]
            sin_v = np.sqrt((1 - cos_v) * (1 + cos_v))
            phi = 2 * np.pi * u[..., 1]
            return np.stack([sin_v * np.cos(phi), sin_v * np.sin(phi), cos_v], -1)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
            return self._sample_direction(L, u, strategy)

    def _sample_direction(self, L, u, strategy):
        raise NotImplementedError(f"{self.name}: no sampler {strategy!r}")

    def _pdf(self, L, V, strategy):
        raise NotImplementedError(f"{self.name}: no pdf for {strategy!r}")

    # --- parameters ---------------------------------------------------------------------------
    @property
    def params(self) -> dict:
        """Parameters as the published-values file names them (n, m, C, ...); tables the model was
        built with (:func:`table_field`) are not parameters."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if not _is_table(f)}

    @classmethod
    def param_columns(cls) -> tuple[str, ...]:
        """The names of the model's parameters (its CSV columns)."""
        return tuple(f.name for f in dataclasses.fields(cls) if not _is_table(f))

    # --- what the model says about itself -----------------------------------------------------
    #: Ranges of the numeric parameters the model is valid for (those ``__post_init__`` accepts):
    #: name -> :class:`Interval`; an infinite bound means unbounded.  Sweeps, property tests and the
    #: config schema take the ranges from here.
    param_ranges: ClassVar[dict[str, "Interval"]] = {}
    #: Ranges within which :func:`brdfs.numerics.tables.pump` tabulates the model's albedo at its default
    #: target (it refuses beyond them in one line, before any work); none beyond :attr:`param_ranges` by default.
    pumping_ranges: ClassVar[dict[str, "Interval"]] = {}
    #: The choices of the model's categorical parameters (e.g. Cook–Torrance's G), name -> values.
    param_choices: ClassVar[dict[str, tuple]] = {}
    #: What a parameter that is neither a number in a range nor a choice takes (a function, a tuple), in
    #: words, name -> text: the model reference shows it where it shows the ranges; the model checks it.
    param_texts: ClassVar[dict[str, str]] = {}
    #: Where the generic tests (properties, protocol, chi-square) draw each numeric parameter: name ->
    #: :class:`DrawRange`, bounded and inside :attr:`param_ranges` (the thesis's narrowest lobes
    #: included).  A bounded declared range needs none (it is drawn linearly); an unbounded one does.
    #: A parameter with neither is held at its default.
    test_ranges: ClassVar[dict[str, "DrawRange"]] = {}
    #: Narrower test ranges for the energy-conservation property alone (name -> :class:`DrawRange`),
    #: where the full range costs too much per draw; the reason goes in a comment.
    energy_test_ranges: ClassVar[dict[str, "DrawRange"]] = {}
    #: The name of f's constant factor, which the claims (``conserves_energy``) hold at its default:
    #: the property tests draw it only where a claim does not depend on it.
    scale_parameter: ClassVar[str | None] = "C"
    #: Example parameters for sweeps and tests: ``"typical"`` (the default of :meth:`example`) and
    #: ``"narrowest"`` (the sharpest lobe the thesis or the package treats), each inside
    #: :attr:`param_ranges`.
    examples: ClassVar[dict[str, dict]] = {}
    #: Whether the model claims a(θ) = ∫ f cos θ_V dω_V ≤ 1 at every θ for every parameter of its
    #: ranges with its default constant.  No claim (False) unless a model makes it; a model that
    #: declares False says why in a comment.
    conserves_energy: ClassVar[bool] = False
    #: The chapter of the thesis that defines or treats the model; None for a model beyond it.
    chapter: ClassVar[int | None] = None
    #: The pumped chains of this model integrate by the polar-azimuth reduction of
    #: :func:`brdfs.numerics.pumping.pumped_albedo` (a cosine-power lobe around R or H without kinks
    #: of its own); any other model goes through the hemisphere engine.
    pumping_reducible: ClassVar[bool] = False
    #: Families of the accuracy map (``extra_accuracy_map``) this model stands for: family name ->
    #: (the swept parameter, fixed parameters); ``config.yaml`` gives each family's values.  A fixed
    #: parameter ``pumping`` (``"g1"``/``"g2"``) maps the model pumped once with that correction.
    accuracy_families: ClassVar[dict[str, tuple[str, dict]]] = {}
    #: Cosine-lobe models: k with the lobe ≈ cos^{k n} δ in the half-vector angle δ at normal incidence
    #: (1 for (N·H)^n; 4 for a mirror lobe (R·V)^n, R·V = cos 2δ), the exponent matched to a
    #: microfacet roughness by Walter et al. 2007, sec. 5.2 (n_Blinn = 2/α² − 2); None otherwise.
    half_angle_exponent_factor: ClassVar[float | None] = None
    #: The thesis's new model that corrects this one (chapter 3: divided by max(N·L, N·V)), by name.
    corrected_by: ClassVar[str | None] = None
    #: The thesis's constant of this model is computed, C = 1/max a (Table 3.1 for the Blinn models),
    #: rather than the default of the ``C`` field.
    constant_is_computed: ClassVar[bool] = False

    @classmethod
    def test_range(cls, key: str, energy: bool = False) -> "DrawRange | None":
        """Where the generic tests draw parameter ``key``: :attr:`energy_test_ranges` (``energy``),
        else :attr:`test_ranges`, else a bounded :attr:`param_ranges` entry drawn linearly; None when
        the parameter is not drawn (no range, or an unbounded one without a test range)."""
        if energy and key in cls.energy_test_ranges:
            return cls.energy_test_ranges[key]
        if key in cls.test_ranges:
            return cls.test_ranges[key]
        interval = cls.param_ranges.get(key)
        if interval is not None and np.isfinite(interval.lo) and np.isfinite(interval.hi):
            return DrawRange(interval.lo, interval.hi)
        return None

    @classmethod
    def example(cls, kind: str = "typical") -> "BRDF":
        """The model at its example parameters :attr:`examples` [``kind``] (``"typical"`` or
        ``"narrowest"``).

        >>> from brdfs.physics.models import MODELS
        >>> MODELS["phong"].example().n
        20.0
        """
        try:
            params = cls.examples[kind]
        except KeyError:
            raise ValueError(f"{cls.name}: no example {kind!r}; declared: {sorted(cls.examples)}") from None
        return cls(**params)

    @classmethod
    def table_requests(cls, **params) -> dict:
        """The tables a model with ``params`` needs, built by a factory above the physics layer
        (:func:`brdfs.numerics.tables.build`): field name -> :class:`brdfs.physics.tables.TableRequest`.
        None by default: a plain model needs no table."""
        return {}


class Interval(NamedTuple):
    """A range lo ≤ x ≤ hi of a parameter (``lo_open``: lo < x, ``hi_open``: x < hi); an infinite
    bound is never reached (parameters are finite).

    >>> Interval(0.0, 2.0, lo_open=True).contains(2.0), positive().contains(0.0)
    (True, False)
    """

    lo: float
    hi: float
    lo_open: bool = False
    hi_open: bool = False

    def contains(self, x) -> bool:
        x = float(x)
        above = x > self.lo if self.lo_open else x >= self.lo
        below = x < self.hi if self.hi_open else x <= self.hi
        return bool(np.isfinite(x) and above and below)

    def text(self) -> str:
        """``[0, 1]``, ``(0, inf)``: the interval as a message or a table shows it."""
        lo = "(" if self.lo_open or math.isinf(self.lo) else "["
        hi = ")" if self.hi_open or math.isinf(self.hi) else "]"
        return f"{lo}{self.lo:g}, {self.hi:g}{hi}"


class DrawRange(NamedTuple):
    """Where the generic tests draw a parameter: lo ≤ x ≤ hi (clipped to the declared range's open
    bounds), log-uniformly (``log``) or uniformly; ``zero`` adds the value 0 itself to a log range,
    ``none`` adds None (a feature switched off, e.g. F = 1 without an index of refraction).  lo = hi
    holds the parameter at that value.

    >>> DrawRange(1e-2, 1e4, log=True, zero=True).contains(0.0)
    True
    """

    lo: float
    hi: float
    log: bool = False
    zero: bool = False
    none: bool = False

    def contains(self, x) -> bool:
        if x is None:
            return self.none
        x = float(x)
        return bool((self.zero and x == 0.0) or self.lo <= x <= self.hi)


def log_range(lo: float, hi: float, *, zero: bool = False, none: bool = False) -> DrawRange:
    """A test range drawn log-uniformly (a scale, a roughness, an exponent)."""
    return DrawRange(float(lo), float(hi), log=True, zero=zero, none=none)


def linear_range(lo: float, hi: float) -> DrawRange:
    """A test range drawn uniformly (an angle, a fraction)."""
    return DrawRange(float(lo), float(hi))


def positive(hi: float = np.inf) -> Interval:
    """0 < x ≤ hi (what :func:`check_positive` accepts, up to ``hi``)."""
    return Interval(0.0, hi, lo_open=True)


def non_negative(hi: float = np.inf) -> Interval:
    """0 ≤ x ≤ hi (:func:`check_positive` with ``allow_zero``, up to ``hi``)."""
    return Interval(0.0, hi)


#: The ends of the declared ranges (:attr:`BRDF.param_ranges`) where a parameter stops before the
#: model or the engine stops coping (issue 41; beyond them brdfs.model and brdfs.albedo refuse in one line):
#: cosine powers to n = 10⁵ (the limit checks of chapter 3 take n = 10⁵; engine and disk agree within
#: their errors there, the sweep holds n ≤ 10⁴; the pumping tables reach n ≤ 10⁴, :data:`PUMP_N_MAX`); Beckmann's m of Ward and Cook–Torrance from 0.005 (Table 3.2's narrowest, the sweep's
#: end; m = 1e-300 divided by zero); the Smith models' α in [0.01, 1], where the sweep's independent
#: truths reach (α = 1e-9 came back 0.9961 for the mirror's 1 at 0°, α = 1e-12 took 110 s, α = 1e6 was off
#: 35 errors at 90°; engine and disk agree within their errors down to α = 1e-8, but the long-double
#: truths take minutes a cell below α = 1e-3, so the range stops where it is held); patch radii from
#: 1e-8 (R, m_clip = 1e-300 made C infinite or NaN; the lens areas are held to 50 digits down to R = 1e-8),
#: the ellipse's b from 1e-3 (b = 1e-30 gave an albedo of 0, b = 1e-12 ran out of budget).
N_MAX = 1.0e5
#: The largest n whose albedo table :func:`brdfs.numerics.tables.pump` builds at its default target
#: (1e-9; beyond, pieces of degree 256 miss it: Blinn n = 3e4, Phong n = 3e4): ``pumping_ranges``.
PUMP_N_MAX = 1.0e4
M_MIN = 0.005
#: Cook–Torrance's m up to 10⁵: with Smith's G (eq. 1.38) the albedo ~0.84/m³ takes ~1/m of it from
#: G*'s turn at θ_V ~ 1/(√2 m), where G* is computed from N·V = cos θ_V: 1 − (N·V)² keeps ~ε m² of its
#: relative precision there, and beyond m ~ 10⁶ the rounding outgrows the error reported (m = 10⁶ at 0°:
#: 1.2 errors off; at m ≥ 1.34e154, m² overflows).  Polar route and disk agree with an independent
#: nested quadrature within their errors from m = 1 to 10⁵, θ from 0 to 90° − 1e-9°.
CT_M_MAX = 1.0e5
ALPHA_MIN, ALPHA_MAX = 0.01, 1.0
RADIUS_MIN, ELLIPSE_B_MIN = 1.0e-8, 1.0e-3


def table_field():
    """A dataclass field for a table the model receives when it is built (not a parameter: not in
    :attr:`BRDF.params`, not compared; :func:`brdfs.numerics.tables.build` fills it)."""
    return dataclasses.field(default=None, compare=False, repr=False, metadata={"table": True})


def _is_table(f) -> bool:
    return bool(f.metadata.get("table"))


def positive_power(x, n):
    """((x)^+)^n with 0^0 = 1 only for x > 0."""
    return np.where(x > 0, np.maximum(x, 0.0) ** n, 0.0)


