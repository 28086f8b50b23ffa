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

.PHONY: help lab test figures bench book lock clean distclean
.DEFAULT_GOAL := help

help:
	@echo "make lab        open the notebooks in JupyterLab (sets up $(VENV) on first use)"
	@echo "make test       run every test and every notebook, headless"
	@echo "make figures    rebuild the pictures in figures/"
	@echo "make bench      compare against OpenMesh, fast-simplification and PyMeshLab"
	@echo "make book       build the website (executed chapters, CLI and API) in build/book"
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

$(DEV_STAMP): pyproject.toml $(LOCK) | $(PY)
	$(call install,dev,$@)

$(BENCH_STAMP): pyproject.toml $(LOCK) | $(PY)
	$(call install,dev$(COMMA)bench,$@)
	@cp $@ $(DEV_STAMP)

lab: $(DEV_STAMP)
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

figures: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	$(HEADLESS_ENV) $(PY) -m halfedge_edu.figures

bench: $(BENCH_STAMP)
	$(PY) benchmarks/run_all.py

# Sphinx + myst-nb over the executed notebooks (never re-executed: their stored outputs
# are the pictures) and the docstrings; offline, nothing is downloaded. Not -W: docstrings
# are written for help() and the notebooks, not as reST, so docutils warns about some
# indented lines; tests/browser/test_book.py checks what matters (links, pictures).
book: $(DEV_STAMP)
	$(PY) -m sphinx -q -b html docs build/book
	@echo "open build/book/index.html"

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
