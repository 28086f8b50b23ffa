"""What several benchmark scripts share: timing, the ~100k-face inputs, surface distance."""

from __future__ import annotations

import time

import numpy as np

import halfedge_edu as hx


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
