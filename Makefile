# The commands of the README: `make run`, `make test` and `make docs`.
# Each builds the virtual environment .venv if it is missing; every install is
# constrained to the tested versions (constraints.txt).
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
PIP := $(BIN)/python -m pip install --quiet -c constraints.txt

.PHONY: run test docs bench clean

$(STAMP): pyproject.toml constraints.txt
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(PIP) -e '.[test,dask,export,explore]'
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/mechopt reproduce all
	$(BIN)/mechopt report results --out results/report.html

# The suite starts a few hundred interpreters (workers, pools, command-line runs): with
# bytecode caches, Python's default, which PYTHONDONTWRITEBYTECODE turns off where it is
# set, none of them compiles the package's sources again (about 50 s of CPU).
test: $(STAMP)
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m compileall -q mechopt problems experiments tests
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -q -n 2

# the API reference (autodoc + numpydoc), the tutorials and the output reference
# (myst-parser), warnings as errors; the docs extra is installed when missing
docs: $(STAMP)
	$(BIN)/python -c "import sphinx, numpydoc, myst_parser" 2>/dev/null || $(PIP) -e '.[docs]'
	$(BIN)/sphinx-build -W --keep-going -b html docs build/docs

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_lci.py

clean:
	rm -rf $(VENV) build *.egg-info
