"""Headless settings for the viz tests, set before anything imports pyvista.

The values are those of docs/headless.md: EGL instead of X
(else VTK warns on stderr), PyVista's static notebook backend, and an empty VTK.wasm
folder so trame-vtklocal downloads nothing. Each scene is closed after its test.
"""

from __future__ import annotations

import os
import sys
import tempfile

_empty_wasm_dir = os.path.join(tempfile.gettempdir(), "halfedge_edu-vtk-wasm-empty")
os.makedirs(_empty_wasm_dir, exist_ok=True)
if sys.platform.startswith("linux"):
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
os.environ.setdefault("PYVISTA_JUPYTER_BACKEND", "static")
os.environ.setdefault("VTK_WASM_DIR_OVERRIDE", _empty_wasm_dir)

import pytest  # noqa: E402

import halfedge_edu as hx  # noqa: E402
from halfedge_edu.data import sample  # noqa: E402


@pytest.fixture(scope="session")
def bunny_arrays():
    """The bunny's arrays, read once per session (each test builds its own mesh)."""
    return sample("bunny").to_arrays()


@pytest.fixture
def bunny(bunny_arrays):
    return hx.HalfedgeMesh.from_faces(*bunny_arrays)


@pytest.fixture
def closing():
    """Collects scenes and widgets and closes them after the test (frees GL contexts)."""
    made = []
    yield made.append
    for thing in made:
        thing.close()
