"""Settings that make the test suite, notebooks included, run the same headless.

Only environment and notebook settings live here; test fixtures belong in tests/.
The values were measured in shared/notes/notebooks-headless.md. `make test` sets the
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
    if config.getoption("nbval", default=False) and config.getoption("dist", default="no") in (
        "load",
        "worksteal",
    ):
        config.option.dist = "loadfile"
        # xdist would then hand files out by their number of tests, most first, which
        # puts the browser tests (few tests, most of the time) last: the order is set
        # by time instead (pytest_collection_modifyitems, pytest_xdist_make_scheduler).
        config.option.loadscopereorder = False


#: Files that take long whatever their number of tests, handed to the workers first so
#: that no worker starts one when the others are nearly done (the longest-first rule of
#: scheduling). Measured with `make test PYTEST_ARGS=--durations=100` (2026-11-27):
#: test_lab_widgets.py runs 13 tests in about 40 % of all the workers' time; the other
#: browser files and test_course.py (a wheel installed into a fresh venv) take 30-170 s
#: each for 1-2 tests.
SLOW_FILES_FIRST = ("tests/browser/test_lab_widgets.py", "tests/browser/", "tests/test_course.py")

#: Files whose tests are dealt out to this many workers instead of one (each part starts
#: its own JupyterLab, about 15 s): on its own, test_lab_widgets.py outlasted the rest
#: of the suite on the other workers.
FILES_IN_PARTS = {"tests/browser/test_lab_widgets.py": 2}


def _file_order(path: str, tests_in_file: int) -> tuple[int, int]:
    """Sort key of a test file for the workers: slow files first (in
    SLOW_FILES_FIRST's order), then the rest by their number of tests, most first
    (what xdist's own reordering does)."""
    for rank, prefix in enumerate(SLOW_FILES_FIRST):
        if path.startswith(prefix):
            return rank, -tests_in_file
    return len(SLOW_FILES_FIRST), -tests_in_file


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """On an xdist worker, order the files the way they should be handed out (slow
    first): the controller hands out files in the order the workers collected them.
    A file's own tests keep their order; without xdist nothing moves."""
    if not hasattr(config, "workerinput"):
        return
    files: dict[str, list[pytest.Item]] = {}
    for item in items:
        files.setdefault(item.nodeid.split("::")[0], []).append(item)
    ordered = sorted(files, key=lambda path: _file_order(path, len(files[path])))
    items[:] = [item for path in ordered for item in files[path]]


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log):
    """xdist's loadfile scheduling, except that the files of FILES_IN_PARTS are dealt
    out in parts (test k of the file goes to part k mod parts)."""
    if config.getvalue("dist") != "loadfile":
        return None
    from xdist.scheduler import LoadFileScheduling

    class LoadFileInPartsScheduling(LoadFileScheduling):
        def __init__(self, config: pytest.Config, log=None) -> None:
            super().__init__(config, log)
            self.part_of: dict[str, str] = {}       # node id -> its scope, once decided
            self.dealt: dict[str, int] = {}         # file -> tests dealt out so far

        def _split_scope(self, nodeid: str) -> str:
            path = super()._split_scope(nodeid)
            parts = FILES_IN_PARTS.get(path)
            if parts is None:
                return path
            if nodeid not in self.part_of:
                # First seen in collection order (in schedule()), so the parts are the
                # same on every run.
                k = self.dealt.get(path, 0)
                self.dealt[path] = k + 1
                self.part_of[nodeid] = f"{path} (part {k % parts + 1} of {parts})"
            return self.part_of[nodeid]

    return LoadFileInPartsScheduling(config, log)
