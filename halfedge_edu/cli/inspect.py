"""``info FILE`` and ``check FILE``: read one mesh file and print plain text.

``info`` prints the element counts, Euler characteristic, genus, boundary loops and the
vertex-degree histogram; a file the halfedge structure cannot hold gets a report of what
keeps it from being one instead (non-manifold edges and vertices, edges used twice in the
same direction, degenerate and duplicate faces). ``check`` validates every halfedge
invariant: exit status 0 for a valid mesh, 1 naming the broken rule.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import halfedge_edu as hx
from halfedge_edu.cli.errors import EXIT_INVALID, EXIT_OK, InputProblem, echo, listing, one_line
from halfedge_edu.cli.files import load, load_or_fail, names_the_file, read_raw, with_path
from halfedge_edu.core.errors import MeshInputError, MeshInvariantError


@names_the_file
def run_info(args: argparse.Namespace) -> int:
    """``info FILE``: describe the mesh, or its non-manifold parts if it cannot be built."""
    path = args.file
    try:
        mesh = load(path, repair=args.repair)
    except MeshInputError as error:
        return _info_not_buildable(path, error)

    live_degrees = mesh.vertex_degrees()[~np.asarray(mesh.vertex_deleted)]  # (n_vertices,)
    lines = [
        f"file: {path}",
        f"vertices: {mesh.n_vertices}",
        f"edges: {mesh.n_edges}",
        f"faces: {mesh.n_faces}",
        f"halfedges: {mesh.n_halfedges}",
        f"euler characteristic: {mesh.euler_characteristic}",
        f"genus: {mesh.genus}",
        f"boundary loops: {mesh.n_boundary_loops}",
        "manifold: yes",
        "vertex degrees:",
    ]
    counts = np.bincount(live_degrees) if live_degrees.size else np.zeros(0, dtype=int)
    lines += [f"  {degree:>3}: {count}" for degree, count in enumerate(counts) if count]
    echo("\n".join(lines))
    return EXIT_OK


#: What keeps a face list from being a halfedge mesh: (title, ``ManifoldReport`` field, how one is named).
PROBLEMS = (
    ("non-manifold edges (more than two faces)", "nonmanifold_edges", "{0}-{1}"),
    ("non-manifold vertices (more than one fan)", "nonmanifold_vertices", "{0}"),
    ("edges used twice in the same direction", "inconsistent_edges", "{0}->{1}"),
    ("degenerate faces (a repeated vertex)", "degenerate_faces", "{0}"),
    ("duplicate faces", "duplicate_faces", "{0}"),
)


def _info_not_buildable(path: Path, error: Exception) -> int:
    """Report on a file the halfedge structure cannot hold: what keeps it from being one."""
    try:
        vertices, faces = read_raw(path)  # (n, 3) float, (m, 3) int
        report = hx.manifold_report(faces)
    except Exception:
        # Not even a face list (a bad line, an index out of range): say why not.
        raise InputProblem(with_path(path, error)) from error
    if report:
        # A manifold, consistently oriented face list that still did not build: the
        # library's message says what else is wrong.
        raise InputProblem(with_path(path, error))

    corners = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)  # (3m, 2) directed edges
    n_edges = len(np.unique(np.sort(corners, axis=1), axis=0))
    manifold = not (len(report.nonmanifold_edges) or len(report.nonmanifold_vertices))
    lines = [
        f"file: {path}",
        f"vertices: {len(vertices)}",
        f"edges: {n_edges}",
        f"faces: {len(faces)}",
        f"manifold: {'yes' if manifold else 'no'}",
        "halfedge mesh: no, because of",
    ]
    for title, attribute, form in PROBLEMS:
        found = np.asarray(getattr(report, attribute, []))
        if len(found):
            rows = found.reshape(len(found), -1).tolist()
            lines.append(f"  {title}: {len(found)}{listing(form.format(*row) for row in rows)}")
    lines.append(f"loading said: {one_line(str(error))}")
    echo("\n".join(lines))
    return EXIT_OK


@names_the_file
def run_check(args: argparse.Namespace) -> int:
    """``check FILE``: exit 0 if the file is a valid halfedge mesh, 1 if an invariant breaks."""
    path = args.file
    mesh = load_or_fail(path, repair=args.repair)
    try:
        mesh.validate()
    except MeshInvariantError as error:
        echo(f"{path}: not a valid halfedge mesh: {one_line(str(error))}")
        return EXIT_INVALID
    echo(f"{path}: valid halfedge mesh ({mesh.n_vertices} vertices, {mesh.n_faces} faces)")
    return EXIT_OK
