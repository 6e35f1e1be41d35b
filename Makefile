# Two commands do all set-up on a fresh machine:
#   make test   create .venv if missing, install tribodyn with its test extras, lint, run pytest
#   make run    install what running needs (no test tools), compile the numerical kernels
#               into numba's cache (tribodyn warmup), then run the main job on the paper case
#               with its figures (the paper's Figs. 5–18 among them)
#   make docs   build the documentation site into docs/_build/html (warnings are errors)
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python
OUT    ?= results
STAMP   = $(VENV)/.installed
RUN_STAMP = $(VENV)/.installed-run

.PHONY: test lint run bench docs clean

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test]"
	touch $(STAMP)

lint: $(STAMP)
	$(VENV)/bin/ruff check src tests benchmarks
	$(VENV)/bin/ruff format --check src tests benchmarks
	$(VENV)/bin/mypy

test: lint
	$(PY) -m pytest -q

# running needs the package alone; the kernels are compiled once here, not in the first run
$(RUN_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e .
	$(VENV)/bin/tribodyn warmup
	touch $(RUN_STAMP)

run: $(RUN_STAMP)
	$(VENV)/bin/tribodyn run --figures -o $(OUT)

DOCS_STAMP = $(VENV)/.docs-installed

$(DOCS_STAMP): $(STAMP)
	$(PY) -m pip install --quiet -e ".[docs]"
	touch $(DOCS_STAMP)

# The documentation site (Sphinx, PyData theme, MyST); warnings are errors.
docs: $(DOCS_STAMP)
	$(PY) -m sphinx -W --keep-going -b html docs docs/_build/html

bench: $(STAMP)
	for b in benchmarks/bench_*.py; do echo "== $$b"; $(PY) $$b; done

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache build src/*.egg-info docs/_build
