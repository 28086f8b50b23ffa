"""Isotropic remeshing, 5 iterations at the input's mean edge length: halfedge_edu beside PyMeshLab and gpytoolbox.

    python benchmarks/bench_remesh.py
    python benchmarks/bench_remesh.py --quick        # the bunny only
    python benchmarks/bench_remesh.py --repeats 5    # medians of 5 runs (default 3)

Each input is remeshed by three methods in the same process, with the same target
length L (the input's mean edge length) and 5 iterations; each time is the median of
``--repeats`` rounds, each running every method once in turn:
* halfedge_edu: ``remesh`` with ``feature_angle=30`` (creases sharper than 30 degrees and
  the boundary kept; PyMeshLab's default angle, so both keep the same creases), once
  with the full tangential smoothing step (the default: the most even triangles) and
  once ("halfedge_edu 0.5") with ``smoothing_step=0.5``, which leaves vertices nearer
  the input's, and so more of them within ``SNAP_TO_INPUT_VERTEX * L`` of one, where
  the projection puts them: closer to a noisy scan, less even triangles;
* PyMeshLab: ``meshing_isotropic_explicit_remeshing`` (VCG, C++, one edge at a time),
  its defaults otherwise (``featuredeg=30``, and ``checksurfdist``: no operation may
  move the surface more than 1% of the bounding box diagonal);
* gpytoolbox: ``remesh_botsch`` (Botsch and Kobbelt 2004 in C++, with projection; it
  keeps no creases).

Quality beside time: the result's face count; valid (a manifold, oriented halfedge mesh
that passes ``validate()``); genus and boundary loops kept; the distance between result
and input, in units of L, measured two ways by the same code for every method, both
**symmetric** (from each surface to the other, both directions pooled: the mean is the
average of the two directions' means, the max the larger max):
* at the vertices (``_common.surface_distance``): from each mesh's vertices to the other
  surface. It favours a method whose vertices stay on the input's vertices, where the
  input-to-result distance is zero however the surface between them runs;
* at surface samples: from ``SAMPLES`` points spread uniformly by area over each
  surface (seeded, the same for every method) to the other surface: the distance
  between the surfaces themselves, as the Metro tool measures it.
Distances are PyVista's implicit distance (the exact nearest point on the triangles).
Then the edge-length spread (std / mean), the share of edges between 4/5 L and 4/3 L
(what the remeshers aim for; on a noisy scan it trades against the distance: a smaller
smoothing step follows the scan more closely with fewer edges in that band), the mean ``|degree - 6|`` (``|degree - 4|``
for boundary vertices), and the mean smallest angle of the faces. Ratios are
halfedge_edu's over the peer's (time over PyMeshLab's and gpytoolbox's; distances over
PyMeshLab's). The goal (issue 15): time <= 1.0x gpytoolbox, mean and max distance <=
PyMeshLab's.
"""

from __future__ import annotations

import argparse

import numpy as np

import halfedge_edu as hx
from _common import hundred_k_inputs as inputs, interleaved_medians, surface_distance
from halfedge_edu.algorithms.remesh import COLLAPSE_BELOW, SPLIT_ABOVE, quality_report, remesh
from halfedge_edu.core.corner_table import edge_table

ITERATIONS = 5
#: Creases sharper than this (degrees) are kept: PyMeshLab's ``featuredeg`` default.
FEATURE_ANGLE = 30.0
#: Points sampled on each surface for the sampled distance.
SAMPLES = 100_000


#: The shorter smoothing step of the second halfedge_edu row.
SHORT_STEP = 0.5


def run_ours(mesh, length, smoothing_step=1.0):
    return remesh(mesh, length, ITERATIONS, feature_angle=FEATURE_ANGLE, smoothing_step=smoothing_step).to_arrays()


def run_pymeshlab(vertices, faces, length):
    import pymeshlab

    # PyMeshLab 2023.12 renamed AbsoluteValue to PureValue.
    absolute = getattr(pymeshlab, "PureValue", None) or getattr(pymeshlab, "AbsoluteValue")
    meshes = pymeshlab.MeshSet()
    meshes.add_mesh(pymeshlab.Mesh(vertices, faces))
    meshes.meshing_isotropic_explicit_remeshing(iterations=ITERATIONS, targetlen=absolute(length))
    result = meshes.current_mesh()
    return result.vertex_matrix(), result.face_matrix()


def run_gpytoolbox(vertices, faces, length):
    """gpytoolbox's remesh_botsch (Botsch and Kobbelt 2004, in C++), the same iterations and length."""
    import gpytoolbox

    return gpytoolbox.remesh_botsch(np.asarray(vertices, float), np.asarray(faces, np.int32),
                                    i=ITERATIONS, h=length, project=True)


def sample_surface(vertices: np.ndarray, faces: np.ndarray, count: int, seed: int = 0) -> np.ndarray:
    """(count, 3) points spread uniformly by area over the triangles (seeded)."""
    rng = np.random.default_rng(seed)
    corners = np.asarray(vertices, float)[np.asarray(faces)]                      # (m, 3, 3)
    area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    face = rng.choice(len(corners), size=count, p=area / area.sum())
    u, v = rng.random(count), rng.random(count)
    outside = u + v > 1                                     # fold the far half of the square back
    u[outside], v[outside] = 1 - u[outside], 1 - v[outside]
    picked = corners[face]
    return picked[:, 0] + (picked[:, 1] - picked[:, 0]) * u[:, None] + (picked[:, 2] - picked[:, 0]) * v[:, None]


def sampled_distance(vertices_a, faces_a, vertices_b, faces_b) -> tuple[float, float]:
    """Symmetric (mean, max) distance between two surfaces at ``SAMPLES`` points of each."""
    import pyvista as pv

    surfaces = [pv.PolyData.from_regular_faces(np.asarray(v, float), np.asarray(f))
                for v, f in ((vertices_a, faces_a), (vertices_b, faces_b))]
    gaps = []
    for (vertices, faces), other in (((vertices_a, faces_a), surfaces[1]), ((vertices_b, faces_b), surfaces[0])):
        points = pv.PolyData(sample_surface(vertices, faces, SAMPLES))
        gaps.append(np.abs(points.compute_implicit_distance(other)["implicit_distance"]))
    return 0.5 * (gaps[0].mean() + gaps[1].mean()), float(max(gaps[0].max(), gaps[1].max()))


def share_in_band(vertices: np.ndarray, faces: np.ndarray, length: float) -> float:
    """The share of the edges between 4/5 L and 4/3 L: what remeshing aims for."""
    edges = edge_table(np.asarray(faces), len(vertices)).edges                   # (E, 2)
    relative = np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1) / length
    return float(np.mean((relative >= COLLAPSE_BELOW) & (relative <= SPLIT_ABOVE)))


def measure(vertices, faces, reference, length) -> dict | None:
    """The quality of one result, or None if it is not a valid halfedge mesh."""
    ref_vertices, ref_faces, ref_mesh = reference
    try:
        mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
        mesh.validate()
    except (hx.MeshInputError, hx.MeshInvariantError):
        return None
    quality = quality_report(mesh)
    at_vertices = surface_distance(ref_vertices, ref_faces, vertices, faces)
    sampled = sampled_distance(ref_vertices, ref_faces, vertices, faces)
    return {
        "kept": mesh.genus == ref_mesh.genus and mesh.n_boundary_loops == ref_mesh.n_boundary_loops,
        "vertex_mean": at_vertices[0] / length, "vertex_max": at_vertices[1] / length,
        "sample_mean": sampled[0] / length, "sample_max": sampled[1] / length,
        "spread": quality.edge_length_spread, "degree": quality.degree_deviation, "angle": quality.min_angle_mean,
        "band": share_in_band(np.asarray(vertices, float), faces, length),
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the bunny only")
    parser.add_argument("--repeats", type=int, default=3, help="runs per method; the median time is shown (default 3)")
    args = parser.parse_args(argv)

    header = (
        f"{'input':<24}{'method':>18}{'faces':>8}{'time s':>8}{'/pml':>7}{'/gpy':>7}{'valid':>6}{'kept':>5}"
        f"{'vtx mean':>9}{'vtx max':>8}{'smp mean':>9}{'smp max':>8}"
        f"{'vmean/pml':>10}{'vmax/pml':>9}{'smean/pml':>10}{'smax/pml':>9}{'spread':>7}{'band':>6}{'|deg-6|':>8}{'min ang':>8}"
    )
    print(f"Isotropic remeshing, {ITERATIONS} iterations, L = the input's mean edge length; "
          f"median time of {args.repeats} runs; distances symmetric, in units of L")
    print(header)
    print("-" * len(header))
    for name, mesh in inputs(args.quick):
        vertices, faces = mesh.to_arrays()
        before = quality_report(mesh)
        length = before.edge_length_mean
        print(f"{name:<24}{'input':>18}{len(faces):>8,}{'':>8}{'':>7}{'':>7}{'':>6}{'':>5}{'':>9}{'':>8}{'':>9}{'':>8}"
              f"{'':>10}{'':>9}{'':>10}{'':>9}{before.edge_length_spread:>7.3f}"
              f"{share_in_band(vertices, faces, length):>6.0%}{before.degree_deviation:>8.3f}"
              f"{before.min_angle_mean:>8.1f}")
        results = interleaved_medians(args.repeats, {        # one run of each in turn, per round
            "halfedge_edu": lambda: run_ours(mesh, length),
            f"halfedge_edu {SHORT_STEP:g}": lambda: run_ours(mesh, length, SHORT_STEP),
            "pymeshlab": lambda: run_pymeshlab(vertices, faces, length),
            "gpytoolbox": lambda: run_gpytoolbox(vertices, faces, length),
        })
        reference = (vertices, faces, mesh)
        quality = {label: measure(*result, reference, length) for label, (_, result) in results.items()}
        peer = quality["pymeshlab"]
        for label, (seconds, (v, f)) in results.items():
            q = quality[label]
            ours = label.startswith("halfedge_edu")
            row = f"{'':<24}{label:>18}{len(f):>8,}{seconds:>8.2f}"
            row += "".join(f"{seconds / results[p][0]:>6.2f}x" if ours else f"{'':>7}" for p in ("pymeshlab", "gpytoolbox"))
            if q is None:
                print(row + f"{'no':>6}")
                continue
            row += f"{'yes':>6}{'yes' if q['kept'] else 'no':>5}"
            row += f"{q['vertex_mean']:>9.4f}{q['vertex_max']:>8.3f}{q['sample_mean']:>9.4f}{q['sample_max']:>8.3f}"
            if ours and peer is not None:
                row += "".join(f"{q[key] / peer[key]:>{width}.2f}" for key, width in
                               (("vertex_mean", 10), ("vertex_max", 9), ("sample_mean", 10), ("sample_max", 9)))
            else:
                row += f"{'':>10}{'':>9}{'':>10}{'':>9}"
            print(row + f"{q['spread']:>7.3f}{q['band']:>6.0%}{q['degree']:>8.3f}{q['angle']:>8.1f}")
    print("time /pml, /gpy: halfedge_edu's median time over the peer's (goal <= 1.0x gpytoolbox);")
    print("vtx: distance measured at the vertices of both meshes; smp: at", f"{SAMPLES:,}",
          "area-uniform samples of each surface;")
    print("*/pml: halfedge_edu's distance over PyMeshLab's (goal <= 1.0 for mean and max);")
    print(f"halfedge_edu keeps creases above {FEATURE_ANGLE:g} degrees (PyMeshLab's featuredeg); gpytoolbox keeps none;")
    print("band: share of edges between 4/5 L and 4/3 L (distance and band trade against each other: see docs/performance.md);")
    print("|deg-6|: mean over vertices (|deg-4| on the boundary); min ang: mean smallest face angle, degrees")


if __name__ == "__main__":
    main()
