"""Build speed and memory: halfedge_edu beside openmesh and trimesh, in the same run.

    python benchmarks/bench_build.py            # ~10k, ~100k, ~1.3M faces
    python benchmarks/bench_build.py --quick    # the two smaller sizes only
    python benchmarks/bench_build.py --rounds 9 # rounds of turns (default 5)

Every size builds the same faces three ways, in two orders:
* halfedge_edu: ``HalfedgeMesh.from_faces`` (checks included: manifold, orientation,
  fans);
* openmesh: ``openmesh.TriMesh(points, faces)`` (its C++ add_face loop);
* trimesh: what it takes to answer the same adjacency questions
  (``edges_unique`` + ``face_adjacency`` + ``vertex_neighbors``) on a fresh Trimesh.
"as generated" is trimesh's icosphere in the order it makes it; "random order" shuffles
the faces and renumbers the vertices at random, which is what a mesh from a scanner or an
exporter looks like to the cache. Our build, openmesh's and ``validate()`` over our build
take turns, both orders in the same rounds (``--rounds`` of them, medians), so that a
busy spell of the shared machine lands on every contender and both orders alike;
trimesh is timed after them (one run at 1.3M faces, which takes tens of seconds there).
Ratios are halfedge_edu's time over the peer's: below 1.0 means we are faster. Read
the ratios, not the seconds, and the load printed before and after: openmesh's
add_face loop gains most from the as-generated order's locality, so a busy machine
(other jobs evicting the cache) flatters our ratio there.

"validate/build" is ``mesh.validate()`` over our build (medians of the same rounds), in
wall time and in CPU time (``time.process_time``: the time this process ran, which other
processes on a busy machine change less than the wall time), "validate/around"
``validate()`` over ``validate_around`` after one flip.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
import tracemalloc

import numpy as np

import halfedge_edu as hx
from _common import OtherWork, machine_report
from halfedge_edu.core.validate import validate_around


def icosphere(level: int) -> tuple[np.ndarray, np.ndarray]:
    """(V, F) of a unit icosphere with 20 * 4**level faces (trimesh's construction)."""
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=level)
    return np.asarray(sphere.vertices), np.asarray(sphere.faces)


def shuffled(vertices: np.ndarray, faces: np.ndarray, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """The same mesh with faces in random order and vertices renumbered at random."""
    rng = np.random.default_rng(seed)
    relabel = rng.permutation(len(vertices))          # old vertex -> new vertex
    new_vertices = np.empty_like(vertices)
    new_vertices[relabel] = vertices
    return new_vertices, relabel[faces][rng.permutation(len(faces))]


def median_time(function, repeats: int) -> float:
    """Median wall time of ``repeats`` calls (the issue's rule: medians, peers in the same run)."""
    return interleaved_medians(repeats, only=function)["only"]


def interleaved_medians(repeats: int, **functions) -> dict[str, float]:
    """Median wall time of each function over ``repeats`` rounds, each round calling them all in turn.

    Taking turns spreads a busy spell of the machine over every contender instead of
    letting it land on one of them.
    """
    return interleaved_wall_and_cpu_medians(repeats, **functions)[0]


def interleaved_wall_and_cpu_medians(repeats: int, **functions) -> tuple[dict[str, float], dict[str, float]]:
    """(wall, cpu): median wall time and median CPU time of each function, in the same rounds.

    As :func:`interleaved_medians`; the CPU time (``time.process_time``) leaves out the
    time this process waited while others ran, so on a shared machine it moves less
    between runs than the wall time.
    """
    wall: dict[str, list[float]] = {name: [] for name in functions}
    cpu: dict[str, list[float]] = {name: [] for name in functions}
    for _ in range(repeats):
        for name, function in functions.items():
            start, start_cpu = time.perf_counter(), time.process_time()
            function()
            wall[name].append(time.perf_counter() - start)
            cpu[name].append(time.process_time() - start_cpu)
    return ({name: float(np.median(seconds)) for name, seconds in wall.items()},
            {name: float(np.median(seconds)) for name, seconds in cpu.items()})


def build_ours(vertices, faces):
    return hx.HalfedgeMesh.from_faces(vertices, faces)


def build_openmesh(vertices, faces):
    import openmesh

    return openmesh.TriMesh(vertices, faces)


def build_trimesh_adjacency(vertices, faces):
    import trimesh

    mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
    mesh.edges_unique
    mesh.face_adjacency
    mesh.vertex_neighbors
    return mesh


def peak_build_memory_mib(vertices, faces) -> float:
    """Peak memory numpy allocates while building (tracemalloc sees numpy's buffers)."""
    tracemalloc.start()
    mesh = build_ours(vertices, faces)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    del mesh
    return peak / 2**20


def import_time_and_pyvista() -> tuple[float, bool]:
    """Seconds for ``import halfedge_edu`` in a fresh interpreter, and whether it pulled pyvista in."""
    code = (
        "import time, sys; t = time.perf_counter(); import halfedge_edu; "
        "print(time.perf_counter() - t, 'pyvista' in sys.modules)"
    )
    seconds, pyvista = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    return float(seconds), pyvista == "True"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the 1.3M-face mesh")
    parser.add_argument("--rounds", type=int, default=5, help="rounds of turns (medians over them)")
    args = parser.parse_args(argv)

    print(machine_report(), flush=True)
    other_work = OtherWork(adopt_orphans=True).start()  # other processes' CPU time while this runs
    levels = [5, 6] if args.quick else [5, 6, 8]       # 20,480 / 81,920 / 1,310,720 faces
    header = (
        f"{'mesh':<34}{'faces':>10}{'ours s':>9}{'openmesh s':>12}{'trimesh s':>11}"
        f"{'vs openmesh':>13}{'vs trimesh':>12}{'validate/build':>16}{'(cpu)':>7}{'validate/around':>17}"
    )
    print("Build: HalfedgeMesh.from_faces vs openmesh.TriMesh vs trimesh adjacency")
    print(header)
    print("-" * len(header))
    for level in levels:
        ordered = icosphere(level)
        inputs = {f"icosphere({level}), as generated": ordered,
                  f"icosphere({level}), random order": shuffled(*ordered)}
        meshes = {name: build_ours(vertices, faces) for name, (vertices, faces) in inputs.items()}
        turns = {}                                     # (order, contender) -> its call, all in each round
        for name, (vertices, faces) in inputs.items():
            turns[name, "ours"] = lambda v=vertices, f=faces: build_ours(v, f)
            turns[name, "openmesh"] = lambda v=vertices, f=faces: build_openmesh(v, f)
            turns[name, "validate"] = meshes[name].validate
        wall, cpu = interleaved_wall_and_cpu_medians(
            args.rounds, **{f"{name}|{who}": call for (name, who), call in turns.items()})
        for name, (vertices, faces) in inputs.items():
            ours, peer_openmesh = wall[f"{name}|ours"], wall[f"{name}|openmesh"]
            validate = wall[f"{name}|validate"]
            big = len(faces) > 500_000
            peer_trimesh = median_time(lambda: build_trimesh_adjacency(vertices, faces), 1 if big else 5)
            mesh = meshes[name]
            flipped = mesh.flip(len(faces) // 3)
            around = median_time(lambda: validate_around(mesh, edges=[flipped]), 50)
            print(
                f"{name:<34}{len(faces):>10,}{ours:>9.3f}{peer_openmesh:>12.3f}{peer_trimesh:>11.3f}"
                f"{ours / peer_openmesh:>12.2f}x{ours / peer_trimesh:>11.3f}x{validate / ours:>15.0%}"
                f"{cpu[f'{name}|validate'] / cpu[f'{name}|ours']:>7.0%}"
                f"{validate / around:>16.0f}x",
                flush=True,
            )
        del meshes

    vertices, faces = icosphere(levels[-1])
    print()
    print(f"peak memory while building {len(faces):,} faces: {peak_build_memory_mib(vertices, faces):.0f} MiB (tracemalloc)")
    seconds, pyvista = import_time_and_pyvista()
    print(f"import halfedge_edu: {seconds:.3f} s, pyvista imported: {pyvista}")
    print("goals: vs openmesh <= 1.0x, vs trimesh <= 0.1x, peak < 300 MiB, validate < 25% of build, "
          "validate / validate_around after one flip >= 100x at 1.3M faces, import < 0.3 s")
    print()
    print(machine_report())
    print(other_work.stop().verdict()[1])


if __name__ == "__main__":
    main()
