"""The examples in the docstrings run and hold."""

import doctest

import pytest

from brdfs import fresnel, published
from brdfs.artifacts import extra_metal_a0_readings


@pytest.mark.parametrize("module", [fresnel, published, extra_metal_a0_readings])
def test_docstring_examples(module):
    result = doctest.testmod(module)
    assert result.attempted > 0 and result.failed == 0
