"""The `make benchmark` scripts import against the current package (they are not run by the suite:
wall times are measured only by `make benchmark`)."""
import importlib.util
from pathlib import Path

import pytest

BENCHMARKS = sorted((Path(__file__).resolve().parents[2] / "benchmarks").glob("bench_*.py"))


def test_every_benchmark_script_is_found():
    assert len(BENCHMARKS) >= 5


@pytest.mark.parametrize("path", BENCHMARKS, ids=lambda p: p.stem)
def test_benchmark_script_imports_and_has_a_main(path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)          # a moved or renamed package name fails here
    assert callable(getattr(module, "main", None))
