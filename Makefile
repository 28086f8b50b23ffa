# halfedge_edu: `make lab` to work through the notebooks, `make test` to check everything.
# Both create .venv with $(PYTHON) and install the package into it on first use (a few
# minutes); later runs reuse it and start at once. Reinstalls when pyproject.toml changes.

PYTHON ?= python3
VENV ?= .venv
PYTEST_ARGS ?=
# The semester lock (pip constraints): every student and CI get the versions this
# semester was tested with, not whatever was released the night before a lab. `LOCK=`
# installs the newest versions within pyproject.toml's bounds instead. A lock that cannot
# install on this Python (no wheels for it) falls back to that too, saying so.
SEMESTER ?= 2026-fall
LOCK ?= constraints/$(SEMESTER).txt

PY := $(VENV)/bin/python
# What each target installs: `make lab` the notebooks extra (what a student needs),
# `make test` the dev extra (which includes it), `make bench` dev and bench.
NOTEBOOKS_STAMP := $(VENV)/.installed-notebooks
DEV_STAMP := $(VENV)/.installed-dev
BENCH_STAMP := $(VENV)/.installed-bench
WASM_EMPTY := $(abspath $(VENV))/vtk-wasm-empty
UNAME := $(shell uname -s)

# Running notebooks with no screen (tests, figure builds): see shared notes and conftest.py.
HEADLESS_ENV := PYVISTA_JUPYTER_BACKEND=static VTK_WASM_DIR_OVERRIDE=$(WASM_EMPTY)
ifeq ($(UNAME),Linux)
HEADLESS_ENV += VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow
endif

# The live Lab keeps its interactive defaults; only a Linux server without a screen
# needs VTK pointed at EGL, and root (containers) needs JupyterLab's permission.
# trame-vtklocal (pulled in by the live view) tries to download VTK's WebAssembly files
# at start unless pointed at a folder: without this a learner's first live view shows a
# red "Task exception was never retrieved" traceback (and tries the network).
LAB_ENV := VTK_WASM_DIR_OVERRIDE=$(WASM_EMPTY)
LAB_FLAGS :=
ifeq ($(UNAME),Linux)
ifeq ($(DISPLAY)$(WAYLAND_DISPLAY),)
LAB_ENV += VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow
endif
endif
ifeq ($(shell id -u),0)
LAB_FLAGS += --ServerApp.allow_root=True
endif

COMMA := ,
PIP := PIP_DISABLE_PIP_VERSION_CHECK=1 $(if $(CI),PIP_PROGRESS_BAR=off) $(PY) -m pip

# $(call install,EXTRAS,STAMP): pip install -e ".[EXTRAS]" with the lock if it installs,
# else without it; STAMP records which (tests/test_environments.py reads it).
define install
	$(PIP) install --quiet "pip>=21.3"
	@if [ -n "$(LOCK)" ] && $(PIP) install -e ".[$(1)]" -c "$(LOCK)"; then \
	  echo "$(LOCK)" > $(2); \
	else \
	  if [ -n "$(LOCK)" ]; then echo "*** $(LOCK) does not install with $$($(PY) --version); installing the newest versions within pyproject.toml's bounds instead"; fi; \
	  $(PIP) install -e ".[$(1)]" && : > $(2); \
	fi
endef

.PHONY: help lab check test test-lowest dist figures bench book lock clean distclean
.DEFAULT_GOAL := help

help:
	@echo "make lab        open the notebooks in JupyterLab (sets up $(VENV) on first use)"
	@echo "make check      lint and the quick tests (no notebooks, browser, grading runs or wheel): minutes"
	@echo "make test       run every test and every notebook, headless"
	@echo "make test-lowest  the library tests and one chapter with the lowest versions pyproject.toml allows"
	@echo "make dist       build the sdist and the wheel into dist/ and check their metadata"
	@echo "make figures    rebuild the pictures in figures/"
	@echo "make bench      compare against OpenMesh, fast-simplification and PyMeshLab; a quiet run writes docs/benchmark-run.md"
	@echo "make book       build the website (student edition: no answers) in build/book"
	@echo "                make book EDITION=solutions: with the answers, for instructors, in build/book-solutions"
	@echo "make lock       write the installed versions to constraints/\$$SEMESTER.txt"
	@echo "make clean      remove caches and build files (distclean: also $(VENV))"
	@echo "options: PYTHON=python3.12  PYTEST_ARGS='-k cli -x'  LOCK= (no semester lock)"

$(PY):
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 10))' 2>/dev/null || \
	  { echo "halfedge_edu needs Python 3.10 or newer; '$(PYTHON)' is not. Try: make PYTHON=python3.12 ..."; exit 1; }
	@if [ -e "$(VENV)" ]; then fresh=no; else fresh=yes; fi; \
	if ! $(PYTHON) -m venv "$(VENV)"; then \
	  if [ $$fresh = yes ]; then rm -rf "$(VENV)"; fi; \
	  echo "Could not create $(VENV). On Debian/Ubuntu: sudo apt-get install python3-venv, then run make again."; \
	  exit 1; \
	fi

$(NOTEBOOKS_STAMP): pyproject.toml $(LOCK) | $(PY)
	$(call install,notebooks,$@)

# The dev extra includes the notebooks extra: a `make test` environment is a `make lab` one.
$(DEV_STAMP): pyproject.toml $(LOCK) | $(PY)
	$(call install,dev,$@)
	@cp $@ $(NOTEBOOKS_STAMP)

$(BENCH_STAMP): pyproject.toml $(LOCK) | $(PY)
	$(call install,dev$(COMMA)bench,$@)
	@cp $@ $(DEV_STAMP)
	@cp $@ $(NOTEBOOKS_STAMP)

lab: $(NOTEBOOKS_STAMP)
	@mkdir -p notebooks "$(WASM_EMPTY)"
	$(LAB_ENV) $(VENV)/bin/jupyter lab $(LAB_FLAGS) notebooks/

# Two pytest-xdist workers, one file each at a time (conftest.py switches `-n` to
# --dist loadfile, so a notebook's cells stay in order in one kernel). The browser tests
# mostly wait on a Lab, so this halves the suite on 2 cores: 9 min 45 s against
# 17 min 55 s in one process (measured 2026-11-25, 2248 tests). PYTEST_ARGS='-n 0' for one.
PYTEST_WORKERS ?= -n 2
test: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	HALFEDGE_EDU_LOCK="$$(cat $(DEV_STAMP))" $(HEADLESS_ENV) $(PY) -m pytest $(PYTEST_WORKERS) $(PYTEST_ARGS)

# The contributor's quick target: ruff's floor ([tool.ruff] in pyproject.toml) and every
# test that needs no executed notebook, browser, hub, sandboxed grading run or built
# wheel. `make test` (and CI) is still the whole check.
CHECK_SKIPS := --ignore=tests/browser --ignore=tests/exercises/test_grading.py \
	--ignore=tests/exercises/test_grading_hostile.py --ignore=tests/test_deploy.py \
	--ignore=tests/test_course.py --ignore=tests/test_live_backend.py
check: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	$(VENV)/bin/ruff check .
	HALFEDGE_EDU_LOCK="$$(cat $(DEV_STAMP))" $(HEADLESS_ENV) $(PY) -m pytest $(PYTEST_WORKERS) -q tests $(CHECK_SKIPS) $(PYTEST_ARGS)

# The lowest versions pyproject.toml allows for the library and the notebooks extra
# (constraints/lowest.py), in a venv of their own made afresh, with the test tools at
# their newest: the library tests and chapter 07 (it renders and uses Pillow) executed
# headless. Not part of `make test`: it downloads the old versions (about 0.5 GB).
LOWEST_VENV ?= $(VENV)/lowest
LOWEST_TOOLS := "pytest>=8" "pytest-xdist>=3.5" "nbval>=0.11" "hypothesis>=6.100" "rtree>=1.0" "pycollada>=0.9" \
  "pyyaml>=6" "nbclient>=0.8" "nbformat>=5.9" "jupytext>=1.16"
LOWEST_TESTS ?= tests/core tests/io tests/algorithms tests/exercises tests/test_samples.py
test-lowest:
	rm -rf "$(LOWEST_VENV)"
	$(PYTHON) -m venv "$(LOWEST_VENV)"
	@mkdir -p "$(WASM_EMPTY)"
	$(PYTHON) constraints/lowest.py notebooks > "$(LOWEST_VENV)/lowest.txt"
	PIP_DISABLE_PIP_VERSION_CHECK=1 "$(LOWEST_VENV)/bin/python" -m pip install --quiet -e ".[notebooks]" $(LOWEST_TOOLS) -c "$(LOWEST_VENV)/lowest.txt"
	@"$(LOWEST_VENV)/bin/python" -c 'import sys, importlib.metadata as m; print("installed:", ", ".join(f"{n}=={m.version(n)}" for n in (l.split("==")[0] for l in open(sys.argv[1]))))' "$(LOWEST_VENV)/lowest.txt"
	$(HEADLESS_ENV) "$(LOWEST_VENV)/bin/python" -m pytest -n 2 -p no:cacheprovider $(LOWEST_TESTS)
	$(HEADLESS_ENV) "$(LOWEST_VENV)/bin/python" -m pytest -n 0 -p no:cacheprovider -o addopts="-ra" --nbval-lax --nbval-current-env notebooks/07_edge_collapse.ipynb

# The sdist and the wheel, as they would be uploaded, with their metadata checked
# (twine check --strict: the README renders on the package index, nothing missing).
dist: $(DEV_STAMP)
	rm -rf dist
	$(PY) -m build --outdir dist .
	$(PY) -m twine check --strict dist/*

figures: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	$(HEADLESS_ENV) $(PY) -m halfedge_edu.figures

bench: $(BENCH_STAMP)
	$(PY) benchmarks/run_all.py --docs

# Sphinx + myst-nb over the executed notebooks (never re-executed: their stored outputs
# are the pictures) and the docstrings; offline, nothing is downloaded. Not -W: docstrings
# are written for help() and the notebooks, not as reST, so docutils warns about some
# indented lines; tests/browser/test_book.py checks what matters (links, pictures).
# EDITION=student (the default) shows each exercise as a student gets it; the
# solution edition only when asked for (HALFEDGE_EDU_BOOK_EDITION, read by docs/conf.py).
EDITION ?= student
BOOK_OUT := build/$(if $(filter solutions,$(EDITION)),book-solutions,book)
book: $(DEV_STAMP)
	HALFEDGE_EDU_BOOK_EDITION=$(EDITION) $(PY) -m sphinx -q -b html docs $(BOOK_OUT)
	@echo "open $(BOOK_OUT)/index.html"

# Write the current environment as the semester lock (after `make test` passed with it).
lock: $(DEV_STAMP)
	@mkdir -p constraints
	{ echo "# Semester lock $(SEMESTER): the versions 'make test' passed with ($$($(PY) --version), $$(uname -sm))."; \
	  echo "# Made by 'make lock'; 'make lab' and 'make test' install with it (see Makefile, LOCK)."; \
	  $(PIP) freeze --exclude-editable | grep -v -i '^halfedge[-_]edu'; } > constraints/$(SEMESTER).txt

clean:
	rm -rf build dist .pytest_cache .hypothesis *.egg-info docs/_build
	find . -path ./$(VENV) -prune -o -name __pycache__ -type d -prune -exec rm -rf {} +

distclean: clean
	rm -rf "$(VENV)"
