"""A whole class on one machine: a real JupyterHub, N students, chapter 03 and its widgets.

    python benchmarks/bench_class.py --students 5
    python benchmarks/bench_class.py --sweep 1,5,10,20
    python benchmarks/bench_class.py --students 2 --live-backend client

Setup, once (nothing is downloaded while the script runs; it checks and names what is missing):

    pip install 'halfedge_edu[hub]'                 # jupyterhub, jupyter-server-proxy, psutil, websocket-client
    npm install -g configurable-http-proxy          # the hub's proxy (node is needed)
    apt-get install chromium                        # the two students who look at the live view

For each N the script starts deploy/jupyterhub/jupyterhub_config.py on 127.0.0.1 (a
fresh state folder, free ports, an admin API token of its own), and then, all students
at the same time:

1. spawns N single-user servers through the hub's REST API (spawn time: request to ready);
2. opens chapter 03 in each server (a Jupyter session, as JupyterLab opens it) and runs
   every code cell through the kernel's websocket (chapter time);
3. measures each student's memory: PSS (and RSS) of the single-user server plus its
   kernel, read with psutil;
4. runs a stepper session in every kernel: ``bunny_explorer.go(move)`` (the chapter's
   explorer on the 69k-face bunny) once every ``--step-interval`` seconds, as students
   clicking; step latency is the round trip of that request, and server CPU per step is
   the server's and kernel's CPU time over the session divided by the steps;
5. logs two students into the hub in headless Chromium, shows the chapter's explorer in
   their notebook, checks from screenshots that the live 3D view is drawn and that a
   click on ``next`` moves the arrow, then drags the view for ``--rotate-seconds`` and
   reads the server's CPU time while it rotates.

Then it stops the servers and the hub. Every wait is bounded (``--timeout``), every
loop counted. Timings on a shared machine are noisy: the table says how loaded it was
(the load average at the start of each N), and a sweep should be read by its medians.

``--live-backend`` sets ``HALFEDGE_EDU_LIVE_BACKEND`` for every student through the hub
(``client``: vtk.js draws in the browser, the recipes' default, see
deploy/singleuser-start.sh; ``server``: the kernel renders, as ``make lab`` does).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import importlib.util
import io
import json
import os
import re
import secrets
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import uuid
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HUB_CONFIG = ROOT / "deploy" / "jupyterhub" / "jupyterhub_config.py"
CHAPTER = "03_navigating.ipynb"
PASSWORD = "halfedge-bench"
MIB = 1024 * 1024
# The stepper session's moves, cycled (bunny_explorer sits on a boundary loop: twin
# crosses into the mesh, next walks along, prev comes back).
MOVES = ("next", "twin", "next", "prev", "twin", "next")
# A drawn view and a click that moved something (as tests/browser/test_lab_chapter03.py).
MIN_STD, MIN_COLOURS = 8.0, 64
CHANGED_LEVEL, MIN_CHANGED_SHARE = 40, 0.002
SETUP = {
    "jupyterhub": "pip install 'halfedge_edu[hub]'",
    "jupyter_server_proxy": "pip install 'halfedge_edu[hub]'",
    "psutil": "pip install 'halfedge_edu[hub]'",
    "websocket": "pip install 'halfedge_edu[hub]'",
    "playwright": "pip install 'halfedge_edu[dev]'",
}


class BenchError(RuntimeError):
    """The hub, a server or a kernel did not do what the benchmark asked in time."""


def missing_setup(browser: bool = True) -> list[str]:
    """The setup commands still to run (empty when everything is installed)."""
    needed = [command for module, command in SETUP.items()
              if (browser or module != "playwright") and importlib.util.find_spec(module) is None]
    if shutil.which("configurable-http-proxy") is None:
        needed.append("npm install -g configurable-http-proxy")
    if browser and chromium_path() is None:
        needed.append("apt-get install chromium")
    return list(dict.fromkeys(needed))


def chromium_path() -> str | None:
    return "/usr/bin/chromium" if Path("/usr/bin/chromium").exists() else shutil.which("chromium")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def percentile(values: list[float], share: float) -> float:
    """The ``share`` quantile (0..1) of ``values``, linear between ranks; nan if empty."""
    if not values:
        return float("nan")
    ordered = sorted(values)
    rank = share * (len(ordered) - 1)
    low = int(rank)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (rank - low)


# --------------------------------------------------------------------------- the hub

@dataclass
class Hub:
    """A running JupyterHub: its address, admin token, process and state folder."""

    url: str
    token: str
    process: subprocess.Popen
    state: Path
    log: Path

    def api(self, method: str, path: str, body: dict | None = None, timeout: float = 30) -> dict | None:
        """Call the hub's REST API (``/hub/api`` + ``path``) with the admin token."""
        return http_json(method, f"{self.url}/hub/api{path}", self.token, body, timeout)

    def log_tail(self, lines: int = 30) -> str:
        try:
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return ""


def http_json(method: str, url: str, token: str, body: dict | None = None, timeout: float = 30) -> dict | None:
    """One JSON request with a token; the decoded answer (None when empty)."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(url, data=data, method=method,
                                     headers={"Authorization": f"token {token}", "Content-Type": "application/json"})
    with urllib.request.urlopen(request, timeout=timeout) as answer:
        text = answer.read()
    return json.loads(text) if text.strip() else None


def start_hub(state: Path, live_backend: str, timeout: float) -> Hub:
    """deploy/jupyterhub/jupyterhub_config.py on free ports, answering within ``timeout``."""
    port, token = free_port(), secrets.token_hex(24)
    env = dict(os.environ)
    for name in list(env):
        if name.startswith(("PYVISTA_", "VTK_", "HALFEDGE_EDU_")):
            del env[name]   # the students get the hub's settings, not this shell's
    env.update(
        HALFEDGE_HUB_STATE=str(state), HALFEDGE_HUB_PORT=str(port), HALFEDGE_HUB_PASSWORD=PASSWORD,
        HALFEDGE_HUB_API_TOKEN=token, HALFEDGE_HUB_INTERNAL_PORT=str(free_port()),
        HALFEDGE_HUB_PROXY_API_PORT=str(free_port()), HALFEDGE_EDU_LIVE_BACKEND=live_backend,
        PATH=os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", ""),
    )
    log = state / "jupyterhub.log"
    with log.open("wb") as out:
        process = subprocess.Popen([sys.executable, "-m", "jupyterhub", "-f", str(HUB_CONFIG)], cwd=state,
                                   env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
    hub = Hub(url=f"http://127.0.0.1:{port}", token=token, process=process, state=state, log=log)
    deadline = time.monotonic() + timeout
    try:
        while True:
            if process.poll() is not None:
                raise BenchError(f"jupyterhub exited with status {process.returncode}:\n{hub.log_tail()}")
            try:
                hub.api("GET", "/", timeout=5)
                return hub
            except (urllib.error.URLError, OSError):
                pass
            if time.monotonic() > deadline:
                raise BenchError(f"jupyterhub did not answer within {timeout:.0f} s:\n{hub.log_tail()}")
            time.sleep(0.5)
    except BaseException:
        # Also on Ctrl-C while waiting: a hub left running keeps its ports and proxy.
        stop_hub(hub)
        raise


def stop_hub(hub: Hub) -> None:
    """SIGTERM (the hub stops its proxy and, cleanup_servers, the students' servers), then SIGKILL."""
    if hub.process.poll() is None:
        hub.process.terminate()
        try:
            hub.process.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(hub.process.pid, signal.SIGKILL)
            hub.process.wait(timeout=10)


def prepare_home(state: Path, name: str) -> None:
    """A student's home before the first spawn: the Lab's app exposed to the page (the
    browser part runs Lab commands) and its news pop-up off."""
    home = state / name
    config = home / ".jupyter"
    config.mkdir(parents=True, exist_ok=True)
    (config / "jupyter_server_config.json").write_text(json.dumps({"LabApp": {"expose_app_in_browser": True}}))
    notification = config / "lab" / "user-settings" / "@jupyterlab" / "apputils-extension" / "notification.jupyterlab-settings"
    notification.parent.mkdir(parents=True, exist_ok=True)
    notification.write_text(json.dumps({"fetchNews": "false", "checkForUpdates": False}))


def spawn(hub: Hub, name: str, timeout: float) -> float:
    """Create ``name``, start their server, wait until the hub says it is ready: seconds."""
    hub.api("POST", f"/users/{name}")
    start = time.monotonic()
    hub.api("POST", f"/users/{name}/server", {}, timeout=timeout)
    while time.monotonic() - start < timeout:
        server = (hub.api("GET", f"/users/{name}") or {}).get("servers", {}).get("", {})
        if server.get("ready"):
            return time.monotonic() - start
        time.sleep(0.25)
    raise BenchError(f"{name}'s server was not ready within {timeout:.0f} s:\n{hub.log_tail()}")


# --------------------------------------------------------------------------- kernels

class Kernel:
    """One kernel of a student's server, driven over its websocket (Jupyter's JSON protocol)."""

    def __init__(self, hub: Hub, user: str, notebook_path: str, timeout: float):
        import websocket

        base = f"{hub.url}/user/{user}/api"
        session = http_json("POST", f"{base}/sessions", hub.token, {
            "path": notebook_path, "name": Path(notebook_path).name, "type": "notebook",
            "kernel": {"name": "python3"}}, timeout=timeout)
        self.kernel_id = session["kernel"]["id"]
        self.session = uuid.uuid4().hex
        url = f"{base}/kernels/{self.kernel_id}/channels?session_id={self.session}".replace("http://", "ws://")
        self.ws = websocket.create_connection(url, header=[f"Authorization: token {hub.token}"], timeout=timeout)

    def execute(self, code: str, timeout: float) -> tuple[float, str]:
        """Run ``code``; (seconds until its execute_reply, its printed text).

        Raises:
            BenchError: the code raised, or no reply came within ``timeout``.
        """
        msg_id = uuid.uuid4().hex
        self.ws.send(json.dumps({
            "header": {"msg_id": msg_id, "username": "bench", "session": self.session,
                       "msg_type": "execute_request", "version": "5.3"},
            "parent_header": {}, "metadata": {}, "channel": "shell", "buffers": [],
            "content": {"code": code, "silent": False, "store_history": True, "user_expressions": {},
                        "allow_stdin": False, "stop_on_error": True}}))
        start = time.monotonic()
        printed = []
        while True:
            left = timeout - (time.monotonic() - start)
            if left <= 0:
                raise BenchError(f"no reply within {timeout:.0f} s to: {code[:80]!r}")
            self.ws.settimeout(left)
            frame = self.ws.recv()
            if isinstance(frame, bytes):
                # A message with binary buffers (a widget's picture, a live view's arrays)
                # comes as a binary frame; the replies waited for here never carry buffers.
                continue
            message = json.loads(frame)
            if message.get("parent_header", {}).get("msg_id") != msg_id:
                continue
            kind = message["header"]["msg_type"]
            if kind == "stream":
                printed.append(message["content"]["text"])
            elif kind == "error":
                content = message["content"]
                where = re.sub(r"\x1b\[[0-9;]*m", "", "\n".join(content.get("traceback", [])[-3:]))
                raise BenchError(f"{content['ename']}: {content['evalue']} in {code[:80]!r}\n{where}")
            elif kind == "execute_reply":
                return time.monotonic() - start, "".join(printed)

    def close(self) -> None:
        self.ws.close()


def chapter_cells(path: Path) -> list[str]:
    """The code cells of a notebook, in order."""
    notebook = json.loads(path.read_text())
    return ["".join(cell["source"]) for cell in notebook["cells"] if cell["cell_type"] == "code"]


# --------------------------------------------------------------------------- processes

def server_processes(home: Path):
    """(the single-user server, its descendants) whose HOME is ``home``: a student of this
    hub (two hubs on one machine both have a student00; their homes differ)."""
    import psutil

    for process in psutil.process_iter(["cmdline"]):
        try:
            if any("jupyterhub-singleuser" in part for part in process.info["cmdline"] or []) \
                    and process.environ().get("HOME") == str(home):
                return process, process.children(recursive=True)
        except (psutil.NoSuchProcess, psutil.AccessDenied):
            continue
    raise BenchError(f"no jupyterhub-singleuser process with HOME={home}")


def memory(home: Path) -> tuple[float, float, float]:
    """(PSS of server + kernel, PSS of the kernel alone, RSS of server + kernel) in MiB."""
    server, children = server_processes(home)
    pss = rss = kernel_pss = 0.0
    for process in [server, *children]:
        info = process.memory_full_info()
        pss += info.pss
        rss += info.rss
        if process is not server:
            kernel_pss += info.pss
    return pss / MIB, kernel_pss / MIB, rss / MIB


def cpu_seconds(home: Path) -> float:
    """User + system CPU seconds used so far by the server of ``home`` and its kernel."""
    server, children = server_processes(home)
    total = 0.0
    for process in [server, *children]:
        times = process.cpu_times()
        total += times.user + times.system
    return total


# --------------------------------------------------------------------------- one class

@dataclass
class Student:
    name: str
    home: Path
    spawn_s: float = float("nan")
    chapter_s: float = float("nan")
    pss_mib: float = float("nan")
    kernel_pss_mib: float = float("nan")
    rss_mib: float = float("nan")
    steps_ms: list[float] = field(default_factory=list)
    cpu_per_step_ms: float = float("nan")
    kernel: Kernel | None = None


@dataclass
class ClassResult:
    students: int
    load: float
    hub_start_s: float
    members: list[Student]
    browser: list[dict]

    def row(self) -> dict:
        """The table's numbers: medians over students (p50/p95 over all steps)."""
        steps = [ms for student in self.members for ms in student.steps_ms]
        median = lambda values: statistics.median(values) if values else float("nan")  # noqa: E731
        views = [view for view in self.browser if "failed" not in view]
        rotate = [view["rotate_cpu_per_s"] for view in views]
        return {
            "students": self.students, "load": self.load,
            "pss_mib": median([s.pss_mib for s in self.members]),
            "kernel_pss_mib": median([s.kernel_pss_mib for s in self.members]),
            "rss_mib": median([s.rss_mib for s in self.members]),
            "spawn_s": median([s.spawn_s for s in self.members]),
            "chapter_s": median([s.chapter_s for s in self.members]),
            "step_p50_ms": percentile(steps, 0.5), "step_p95_ms": percentile(steps, 0.95),
            "cpu_per_step_ms": median([s.cpu_per_step_ms for s in self.members]),
            "rotate_cpu_per_s": median(rotate),
            "drags_per_s": median([view["drags_per_s"] for view in views]),
            "views_drawn": f"{len(views)}/{len(self.browser)}",
            "click_to_settled_ms": median([view["click_to_settled_ms"] for view in views]),
        }


def run_class(n: int, *, steps: int = 20, step_interval: float = 1.0, rotate_seconds: float = 5.0,
              browsers: int = 2, live_backend: str = "client", timeout: float = 900.0,
              screenshots: Path | None = None, log=print) -> ClassResult:
    """Everything the module docstring lists, for ``n`` students; always stops the hub."""
    # A short path: each student's kernels listen on Unix sockets under their home
    # (the hub config's ipc transport), and a socket's path may be at most 107 bytes.
    state = Path(tempfile.mkdtemp(prefix=f"hc{n}-", dir="/tmp"))
    load = os.getloadavg()[0]
    members = [Student(f"student{i:02d}", state / f"student{i:02d}") for i in range(n)]
    for student in members:
        prepare_home(state, student.name)
    started = time.monotonic()
    hub = start_hub(state, live_backend, timeout=min(timeout, 180))
    hub_start = time.monotonic() - started
    log(f"[{n} students] hub up in {hub_start:.1f} s (load average {load:.1f})")
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=n) as pool:
            spawned = list(pool.map(lambda s: spawn(hub, s.name, timeout), members))
            for student, seconds in zip(members, spawned):
                student.spawn_s = seconds
            log(f"[{n} students] spawned: median {statistics.median(spawned):.1f} s")
            list(pool.map(lambda s: run_chapter(hub, s, timeout), members))
            log(f"[{n} students] chapter 03 ran: median {statistics.median(s.chapter_s for s in members):.1f} s")
            for student in members:
                student.pss_mib, student.kernel_pss_mib, student.rss_mib = memory(student.home)
            list(pool.map(lambda s: stepper_session(s, steps, step_interval, timeout), members))
        views = []
        if browsers:
            views = look_in_browser(hub, members[:browsers], rotate_seconds, timeout, screenshots or state, log)
        for student in members:
            if student.kernel is not None:
                student.kernel.close()
        return ClassResult(n, load, hub_start, members, views)
    except BaseException:
        log(f"the hub's log ends with:\n{hub.log_tail()}")
        raise
    finally:
        stop_hub(hub)
        shutil.rmtree(state, ignore_errors=True)


def run_chapter(hub: Hub, student: Student, timeout: float) -> None:
    """Open chapter 03 as JupyterLab does (a session) and run every code cell."""
    path = f"course/{CHAPTER}"
    cells = chapter_cells(hub.state / student.name / path)
    student.kernel = Kernel(hub, student.name, path, timeout=60)
    start = time.monotonic()
    for code in cells:
        student.kernel.execute(code, timeout=max(1.0, timeout - (time.monotonic() - start)))
    student.chapter_s = time.monotonic() - start


def stepper_session(student: Student, steps: int, interval: float, timeout: float) -> None:
    """``steps`` clicks on the bunny explorer, one every ``interval`` seconds, each timed
    from request to reply; CPU per step from the server's and kernel's CPU times."""
    # Students do not click in lockstep: start at a random moment within one interval.
    time.sleep(interval * secrets.randbelow(1000) / 1000)
    cpu_before, started = cpu_seconds(student.home), time.monotonic()
    for k in range(steps):
        if time.monotonic() - started > timeout:
            break
        tick = time.monotonic()
        seconds, _ = student.kernel.execute(f"bunny_explorer.go({MOVES[k % len(MOVES)]!r})", timeout=60)
        student.steps_ms.append(1000 * seconds)
        time.sleep(max(0.0, interval - (time.monotonic() - tick)))
    if student.steps_ms:
        student.cpu_per_step_ms = 1000 * (cpu_seconds(student.home) - cpu_before) / len(student.steps_ms)


# --------------------------------------------------------------------------- browser

def as_array(png: bytes):
    import numpy as np
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def is_drawn(picture) -> bool:
    """A grey mesh with coloured arrows, not a blank frame."""
    import numpy as np

    return float(picture.mean(axis=2).std()) >= MIN_STD and len(np.unique(picture.reshape(-1, 3), axis=0)) >= MIN_COLOURS


def changed_share(a, b) -> float:
    """The share of pixels that changed by more than CHANGED_LEVEL in some channel."""
    if a.shape != b.shape:
        return 1.0
    return float((abs(a - b).max(axis=2) > CHANGED_LEVEL).mean())


def settled_picture(frame, unlike, timeout: float):
    """(png, picture) of ``frame`` once drawn, different from ``unlike`` (if given) and
    the same in two shots a second apart; raises BenchError after ``timeout``."""
    previous, deadline = None, time.monotonic() + timeout
    while time.monotonic() < deadline:
        png = frame.screenshot(animations="disabled", timeout=30_000)
        picture = as_array(png)
        ok = is_drawn(picture) and (unlike is None or changed_share(unlike, picture) >= MIN_CHANGED_SHARE)
        if ok and previous is not None and changed_share(previous, picture) < MIN_CHANGED_SHARE / 4:
            return png, picture
        previous = picture
        time.sleep(1.0)
    raise BenchError(f"the live view did not settle {'on a new picture ' if unlike is not None else ''}"
                     f"within {timeout:.0f} s")


SHOW_EXPLORER = """() => {
    const app = window.jupyterapp;
    const panel = app.shell.currentWidget;
    const notebook = panel.content;
    notebook.activeCellIndex = notebook.widgets.length - 1;
    return app.commands.execute('notebook:insert-cell-below').then(() => {
        notebook.activeCell.model.sharedModel.setSource('explorer');
        return app.commands.execute('notebook:run-cell');
    });
}"""
NOTEBOOK_READY = """() => {
    const app = window.jupyterapp;
    const panel = app && app.shell.currentWidget;
    const kernel = panel && panel.sessionContext && panel.sessionContext.session
        && panel.sessionContext.session.kernel;
    return kernel && kernel.status === 'idle' && panel.context.isReady;
}"""


def look_in_browser(hub: Hub, students: list[Student], rotate_seconds: float, timeout: float,
                    screenshots: Path, log) -> list[dict]:
    """Each student's live view through the hub: drawn, a click moves the arrow, a drag
    rotates it; the server's CPU time while it rotates."""
    from playwright.sync_api import sync_playwright

    results = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium_path(), headless=True, args=[
            "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync"])
        try:
            for student in students:
                context = browser.new_context(viewport={"width": 1400, "height": 1000})
                page = context.new_page()
                console = []
                page.on("console", lambda message: console.append(f"{message.type}: {message.text}"))
                page.on("pageerror", lambda error: console.append(f"pageerror: {error}"))
                try:
                    results.append(one_view(hub, page, student, rotate_seconds, timeout, screenshots))
                except BenchError as error:
                    # One student's view failing is a result too: the others still count.
                    shot = screenshots / f"{student.name}-failure-page.png"
                    page.screenshot(path=str(shot))
                    sources = page.eval_on_selector_all("iframe", "frames => frames.map(f => f.src)")
                    log(f"[{student.name}] live view FAILED: {error}; the page: {shot}; its iframes: {sources}")
                    log("  browser console:\n  " + "\n  ".join(console[-15:]))
                    results.append({"student": student.name, "failed": str(error)})
                finally:
                    context.close()
                log(f"[{student.name}] live view: {results[-1]}")
        finally:
            browser.close()
    return results


def one_view(hub: Hub, page, student: Student, rotate_seconds: float, timeout: float, shots: Path) -> dict:
    ms = int(1000 * min(timeout, 180))
    page.goto(f"{hub.url}/hub/login", timeout=ms)
    page.fill("input[name=username]", student.name)
    page.fill("input[name=password]", PASSWORD)
    page.click("input[type=submit], button[type=submit]")
    page.wait_for_url("**/user/**", timeout=ms)
    page.goto(f"{hub.url}/user/{student.name}/lab/tree/course/{CHAPTER}?reset", timeout=ms)
    page.wait_for_function(NOTEBOOK_READY, polling=500, timeout=ms)
    page.evaluate(SHOW_EXPLORER)
    output = page.locator(".jp-OutputArea-output").filter(has_text="Halfedge explorer").last
    frame = output.locator("iframe").first
    frame.wait_for(state="visible", timeout=ms)
    frame.scroll_into_view_if_needed(timeout=ms)
    png, before = settled_picture(frame, None, timeout=min(timeout, 120))
    (shots / f"{student.name}-0-drawn.png").write_bytes(png)

    clicked = time.monotonic()
    output.get_by_role("button", name="next", exact=True).click()
    png, after = settled_picture(frame, before, timeout=min(timeout, 120))
    click_to_settled_ms = 1000 * (time.monotonic() - clicked)   # screenshots 1 s apart: not a latency (bench_clicks)
    (shots / f"{student.name}-1-next.png").write_bytes(png)
    moved = changed_share(before, after)

    box = frame.bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(cx, cy)
    cpu_before, start = cpu_seconds(student.home), time.monotonic()
    page.mouse.down()
    moves = 0
    while time.monotonic() - start < rotate_seconds and moves < 10_000:
        moves += 1
        # A slow circle of 80 px radius: the camera keeps turning.
        angle = moves * 0.05
        page.mouse.move(cx + 80 * (1 - abs((angle % 4) - 2)), cy + 40 * (1 - abs(((angle + 1) % 4) - 2)), steps=1)
        page.wait_for_timeout(16)
    page.mouse.up()
    dragged = time.monotonic() - start
    rotate_cpu = (cpu_seconds(student.home) - cpu_before) / dragged
    png, rotated = settled_picture(frame, after, timeout=min(timeout, 120))
    (shots / f"{student.name}-2-rotated.png").write_bytes(png)
    return {"student": student.name, "click_changed": round(moved, 4), "click_to_settled_ms": round(click_to_settled_ms),
            "rotate_changed": round(changed_share(after, rotated), 4),
            "rotate_cpu_per_s": round(rotate_cpu, 3), "drag_events": moves,
            "drags_per_s": round(moves / dragged, 1)}


# --------------------------------------------------------------------------- table

COLUMNS = [
    ("students", "N", "{:d}"), ("load", "load", "{:.1f}"),
    ("pss_mib", "PSS MiB", "{:.0f}"), ("kernel_pss_mib", "kernel PSS", "{:.0f}"), ("rss_mib", "RSS MiB", "{:.0f}"),
    ("spawn_s", "spawn s", "{:.1f}"), ("chapter_s", "ch.03 s", "{:.1f}"),
    ("step_p50_ms", "step p50 ms", "{:.0f}"), ("step_p95_ms", "step p95 ms", "{:.0f}"),
    ("cpu_per_step_ms", "CPU/step ms", "{:.0f}"), ("rotate_cpu_per_s", "CPU/s rotating", "{:.2f}"),
    ("drags_per_s", "drags/s", "{:.0f}"),
    ("views_drawn", "views ok", "{}"),
]


def table(rows: list[dict]) -> str:
    """A Markdown table of ``rows`` (ClassResult.row())."""
    lines = ["| " + " | ".join(title for _, title, _ in COLUMNS) + " |",
             "|" + "---:|" * len(COLUMNS)]
    for row in rows:
        cells = ["-" if row[key] != row[key] else fmt.format(row[key]) for key, _, fmt in COLUMNS]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def sizing(row: dict, cores: int) -> str:
    """GiB and cores per 100 students, from one row of the table."""
    gib = 100 * row["pss_mib"] / 1024
    step_cores = 100 * row["cpu_per_step_ms"] / 1000 / 1.0   # every student clicking once a second
    return (f"per 100 students: {gib:.0f} GiB (PSS after chapter 03); {step_cores:.1f} cores with every "
            f"student clicking once a second, plus {row['rotate_cpu_per_s']:.2f} core per student rotating "
            f"(measured on {cores} cores, load average {row['load']:.1f})")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--students", type=int, default=2, help="students in the class (default 2)")
    group.add_argument("--sweep", help="comma-separated class sizes, e.g. 1,5,10,20")
    parser.add_argument("--steps", type=int, default=20, help="stepper clicks per student (default 20)")
    parser.add_argument("--step-interval", type=float, default=1.0, help="seconds between a student's clicks")
    parser.add_argument("--rotate-seconds", type=float, default=5.0, help="how long to drag each live view")
    parser.add_argument("--browsers", type=int, default=2, help="students whose live view Chromium opens")
    parser.add_argument("--live-backend", choices=("server", "client"), default="client",
                        help="HALFEDGE_EDU_LIVE_BACKEND for every student")
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds any one phase may take")
    parser.add_argument("--screenshots", type=Path, help="folder for the live views' screenshots")
    parser.add_argument("--json", type=Path, help="also write the rows here")
    args = parser.parse_args(argv)
    needed = missing_setup(browser=args.browsers > 0)
    if needed:
        print("bench_class needs, once:\n  " + "\n  ".join(needed), file=sys.stderr)
        return 2
    sizes = [int(part) for part in args.sweep.split(",")] if args.sweep else [args.students]
    if args.screenshots:
        args.screenshots.mkdir(parents=True, exist_ok=True)
    rows = []
    for n in sizes:
        result = run_class(n, steps=args.steps, step_interval=args.step_interval,
                           rotate_seconds=args.rotate_seconds, browsers=min(args.browsers, n),
                           live_backend=args.live_backend, timeout=args.timeout, screenshots=args.screenshots)
        rows.append(result.row())
        print(table(rows[-1:]), flush=True)
        if args.json:
            args.json.write_text(json.dumps(rows, indent=1))
    print(f"\nlive backend: {args.live_backend}; {os.cpu_count()} cores; medians over students; "
          f"a step is bunny_explorer.go(move) once every {args.step_interval:g} s per student\n")
    print(table(rows))
    print(sizing(rows[-1], os.cpu_count() or 1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
