"""Argument checks of the front doors :func:`brdfs.albedo` and :func:`brdfs.model`: before any work,
each bad argument is refused with one line naming the argument and its value,
``<where>: <argument> = <value>: <what is wrong>``, as an :class:`ArgumentError`.

What is valid is read from where it is declared, never from a list kept here:

* a model's parameters, their types and defaults from its dataclass fields, their ranges from its
  ``param_ranges`` and the values of its categorical parameters from its ``param_choices``;
* the methods from the table the front door passes (:data:`brdfs.numerics.albedo.ALBEDO_METHODS`:
  this module imports nothing of the numerics above it), and each method's options, their types and
  their constraints from the keyword parameters of the method's function (their annotations:
  ``Annotated[int, AtLeast(2)]``, ``Annotated[str, OneOf(...)]``);
* the tolerances once, as a :class:`Tolerance` value that the front door carries.

>>> from brdfs import model
>>> model("phong", n="20")
Traceback (most recent call last):
...
brdfs.numerics.arguments.ArgumentError: model('phong'): n = '20': must be a real number, not str
"""
from __future__ import annotations

import dataclasses
import functools
import inspect
import math
import numbers
import operator
import typing
import weakref
from dataclasses import dataclass

import numpy as np

from brdfs.physics.models import BRDF, MODELS


class ArgumentError(ValueError, TypeError):
    """A bad argument of a front door; a ValueError and a TypeError alike (a wrong type or a wrong
    value), so that either ``except`` catches it.  The message is one line naming the argument and
    its value."""


class AtLeast(float):
    """Annotation of a numeric option: its least valid value (``Annotated[int, AtLeast(2)]``)."""


class Above(float):
    """Annotation of a numeric option: a bound it must exceed (``Annotated[float, Above(0.0)]``)."""


class OneOf(tuple):
    """Annotation of a string option: its valid values (``Annotated[str, OneOf(("a", "b"))]``)."""


def _show(value) -> str:
    """A short repr of a value for a one-line message."""
    text = repr(value)
    if isinstance(value, np.ndarray):
        text = np.array2string(value, threshold=6, separator=", ").replace("\n", "")
    return text if len(text) <= 80 else text[:77] + "..."


def _fail(where, argument, value, problem):
    raise ArgumentError(f"{where}: {argument} = {_show(value)}: {problem}")


def _is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _check_real(where, argument, value, interval=None):
    """A finite real number (not a bool, not a string), inside ``interval`` if one is declared."""
    if not _is_real(value):
        _fail(where, argument, value, f"must be a real number, not {type(value).__name__}")
    try:
        real = float(value)
    except OverflowError:                             # an int beyond the floats (numpy's isnan raised TypeError)
        _fail(where, argument, value, "must be finite")
    if math.isnan(real):
        _fail(where, argument, value, "must be a number, not NaN")
    if not math.isfinite(real):
        _fail(where, argument, value, "must be finite")
    if interval is not None and not interval.contains(value):
        _fail(where, argument, value, f"must be {_describe_interval(interval)}")


def _describe_interval(interval) -> str:
    """'> 0', '>= 0' or 'in [0, 1]' (open ends as parentheses)."""
    lower = (">" if interval.lo_open else ">=") + f" {interval.lo:g}"
    if np.isinf(interval.hi):
        return lower
    return ("in (" if interval.lo_open else "in [") + f"{interval.lo:g}, {interval.hi:g}" + (")" if interval.hi_open else "]")


class PerModel:
    """Facts of a model object that depend on its values alone, found once and kept while the object
    lives and its values stay the ones they were found with: looked up by its identity, a weak
    reference telling that it is the same object, and its attributes (``vars``) compared by identity
    with those seen when the fact was found, so that a value set after building (a plain user class,
    or ``object.__setattr__`` on a frozen one) is asked again.  A model that takes no weak reference or
    has no ``__dict__`` is asked every time; a fact whose finding raises is not kept."""

    def __init__(self):
        self._kept: dict = {}

    def get(self, model, key, find):
        """The fact ``key`` of ``model``: kept, or ``find()`` (then kept)."""
        at = (id(model), key)
        kept = self._kept.get(at)
        try:
            state = tuple(vars(model).values())
        except TypeError:
            return find()
        if kept is not None and kept[0]() is model and _same_objects(kept[1], state):
            return kept[2]
        fact = find()
        try:
            ref = weakref.ref(model, lambda _, at=at: self._kept.pop(at, None))
        except TypeError:
            return fact
        # seen after finding: what the finding itself cached on the model (a cached_property) is part of it
        self._kept[at] = (ref, tuple(vars(model).values()), fact)
        return fact


def _same_objects(seen: tuple, now: tuple) -> bool:
    """The attributes' values are the very objects seen (the kept tuple holds them, so no id is reused);
    compared by ``operator.is_`` in C, where a generator's frame per attribute cost a single call ~2 µs."""
    return len(seen) == len(now) and all(map(operator.is_, seen, now))


#: The front doors' facts of model objects (their declared ranges checked, their single angle's route).
PER_MODEL = PerModel()


# --- brdfs.model -------------------------------------------------------------------------------

def check_model_call(name, params) -> None:
    """Refuse a bad :func:`brdfs.model` call before any table is computed: the name (a string
    naming a registered model), every parameter's name, type, finiteness, range and choice."""
    if isinstance(name, BRDF):
        _fail("model()", "name", name, "already a model; pass it to albedo() as it is")
    if not isinstance(name, str):
        _fail("model()", "name", name, f"must be a model name (a str), one of {', '.join(MODELS)}")
    if name not in MODELS:
        _fail("model()", "name", name, f"unknown model; known models: {', '.join(MODELS)}")
    cls = MODELS[name]
    where = f"model({name!r})"
    fields = {f.name: f for f in dataclasses.fields(cls)}
    for key in params:
        if key not in fields:
            _fail(where, key, params[key], f"unknown parameter; {name} takes {', '.join(fields)}")
    for key, f in fields.items():
        if key not in params:
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                raise ArgumentError(f"{where}: {key} is missing: a required parameter of {name} "
                                    f"(parameters: {', '.join(fields)})")
            continue
        _check_parameter(cls, where, f, params[key])


def _check_parameter(cls, where, field, value):
    """One parameter against its field's type and the class's declared range or choices."""
    if field.metadata.get("table"):
        return                                   # a table the factory computes (checked by the model)
    kind = str(field.type)
    if value is None and "None" in kind:
        return
    if field.name in cls.param_choices:
        choices = cls.param_choices[field.name]
        if not isinstance(value, str) or value not in choices:
            _fail(where, field.name, value, f"must be one of {', '.join(map(str, choices))}")
        return
    if "float" in kind or "int" in kind or field.name in cls.param_ranges:
        _check_real(where, field.name, value, cls.param_ranges.get(field.name))
    elif "Callable" in kind and not callable(value):
        _fail(where, field.name, value, "must be callable")
    elif kind == "str" and not isinstance(value, str):
        _fail(where, field.name, value, f"must be a str, not {type(value).__name__}")


# --- brdfs.albedo ------------------------------------------------------------------------------

DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-14


@dataclass(frozen=True)
class Tolerance:
    """The error an albedo call asks for, max(rtol |a|, atol): both finite and > 0, checked once
    (:meth:`checked`, the first check of a front door) and carried as one value through the plan,
    the routes and the merge."""

    rtol: float = DEFAULT_RTOL
    atol: float = DEFAULT_ATOL

    @classmethod
    def checked(cls, rtol=None, atol=None, where="albedo()") -> "Tolerance":
        """The tolerance of a call (None: the default), or :class:`ArgumentError` naming the bad one
        (floats checked once per value and kept: :func:`_checked_floats`)."""
        if (rtol is None or type(rtol) is float) and (atol is None or type(atol) is float):
            return _checked_floats(cls, rtol, atol, where)
        return cls._checked(rtol, atol, where)

    @classmethod
    def _checked(cls, rtol, atol, where):
        for argument, value in (("rtol", rtol), ("atol", atol)):
            if value is not None:
                _check_real(where, argument, value)
                if value <= 0:
                    _fail(where, argument, value, "must be > 0")
        return cls(DEFAULT_RTOL if rtol is None else rtol, DEFAULT_ATOL if atol is None else atol)

    def target(self, value):
        """max(rtol |value|, atol), element by element."""
        return np.maximum(self.rtol * np.abs(value), self.atol)


@functools.lru_cache(maxsize=64)
def _checked_floats(cls, rtol, atol, where):
    """:meth:`Tolerance.checked` of floats (or None), kept per value: a frozen value, shared (a bad one
    raises every time: nothing is kept)."""
    return cls._checked(rtol, atol, where)


def check_albedo_call(model, theta_deg, method, methods, options, strict=False, warn=True) -> None:
    """Refuse a bad :func:`brdfs.albedo` call (``methods``: the albedo methods by name; ``options``:
    the method's keyword options): the model (a model object, not its name), the angles (finite, in
    [0°, 90°]), the method, ``strict`` and ``warn`` (bools) and every option of the method.  The
    tolerances are :meth:`Tolerance.checked` before."""
    where = "albedo()"
    if isinstance(model, str):
        hint = ", ".join(f"{k}=..." for k in MODELS[model].param_columns()) if model in MODELS else "..."
        _fail(where, "model", model, f"a model name, not a model; build one with brdfs.model({model!r}, {hint})")
    if not isinstance(model, BRDF):
        _fail(where, "model", model, f"must be a model (brdfs.model(name, ...)), not {type(model).__name__}")
    _check_declared_ranges(where, model)
    check_angles(where, theta_deg)
    if not isinstance(method, str) or method not in methods:
        _fail(where, "method", method, f"unknown method; choose one of {', '.join(methods)}")
    for argument, value in (("strict", strict), ("warn", warn)):
        if not isinstance(value, (bool, np.bool_)):
            _fail(where, argument, value, f"must be True or False, not {type(value).__name__}")
    if options:                                       # (its name is formatted only where there is one to check)
        _check_options(f"albedo(method={method!r})", methods[method], options)


def _check_declared_ranges(where, model):
    """A model built past its declared ranges (its class called directly, which brdfs.model would
    have refused): beyond them the model or the engine cannot cope, so no work starts.  A model found
    within them is not checked again (:data:`PER_MODEL`)."""
    PER_MODEL.get(model, "within its declared ranges", lambda: _within_declared_ranges(where, model))


def _within_declared_ranges(where, model) -> bool:
    for key, interval in type(model).param_ranges.items():
        value = getattr(model, key, None)
        if _is_real(value) and not interval.contains(value):
            _fail(where, f"model.{key}", value, f"outside the range {model.name} declares: must be "
                  f"{_describe_interval(interval)}")
    return True


def check_table_call(models, theta_deg) -> None:
    """Refuse a bad :func:`brdfs.albedo_table` call: a list of model objects, angles (the tolerances
    are :meth:`Tolerance.checked` before)."""
    where = "albedo_table()"
    if isinstance(models, (str, BRDF)) or not hasattr(models, "__iter__"):
        _fail(where, "models", models, "must be a list of models (brdfs.model(name, ...))")
    for k, m in enumerate(models):
        if not isinstance(m, BRDF):
            _fail(where, f"models[{k}]", m, f"must be a model (brdfs.model(name, ...)), not {type(m).__name__}")
    check_angles(where, theta_deg)


def check_angles(where, theta_deg) -> None:
    """Refuse angles that are not real, finite and in [0, 90] degrees (``where`` names the call)."""
    if isinstance(theta_deg, float) and 0.0 <= theta_deg <= 90.0:
        return                                        # one angle, valid (NaN fails the comparison)
    try:
        theta = np.asarray(theta_deg)
    except Exception:                                 # a ragged list
        _fail(where, "theta_deg", theta_deg, "must be an angle or an array of angles in degrees")
    if theta.dtype.kind not in "iuf":
        _fail(where, "theta_deg", theta_deg, f"must be real angles in degrees, not {theta.dtype.kind!r}-typed "
              f"({type(theta_deg).__name__})")
    if theta.size == 0:
        _fail(where, "theta_deg", theta_deg, "must hold at least one angle")
    bad = ~((theta >= 0) & (theta <= 90))            # NaN is bad too
    if bad.any():
        _fail(where, "theta_deg", theta[bad].ravel()[:5], "must be finite angles in [0, 90] degrees")


@functools.lru_cache(maxsize=None)
def method_options(method) -> dict[str, inspect.Parameter]:
    """The options of an albedo method: the parameters of its function after (model, theta, rtol, atol).
    Read once per method (``inspect.signature`` cost a single-angle call more than its integration's
    bookkeeping); the dict returned is shared, not to be changed."""
    params = list(inspect.signature(method).parameters.values())[4:]
    return {p.name: p for p in params if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}


@functools.lru_cache(maxsize=None)
def _option_hints(method) -> dict:
    """The annotations of a method's options (``typing.get_type_hints``, read once per method)."""
    return typing.get_type_hints(inspect.unwrap(method), include_extras=True)


def _check_options(where, method, options):
    if not options:
        return
    valid = method_options(method)
    hints = _option_hints(method)
    for key, value in options.items():
        if key not in valid:
            listed = ", ".join(valid) if valid else "none"
            _fail(where, key, value, f"unknown option; the options of this method: {listed}")
        _check_option(where, key, value, hints.get(key))


def _check_option(where, key, value, hint):
    """``value`` against the annotation ``hint`` of its option (int, float, str, None, sequences of
    int, unions of these; Annotated with :class:`AtLeast` or :class:`OneOf`)."""
    if hint is None:
        return
    extras = ()
    if typing.get_origin(hint) is typing.Annotated:
        hint, *extras = typing.get_args(hint)
    if not _matches(value, hint):
        _fail(where, key, value, f"must be {_describe(hint)}, not {type(value).__name__}")
    for extra in extras:
        if isinstance(extra, AtLeast) and _is_real(value) and not value >= extra:
            _fail(where, key, value, f"must be >= {extra:g}")
        if isinstance(extra, AtLeast) and isinstance(value, (list, tuple, np.ndarray)) and not np.all(np.asarray(value) >= extra):
            _fail(where, key, value, f"must be >= {extra:g}")
        if isinstance(extra, Above) and _is_real(value) and not value > extra:
            _fail(where, key, value, f"must be > {extra:g}")
        if isinstance(extra, OneOf) and value not in extra:
            _fail(where, key, value, f"must be one of {', '.join(extra)}")


def _matches(value, hint) -> bool:
    if hint is type(None):
        return value is None
    if hint is int:
        return isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))
    if hint is float:
        return _is_real(value) and bool(np.isfinite(value))
    if hint is str:
        return isinstance(value, str)
    origin = typing.get_origin(hint)
    if origin in (typing.Union, getattr(__import__("types"), "UnionType", typing.Union)):
        return any(_matches(value, h) for h in typing.get_args(hint))
    if origin in (tuple, list, typing.Sequence) or (origin is not None and issubclass(origin, typing.Sequence)):
        (item,) = typing.get_args(hint)[:1] or (object,)
        return (isinstance(value, (list, tuple)) or (isinstance(value, np.ndarray) and value.ndim == 1)) \
            and len(value) > 0 and all(_matches(v, item) for v in value)
    return True


def _describe(hint) -> str:
    if hint is type(None):
        return "None"
    if hint in (int, float, str):
        return {"int": "an integer", "float": "a finite real number", "str": "a str"}[hint.__name__]
    args = typing.get_args(hint)
    if typing.get_origin(hint) in (typing.Union, getattr(__import__("types"), "UnionType", typing.Union)):
        return " or ".join(_describe(h) for h in args)
    return f"a sequence of {_describe(args[0])}" if args else str(hint)
