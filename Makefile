# tvtrack-repro: `make reproduce` (the main job) and `make test`. See README.md.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: reproduce test bench report site kernel sweep clean-runs hooks lint

$(STAMP): environment.txt pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q -r environment.txt
	$(BIN)/python -m pip install -q --no-deps -e .
	$(MAKE) --no-print-directory hooks
	touch $(STAMP)

# notebooks enter git without outputs (nbstripout as a git filter; see .gitattributes), so editing
# and running a notebook in JupyterLab never dirties a tracked file
hooks:
	@if git rev-parse --git-dir >/dev/null 2>&1; then \
	  git config filter.nbstripout.clean "$(abspath $(BIN))/python -m nbstripout"; \
	  git config filter.nbstripout.smudge cat; \
	  git config filter.nbstripout.required true; \
	  git config diff.ipynb.textconv "$(abspath $(BIN))/python -m nbstripout -t"; \
	fi

lint: $(STAMP)
	$(BIN)/ruff check lib tests benchmarks notebooks

kernel: $(STAMP)
	$(BIN)/python -m ipykernel install --user --name tvtrack-repro --display-name "Python (tvtrack-repro)" >/dev/null

# all notebooks side by side on the usable cores; make reproduce JOBS=1 PROFILE=smoke
reproduce: $(STAMP) kernel
	$(BIN)/python -m tvtrack reproduce $(if $(JOBS),--jobs $(JOBS)) $(if $(PROFILE),--profile $(PROFILE))

report: $(STAMP)
	$(BIN)/python -m tvtrack report

# offline HTML site from papermill_runs/ (after make reproduce): papermill_runs/site/index.html
site: $(STAMP)
	$(BIN)/python -m tvtrack site

test: $(STAMP)
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	mkdir -p benchmarks/results
	$(BIN)/python -m pytest benchmarks -q --benchmark-only --benchmark-json=benchmarks/results/benchmarks.json

# make sweep SPEC=papermill_runs/sweeps/004_horizon.toml JOBS=2
sweep: $(STAMP)
	$(BIN)/python -m tvtrack sweep $(SPEC) --jobs $(or $(JOBS),2)

clean-runs:
	rm -rf papermill_runs/reproduce papermill_runs/runs papermill_runs/interactive
