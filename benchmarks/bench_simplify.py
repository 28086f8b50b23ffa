"""Quadric simplification to 10%: halfedge_edu beside openmesh and fast-simplification.

    python benchmarks/bench_simplify.py
    python benchmarks/bench_simplify.py --quick     # the bunny only
    python benchmarks/bench_simplify.py --repeat 5  # median of 5 runs each (default 3)
    python benchmarks/bench_simplify.py --profile   # where our time goes, phase by phase
    python benchmarks/bench_simplify.py --cpu       # CPU time of this process instead of wall-clock time

Three inputs of about 100k faces, three kinds of surface: the bunny (a scan), Spot
subdivided twice at edge midpoints (piecewise flat: many collapses cost nothing) and
Spot Loop-subdivided twice (smooth: costs vary slowly, so cheap edges lie in broad
regions). Each row simplifies the same input to 10% of its faces three ways, in the
same run:
* halfedge_edu: ``simplify`` (rounds of independent collapses, numpy);
* openmesh: ``TriMeshDecimater`` with ``ModQuadric`` (C++, one collapse at a time);
* fast-simplification: ``simplify(..., target_reduction=0.9)`` (C++, Fast-Quadric-Mesh-Simplification).
Quality is the symmetric mean and max distance between result and input surfaces
(PyVista's implicit distance from each one's vertices to the other), as a fraction of
the bounding-box diagonal. Times are the median of ``--repeat`` runs, for every method
alike; ratios are our time over the peer's. With ``--cpu`` a time is the CPU time the
process spent (user + system, ``time.process_time``): every method runs on one thread,
so on a machine shared with other jobs that is steadier than the wall clock, which also
counts the time the process waited for a core.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import halfedge_edu as hx
from _common import median_of, hundred_k_inputs, surface_distance
from halfedge_edu.algorithms.simplify import simplify, simplify_with_report

#: The phases of a round, as the functions that do them (cumulative time of each).
PHASES = [
    ("edge and ring tables", "round_tables"),
    ("pricing (re-price changed edges)", "update"),
    ("round choice, all passes", "choose_round"),
    ("  topology checks", "collapse_topology_ok"),
    ("  turned-face checks", "no_turned_faces"),
    ("  independence", "independent_edges"),
    ("folds between collapses", "drop_folding_neighbours"),
    ("apply (merge vertices)", "merge_vertices"),
    ("vertex quadrics (start)", "_accumulate_rows"),
]


def inputs(quick: bool):
    """The shared ~100k-face inputs and, unless quick, Spot Loop-subdivided twice (94k)."""
    yield from hundred_k_inputs(quick)
    if not quick:
        yield "spot, Loop twice", hx.loop_subdivide(hx.sample("spot"), levels=2)


def run_ours(mesh, target):
    result = simplify(mesh, target)
    return result.to_arrays()


def run_openmesh(vertices, faces, target):
    import openmesh

    om = openmesh.TriMesh(vertices, faces)
    decimater = openmesh.TriMeshDecimater(om)
    quadric = openmesh.TriMeshModQuadricHandle()
    decimater.add(quadric)
    decimater.initialize()
    decimater.decimate_to_faces(0, target)
    om.garbage_collection()
    return om.points(), om.face_vertex_indices()


def run_fast_simplification(vertices, faces, target):
    import fast_simplification

    return fast_simplification.simplify(
        vertices.astype(np.float32), faces.astype(np.int32), target_count=target
    )


def profile(name: str, mesh, target: int) -> None:
    """Print the cumulative time of each phase of ``simplify`` (cProfile) and the number of rounds."""
    import cProfile
    import pstats

    profiler = cProfile.Profile()
    profiler.enable()
    result = simplify_with_report(mesh, target)
    profiler.disable()
    stats = pstats.Stats(profiler).stats                       # {(file, line, function): (..., cumtime, ...)}
    total = max(cumulative for (_, _, function), (_, _, _, cumulative, _) in stats.items() if function == "_simplify")
    print(f"{name}: {total:.3f} s under cProfile, {result.report.rounds} rounds")
    for label, function in PHASES:
        seconds = sum(cumulative for (path, _, called), (_, _, _, cumulative, _) in stats.items()
                      if called == function and "halfedge_edu" in path)
        print(f"   {label:<36}{seconds:7.3f} s {100 * seconds / total:5.1f}%")


def median_cpu_of(repeats: int, function, *args):
    """``(seconds, result)`` like ``median_of``, in CPU time of this process (``time.process_time``)."""
    runs = []
    for _ in range(max(1, repeats)):
        start = time.process_time()
        result = function(*args)
        runs.append((time.process_time() - start, result))
    return float(np.median([seconds for seconds, _ in runs])), runs[-1][1]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the bunny only")
    parser.add_argument("--repeat", type=int, default=3, help="time each method this many times, keep the median")
    parser.add_argument("--profile", action="store_true", help="profile our phases instead of timing the peers")
    parser.add_argument("--cpu", action="store_true", help="time in CPU seconds of this process, not wall-clock")
    args = parser.parse_args(argv)
    timer = median_cpu_of if args.cpu else median_of
    if args.profile:
        simplify(hx.sample("spot"), 1000)          # first call: imports (scipy.sparse) stay out of the profile
        for name, mesh in inputs(args.quick):
            profile(name, mesh, mesh.n_faces // 10)
        return

    header = f"{'input':<24}{'faces':>8}{'method':>21}{'result':>8}{'time s':>9}{'ours/peer':>11}{'mean dist':>11}{'max dist':>10}{'valid':>7}"
    print("Quadric simplification to 10% of the faces" + (" (CPU seconds)" if args.cpu else ""))
    print(header)
    print("-" * len(header))
    for name, mesh in inputs(args.quick):
        vertices, faces = mesh.to_arrays()
        diagonal = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
        target = len(faces) // 10
        t_ours, (v_ours, f_ours) = timer(args.repeat, run_ours, mesh, target)
        rows = [("halfedge_edu", t_ours, v_ours, f_ours)]
        for label, function in (("openmesh", run_openmesh), ("fast-simplification", run_fast_simplification)):
            seconds, (v, f) = timer(args.repeat, function, vertices, faces, target)
            rows.append((label, seconds, np.asarray(v), np.asarray(f)))
        for label, seconds, v, f in rows:
            mean, worst = surface_distance(vertices, faces, v, f)
            try:
                hx.HalfedgeMesh.from_faces(v, f).validate()
                valid = "yes"
            except (hx.MeshInputError, hx.MeshInvariantError):
                valid = "no"
            ratio = "" if label == "halfedge_edu" else f"{t_ours / seconds:.1f}x"
            print(
                f"{name:<24}{len(faces):>8,}{label:>21}{len(f):>8,}{seconds:>9.3f}{ratio:>11}"
                f"{mean / diagonal:>11.2e}{worst / diagonal:>10.2e}{valid:>7}"
            )
    print("goal: <= 1.5x openmesh's time, mean distance <= fast-simplification's")


if __name__ == "__main__":
    main()
