"""What several benchmark scripts share: the machine report, timing, the ~100k-face inputs, surface distance."""

from __future__ import annotations

import time

import numpy as np

import halfedge_edu as hx


#: A run is fit for the docs' tables only if the 1-minute load average stayed below this
#: share of the logical cores before and after it (these machines are shared and noisy).
QUIET_LOAD_SHARE = 0.25


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


def fit_for_the_docs(load_before: float, load_after: float, cores: int | None = None) -> tuple[bool, str]:
    """Whether a run whose 1-minute load was ``load_before`` and ``load_after`` may feed
    the docs' tables, and the sentence that says so."""
    import os

    cores = cores or os.cpu_count() or 1
    limit = QUIET_LOAD_SHARE * cores
    worst = max(load_before, load_after)
    if worst < limit:
        return True, f"load {load_before:.2f} before, {load_after:.2f} after (< {limit:.2f}): fit for the docs' tables"
    return False, (f"load {load_before:.2f} before, {load_after:.2f} after (limit {limit:.2f} on {cores} cores): "
                   f"the machine was busy; these figures are NOT fit for the docs' tables, run again when it is idle")


def timed(function, *args):
    """``(seconds, result)`` of one call."""
    start = time.perf_counter()
    result = function(*args)
    return time.perf_counter() - start, result


def median_of(repeats: int, function, *args):
    """``(seconds, result)``: the median of ``repeats`` calls, and the last call's result.

    Medians, with every peer timed in the same process run: the issue's rule for the table.
    """
    runs = [timed(function, *args) for _ in range(max(1, repeats))]
    return float(np.median([seconds for seconds, _ in runs])), runs[-1][1]


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
