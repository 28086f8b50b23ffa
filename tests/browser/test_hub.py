"""A class of two on a real JupyterHub: benchmarks/bench_class.py's smallest case; and
the recipe's kernel culling, seen on a real hub.

The hub of deploy/jupyterhub/jupyterhub_config.py on 127.0.0.1 spawns two students'
servers through its REST API (deploy/singleuser-start.sh copies the course), runs
chapter 03 in both kernels at once, steps the bunny explorer in both, and then opens
both students' live 3D views through the hub in headless Chromium: each must be drawn,
move its arrow on a click of ``next`` and turn when dragged. The live views are the
recipes' default, drawn by vtk.js in the browser (``make lab``'s server-rendered view
has its own browser tests). What the benchmark measures on the way (memory, step
latency, CPU) is checked for being measured at all; its size is the benchmark's
business, not a pass/fail line on a shared machine. The one exception: a view drawn in
the browser turns without the student's server, so dragging costs it (almost) no CPU.
"""

from __future__ import annotations

import importlib.util
import math
import shutil
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
STEPS = 5


def bench_class():
    """benchmarks/bench_class.py as a module (benchmarks/ is not a package)."""
    spec = importlib.util.spec_from_file_location("bench_class", ROOT / "benchmarks" / "bench_class.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module   # dataclasses look their module up by name
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def hub_setup(chromium_executable):
    if shutil.which("configurable-http-proxy") is None:
        pytest.skip("configurable-http-proxy not installed: npm install -g configurable-http-proxy")
    bench = bench_class()
    missing = bench.missing_setup()
    assert not missing, f"bench_class names setup that is still missing: {missing}"
    return bench


def test_two_students_run_chapter_03_and_see_their_live_views_through_the_hub(hub_setup, screenshot_dir):
    bench = hub_setup
    result = bench.run_class(2, steps=STEPS, step_interval=0.5, rotate_seconds=2.0, browsers=2,
                             live_backend="client", timeout=600, screenshots=screenshot_dir)
    print(bench.table([result.row()]))
    assert [student.name for student in result.members] == ["student00", "student01"]
    for student in result.members:
        assert student.spawn_s > 0 and student.chapter_s > 0
        # Server plus kernel, after chapter 03: the kernel holds VTK and the bunny.
        assert 0 < student.kernel_pss_mib < student.pss_mib <= student.rss_mib
        assert len(student.steps_ms) == STEPS and all(ms > 0 for ms in student.steps_ms)
        assert student.cpu_per_step_ms > 0 and math.isfinite(student.cpu_per_step_ms)
    assert [view["student"] for view in result.browser] == ["student00", "student01"]
    for view in result.browser:
        assert "failed" not in view, view
        assert view["click_changed"] >= bench.MIN_CHANGED_SHARE, view
        assert view["rotate_changed"] >= bench.MIN_CHANGED_SHARE, view
        # Under 50 ms of CPU a second of dragging (server-rendered: 0.17-0.49, measured).
        assert view["drag_events"] > 0 and 0 <= view["rotate_cpu_per_s"] < 0.05, view
        for shot in ("0-drawn", "1-next", "2-rotated"):
            assert (screenshot_dir / f"{view['student']}-{shot}.png").stat().st_size > 0
    row = result.row()
    assert row["step_p50_ms"] <= row["step_p95_ms"]


# The kernel-culling test: the recipe's own config with a short timeout, as an instructor
# would shorten it to try it. cull_interval is a tenth of it, at least 1 s.
KERNEL_CULL_SECONDS = 6


def test_the_recipes_hub_culls_a_students_idle_kernel_even_with_its_tab_connected(tmp_path, monkeypatch):
    if shutil.which("configurable-http-proxy") is None:
        pytest.skip("configurable-http-proxy not installed: npm install -g configurable-http-proxy")
    bench = bench_class()
    monkeypatch.setenv("HALFEDGE_HUB_KERNEL_CULL_SECONDS", str(KERNEL_CULL_SECONDS))
    # A long home on purpose (pytest's tmp_path): the kernels' sockets must not live under
    # it (singleuser-start.sh's JUPYTER_RUNTIME_DIR), or no kernel starts.
    state = tmp_path
    hub = bench.start_hub(state, "client", timeout=120)
    try:
        import psutil

        culler = [process for process in psutil.Process(hub.process.pid).children(recursive=True)
                  if "jupyterhub_idle_culler" in " ".join(process.cmdline())]
        assert culler, f"the recipe's hub runs no jupyterhub-idle-culler:\n{hub.log_tail()}"
        bench.prepare_home(state, "student00")
        bench.spawn(hub, "student00", timeout=180)
        kernels_url = f"{hub.url}/user/student00/api/kernels"
        kernel = bench.Kernel(hub, "student00", "course/00_setup_and_tour.ipynb", timeout=120)
        try:
            kernel.execute("import halfedge_edu as hx; mesh = hx.sample('cube')", timeout=120)
            assert [k["id"] for k in bench.http_json("GET", kernels_url, hub.token)] == [kernel.kernel_id]
            # The websocket stays open (its tab is open) and nothing runs: the kernel goes.
            started, alive = time.monotonic(), True
            while alive and time.monotonic() - started < 20 * KERNEL_CULL_SECONDS:
                time.sleep(1)
                alive = bool(bench.http_json("GET", kernels_url, hub.token))
            waited = time.monotonic() - started
        finally:
            kernel.close()
        assert not alive, f"the idle kernel still runs after {waited:.0f} s:\n{hub.log_tail()}"
        assert waited >= KERNEL_CULL_SECONDS - 1, f"culled after {waited:.1f} s, before it was idle long enough"
        print(f"idle kernel culled {waited:.1f} s after its last cell (cull_idle_timeout={KERNEL_CULL_SECONDS})")
    finally:
        bench.stop_hub(hub)
