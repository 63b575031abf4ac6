"""The front door answers as it did before its plan → run → merge refactor (issue 41): 1,500-odd
stored cells (``tests/data/front_door_cells.npz``, recorded by :mod:`front_door_cells` on the code
before the change) — every registered model at its examples, angles from 0° through 1e-6° to
90° − 1e-9° and 90°, two tolerances, single angles, a 2-D array, every method, ``albedo_table`` and
``albedo_pairs`` on mixed models — held to the bit: value, error, status, route, the call's
evaluations, whether it warned and its shape."""
import functools

import numpy as np
import pytest

from brdfs.core.compiled import numpy_only

from front_door_cells import DATA, WITHIN_ERRORS, answer, calls

CALLS = calls()


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
    with numpy_only():                   # the reference path, to the bit (compiled routes: their own tests)
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
