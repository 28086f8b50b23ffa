"""Quadric simplification to 10%: halfedge_edu beside openmesh and fast-simplification.

    python benchmarks/bench_simplify.py
    python benchmarks/bench_simplify.py --quick     # the bunny only
    python benchmarks/bench_simplify.py --repeat 5  # median of 5 runs each (default 3)
    python benchmarks/bench_simplify.py --profile   # where our time goes, phase by phase
    python benchmarks/bench_simplify.py --cpu       # CPU time of this process instead of wall-clock time
    python benchmarks/bench_simplify.py --rounds    # each round's phases, and how much of the mesh it touched

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
the bounding-box diagonal. Times are the median of ``--repeat`` rounds, each of which
runs every method once in turn (``_common.interleaved_medians``); ratios are our time
over the peer's. With ``--cpu`` a time is the CPU time the
process spent (user + system, ``time.process_time``): every method runs on one thread,
so on a machine shared with other jobs that is steadier than the wall clock, which also
counts the time the process waited for a core.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

import halfedge_edu as hx
from _common import hundred_k_inputs, interleaved_medians, surface_distance
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


#: The phases ``--rounds`` times, as (column, function name in the simplify module). The
#: first two do the same work whatever the round collapses (sorts of, or a pass over,
#: every face); the others work mostly on what the round picks and changes.
ROUND_PHASES = [
    ("tables", "round_tables"),          # two sorts of the face array
    ("apply", "merge_vertices"),         # one pass over the face array
    ("pricing", "_EdgePrices.update"),   # re-prices the edges at moved vertices
    ("choice", "choose_round"),          # picks, topology and turned-face checks
    ("folds", "drop_folding_neighbours"),
]


def profile_rounds(name: str, mesh, target: int) -> None:
    """Print, round by round, the CPU time of each phase of ``simplify`` and how much of the mesh the round touched.

    The phases are timed by wrapping the functions the simplify module calls (the
    wrappers are taken off again at the end). "touched" is the share of the faces that
    hold an end of one of the round's collapses: the region a round changes (counting
    it is left out of the times). "tables" in a row are those the round worked on
    (built at the end of the round before).
    """
    module = sys.modules[simplify.__module__]
    seconds = {}                                 # (round, column) -> CPU seconds
    touched = []                                 # per round: (faces before, collapses, faces touched)
    state = {"round": 0, "counting": 0.0}        # the round under way; CPU seconds spent counting touched faces

    def owner_and_name(path):                    # "f" is module.f, "C.f" is module.C.f
        *owner, name = path.split(".")
        return (getattr(module, owner[0]) if owner else module), name

    originals = {path: getattr(*owner_and_name(path)) for _, path in ROUND_PHASES}

    def timed_phase(column, function):
        def wrapper(*args, **kwargs):
            start = time.process_time()
            result = function(*args, **kwargs)
            key = (state["round"], column)
            seconds[key] = seconds.get(key, 0.0) + time.process_time() - start
            if column == "apply":                # merge_vertices(faces, remove, keep, n) ends a round
                counting = time.process_time()
                faces, remove, keep, n = args
                merged = np.zeros(n, dtype=bool)
                merged[remove] = True
                merged[keep] = True
                touched.append((len(faces), len(remove), int(merged[faces].any(axis=1).sum())))
                state["round"] += 1
                state["counting"] += time.process_time() - counting
            return result
        return wrapper

    for column, path in ROUND_PHASES:
        setattr(*owner_and_name(path), timed_phase(column, originals[path]))
    try:
        start = time.process_time()
        result = simplify_with_report(mesh, target)
        total = time.process_time() - start - state["counting"]
    finally:
        for path, original in originals.items():
            setattr(*owner_and_name(path), original)
    columns = [column for column, _ in ROUND_PHASES]
    print(f"{name}: {total:.3f} s CPU, {result.report.rounds} rounds (ms of CPU per phase)")
    print(f"{'round':>5}{'faces':>8}{'collapses':>10}{'touched':>9}" + "".join(f"{c:>9}" for c in columns))
    for index, (faces, collapses, faces_touched) in enumerate(touched):
        times = "".join(f"{1000 * seconds.get((index, column), 0.0):9.1f}" for column in columns)
        print(f"{index + 1:>5}{faces:>8}{collapses:>10}{faces_touched / faces:>9.0%}{times}")
    sums = {column: sum(s for (_, c), s in seconds.items() if c == column) for column in columns}
    whole = sums["tables"] + sums["apply"]
    print("  sums: " + ", ".join(f"{c} {1000 * sums[c]:.0f} ms" for c in columns)
          + f", the rest (first quadrics, candidate order) {1000 * (total - sum(sums.values())):.0f} ms")
    print(f"  whole-mesh rebuilds (tables + apply): {100 * whole / total:.0f}% of the time; "
          f"faces touched per round: {sum(t for _, _, t in touched) / sum(f for f, _, _ in touched):.0%} on average")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the bunny only")
    parser.add_argument("--repeat", type=int, default=3, help="time each method this many times, keep the median")
    parser.add_argument("--profile", action="store_true", help="profile our phases instead of timing the peers")
    parser.add_argument("--cpu", action="store_true", help="time in CPU seconds of this process, not wall-clock")
    parser.add_argument("--rounds", action="store_true", help="each round's phases and the share of faces it touched")
    args = parser.parse_args(argv)
    if args.rounds:
        simplify(hx.sample("spot"), 1000)          # first call: imports stay out of the timings
        for name, mesh in inputs(args.quick):
            profile_rounds(name, mesh, mesh.n_faces // 10)
        return
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
        timings = interleaved_medians(args.repeat, {
            "halfedge_edu": lambda: run_ours(mesh, target),
            "openmesh": lambda: run_openmesh(vertices, faces, target),
            "fast-simplification": lambda: run_fast_simplification(vertices, faces, target),
        }, cpu=args.cpu)
        t_ours = timings["halfedge_edu"][0]
        rows = [(label, seconds, np.asarray(result[0]), np.asarray(result[1]))
                for label, (seconds, result) in timings.items()]
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
    print("goal: <= 1.0x openmesh's time (issue 29), mean distance <= fast-simplification's")


if __name__ == "__main__":
    main()
