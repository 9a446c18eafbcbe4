# eotrack — the two commands a new user runs are `make repro` and `make test`.
# Every target sets up .venv from environment.txt first if it is missing or stale.
PY      := .venv/bin/python
STAMP   := .venv/.installed-stamp
NB_SAN  := tests/notebooks/sanitize.cfg

.PHONY: setup repro repro-quick repro-stability test check lint unit papers figures notebooks \
	browser ci lab bench mutation execute clean book durations

# pytest-xdist workers for the test targets (one per core of the 2-core reference machine);
# `make test JOBS=1` runs serially. Items are spread by file (--dist loadfile): a file's items
# stay together (nbval runs a notebook's cells in order in one kernel). Files are handed out
# longest first (./conftest.py orders them by tests/file_durations.json, `make durations`;
# --no-loadscope-reorder keeps that order instead of xdist's "most items first").
JOBS    ?= 2
XDIST   := $(if $(filter-out 1,$(JOBS)),-n $(JOBS) --dist loadfile --no-loadscope-reorder,)
NBVAL   := --nbval-lax --nbval-sanitize-with $(NB_SAN) --nbval-cell-timeout=600
K       ?= 5

# The stamp holds a hash of what the install depends on (environment.txt, and pyproject.toml less
# its [tool.*] sections other than [tool.setuptools*]): a newer file with the same content (a
# checkout, a ruff or pytest setting) does not reinstall; a changed pin or dependency does.
ENV_HASH = cat environment.txt && \
	awk '/^\[/{t=($$0 ~ /^\[tool\./ && $$0 !~ /^\[tool\.setuptools/)} !t' pyproject.toml
$(STAMP): environment.txt pyproject.toml
	@test -x $(PY) || python3 -m venv .venv
	@h=$$( ( $(ENV_HASH) ) | sha256sum | cut -d' ' -f1); \
	if [ "$$(cat $(STAMP) 2>/dev/null)" = "$$h" ]; then touch $(STAMP); exit 0; fi; \
	set -e; \
	$(PY) -m pip install -q --upgrade pip; \
	$(PY) -m pip install -q -r environment.txt; \
	$(PY) -m pip install -q --no-deps -e .; \
	echo "$$h" > $(STAMP)

setup: $(STAMP)

## the main job: every paper at its full trial counts -> papers_repro/<slug>/
repro: setup
	$(PY) -m eotrack.repro

repro-quick: setup
	$(PY) -m eotrack.repro --quick --out /tmp/eotrack-repro-quick

## every paper at its full counts on K independent root seeds (default 5) as well: writes
## papers_repro/<slug>/stability.json; the REPORTs show each claim's stability (fragile if any differs)
repro-stability: setup
	$(PY) -m eotrack.repro --seeds $(K) --no-progress

## the README's test command: lint, then unit + exercise + figure-lint + paper tests and every
## notebook (nbval) in one pytest run over $(JOBS) workers. The browser tests (JupyterLab in
## Chromium) are `make browser`; CI (.ci/run) runs both.
test: setup lint check

check: setup
	$(PY) -m pytest -q -p no:randomly $(XDIST) tests/unit tests/exercises tests/figures \
		tests/papers notebooks $(NBVAL)

## re-measure the seconds per test file that order `make test` (writes tests/file_durations.json)
durations: setup
	EOTRACK_WRITE_DURATIONS=1 $(PY) -m pytest -q -p no:randomly $(XDIST) tests/unit \
		tests/exercises tests/figures tests/papers notebooks $(NBVAL)

## CI's checks on this machine: make test, the browser tests, then nbval with AVX-512 off
ci: setup
	bash .ci/run

lint: setup
	$(PY) -m ruff check lib tests benchmarks notebooks/py .ci
	$(PY) .ci/check_twins.py

unit: setup
	$(PY) -m pytest -q $(XDIST) tests/unit tests/exercises

figures: setup
	$(PY) -m pytest -q $(XDIST) tests/figures

papers: setup
	$(PY) -m pytest -q $(XDIST) tests/papers

## nbval in lax mode: every cell runs and must not raise; only cells marked `# NBVAL_CHECK_OUTPUT`
## have their text compared (a notebook with no marked cell still runs). notebooks/ includes
## notebooks/solutions/; .ipynb_checkpoints/ is skipped (pytest ignores dot-directories).
## NB_FILES: the notebooks (files or folders) to run; .ci/run's AVX-512-off pass names those
## the browser stage does not run
NB_FILES ?= notebooks
notebooks: setup
	$(PY) -m pytest -q -p no:randomly $(XDIST) $(NB_FILES) $(NBVAL)

browser: setup
	$(PY) -m pytest -q -rs tests/browser

## open the collection in JupyterLab: the server's root is the repository (README, REPORTs and
## ../papers_repro links resolve), landing on notebooks/00_index.ipynb; --allow-root only as root
LAB_OPEN := $(if $(wildcard notebooks/00_index.ipynb),notebooks/00_index.ipynb,notebooks)
LAB_ARGS ?=
lab: setup
	exec .venv/bin/jupyter lab --ServerApp.root_dir="$(CURDIR)" \
		--LabApp.default_url=/lab/tree/$(LAB_OPEN) \
		$$( [ "$$(id -u)" = 0 ] && echo --allow-root ) $(LAB_ARGS)

## the static HTML book of the stored notebooks (no re-execution; warnings fail) -> build/book
book: setup
	$(PY) -m sphinx -b html -E -a -W --keep-going -q -c notebooks/_book . build/book

## side-by-side timings against the peer libraries
bench: setup
	@for f in benchmarks/bench_*.py; do echo "== $$f"; $(PY) $$f || exit 1; done

## hand mutations of the core kernels (tests/mutations/): each must make a unit test fail;
## prints the mutation score (not part of `make test`)
mutation: setup
	$(PY) tests/mutations/run.py

## re-execute the notebooks from their .py twins and store the outputs in the .ipynb files
execute: setup
	$(PY) .ci/execute_notebooks.py

clean:
	rm -rf .venv .pytest_cache .hypothesis
