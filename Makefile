# Two entry points (see README "Quick start"): `make all` rebuilds every artifact, `make test` runs the tests.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: all test venv benchmark clean baseline

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e '.[test]'
	touch $(STAMP)

venv: $(STAMP)

all: $(STAMP)
	$(BIN)/snakemake --profile workflow/profiles/default

test: $(STAMP)
	$(BIN)/python -m pytest

benchmark: $(STAMP)
	$(BIN)/python benchmarks/bench_tables.py
	$(BIN)/python benchmarks/bench_sampling.py

# Re-record the regression baseline after a deliberate, reviewed change of numbers.
baseline: $(STAMP)
	$(BIN)/python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv

clean:
	rm -rf results .snakemake
