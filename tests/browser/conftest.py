"""Fixtures for the browser tests: a real JupyterLab and a headless Chromium driving it.

As docs/headless.md says ("A real JupyterLab in headless
Chromium"): Debian's chromium (never `playwright install`), the flags below, a fresh
profile, the Lab app exposed to the page so a test can run its commands, and the news
pop-up turned off in a settings folder of our own.

The Lab runs in a temporary folder holding each chapter as a notebook written from its
source (notebooks/src/NN_*.py, unexecuted: the tests run every cell themselves), so the
state JupyterLab saves never touches the repository and a test always drives the cells
the sources say. Its environment is that of `make lab`, not that of the headless
notebook tests: no PYVISTA_JUPYTER_BACKEND=static (which the root conftest.py sets for
nbval), so the widgets choose the live trame view; and an empty VTK.wasm folder, so
trame-vtklocal never tries the network.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

SKIP_REASON = "Chromium not installed: apt-get install chromium (see README)"
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
LAB_START_TIMEOUT = 120  # seconds; a shared 2-core machine can be slow to import the Lab


def chromium_path() -> str | None:
    if Path("/usr/bin/chromium").exists():
        return "/usr/bin/chromium"
    return shutil.which("chromium")


@pytest.fixture(scope="session")
def chromium_executable() -> str:
    path = chromium_path()
    if path is None:
        pytest.skip(SKIP_REASON)
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        pytest.skip("the playwright package is not installed: make test installs it (the dev extra)")
    return path


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@dataclass
class Lab:
    url: str          # http://127.0.0.1:PORT
    token: str
    root: Path        # the folder the Lab serves (copies of notebooks)
    log: Path         # the server's stdout and stderr

    def open_url(self, notebook: str) -> str:
        return f"{self.url}/lab/tree/{notebook}?reset&token={self.token}"

    def log_tail(self, lines: int = 40) -> str:
        try:
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return ""


def lab_environment(base: Path) -> dict[str, str]:
    """`make lab`'s environment, with Jupyter's per-user folders moved into ``base``."""
    env = dict(os.environ)
    # The notebook tests force PNG output; the Lab must choose the live view itself.
    env.pop("PYVISTA_JUPYTER_BACKEND", None)
    env.pop("HALFEDGE_EDU_VIZ", None)
    wasm = base / "vtk-wasm-empty"         # as `make lab` sets it: nothing to download
    wasm.mkdir(exist_ok=True)
    env["VTK_WASM_DIR_OVERRIDE"] = str(wasm)
    if sys.platform.startswith("linux"):
        env["VTK_DEFAULT_OPENGL_WINDOW"] = "vtkEGLRenderWindow"  # no X server here
    settings = base / "lab-settings"
    notification = settings / "@jupyterlab" / "apputils-extension" / "notification.jupyterlab-settings"
    notification.parent.mkdir(parents=True)
    notification.write_text(json.dumps({"fetchNews": "false", "checkForUpdates": False}))
    for name, folder in [
        ("JUPYTERLAB_SETTINGS_DIR", settings),
        ("JUPYTERLAB_WORKSPACES_DIR", base / "lab-workspaces"),
        ("JUPYTER_CONFIG_DIR", base / "jupyter-config"),
        ("JUPYTER_DATA_DIR", base / "jupyter-data"),     # no user kernels named python3
        ("JUPYTER_RUNTIME_DIR", base / "jupyter-runtime"),
        ("IPYTHONDIR", base / "ipython"),
    ]:
        folder.mkdir(parents=True, exist_ok=True)
        env[name] = str(folder)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    return env


@pytest.fixture(scope="module")
def lab(chromium_executable, tmp_path_factory) -> Lab:
    """A JupyterLab on 127.0.0.1 (free port, random token) serving the chapters, each
    written from its source."""
    import nbformat

    from tools.build_notebooks import chapter_sources, new_notebook, parse_source

    base = tmp_path_factory.mktemp("lab")
    root = base / "notebooks"
    root.mkdir()
    for source in chapter_sources([]):
        notebook = new_notebook(parse_source(source.read_text(encoding="utf-8")))
        nbformat.write(notebook, root / (source.stem + ".ipynb"))
    port, token = _free_port(), secrets.token_hex(16)
    log = base / "jupyter-lab.log"
    command = [
        sys.executable, "-m", "jupyterlab", "--no-browser",
        "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={port}", "--ServerApp.port_retries=0",
        f"--IdentityProvider.token={token}", "--ServerApp.allow_root=True",
        "--LabApp.expose_app_in_browser=True", f"--ServerApp.root_dir={root}",
    ]
    with log.open("wb") as out:
        server = subprocess.Popen(command, cwd=root, env=lab_environment(base), stdout=out,
                                  stderr=subprocess.STDOUT, start_new_session=True)
    the_lab = Lab(url=f"http://127.0.0.1:{port}", token=token, root=root, log=log)
    try:
        deadline = time.monotonic() + LAB_START_TIMEOUT
        while True:
            if server.poll() is not None:
                pytest.fail(f"JupyterLab exited with status {server.returncode}:\n{the_lab.log_tail()}")
            try:
                with urllib.request.urlopen(f"{the_lab.url}/api/status?token={token}", timeout=5) as answer:
                    if answer.status == 200:
                        break
            except (urllib.error.URLError, OSError):
                pass
            if time.monotonic() > deadline:
                pytest.fail(f"JupyterLab did not answer within {LAB_START_TIMEOUT} s:\n{the_lab.log_tail()}")
            time.sleep(0.5)
        yield the_lab
    finally:
        # SIGTERM lets the server shut its kernels down; then the whole group, if needed.
        server.terminate()
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)
            server.wait(timeout=10)


@pytest.fixture(scope="module")
def browser_context(chromium_executable, tmp_path_factory):
    """A headless Chromium with a fresh profile; one page per test."""
    from playwright.sync_api import sync_playwright

    profile = tmp_path_factory.mktemp("chromium-profile")
    with sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            str(profile),
            executable_path=chromium_executable,
            headless=True,
            args=CHROMIUM_FLAGS,
            viewport={"width": 1400, "height": 1000},
        )
        try:
            yield context
        finally:
            context.close()


@pytest.fixture(scope="session")
def screenshot_dir(tmp_path_factory) -> Path:
    """Where the screenshots go: $HALFEDGE_EDU_SCREENSHOTS, else pytest's temporary
    folder (kept for the last three runs; the test prints the path when it fails)."""
    chosen = os.environ.get("HALFEDGE_EDU_SCREENSHOTS")
    if not chosen:
        return tmp_path_factory.mktemp("screenshots")
    folder = Path(chosen)
    folder.mkdir(parents=True, exist_ok=True)
    return folder
