"""Isotropic remeshing, 5 iterations at the input's mean edge length: halfedge_edu beside PyMeshLab.

    python benchmarks/bench_remesh.py
    python benchmarks/bench_remesh.py --quick     # the bunny only

Each input is remeshed twice in the same run, with the same target length L (the
input's mean edge length) and 5 iterations:
* halfedge_edu: ``remesh`` (split / collapse / flip / smooth / project, each phase on
  whole arrays with numpy);
* PyMeshLab: ``meshing_isotropic_explicit_remeshing`` (VCG, C++, one edge at a time),
  with its defaults otherwise (it also preserves creases sharper than 30 degrees).
Quality beside time: the result's face count; valid (a manifold, oriented halfedge mesh
that passes ``validate()``); genus and boundary loops kept; the mean and max distance
between result and input surfaces (PyVista's implicit distance, from each one's vertices
to the other surface, both ways), in units of L; edge-length spread (std / mean); the mean
``|degree - 6|`` (``|degree - 4|`` for boundary vertices); and the mean smallest angle
of the faces. The ratio is our time over PyMeshLab's; the goal is at most 3x.
"""

from __future__ import annotations

import argparse

import numpy as np

import halfedge_edu as hx
from _common import hundred_k_inputs as inputs, surface_distance, timed
from halfedge_edu.algorithms.remesh import quality_report, remesh

ITERATIONS = 5




def run_ours(mesh, length):
    return remesh(mesh, length, ITERATIONS).to_arrays()


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






def describe(label, seconds, ratio, vertices, faces, reference, length):
    ref_vertices, ref_faces, ref_mesh = reference
    try:
        mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
        mesh.validate()
    except (hx.MeshInputError, hx.MeshInvariantError):
        return f"{label:>14}{len(faces):>8,}{seconds:>9.2f}{ratio:>8}{'no':>7}"
    kept = mesh.genus == ref_mesh.genus and mesh.n_boundary_loops == ref_mesh.n_boundary_loops
    mean, worst = surface_distance(ref_vertices, ref_faces, vertices, faces)
    quality = quality_report(mesh)
    return (
        f"{label:>14}{len(faces):>8,}{seconds:>9.2f}{ratio:>8}{'yes':>7}{'yes' if kept else 'no':>6}"
        f"{mean / length:>10.4f}{worst / length:>9.3f}{quality.edge_length_spread:>8.3f}"
        f"{quality.degree_deviation:>8.3f}{quality.min_angle_mean:>8.1f}"
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the bunny only")
    args = parser.parse_args(argv)

    header = (
        f"{'input':<24}{'faces':>8}{'method':>14}{'result':>8}{'time s':>9}{'ratio':>8}{'valid':>7}{'kept':>6}"
        f"{'mean d/L':>10}{'max d/L':>9}{'spread':>8}{'|deg-6|':>8}{'min ang':>8}"
    )
    print(f"Isotropic remeshing, {ITERATIONS} iterations, L = the input's mean edge length")
    print(header)
    print("-" * len(header))
    for name, mesh in inputs(args.quick):
        vertices, faces = mesh.to_arrays()
        length = quality_report(mesh).edge_length_mean
        before = quality_report(mesh)
        print(
            f"{name:<24}{len(faces):>8,}{'input':>14}{len(faces):>8,}{'':>9}{'':>8}{'':>7}{'':>6}{'':>10}{'':>9}"
            f"{before.edge_length_spread:>8.3f}{before.degree_deviation:>8.3f}{before.min_angle_mean:>8.1f}"
        )
        t_ours, (v_ours, f_ours) = timed(run_ours, mesh, length)
        t_peer, (v_peer, f_peer) = timed(run_pymeshlab, vertices, faces, length)
        t_gpy, (v_gpy, f_gpy) = timed(run_gpytoolbox, vertices, faces, length)
        reference = (vertices, faces, mesh)
        print(f"{'':<32}" + describe("halfedge_edu", t_ours, "", v_ours, f_ours, reference, length))
        print(f"{'':<32}" + describe("pymeshlab", t_peer, f"{t_ours / t_peer:.2f}x", v_peer, f_peer, reference, length))
        print(f"{'':<32}" + describe("gpytoolbox", t_gpy, f"{t_ours / t_gpy:.2f}x", v_gpy, f_gpy, reference, length))
    print("ratio: halfedge_edu's time over the peer's (goal <= 1.0x gpytoolbox, mean and max d <= PyMeshLab's);")
    print("d: surface distance to the input;")
    print("|deg-6|: mean over vertices (|deg-4| on the boundary); min ang: mean smallest face angle, degrees")


if __name__ == "__main__":
    main()
