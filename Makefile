# eotrack — the two commands a new user runs are `make repro` and `make test`.
# Every target sets up .venv from environment.txt first if it is missing or stale.
PY      := .venv/bin/python
STAMP   := .venv/.installed-stamp
NB_SAN  := tests/notebooks/sanitize.cfg

.PHONY: setup repro repro-quick test lint unit papers notebooks browser lab bench execute clean

$(STAMP): environment.txt pyproject.toml
	@test -x $(PY) || python3 -m venv .venv
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r environment.txt
	$(PY) -m pip install -q --no-deps -e .
	@touch $(STAMP)

setup: $(STAMP)

## the main job: every paper at its full trial counts -> papers_repro/<slug>/
repro: setup
	$(PY) -m eotrack.repro

repro-quick: setup
	$(PY) -m eotrack.repro --quick --out /tmp/eotrack-repro-quick

## lint, unit tests, paper tests, notebooks (nbval), browser test
test: setup lint unit papers notebooks browser

lint: setup
	$(PY) -m ruff check lib tests benchmarks notebooks/py
	$(PY) .ci/check_twins.py

unit: setup
	$(PY) -m pytest -q tests/unit

papers: setup
	$(PY) -m pytest -q tests/papers

notebooks: setup
	$(PY) -m pytest -q -p no:randomly --nbval-lax notebooks --nbval-sanitize-with $(NB_SAN) \
		--nbval-cell-timeout=600

browser: setup
	$(PY) -m pytest -q -rs tests/browser

## open the notebooks in JupyterLab
lab: setup
	.venv/bin/jupyter lab notebooks

## side-by-side timings against the peer libraries
bench: setup
	@for f in benchmarks/bench_*.py; do echo "== $$f"; $(PY) $$f || exit 1; done

## re-execute the notebooks from their .py twins and store the outputs in the .ipynb files
execute: setup
	$(PY) .ci/execute_notebooks.py

clean:
	rm -rf .venv .pytest_cache .hypothesis
