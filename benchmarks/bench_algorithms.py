"""Whole-mesh algorithms: halfedge_edu beside trimesh and VTK, in the same run.

    python benchmarks/bench_algorithms.py            # Loop on ~82k faces, smoothing on ~1.3M
    python benchmarks/bench_algorithms.py --quick    # ~20k and ~82k faces

Rows (median of a few runs each; the inputs are built before the clock starts):
* Loop x1: ``hx.loop_subdivide(mesh)`` from a HalfedgeMesh, against
  ``trimesh.remesh.subdivide_loop(vertices, faces)`` (arrays in, arrays out) and VTK's
  ``vtkLoopSubdivisionFilter`` through ``pyvista.PolyData.subdivide(1, "loop")``.
* Laplacian x10: ``hx.smooth(mesh, 10)`` (uniform weights, Jacobi) from a fresh copy
  (so no cached adjacency), against ``trimesh.smoothing.filter_laplacian(tm, lamb=1,
  iterations=10, volume_constraint=False)`` on a fresh Trimesh (building its Laplacian
  included, as in its default use). On a closed mesh both compute the same positions;
  the script checks that before timing.
Ratios are halfedge_edu's time over the peer's: below 1.0 means we are faster. The
machine is shared and noisy, so read the ratios, not the seconds.

The meshes are icospheres with shuffled vertex and face order (what a mesh from a
scanner or exporter looks like to the cache).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import halfedge_edu as hx
from halfedge_edu.algorithms import loop_subdivide, smooth


def sphere(faces_wanted: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """A unit icosphere with the ``20 * 4**k`` faces nearest ``faces_wanted``, its
    vertices renumbered and faces shuffled at random."""
    import trimesh

    level = int(round(np.log(faces_wanted / 20) / np.log(4)))
    mesh = trimesh.creation.icosphere(subdivisions=level)
    vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    rng = np.random.default_rng(seed)
    relabel = rng.permutation(len(vertices))
    shuffled = np.empty_like(vertices)
    shuffled[relabel] = vertices
    return shuffled, relabel[faces][rng.permutation(len(faces))]


def interleaved_times(repeats: int, contenders: dict) -> dict[str, float]:
    """``{name: median wall seconds}`` of ``function(prepare())`` for each ``name: (function, prepare)``.

    ``prepare`` is untimed. Every round runs each contender once, in turn, so a spell of
    other work on the machine falls on ours and the peers' alike.
    """
    times: dict[str, list[float]] = {name: [] for name in contenders}
    for _ in range(repeats):
        for name, (function, prepare) in contenders.items():
            argument = prepare()
            start = time.perf_counter()
            function(argument)
            times[name].append(time.perf_counter() - start)
    return {name: float(np.median(seconds)) for name, seconds in times.items()}


def row(name: str, faces: int, ours: float, peers: dict[str, float]) -> str:
    cells = [f"{name:<14}", f"{faces:>9,}", f"{ours:>8.3f}"]
    for peer, seconds in peers.items():
        cells.append(f"{peer} {seconds:.3f} s = {ours / seconds:4.2f}x")
    return "  ".join(cells)


def bench_loop(faces_wanted: int, repeats: int) -> str:
    import pyvista
    import trimesh

    vertices, faces = sphere(faces_wanted)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    polydata = pyvista.PolyData.from_regular_faces(vertices, faces)
    seconds = interleaved_times(repeats, {
        "ours": (loop_subdivide, lambda: mesh),
        "trimesh": (lambda _: trimesh.remesh.subdivide_loop(vertices, faces), lambda: None),
        "VTK": (lambda p: p.subdivide(1, "loop"), lambda: polydata),
    })
    return row("Loop x1", len(faces), seconds.pop("ours"), seconds)


def bench_laplacian(faces_wanted: int, repeats: int, iterations: int = 10) -> str:
    import trimesh

    vertices, faces = sphere(faces_wanted)
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)

    def fresh_trimesh():
        return trimesh.Trimesh(vertices=vertices.copy(), faces=faces.copy(), process=False)

    def trimesh_smooth(tm):
        return trimesh.smoothing.filter_laplacian(tm, lamb=1.0, iterations=iterations, volume_constraint=False)

    check = trimesh_smooth(fresh_trimesh())
    assert np.allclose(smooth(mesh, iterations).positions, check.vertices, atol=1e-12), "results differ"
    seconds = interleaved_times(repeats, {
        "ours": (lambda m: smooth(m, iterations), mesh.copy),
        "trimesh": (trimesh_smooth, fresh_trimesh),
    })
    return row(f"Laplacian x{iterations}", len(faces), seconds.pop("ours"), seconds)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="smaller meshes")
    parser.add_argument("--repeats", type=int, default=3, help="runs per measurement (the median is kept)")
    args = parser.parse_args()
    loop_faces, laplacian_faces = (20_000, 80_000) if args.quick else (80_000, 1_300_000)
    print(f"{'algorithm':<14}  {'faces':>9}  {'ours (s)':>8}  peers (ratio = ours / peer)")
    print(bench_loop(loop_faces, args.repeats), flush=True)
    print(bench_laplacian(laplacian_faces, args.repeats), flush=True)


if __name__ == "__main__":
    main()
