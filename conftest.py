"""Settings that make the test suite, notebooks included, run the same headless.

Only environment and notebook settings live here; test fixtures belong in tests/.
The values and why each is needed: docs/headless.md. `make test` sets the
same variables explicitly; these defaults make a bare `pytest` behave the same way.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent


def _headless_defaults() -> dict[str, str]:
    empty_wasm_dir = Path(tempfile.gettempdir()) / "halfedge_edu-vtk-wasm-empty"
    empty_wasm_dir.mkdir(exist_ok=True)
    env = {
        # Stored notebook outputs are PNGs from the static backend; a trame iframe
        # would carry a random port and plotter id and be dead once the kernel exits.
        "PYVISTA_JUPYTER_BACKEND": "static",
        # trame-vtklocal otherwise tries to download VTK.wasm when it starts.
        "VTK_WASM_DIR_OVERRIDE": str(empty_wasm_dir),
    }
    if sys.platform.startswith("linux"):
        # Without it VTK first tries X and writes a timestamped warning into the
        # cell's stderr, which nbval then compares. (No such class on macOS/Windows.)
        env["VTK_DEFAULT_OPENGL_WINDOW"] = "vtkEGLRenderWindow"
    return env


# Set at import, before any test or notebook kernel (a child process) starts.
for _name, _value in _headless_defaults().items():
    os.environ.setdefault(_name, _value)


def pytest_configure(config: pytest.Config) -> None:
    sanitize = config.getoption("nbval_sanitize_with", default=None)
    if sanitize and not Path(sanitize).is_absolute() and not Path(sanitize).exists():
        # nbval opens the file relative to the current directory; let `pytest` work
        # from any folder of the repository.
        config.option.nbval_sanitize_with = str(ROOT / sanitize)

    # A notebook's cells share one kernel and must run in order on one worker.
    # pytest-xdist's default "load" scheduling spreads them over workers and breaks
    # them; "loadfile" keeps each file (notebook or test module) on one worker.
    # (Not "loadgroup": with pytest 9.2 and xdist 3.8 its groups never reach the test
    # ids, so it schedules test by test, and a notebook's cells went to both workers.)
    # Files go out in collection order, not xdist's "most tests first": that order left
    # the browser modules (few tests, a third of the suite's time) to the end, on one
    # worker while the other sat idle (22 min against 20 on a 2-core CI machine).
    if config.getoption("nbval", default=False) and config.getoption("dist", default="no") in (
        "load",
        "worksteal",
        "loadfile",
    ):
        config.option.dist = "loadfile"
        config.option.loadscopereorder = False
