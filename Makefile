# Entry points (README "Quick start"): `make all` rebuilds every artifact, `make test` runs the tests,
# `make report` builds results/report.html. The checks of issue #15 (README "Checks"):
#   make check-reproducible  two clean rebuilds of a few artifacts give byte-identical CSV/PNG files
#   make check-crash         SIGKILL in the middle of a rule, rerun: completes, reruns only what was cut
#   make check-cluster       a few artifacts through the generic cluster executor (workflow/cluster/)
#   make report-check        the report in headless Chromium (`make chromium` installs it; not in `all`)
#   make lint                snakemake --lint
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
SNAKEMAKE := $(CURDIR)/$(BIN)/snakemake
export PYTHONPATH := $(CURDIR)/src

.PHONY: all test venv benchmark clean baseline lock report report-check chromium lint \
        check-reproducible check-crash check-cluster check-slurm-plan checks

# Exact versions of every (transitive) dependency from requirements.lock, then the package itself.
$(STAMP): requirements.lock pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -r requirements.lock
	$(BIN)/pip install --quiet -e . --no-deps
	touch $(STAMP)

venv: $(STAMP)

# Regenerate requirements.lock after changing the dependencies in pyproject.toml.
lock: $(STAMP)
	$(BIN)/pip install --quiet pip-tools==7.6.2
	$(BIN)/pip-compile --quiet --extra test --strip-extras --no-emit-index-url --no-emit-find-links \
	    --output-file requirements.lock pyproject.toml

# The full build batches cheap artifacts (workflow/profiles/full: --config batches=true).
all: $(STAMP)
	$(SNAKEMAKE) --profile workflow/profiles/full

test: $(STAMP)
	$(BIN)/python -m pytest -n 2

benchmark: $(STAMP)
	$(BIN)/python benchmarks/bench_tables.py
	$(BIN)/python benchmarks/bench_model_cost.py
	$(BIN)/python benchmarks/bench_albedo_curves.py
	$(BIN)/python benchmarks/bench_work_precision.py
	$(BIN)/python benchmarks/bench_sampling.py

# Re-record the regression baseline after a deliberate, reviewed change of numbers.
baseline: $(STAMP)
	$(BIN)/python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv

# The self-contained HTML report of the whole build (builds what is missing first).
report: all
	$(SNAKEMAKE) --cores 1 --report results/report.html

# Debian's Chromium, for report-check only (needs root; does nothing when already installed).
chromium:
	@command -v chromium >/dev/null 2>&1 || (apt-get update && apt-get install -y chromium)

report-check: report chromium
	$(BIN)/python workflow/scripts/report_check.py results/report.html results/report_check

# Lint; the one remaining message (a conda environment per rule) is explained in the README.
lint: $(STAMP)
	$(SNAKEMAKE) --lint || true

check-reproducible: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_reproducible.sh

check-crash: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_crash.sh

check-cluster: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_cluster.sh

# The SLURM profile plans the whole workflow (a dry run; no SLURM needed).
check-slurm-plan: $(STAMP)
	$(SNAKEMAKE) -n --profile workflow/profiles/slurm > /dev/null && echo "slurm profile: dry run plans"

checks: check-reproducible check-crash check-cluster check-slurm-plan lint

clean:
	rm -rf results .snakemake .cluster-jobs
