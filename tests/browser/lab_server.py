"""A real JupyterLab serving the chapters, and Debian's Chromium to drive it: plain
functions that the browser tests' fixtures (conftest.py) and the click benchmark
(benchmarks/bench_clicks.py) both call.

As docs/headless.md says ("A real JupyterLab in headless Chromium"): Debian's chromium
(never `playwright install`), the flags below, a fresh profile, the Lab app exposed to
the page so that a test can run its commands, and the news pop-up turned off in a
settings folder of our own.

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

ROOT = Path(__file__).resolve().parents[2]

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
VIEWPORT = {"width": 1400, "height": 1000}


class LabStartError(RuntimeError):
    """JupyterLab exited or did not answer in time; the message holds its log's tail."""


def chromium_path() -> str | None:
    """Debian's Chromium, else the first ``chromium`` on the PATH, else None."""
    if Path("/usr/bin/chromium").exists():
        return "/usr/bin/chromium"
    return shutil.which("chromium")


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


def start_lab(base: Path, extra_env: dict[str, str] | None = None) -> tuple[Lab, subprocess.Popen]:
    """A JupyterLab on 127.0.0.1 (free port, random token) serving the chapters, each
    written from its source into ``base / "notebooks"``, once it answers.

    ``extra_env`` is added to :func:`lab_environment` (e.g. HALFEDGE_EDU_LIVE_BACKEND).
    Returns the Lab and its server process; end it with :func:`stop_lab`.

    Raises:
        LabStartError: the server exited, or did not answer within LAB_START_TIMEOUT
            seconds (it is stopped first); the message holds its log's tail.
    """
    import nbformat

    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from tools.build_notebooks import chapter_sources, new_notebook, parse_source

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
    env = lab_environment(base)
    env.update(extra_env or {})
    with log.open("wb") as out:
        server = subprocess.Popen(command, cwd=root, env=env, stdout=out,
                                  stderr=subprocess.STDOUT, start_new_session=True)
    the_lab = Lab(url=f"http://127.0.0.1:{port}", token=token, root=root, log=log)
    deadline = time.monotonic() + LAB_START_TIMEOUT
    try:
        while True:
            if server.poll() is not None:
                raise LabStartError(f"JupyterLab exited with status {server.returncode}:\n{the_lab.log_tail()}")
            try:
                with urllib.request.urlopen(f"{the_lab.url}/api/status?token={token}", timeout=5) as answer:
                    if answer.status == 200:
                        return the_lab, server
            except (urllib.error.URLError, OSError):
                pass
            if time.monotonic() > deadline:
                raise LabStartError(f"JupyterLab did not answer within {LAB_START_TIMEOUT} s:\n{the_lab.log_tail()}")
            time.sleep(0.5)
    except BaseException:
        stop_lab(server)
        raise


def stop_lab(server: subprocess.Popen) -> None:
    """Stop a Lab :func:`start_lab` started: SIGTERM lets the server shut its kernels
    down; then its whole process group, if needed."""
    server.terminate()
    try:
        server.wait(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(server.pid, signal.SIGKILL)
        server.wait(timeout=10)


def launch_chromium(playwright, profile: Path, executable: str):
    """A headless Chromium (``executable``) with a fresh profile in ``profile``, as a
    Playwright persistent context; close it with ``context.close()``."""
    return playwright.chromium.launch_persistent_context(
        str(profile),
        executable_path=executable,
        headless=True,
        args=CHROMIUM_FLAGS,
        viewport=dict(VIEWPORT),
    )
