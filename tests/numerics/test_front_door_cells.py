"""The front door answers as it did before its plan → run → merge refactor (issue 41): 1,500-odd
stored cells (``tests/data/front_door_cells.npz``, recorded by :mod:`front_door_cells` on the code
before the change) — every registered model at its examples, angles from 0° through 1e-6° to
90° − 1e-9° and 90°, two tolerances, single angles, a 2-D array, every method, ``albedo_table`` and
``albedo_pairs`` on mixed models — held to the bit: value, error, status, route, the call's
evaluations, whether it warned and its shape."""
import functools

import numpy as np
import pytest

from brdfs.core import compiled
from brdfs.numerics.integrate import azimuthal
from brdfs.physics.models import MODELS
from front_door_cells import DATA, WITHIN_ERRORS, answer, calls
from test_azimuthal_compiled import ERRORS_APART, GRAZING, ULPS

CALLS = calls()
#: The single-angle cells the compiled azimuthal route answers (:func:`.azimuthal.compiled_spec`):
#: held to the stored (numpy) cells within ``test_azimuthal_compiled``'s stated ulps and errors apart.
COMPILED = [k for k, (label, name, call) in enumerate(CALLS)    # the single cells are of typical examples
            if label.startswith("single ") and azimuthal.compiled_spec(MODELS[name].example("typical")) is not None]


@functools.cache
def _stored():
    with np.load(DATA) as data:
        return {k: data[k] for k in data.files}


def test_the_store_holds_over_a_thousand_cells_of_every_registered_model():
    import brdfs
    stored = _stored()
    assert stored["value"].size >= 1000 and list(stored["label"]) == [label for label, *_ in CALLS]
    assert set(brdfs.MODELS) <= set(stored["name"])


@pytest.mark.parametrize("k", range(len(CALLS)), ids=[label for label, *_ in CALLS])
def test_the_front_door_gives_the_stored_answer(k):
    label, name, call = CALLS[k]
    stored = _stored()
    rows = stored["call"] == k
    with compiled.numpy_only():          # the numpy path: the reference, to the bit
        value, error, status, route, evaluations, warned, shape = answer(call)
    ndim = stored["per_call"][k, 2]
    assert shape == tuple(stored["per_call"][k, 3:3 + ndim]) and warned == bool(stored["per_call"][k, 1])
    assert list(route) == list(stored["route"][rows]) and list(status) == list(stored["status"][rows])
    if name in WITHIN_ERRORS:            # moved on purpose by another change: within the two errors
        assert np.all(np.abs(value - stored["value"][rows]) <= error + stored["error"][rows])
        return
    np.testing.assert_array_equal(value, stored["value"][rows])
    np.testing.assert_array_equal(error, stored["error"][rows])
    assert evaluations == stored["per_call"][k, 0]


@pytest.mark.skipif(not compiled.available(), reason="numba (the optional extra 'fast') is not installed")
def test_the_compiled_route_gives_the_stored_single_angle_cells_within_ulps():
    assert len(COMPILED) >= 10
    stored = _stored()
    for k in COMPILED:
        label, name, call = CALLS[k]
        rows = stored["call"] == k
        value, error, status, route, evaluations, warned, shape = answer(call)
        assert list(route) == list(stored["route"][rows]) and list(status) == list(stored["status"][rows]), label
        assert warned == bool(stored["per_call"][k, 1]) and evaluations == stored["per_call"][k, 0], label
        theta = float(label.split()[-1])                 # "single <model>/typical <angle>"
        ulps = ULPS + GRAZING / np.cos(np.radians(theta))
        np.testing.assert_allclose(value, stored["value"][rows], rtol=ulps * np.finfo(float).eps, atol=0, err_msg=label)
        np.testing.assert_allclose(error, stored["error"][rows], rtol=ERRORS_APART, atol=0, err_msg=label)
