# tvtrack-repro: `make reproduce` (the main job) and `make test`. See README.md.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: reproduce test bench report site screenshots kernel sweep edit clean-runs hooks lint mutate mutate-ci

$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q -r environment.txt
	$(BIN)/python -m pip install -q --no-deps -e .
	@# pip compiles what it installs but not an editable checkout: compile lib/ once here, so each process (a
	@# kernel, a pool worker, a CLI call) reads bytecode instead of compiling the sources it imports
	$(BIN)/python -m compileall -q lib/tvtrack
	$(MAKE) --no-print-directory hooks
	touch $(STAMP)

# notebooks enter git without outputs (nbstripout as a git filter; see .gitattributes), so editing
# and running a notebook in JupyterLab never dirties a tracked file; the index is refreshed once here, so that
# the `git status` each run records does not pass every notebook of a fresh clone through the filter again
hooks:
	@if git rev-parse --git-dir >/dev/null 2>&1; then \
	  git config filter.nbstripout.clean "$(abspath $(BIN))/python -m nbstripout --keep-id"; \
	  git config filter.nbstripout.smudge cat; \
	  git config filter.nbstripout.required true; \
	  git config diff.ipynb.textconv "$(abspath $(BIN))/python -m nbstripout -t --keep-id"; \
	  git update-index -q --refresh >/dev/null 2>&1 || true; \
	fi

lint: $(STAMP)
	$(BIN)/ruff check lib tests benchmarks notebooks
	$(BIN)/ruff format --check lib tests benchmarks

# this clone's Jupyter kernel, in its own .venv (named tvtrack-repro-<digest of the clone's path>), so two clones
# never repoint each other's kernel; `make edit` opens working copies on it
kernel: $(STAMP)
	$(BIN)/python -m tvtrack.pipeline.kernels

# all notebooks side by side on the usable cores; make reproduce JOBS=1 PROFILE=smoke
# (another profile runs into papermill_runs/reproduce-<profile>/ and never replaces the paper runs);
# started again it resumes (runs finished at this commit are kept); FORCE=1 runs every notebook again
# (SCHEDULER=tcp://HOST:8786: the explorations on a Dask cluster; MAX_REPLICATES=N: every sizing cap; docs/scale.md)
reproduce: $(STAMP) kernel
	$(BIN)/python -m tvtrack reproduce $(if $(JOBS),--jobs $(JOBS)) $(if $(PROFILE),--profile $(PROFILE)) $(if $(FORCE),--force) \
		$(if $(SCHEDULER),--scheduler $(SCHEDULER)) $(if $(MAX_REPLICATES),--max-replicates $(MAX_REPLICATES))

report: $(STAMP)
	$(BIN)/python -m tvtrack report $(if $(PROFILE),--profile $(PROFILE))

# offline HTML site from papermill_runs/ (after make reproduce): papermill_runs/site/index.html
# (make site PROFILE=smoke: the smoke runs, in papermill_runs/site-smoke/)
# the README's screenshots (docs/screenshots/) from the paper runs: the site's first screen, a claim's page and a
# recording in the web viewer (make screenshots CLAIM=C004-1 RECORDING=004_laser_spot_prediction)
screenshots: $(STAMP)
	$(BIN)/python -m tvtrack screenshots $(if $(CLAIM),--claim $(CLAIM)) $(if $(RECORDING),--recording $(RECORDING))

site: $(STAMP)
	$(BIN)/python -m tvtrack site $(if $(PROFILE),--profile $(PROFILE))

# every core: test files are spread over pytest-xdist workers (one file stays on one worker, so its module
# fixtures run once); the notebooks' smoke runs are shared between workers (tests/conftest.py)
test: $(STAMP) lint
	$(BIN)/python -m pytest -q -n auto --dist loadfile --no-loadscope-reorder --durations=15

bench: $(STAMP)
	mkdir -p benchmarks/results
	$(BIN)/python -m pytest benchmarks -q --benchmark-only --benchmark-json=benchmarks/results/benchmarks.json

# mutation testing of the claim wiring (docs/mutation.md): mutmut over each module of mutation/targets.toml with the
# tests that pin it, one process, survivors per module (make mutate ONLY="verdicts claims_004"); not part of make test
mutate: $(STAMP)
	$(BIN)/python mutation/run.py $(if $(ONLY),--only $(ONLY))

# the sampled subset a CI job can afford (each target's `ci` patterns, about two minutes on two cores)
mutate-ci: $(STAMP)
	$(BIN)/python mutation/run.py --ci

# a working copy of a notebook at the smoke profile, opened in JupyterLab: make edit NB=004_laser_spot_prediction
# (as root, e.g. in a container, JupyterLab is started with --allow-root)
edit: $(STAMP) kernel
	$(BIN)/python -m tvtrack edit $(NB) --lab

# make sweep SPEC=papermill_runs/sweeps/004_horizon.toml JOBS=2
sweep: $(STAMP)
	$(BIN)/python -m tvtrack sweep $(SPEC) --jobs $(or $(JOBS),2)

clean-runs:
	rm -rf papermill_runs/reproduce papermill_runs/reproduce-* papermill_runs/runs papermill_runs/interactive papermill_runs/edit
	rm -rf .jit-cache
