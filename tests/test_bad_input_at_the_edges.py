"""Bad input at the edges (issue 26): at θ = 90°, at the ends of every model's declared parameter
ranges and at the parameter values the thesis prints (data/published_values.csv), every front-door
albedo() call answers with a finite value, or +inf with status ``diverged``, or a value whose
shortfall is reported as such (a status other than ``converged`` and a NotConvergedWarning)."""
import math
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from brdfs import NotConvergedWarning, albedo, model
from brdfs.core.estimate import CONVERGED, DIVERGED
from brdfs.numerics.tables import pump
from brdfs.physics.models import MODELS

RTOL = 1e-6
ANGLES = np.array([0.0, 45.0, 89.9, 90.0])
PUBLISHED = Path(__file__).resolve().parents[1] / "data" / "published_values.csv"
def _ends(cls):
    """Parameter sets at the ends of the declared ranges: each closed finite end, and 10 times the
    typical value where the range is unbounded above; the "narrowest" example stands for the open
    end at 0 (the sharpest lobe the package treats)."""
    typical = cls.examples["typical"]
    sets = [dict(cls.examples.get("narrowest", typical))]
    for key, interval in cls.param_ranges.items():
        ends = [end for end, is_open in ((interval.lo, interval.lo_open), (interval.hi, interval.hi_open))
                if np.isfinite(end) and not is_open]
        if np.isinf(interval.hi) and isinstance(typical.get(key), float) and typical[key] > 0:
            ends.append(10.0 * typical[key])
        sets += [{**typical, key: end} for end in ends]
    return [dict(items) for items in dict.fromkeys(tuple(s.items()) for s in sets)]     # each set once


def _published():
    """(model, {param: value}) of every printed row whose parameter value is a finite number."""
    df = pd.read_csv(PUBLISHED, dtype=str)
    out = set()
    for name, param, value in df[["model", "param", "param_value"]].itertuples(index=False):
        try:
            number = float(value)
        except (TypeError, ValueError):
            continue                                    # "<0.2", a metal's name
        if name in MODELS and math.isfinite(number):
            out.add((name, param, number))
    return sorted(out)


def _built(name, params):
    """The model, or None where the model itself refuses this combination (one line, a ValueError)."""
    try:
        return model(name, **params)
    except ValueError as exc:
        assert "\n" not in str(exc)
        return None


def _assert_answered(brdf, label, rtol=RTOL, angles=ANGLES):
    """Every angle of ``angles`` answered: finite, or +inf and diverged at 90°, or reported short."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        est = albedo(brdf, angles, rtol=rtol)
    warned = any(issubclass(w.category, NotConvergedWarning) for w in caught)
    for theta, value, error, status in zip(angles, est.value, est.error, est.status):
        where = f"{label} at {theta} deg: {value} +- {error} ({status})"
        if status == DIVERGED:
            assert value == np.inf and error == 0.0 and theta == 90.0, where
            continue
        assert np.isfinite(value) and np.isfinite(error) and error >= 0, where
        assert status == CONVERGED or warned, where


CASES = [(name, p) for name, cls in MODELS.items() for p in _ends(cls)]


def _case_id(name, params):
    """A stable test id (a weight function by its name, not its address: xdist collects the same ids)."""
    return f"{name}-" + ",".join(f"{k}={getattr(v, '__name__', v)}" for k, v in params.items())


@pytest.mark.parametrize("name, params", CASES, ids=[_case_id(n, p) for n, p in CASES])
def test_every_model_at_the_ends_of_its_ranges_and_at_90_degrees_answers_or_says_why_not(name, params):
    brdf = _built(name, params)
    if brdf is not None:
        _assert_answered(brdf, f"{name}{params}")


def test_every_printed_parameter_value_answers_or_says_why_not():
    rows = _published()
    assert len(rows) >= 50
    for name, param, value in rows:
        brdf = _built(name, {**MODELS[name].examples["typical"], param: value})
        if brdf is not None:
            _assert_answered(brdf, f"{name} {param}={value}")


@pytest.mark.parametrize("name", ["phong", "blinn"])
def test_a_pumped_model_at_90_degrees_answers(name):
    _assert_answered(pump(model(name, n=20.0), target_rtol=1e-6, engine_rtol=1e-9), f"pumped {name}")
