"""Fixtures shared across test modules."""
import pytest

from brdfs.pipeline.registry import compute_all_comparisons
from brdfs.pipeline.config import load_config


@pytest.fixture(scope="session")
def all_comparisons():
    """Every comparison row of the configured pipeline, computed once per test session."""
    return compute_all_comparisons(load_config())
