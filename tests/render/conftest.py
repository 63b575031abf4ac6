"""Shared fixtures of the render tests: Mitsuba in its JIT variant with the package's plugins.

``mitsuba`` (session): ``llvm_ad_rgb`` with every plugin registered; the render tests are skipped with
the one-line reason of :data:`brdfs.render.mitsuba.MISSING_LLVM` on a machine without libllvm19.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))       # the chi-square harness _chi2.py


@pytest.fixture(scope="session")
def mitsuba():
    """The ``mitsuba`` module in ``llvm_ad_rgb`` with the package's plugins registered."""
    from brdfs.render.mitsuba import MissingLLVM, register_plugins, use_variant
    try:
        mi = use_variant("llvm_ad_rgb")
    except MissingLLVM as exc:
        pytest.skip(str(exc))
    register_plugins()
    return mi
