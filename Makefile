# Entry points (README "Quick start"): `make all` rebuilds every artifact, `make test` runs the tests,
# `make report` builds results/report.html. The checks of issue #15 (README "Checks"):
#   make check-reproducible  two clean rebuilds of a few artifacts give byte-identical CSV/PNG files
#   make check-crash         SIGKILL `make all TARGETS=...` mid-job, run it again: completes, reruns only what was cut
#   make check-cluster       a few artifacts through the generic cluster executor (workflow/cluster/)
#   make report-check        the report in headless Chromium (`make chromium` installs it; not in `all`)
#   make lint                snakemake --lint; fails on every message but the one README "Lint" explains
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
SNAKEMAKE := $(CURDIR)/$(BIN)/snakemake
export PYTHONPATH := $(CURDIR)/src
# Mitsuba's llvm_* variants load Debian's libLLVM 19 from here (`make llvm` installs it); expanded
# when a recipe runs, so it sees a library `make llvm` installed earlier in the same make.
export DRJIT_LIBLLVM_PATH ?= $(firstword $(wildcard /usr/lib/*/libLLVM-19.so /usr/lib/llvm-19/lib/libLLVM.so))
# A subset of the build: `make all TARGETS="results/tables/table_3_2_ward_cmax.png ..."` (default: everything).
TARGETS ?=
# Your own values over config.yaml: `make all CONFIGFILE=mine.yaml` (snakemake --configfile), checked first
# with one line for a missing file (Snakemake's own reading of a --configfile shows a stack).
CONFIGFILE ?=
CONFIG_ARGS = $(if $(CONFIGFILE),--configfile $(CONFIGFILE))
CHECK_CONFIG = $(if $(CONFIGFILE),$(BIN)/python -m brdfs.pipeline.config $(CONFIGFILE) || exit 1;)

# Every target that lets Snakemake write in this tree (all, report, clean) runs under an exclusive
# flock(1) on BUILD_LOCK. The kernel releases it when the last process holding it exits, killed or
# not, so it can never be stale. While holding it, a Snakemake lock left in .snakemake/locks can
# only be a killed run's (every writing run of this Makefile holds the flock), and is cleared with
# `snakemake --unlock`: after a crash (SIGKILL, power loss) `make all` just runs again, and
# rerun-incomplete (the profiles) reruns the cut jobs. A second build while one runs fails at once
# with one line (waiting would look like a hang and then only redo or re-check the first build's work).
# Not covered: a plain `snakemake` (no flock) still running when `make all` starts, whose lock
# `make all` would take for stale (README "Crashes").
BUILD_LOCK := .snakemake/make.lock
# A whole `make all` (no TARGETS, no CONFIGFILE) that succeeds touches BUILD_COMPLETE (brdfs.pipeline.io.
# BUILD_COMPLETE): Snakemake judged every result up to date by content then, so the regression check of
# results/ (brdfs.pipeline.regression) counts a CSV stale only if its code or config.yaml changed after
# that; by file times alone a CSV whose config values stayed while a comment of config.yaml changed was stale.
BUILD_COMPLETE := .snakemake/complete_build
MARK_COMPLETE = $(if $(TARGETS)$(CONFIGFILE),true,touch $(BUILD_COMPLETE))
BUILD_LOCK_BUSY := 75
# $(call locked,COMMANDS): run COMMANDS (a shell string without single quotes) holding BUILD_LOCK.
define locked
command -v flock >/dev/null || { echo "make $@: needs flock(1) (util-linux)" >&2; exit 1; }; \
mkdir -p $(dir $(BUILD_LOCK)); \
flock --nonblock --conflict-exit-code $(BUILD_LOCK_BUSY) $(BUILD_LOCK) sh -ec '$(1)' || { rc=$$?; \
  if [ $$rc -eq $(BUILD_LOCK_BUSY) ]; then echo "make $@: another build is running (lock held: $(CURDIR)/$(BUILD_LOCK))" >&2; fi; \
  exit $$rc; }
endef
# Inside $(call locked,...) only: the results whose bytes are not those their job wrote (truncated, edited by
# hand, or from a build that recorded no digests; brdfs.pipeline.io), for `--forcerun`: `make all` rebuilds them.
FORCE_DAMAGED = damaged=$$($(BIN)/python -m brdfs.pipeline.io damaged)
# Inside $(call locked,...) only: remove the results no rule writes any more (of an artifact, a rule or a batch
# that is gone, a killed job's hidden temporary; brdfs.pipeline.registry.stale_results), saying so in one line.
REMOVE_STALE = $(BIN)/python -m brdfs.pipeline.registry remove-stale
# The pre-loaded parent of the artifact jobs (brdfs.pipeline.zygote): started beside Snakemake, gone with it.
ZYGOTE := .snakemake/zygote.sock
START_ZYGOTE = $(BIN)/python -m brdfs.pipeline.zygote $(ZYGOTE) & zygote=$$!; trap "kill $$zygote 2>/dev/null || true" EXIT; export BRDFS_ZYGOTE=$(CURDIR)/$(ZYGOTE)
# Inside $(call locked,...) only: clear the lock a killed Snakemake run left behind.
UNLOCK_STALE = if [ -n "$$(ls -A .snakemake/locks 2>/dev/null)" ]; then \
  echo "make $@: clearing the Snakemake lock of a run that was killed (snakemake --unlock)"; \
  out=$$($(SNAKEMAKE) --unlock 2>&1) || { echo "$$out" >&2; exit 1; }; fi

.PHONY: all test venv compiled llvm docs docs-check sweep sweep-truths renders-final check-mutations benchmark clean baseline lock report report-check chromium lint \
        check-reproducible check-crash check-cluster check-slurm-plan check-wheel checks

# Exact versions and hashes of every (transitive) dependency of the pipeline, cluster, render, docs, fast
# and test extras from requirements.lock, then the package itself (its core needs only numpy, scipy).
$(STAMP): requirements.lock pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet --require-hashes -r requirements.lock
	$(BIN)/pip install --quiet -e . --no-deps
	touch $(STAMP)

venv: $(STAMP)

# numba's cache of the compiled single-angle routes (brdfs.numerics.compiled_cache): compiled once
# here (about half a minute on a fresh clone), loaded in a fraction of a second by every later
# process; a route whose own source or any brdfs module it imports changed is compiled again
# (brdfs.core.compiled.drop_stale_cache), about a second when nothing did.
compiled: $(STAMP)
	@$(BIN)/python -m brdfs.numerics.compiled_cache

# Debian's libllvm19 for Mitsuba's llvm variants (idempotent; as root it apt-get installs it,
# elsewhere it prints the one command to run). `all` and `test` call it.
llvm:
	@workflow/scripts/ensure_llvm.sh

LOCK_EXTRAS := --extra pipeline --extra cluster --extra render --extra docs --extra fast --extra test
# Regenerate requirements.lock after changing the dependencies in pyproject.toml (keeps every
# existing pin; `--upgrade` is yours to add).
lock: $(STAMP)
	$(BIN)/pip install --quiet pip-tools==7.6.2
	$(BIN)/pip-compile --quiet $(LOCK_EXTRAS) --strip-extras --generate-hashes --no-emit-index-url \
	    --no-emit-find-links --output-file requirements.lock pyproject.toml

# The package as a user installs it: a wheel, in fresh virtual environments with only its required
# dependencies (numpy, scipy), computes every model's albedo there and imports none of the extras;
# once with the newest numpy/scipy on this Python, once at the lower bounds on Python 3.10
# (requires-python). Not part of `make test` (it downloads and builds; about a minute).
check-wheel: $(STAMP)
	PYTHON=$(PYTHON) workflow/scripts/check_wheel.sh

# The whole build: one job per artifact, as a plain `snakemake` plans it (the default profile).
all: llvm $(STAMP)
	@$(CHECK_CONFIG) $(call locked,$(UNLOCK_STALE); $(REMOVE_STALE); $(FORCE_DAMAGED); $(START_ZYGOTE); set -x; $(SNAKEMAKE) --profile workflow/profiles/default $(CONFIG_ARGS) $(TARGETS) $${damaged:+--forcerun $$damaged} && $(MARK_COMPLETE))

# Lint first (a few seconds), then the tests (the explorer's run in headless Chromium: `make chromium`).
test: llvm chromium $(STAMP) compiled lint
	$(BIN)/python -m pytest -n 2

benchmark: llvm $(STAMP)
	$(BIN)/python benchmarks/bench_engine_speed.py
	$(BIN)/python benchmarks/bench_mitsuba_plugins.py
	$(BIN)/python benchmarks/bench_patch_plugins.py
	$(BIN)/python benchmarks/render_old_vs_new.py
	$(BIN)/python benchmarks/bench_tables.py
	$(BIN)/python benchmarks/bench_model_cost.py
	$(BIN)/python benchmarks/bench_he_torrance.py
	$(BIN)/python benchmarks/bench_albedo_curves.py
	$(BIN)/python benchmarks/bench_work_precision.py
	$(BIN)/python benchmarks/bench_sampling.py
	$(BIN)/python benchmarks/bench_explorer.py
	$(BIN)/python benchmarks/bench_checked_calls.py
	$(BIN)/python benchmarks/bench_many_angles.py --ggx-million
	$(BIN)/python benchmarks/bench_job_startup.py --preamble snakemake
	$(BIN)/python benchmarks/bench_job_startup.py --preamble snakemake --zygote

# The renders at the publication preset (config.yaml renders.final): a changed config section reruns
# the render jobs, and only them.
renders-final: llvm $(STAMP)
	@$(call locked,$(UNLOCK_STALE); set -x; $(SNAKEMAKE) --profile workflow/profiles/default --config "renders={preset: final}" $(TARGETS))

# The eleven deliberate renderer faults (issue 23's six, mis_weights_apart, issue 42's fresnel_at_theta_l,
# tangent_flipped, clamp_direct and clamp_half_kept), each in a temporary copy; a named test must fail.
check-mutations: llvm $(STAMP)
	bash workflow/scripts/check_mutations.sh

# The documentation (README "Documentation"): Sphinx on docs/, built from results/ (the whole build
# first), warnings as errors; -E re-reads every page so that no warning hides in a cached one.
DOCS_HTML := docs/_build/html
docs: all
	$(BIN)/sphinx-build -E -W --keep-going -q -b html docs $(DOCS_HTML)
	@echo "docs: $(CURDIR)/$(DOCS_HTML)/index.html"

# The built docs in headless Chromium (`make chromium` installs it): every image loads, no internal
# link is broken; screenshots go to docs/_build/check.
docs-check: docs chromium
	$(BIN)/python workflow/scripts/docs_check.py $(DOCS_HTML) docs/_build/check

# The independent sweep of issue 24 (sweep/: a third route importing nothing from brdfs.numerics):
# albedo() by its default method, the engine and the disk against tests/data/sweep_truths.csv;
# per-family report in results/benchmarks/sweep_summary.{csv,md}. sweep-truths computes the truths
# still missing (resumable; on a quiet machine).
sweep: $(STAMP)
	nice -n 10 $(BIN)/python -m sweep.check --out results/benchmarks --workers 2

sweep-truths: $(STAMP)
	nice -n 10 $(BIN)/python -m sweep.tables
	nice -n 10 $(BIN)/python -m sweep.compute_truths --resume tests/data/sweep_truths.csv

# Re-record the regression baselines after a deliberate, reviewed change of numbers: the published rows
# (computed in-process) and every CSV of a fresh build (results/ after `make all`); then the data
# dictionary of those CSVs from docs/contract.md (it names every column the contract does not cover).
baseline: all
	$(BIN)/python -m brdfs.pipeline.regression --write tests/data/regression_baseline.csv
	$(BIN)/python -m brdfs.pipeline.regression --write-results tests/data/results_baseline
	$(BIN)/python -m brdfs.pipeline.data_dictionary

# The self-contained HTML report of the whole build (builds what is missing first).
report: all
	@$(call locked,$(UNLOCK_STALE); set -x; $(SNAKEMAKE) --cores 1 --report results/report.html)

# Debian's Chromium for the explorer's browser tests (`make test`), report-check and docs-check
# (idempotent; as root it apt-get installs it, elsewhere it prints the one command to run).
chromium:
	@workflow/scripts/ensure_chromium.sh

report-check: report chromium
	$(BIN)/python workflow/scripts/report_check.py results/report.html results/report_check

# Lint (both planning modes): fails on any message but the conda environment per rule, which the
# README explains (workflow/scripts/lint_check.py).
lint: $(STAMP)
	$(BIN)/python workflow/scripts/lint_check.py --snakemake $(SNAKEMAKE)

check-reproducible: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_reproducible.sh

# `make all TARGETS=...` in a copy, SIGKILLed mid-job, then the same `make all` (workflow/scripts/check_crash.sh).
check-crash: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_crash.sh

check-cluster: $(STAMP)
	SNAKEMAKE=$(SNAKEMAKE) workflow/scripts/check_cluster.sh

# The SLURM profile plans the whole workflow (a dry run; no SLURM needed).
check-slurm-plan: $(STAMP)
	$(SNAKEMAKE) -n --profile workflow/profiles/slurm > /dev/null && echo "slurm profile: dry run plans"

checks: check-reproducible check-crash check-cluster check-slurm-plan check-wheel lint

# Under the build lock (not while a build runs), and keeping the lock file itself.
clean:
	@$(call locked,set -x; rm -rf results .cluster-jobs docs/_build docs/recomputed docs/api docs/models docs/data_dictionary.rst; find .snakemake -mindepth 1 -maxdepth 1 ! -name $(notdir $(BUILD_LOCK)) -exec rm -rf {} +)
