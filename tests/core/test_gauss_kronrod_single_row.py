"""A single element's first intervals (``gauss_kronrod._initial_intervals`` of one row, whose rows that
ascend strictly between finite ends skip the masks) are the batch path's, row by row: NaN padding, repeated
points, infinite ends and descending pairs are dropped alike."""
import numpy as np
import pytest

from brdfs.core import gauss_kronrod

ROWS = [[0.0, 0.5, np.nan], [0.0, 0.5, 0.5, 1.0], [0.3], [-np.inf, 0.0, 1.0], [0.0, 1.0, np.inf],
        [0.0, np.nan, 1.0], [1.0, 0.0], [0.0, 1.0], [np.nan, np.nan], [0.0, 0.25, 0.75, 1.0]]


def _as_in_a_batch(row):
    """The row's intervals as the batch path finds them (the row beside a second one)."""
    elem, lo, hi = gauss_kronrod._initial_intervals(np.array([row, [0.0] * len(row)]))
    return lo[elem == 0], hi[elem == 0]


@pytest.mark.parametrize("row", ROWS + [sorted(np.random.default_rng(k).random(k + 2)) for k in range(8)],
                         ids=lambda r: str(np.round(r, 2).tolist()))
def test_a_single_rows_intervals_are_the_batch_paths(row):
    elem, lo, hi = gauss_kronrod._initial_intervals(np.array([row], float))
    batch_lo, batch_hi = _as_in_a_batch(row)
    np.testing.assert_array_equal(lo, batch_lo)
    np.testing.assert_array_equal(hi, batch_hi)
    assert elem.dtype == np.intp and elem.size == lo.size and not elem.any()
