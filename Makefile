# halfedge_edu: `make lab` to work through the notebooks, `make test` to check everything.
# Both create .venv with $(PYTHON) and install the package into it on first use (a few
# minutes); later runs reuse it and start at once. Reinstalls when pyproject.toml changes.

PYTHON ?= python3
VENV ?= .venv
PYTEST_ARGS ?=

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
LAB_ENV :=
LAB_FLAGS :=
ifeq ($(UNAME),Linux)
ifeq ($(DISPLAY)$(WAYLAND_DISPLAY),)
LAB_ENV += VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow
endif
endif
ifeq ($(shell id -u),0)
LAB_FLAGS += --ServerApp.allow_root=True
endif

PIP := PIP_DISABLE_PIP_VERSION_CHECK=1 $(if $(CI),PIP_PROGRESS_BAR=off) $(PY) -m pip

.PHONY: help lab test figures bench clean distclean
.DEFAULT_GOAL := help

help:
	@echo "make lab        open the notebooks in JupyterLab (sets up $(VENV) on first use)"
	@echo "make test       run every test and every notebook, headless"
	@echo "make figures    rebuild the pictures in figures/"
	@echo "make bench      compare against OpenMesh, fast-simplification and PyMeshLab"
	@echo "make clean      remove caches and build files (distclean: also $(VENV))"
	@echo "options: PYTHON=python3.12  PYTEST_ARGS='-k cli -x'"

$(PY):
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 10))' 2>/dev/null || \
	  { echo "halfedge_edu needs Python 3.10 or newer; '$(PYTHON)' is not. Try: make PYTHON=python3.12 ..."; exit 1; }
	@if [ -e "$(VENV)" ]; then fresh=no; else fresh=yes; fi; \
	if ! $(PYTHON) -m venv "$(VENV)"; then \
	  if [ $$fresh = yes ]; then rm -rf "$(VENV)"; fi; \
	  echo "Could not create $(VENV). On Debian/Ubuntu: sudo apt-get install python3-venv, then run make again."; \
	  exit 1; \
	fi

$(DEV_STAMP): pyproject.toml | $(PY)
	$(PIP) install --quiet "pip>=21.3"
	$(PIP) install -e ".[dev]"
	@touch $@

$(BENCH_STAMP): pyproject.toml | $(PY)
	$(PIP) install --quiet "pip>=21.3"
	$(PIP) install -e ".[dev,bench]"
	@touch $@ $(DEV_STAMP)

lab: $(DEV_STAMP)
	@mkdir -p notebooks
	$(LAB_ENV) $(VENV)/bin/jupyter lab $(LAB_FLAGS) notebooks/

# No pytest-xdist here: a notebook's cells must run in order in one kernel, and on two
# cores it was not faster (shared notes). conftest.py switches `-n` to --dist loadfile.
test: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	$(HEADLESS_ENV) $(PY) -m pytest $(PYTEST_ARGS)

figures: $(DEV_STAMP)
	@mkdir -p "$(WASM_EMPTY)"
	$(HEADLESS_ENV) $(PY) -m halfedge_edu.figures

bench: $(BENCH_STAMP)
	$(PY) benchmarks/run_all.py

clean:
	rm -rf build dist .pytest_cache .hypothesis *.egg-info
	find . -path ./$(VENV) -prune -o -name __pycache__ -type d -prune -exec rm -rf {} +

distclean: clean
	rm -rf "$(VENV)"
