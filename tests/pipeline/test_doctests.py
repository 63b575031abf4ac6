"""The examples in the docstrings of every package module run and hold."""

import doctest
import importlib
import pkgutil

import pytest

import brdfs

MODULES = sorted(m.name for m in pkgutil.walk_packages(brdfs.__path__, "brdfs."))
WITH_EXAMPLES = [m for m in MODULES if ">>>" in (importlib.util.find_spec(m).loader.get_source(m) or "")]


def test_several_modules_have_examples():
    assert len(WITH_EXAMPLES) >= 5, WITH_EXAMPLES


@pytest.mark.parametrize("name", WITH_EXAMPLES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name))
    assert result.attempted > 0 and result.failed == 0
