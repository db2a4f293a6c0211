# Two entry points (see README): `make all` runs the workflow, `make test` the tests.
# Both create the virtual environment from environment.lock when it is missing, then
# install system packages only when the config needs them and they are missing
# (contactlab.setup_check: CalculiX and the gmsh wheel's libraries, for the FE branch).
VENV ?= .venv
PY := $(VENV)/bin/python
# rules call the `contactlab` command: put the environment first on PATH
export PATH := $(abspath $(VENV))/bin:$(PATH)
STAMP := $(VENV)/.installed
JOBS ?= 2
# The default profile (scheduler, rerun-incomplete, latency-wait, shown commands and failed
# logs). Snakemake looks for profiles/default/ only beside the Snakefile or the working
# directory, so it would not find ours; it also takes --profile from $SNAKEMAKE_PROFILE,
# which `activate` sets to this folder (HOOK below) unless it is set already, so that a
# bare `snakemake` uses it while the environment is active, as the Makefile's runs do.
PROFILE := $(abspath workflow/profiles/default)
HOOK := $(VENV)/.profile-hook
SNAKEMAKE := SNAKEMAKE_PROFILE="$${SNAKEMAKE_PROFILE:-$(PROFILE)}" $(VENV)/bin/snakemake

# system packages for the config files each entry point runs (merged in order)
SETUP_CHECK := $(PY) -m contactlab.setup_check

.PHONY: all test env ccx slurm-for-tests lint report lock rulegraph clean

all: $(HOOK)
	$(SETUP_CHECK) --config config/config.yaml
	$(SNAKEMAKE) -j$(JOBS) all

test: $(HOOK) slurm-for-tests
	$(SETUP_CHECK) --config config/config.yaml --config tests/e2e_config.yaml
	$(PY) -m pytest -n $(JOBS) tests

env: $(HOOK)

$(STAMP): environment.lock pyproject.toml
	test -x $(PY) || python3.11 -m venv $(VENV) || python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --require-hashes --no-deps -r environment.lock
	$(PY) -m pip install --quiet --no-deps --no-build-isolation -e .
	touch $(STAMP)

# activate sets SNAKEMAKE_PROFILE to $(PROFILE) when it is unset, deactivate unsets it
# again when it still names it (lines marked contactlab-profile, rewritten on each change
# of this Makefile)
$(HOOK): $(STAMP) Makefile
	sed -i '/# contactlab-profile$$/d' $(VENV)/bin/activate
	sed -i 's|^deactivate () {$$|&\n    if [ "$${SNAKEMAKE_PROFILE:-}" = "$(PROFILE)" ]; then unset SNAKEMAKE_PROFILE; fi  # contactlab-profile|' $(VENV)/bin/activate
	echo 'if [ -z "$${SNAKEMAKE_PROFILE:-}" ]; then SNAKEMAKE_PROFILE="$(PROFILE)"; export SNAKEMAKE_PROFILE; fi  # contactlab-profile' >> $(VENV)/bin/activate
	touch $(HOOK)

# What the FE branch needs whatever the config says: CalculiX (Debian calculix-ccx) unless
# ccx is on PATH or $CCX is set, and the gmsh wheel's libraries if gmsh does not import.
ccx: $(STAMP)
	$(SETUP_CHECK) --fe

# Not a cluster run (that is `snakemake --profile workflow/profiles/slurm all`, README):
# Slurm and munge for the cluster test (tests/test_slurm.py starts them with .ci/slurm-local),
# installed from Debian (slurm-wlm, munge) only when missing, and only as root; without
# root that test skips locally and fails in CI.
slurm-for-tests:
	@if command -v slurmctld >/dev/null && command -v slurmd >/dev/null \
	  && command -v munged >/dev/null; then :; \
	elif [ "$$(id -u)" = 0 ]; then .ci/slurm-local install; \
	else echo "note: slurm-wlm/munge missing and not root: tests/test_slurm.py will skip" >&2; fi

lint: $(STAMP)
	$(VENV)/bin/ruff check src tests benchmarks workflow
	$(VENV)/bin/snakemake --lint

report: $(STAMP)
	$(SNAKEMAKE) -j$(JOBS) all
	$(SNAKEMAKE) --report results/report/snakemake-report.zip

lock:
	@command -v uv >/dev/null || { echo "error: make lock needs uv (pip install uv)" >&2; exit 1; }
	uv pip compile --python-version 3.11 --generate-hashes --custom-compile-command "make lock" requirements.in -o environment.lock

rulegraph: $(STAMP)
	@command -v dot >/dev/null || { echo "error: make rulegraph needs graphviz's dot" \
	  "(Debian package graphviz)" >&2; exit 1; }
	$(VENV)/bin/snakemake --rulegraph dot all | dot -Tsvg > docs/rulegraph.svg
	$(VENV)/bin/snakemake --rulegraph mermaid-js all > docs/rulegraph.mmd

clean:
	rm -rf results .snakemake
