"""What several benchmark scripts share: the machine report, timing, the ~100k-face inputs, surface distance."""

from __future__ import annotations

import time

import numpy as np

import halfedge_edu as hx


def cpu_model() -> str:
    """The CPU's model name as Linux reports it, else the platform's processor string."""
    import platform

    try:
        with open("/proc/cpuinfo", encoding="utf-8") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def load_average() -> tuple[float, float, float]:
    """The 1-, 5- and 15-minute load averages (zeros where the system has none)."""
    import os

    try:
        return os.getloadavg()
    except OSError:
        return (0.0, 0.0, 0.0)


def machine_report() -> str:
    """One line naming the machine a run is on: CPU, logical cores, load, Python, numpy."""
    import os
    import platform

    one, five, fifteen = load_average()
    return (f"machine: {cpu_model()}, {os.cpu_count()} logical cores, load {one:.2f} / {five:.2f} / {fifteen:.2f} "
            f"(1 / 5 / 15 min); Python {platform.python_version()}, numpy {np.__version__}")


#: A benchmark's figures may go into the docs only if other processes used less than this
#: share of the machine's CPU time while it ran (these machines are shared and noisy).
QUIET_OTHER_SHARE = 0.10


def busy_cpu_seconds() -> float | None:
    """CPU seconds the whole machine has spent busy since boot, all cores, from ``/proc/stat``.

    Busy is user, nice, system, irq, softirq and steal time (steal: time a virtual
    machine's cores waited for the host, which slows a benchmark as much as a neighbour
    does); idle and I/O wait are not busy. ``None`` where there is no ``/proc/stat``.
    """
    import os

    try:
        with open("/proc/stat", encoding="ascii") as stat:
            fields = stat.readline().split()
    except OSError:
        return None
    if not fields or fields[0] != "cpu":
        return None
    ticks = [int(value) for value in fields[1:9]]  # user nice system idle iowait irq softirq steal
    busy = ticks[0] + ticks[1] + ticks[2] + ticks[5] + ticks[6] + ticks[7]
    return busy / os.sysconf("SC_CLK_TCK")


def own_cpu_seconds() -> float:
    """CPU seconds of this process and of every child it has waited for (theirs, recursively)."""
    import os

    times = os.times()
    return times.user + times.system + times.children_user + times.children_system


def adopt_orphans() -> bool:
    """Make this process the one its orphaned descendants are handed to (Linux), not init.

    A benchmark's grandchildren may outlive their parents: bubblewrap's sandbox process
    exits after its parent has, and init reaps it. Their CPU time then never reaches
    this process's children's times (:func:`own_cpu_seconds`), and :class:`OtherWork`
    would count the grader's own work as a neighbour's (and Chromium's, in a browser
    benchmark). Handed to this process instead, they are reaped by
    :func:`reap_orphans`, and their time is ours. It lasts for the process: a test
    process should not ask for it (its orphans would wait, unreaped, as zombies).
    False where the system has no such setting.
    """
    import ctypes

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


#: prctl's option number for "adopt orphaned descendants" (linux/prctl.h).
PR_SET_CHILD_SUBREAPER = 36


def reap_orphans() -> int:
    """Reap every descendant that has exited and was handed to this process; how many."""
    import os

    reaped = 0
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return reaped
        if pid == 0:
            return reaped
        reaped += 1


class OtherWork:
    """How much of the machine other processes used while a ``with`` block ran.

    The load average cannot say it: a benchmark's own work raises it (a one-core script
    running for a minute lifts the 1-minute load to about 0.6), so a run that follows
    another, or one that starts a Lab, a hub and a browser, always looks busy by it.
    This counts the machine's busy CPU time over the block (:func:`busy_cpu_seconds`)
    minus this process's and its children's (:func:`own_cpu_seconds`): what is left is
    the work of everything else, the noise in the figures. A child that is not waited
    for (a daemon it leaves behind) counts as other work, so the verdict errs towards busy.
    """

    def __init__(self, adopt_orphans: bool = False) -> None:
        self.adopt_orphans = adopt_orphans      # see adopt_orphans(): for a benchmark's own process
        self.seconds = 0.0
        self.other_cpu_seconds: float | None = None
        self.load_before = self.load_after = 0.0

    def start(self) -> OtherWork:
        """Begin counting; returns self (``with OtherWork() as other:`` does the same)."""
        if self.adopt_orphans:
            adopt_orphans()
        self.load_before = load_average()[0]
        self._busy, self._own, self._start = busy_cpu_seconds(), own_cpu_seconds(), time.perf_counter()
        return self

    def stop(self) -> OtherWork:
        """Stop counting: ``seconds``, ``other_cpu_seconds`` and ``load_after`` are then set."""
        self.seconds = time.perf_counter() - self._start
        if self.adopt_orphans:
            reap_orphans()
        busy = busy_cpu_seconds()
        if busy is not None and self._busy is not None:
            self.other_cpu_seconds = max(0.0, (busy - self._busy) - (own_cpu_seconds() - self._own))
        self.load_after = load_average()[0]
        return self

    __enter__ = start

    def __exit__(self, *exc_info) -> None:
        self.stop()

    def share(self, cores: int | None = None) -> float | None:
        """Other processes' CPU time as a share of the machine's over the block (None if unknown)."""
        import os

        if self.other_cpu_seconds is None:
            return None
        cores = cores or os.cpu_count() or 1
        return self.other_cpu_seconds / max(self.seconds * cores, 1e-9)

    def verdict(self, cores: int | None = None) -> tuple[bool, str]:
        """Whether the block's figures may feed the docs' tables, and the sentence that says so."""
        import os

        cores = cores or os.cpu_count() or 1
        return fit_for_the_docs(self.share(cores), self.load_before, self.load_after, self.seconds, cores)


def fit_for_the_docs(other_share: float | None, load_before: float, load_after: float, seconds: float,
                     cores: int | None = None) -> tuple[bool, str]:
    """Whether a run in which other processes used ``other_share`` of the machine may feed
    the docs' tables, and the sentence that says so (with the load averages, for the record).

    ``None`` (no ``/proc/stat`` to measure with) is never fit: a figure nobody could
    check the machine for does not go into the docs.
    """
    import os

    cores = cores or os.cpu_count() or 1
    loads = f"load {load_before:.2f} before, {load_after:.2f} after, {seconds:.0f} s"
    if other_share is None:
        return False, (f"{loads}; other processes' CPU time could not be measured (no /proc/stat): "
                       f"these figures are NOT fit for the docs' tables")
    said = f"other processes used {100 * other_share:.1f}% of the {cores} cores' time ({loads})"
    if other_share < QUIET_OTHER_SHARE:
        return True, f"{said} < {100 * QUIET_OTHER_SHARE:.0f}%: fit for the docs' tables"
    return False, (f"{said}, limit {100 * QUIET_OTHER_SHARE:.0f}%: the machine was busy; these figures "
                   f"are NOT fit for the docs' tables, run again when it is idle")


def timed(function, *args):
    """``(seconds, result)`` of one call."""
    start = time.perf_counter()
    result = function(*args)
    return time.perf_counter() - start, result


def interleaved_medians(repeats: int, functions: dict, *, cpu: bool = False) -> dict[str, tuple[float, object]]:
    """``{name: (seconds, result)}``: each function's median time over ``repeats`` rounds, and its last result.

    Every round calls each function once, in turn, so a spell of other work on the
    machine falls on ours and the peers' alike and the ratios hold better than the
    times. ``cpu=True`` times CPU seconds of this process (``time.process_time``), which
    leave out the time it waited while others ran.
    """
    clock = time.process_time if cpu else time.perf_counter
    seconds: dict[str, list[float]] = {name: [] for name in functions}
    results: dict[str, object] = {}
    for _ in range(max(1, repeats)):
        for name, function in functions.items():
            start = clock()
            results[name] = function()
            seconds[name].append(clock() - start)
    return {name: (float(np.median(seconds[name])), results[name]) for name in functions}


def hundred_k_inputs(quick: bool):
    """The bunny (a real scan, 69k faces) and, unless quick, Spot subdivided twice (94k).

    Midpoint subdivision leaves Spot's shape exactly as it was, so the second input is
    full of flat regions where many collapses cost nothing: a hard case for orderings.
    """
    yield "bunny", hx.sample("bunny")
    if not quick:
        import trimesh

        spot = hx.sample("spot").to_trimesh()
        vertices, faces = trimesh.remesh.subdivide(spot.vertices, spot.faces)
        vertices, faces = trimesh.remesh.subdivide(vertices, faces)
        yield "spot, subdivided twice", hx.HalfedgeMesh.from_faces(vertices, faces)


def surface_distance(vertices_a, faces_a, vertices_b, faces_b) -> tuple[float, float]:
    """Symmetric (mean, max) distance between two surfaces, measured at their vertices.

    PyVista's implicit distance from each surface's vertices to the other surface.
    """
    import pyvista as pv

    a = pv.PolyData.from_regular_faces(np.asarray(vertices_a, float), np.asarray(faces_a))
    b = pv.PolyData.from_regular_faces(np.asarray(vertices_b, float), np.asarray(faces_b))
    a_to_b = np.abs(a.compute_implicit_distance(b)["implicit_distance"])
    b_to_a = np.abs(b.compute_implicit_distance(a)["implicit_distance"])
    return 0.5 * (a_to_b.mean() + b_to_a.mean()), float(max(a_to_b.max(), b_to_a.max()))
