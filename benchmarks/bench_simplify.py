"""Quadric simplification to 10%: halfedge_edu beside openmesh and fast-simplification.

    python benchmarks/bench_simplify.py
    python benchmarks/bench_simplify.py --quick     # the bunny only

Each row simplifies the same input to 10% of its faces three ways, in the same run:
* halfedge_edu: ``simplify`` (rounds of independent collapses, numpy);
* openmesh: ``TriMeshDecimater`` with ``ModQuadric`` (C++, one collapse at a time);
* fast-simplification: ``simplify(..., target_reduction=0.9)`` (C++, Fast-Quadric-Mesh-Simplification).
Quality is the symmetric mean and max distance between result and input surfaces
(PyVista's implicit distance from each one's vertices to the other), as a fraction of
the bounding-box diagonal. Ratios are our time over the peer's.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import halfedge_edu as hx
from halfedge_edu.algorithms.simplify import simplify


def surface_distance(vertices_a, faces_a, vertices_b, faces_b) -> tuple[float, float]:
    """Symmetric (mean, max) distance between two surfaces, measured at their vertices."""
    import pyvista as pv

    a = pv.PolyData.from_regular_faces(np.asarray(vertices_a, float), np.asarray(faces_a))
    b = pv.PolyData.from_regular_faces(np.asarray(vertices_b, float), np.asarray(faces_b))
    a_to_b = np.abs(a.compute_implicit_distance(b)["implicit_distance"])
    b_to_a = np.abs(b.compute_implicit_distance(a)["implicit_distance"])
    return 0.5 * (a_to_b.mean() + b_to_a.mean()), float(max(a_to_b.max(), b_to_a.max()))


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


def timed(function, *args):
    start = time.perf_counter()
    result = function(*args)
    return time.perf_counter() - start, result


def inputs(quick: bool):
    yield "bunny", hx.sample("bunny")
    if not quick:
        import trimesh

        spot = hx.sample("spot").to_trimesh()
        vertices, faces = trimesh.remesh.subdivide(spot.vertices, spot.faces)
        vertices, faces = trimesh.remesh.subdivide(vertices, faces)
        yield "spot, subdivided twice", hx.HalfedgeMesh.from_faces(vertices, faces)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the bunny only")
    args = parser.parse_args(argv)

    header = f"{'input':<24}{'faces':>8}{'method':>21}{'result':>8}{'time s':>9}{'ours/peer':>11}{'mean dist':>11}{'max dist':>10}{'valid':>7}"
    print("Quadric simplification to 10% of the faces")
    print(header)
    print("-" * len(header))
    for name, mesh in inputs(args.quick):
        vertices, faces = mesh.to_arrays()
        diagonal = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
        target = len(faces) // 10
        t_ours, (v_ours, f_ours) = timed(run_ours, mesh, target)
        rows = [("halfedge_edu", t_ours, v_ours, f_ours)]
        for label, function in (("openmesh", run_openmesh), ("fast-simplification", run_fast_simplification)):
            seconds, (v, f) = timed(function, vertices, faces, target)
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
    print("goal: <= 5x openmesh's time, mean distance <= fast-simplification's")


if __name__ == "__main__":
    main()
