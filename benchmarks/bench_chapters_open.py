"""Memory of a student who opens chapters in turn, on the real hub: bench_class.py's hub,
students and kernels, several chapters instead of one.

    python benchmarks/bench_chapters_open.py --students 5
    python benchmarks/bench_chapters_open.py --sweep 1,5,10 --chapters 03,06,07

JupyterLab keeps a notebook's kernel when its tab closes, so a student who works through
chapters 03, 06 and 07 in one sitting has three kernels unless they shut each one down
(or the hub's kernel culling does, deploy/jupyterhub/jupyterhub_config.py). For each N
the script starts deploy/jupyterhub/jupyterhub_config.py (bench_class.start_hub), spawns
N students, and then, for each chapter in turn, all students at once:

1. open the chapter from their ``~/course`` (the student edition, a new kernel; the
   earlier chapters' kernels stay, as in JupyterLab) and run every code cell, a "run
   all" burst: its wall time and the server's and kernels' CPU seconds;
2. measure each student's PSS and RSS (server plus all kernels) and each kernel's PSS.

At the end, in every kernel of the first student, what holds the memory: the live
plotters (pyvista's ``_ALL_PLOTTERS``, each with a VTK render window and, for a live
view, a trame server) and the kernel's PSS before and after ``pyvista.close_all()``, a
garbage collection and glibc's ``malloc_trim`` (what a closed widget could give back).

A cell that raises (a student-edition stub) is counted, not fatal: "run all" in the Lab
stops there, the benchmark goes on so that every chapter's widgets are built.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import importlib.util
import json
import os
import shutil
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MIB = 1024 * 1024


def bench_class():
    """benchmarks/bench_class.py as a module (benchmarks/ is not a package)."""
    spec = importlib.util.spec_from_file_location("bench_class", ROOT / "benchmarks" / "bench_class.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


bc = bench_class()

# Printed by a kernel: its process id and what it holds (one JSON line).
HOLDINGS = r"""
import gc, json, os
import pyvista as _pv
from pyvista.plotting.plotter import _ALL_PLOTTERS as _plotters
print(json.dumps({"pid": os.getpid(), "plotters": len(_plotters),
                  "render_windows": sum(1 for p in _plotters.values() if getattr(p, "render_window", None) is not None)}))
"""
RELEASE = r"""
import ctypes, gc, json
import pyvista as _pv
_pv.close_all()
gc.collect()
ctypes.CDLL("libc.so.6").malloc_trim(0)
print(json.dumps({"closed": True}))
"""


@dataclass
class Opened:
    chapter: str
    seconds: float
    cpu_s: float
    errors: int
    pss_mib: float
    rss_mib: float
    kernel_pss_mib: list[float]


@dataclass
class Student:
    name: str
    home: Path
    kernels: list = field(default_factory=list)
    opened: list[Opened] = field(default_factory=list)


def kernel_pid(student: Student, kernel) -> int:
    """The process of ``kernel``: the server's child whose connection file names its id."""
    _, children = bc.server_processes(student.home)
    for process in children:
        if kernel.kernel_id in " ".join(process.cmdline()):
            return process.pid
    raise bc.BenchError(f"no process for kernel {kernel.kernel_id} of {student.name}")


def printed_json(kernel, code: str) -> dict:
    """Run ``code`` and parse the JSON line it prints. The reply can overtake the printed
    text (they come on different channels), so an empty answer is asked for again."""
    for _ in range(5):
        text = kernel.execute(code, timeout=120)[1].strip()
        if text:
            return json.loads(text.splitlines()[-1])
        time.sleep(0.5)
    raise bc.BenchError("the kernel printed nothing")


def kernel_pss(pid: int) -> float:
    import psutil

    return psutil.Process(pid).memory_full_info().pss / MIB


def open_chapter(hub, student: Student, chapter: str, timeout: float) -> None:
    """Open ``chapter`` in a new kernel as the Lab does and run all its cells."""
    path = f"course/{chapter}"
    cells = bc.chapter_cells(student.home / path)
    cpu_before = bc.cpu_seconds(student.home)
    kernel = bc.Kernel(hub, student.name, path, timeout=60)
    student.kernels.append(kernel)
    start, errors = time.monotonic(), 0
    for code in cells:
        try:
            kernel.execute(code, timeout=max(1.0, timeout - (time.monotonic() - start)))
        except bc.BenchError:
            errors += 1
    seconds = time.monotonic() - start
    cpu = bc.cpu_seconds(student.home) - cpu_before
    pss, _, rss = bc.memory(student.home)
    pids = [kernel_pid(student, k) for k in student.kernels]
    student.opened.append(Opened(chapter, seconds, cpu, errors, pss, rss, [kernel_pss(pid) for pid in pids]))


def reconnect(hub, student: Student, kernel) -> None:
    """A new websocket to ``kernel``: the server closes one left idle (unanswered pings)
    while the student worked in the other chapters."""
    import uuid

    import websocket

    kernel.ws.close()
    kernel.session = uuid.uuid4().hex
    url = (f"{hub.url}/user/{student.name}/api/kernels/{kernel.kernel_id}/channels?session_id={kernel.session}"
           .replace("http://", "ws://"))
    kernel.ws = websocket.create_connection(url, header=[f"Authorization: token {hub.token}"], timeout=120)


def holdings(hub, student: Student) -> list[dict]:
    """For each kernel of ``student``: plotters and render windows it holds, PSS before and
    after closing them all."""
    found = []
    for kernel, opened in zip(student.kernels, student.opened):
        reconnect(hub, student, kernel)
        before = printed_json(kernel, HOLDINGS)
        pss_before = kernel_pss(before["pid"])
        kernel.execute(RELEASE, timeout=120)
        time.sleep(1)
        found.append({"chapter": opened.chapter, "plotters": before["plotters"],
                      "render_windows": before["render_windows"], "pss_mib": pss_before,
                      "pss_after_close_all_mib": kernel_pss(before["pid"])})
    return found


def run(n: int, chapters: list[str], live_backend: str, timeout: float, log=print) -> dict:
    state = Path(tempfile.mkdtemp(prefix=f"ho{n}-", dir="/tmp"))
    members = [Student(f"student{i:02d}", state / f"student{i:02d}") for i in range(n)]
    for student in members:
        bc.prepare_home(state, student.name)
    hub = bc.start_hub(state, live_backend, timeout=180)
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=n) as pool:
            list(pool.map(lambda s: bc.spawn(hub, s.name, timeout), members))
            idle = [bc.memory(s.home)[0] for s in members]
            for chapter in chapters:
                list(pool.map(lambda s: open_chapter(hub, s, chapter, timeout), members))
                log(f"[{n}] {chapter}: PSS median {statistics.median(s.opened[-1].pss_mib for s in members):.0f} MiB")
        try:
            held = holdings(hub, members[0])
        except Exception as problem:  # the table above is worth keeping without it
            log(f"[{n}] could not read what the kernels hold: {problem!r}")
            held = []
        for student in members:
            for kernel in student.kernels:
                kernel.close()
        rows = []
        for k, chapter in enumerate(chapters):
            opened = [s.opened[k] for s in members]
            rows.append({
                "students": n, "open": k + 1, "chapter": chapter,
                "pss_mib": statistics.median(o.pss_mib for o in opened),
                "rss_mib": statistics.median(o.rss_mib for o in opened),
                "kernel_pss_mib": statistics.median(o.kernel_pss_mib[-1] for o in opened),
                "run_all_s": statistics.median(o.seconds for o in opened),
                "run_all_max_s": max(o.seconds for o in opened),
                "run_all_cpu_s": statistics.median(o.cpu_s for o in opened),
                "errors": statistics.median(o.errors for o in opened),
            })
        return {"students": n, "idle_server_pss_mib": statistics.median(idle), "rows": rows, "holdings": held,
                "load": os.getloadavg()[0]}
    finally:
        bc.stop_hub(hub)
        shutil.rmtree(state, ignore_errors=True)


def table(results: list[dict]) -> str:
    lines = ["| N | chapters open | last opened | PSS MiB / student | RSS MiB | newest kernel PSS | "
             "run all s (median / max) | run all CPU s | cells raising |",
             "|---:|---:|---|---:|---:|---:|---:|---:|---:|"]
    for result in results:
        for row in result["rows"]:
            lines.append(f"| {row['students']} | {row['open']} | {row['chapter']} | {row['pss_mib']:.0f} | "
                         f"{row['rss_mib']:.0f} | {row['kernel_pss_mib']:.0f} | {row['run_all_s']:.1f} / "
                         f"{row['run_all_max_s']:.1f} | {row['run_all_cpu_s']:.1f} | {row['errors']:.0f} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--students", type=int, default=1)
    group.add_argument("--sweep", help="comma-separated class sizes, e.g. 1,5,10")
    parser.add_argument("--chapters", default="03,06,07", help="chapter numbers opened in turn (default 03,06,07)")
    parser.add_argument("--live-backend", choices=("server", "client"), default="client")
    parser.add_argument("--timeout", type=float, default=900.0)
    parser.add_argument("--json", type=Path, help="also write the results here")
    args = parser.parse_args(argv)
    needed = bc.missing_setup(browser=False)
    if needed:
        print("bench_chapters_open needs, once:\n  " + "\n  ".join(needed), file=sys.stderr)
        return 2
    names = sorted(p.name for p in (ROOT / "notebooks" / "student").glob("[0-9][0-9]*_*.ipynb"))
    chapters = [next(name for name in names if name.startswith(number + "_")) for number in args.chapters.split(",")]
    sizes = [int(part) for part in args.sweep.split(",")] if args.sweep else [args.students]
    results = []
    for n in sizes:
        results.append(run(n, chapters, args.live_backend, args.timeout))
        if args.json:
            args.json.write_text(json.dumps(results, indent=1))
    print(f"\nlive backend: {args.live_backend}; {os.cpu_count()} cores; medians over students\n")
    print(table(results))
    print("\nwhat the first student's kernels hold (PSS MiB before -> after pyvista.close_all() + gc + malloc_trim):")
    for result in results:
        for held in result["holdings"]:
            print(f"  N={result['students']} {held['chapter']}: {held['plotters']} plotters, "
                  f"{held['render_windows']} render windows, {held['pss_mib']:.0f} -> {held['pss_after_close_all_mib']:.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
