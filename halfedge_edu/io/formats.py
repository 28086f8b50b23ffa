"""``load`` and ``save``: one entry point for every file format.

``.obj`` goes through the package's own reader and writer (``halfedge_edu.io.obj``), so
errors name the line of the file. ``.ply``, ``.stl``, ``.off``, ``.glb`` and ``.gltf``
go through trimesh.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np

from halfedge_edu.core.errors import MeshInputError, MeshWarning
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.repair import repair_faces
from halfedge_edu.io.obj import atomic_output, read_obj, write_obj

__all__ = ["load", "save", "SUFFIXES"]

#: The file suffixes ``load`` and ``save`` understand.
SUFFIXES = (".obj", ".ply", ".stl", ".off", ".glb", ".gltf")


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise MeshInputError(
            f"{path.name}: unknown file type {suffix or '(no suffix)'!r}; use one of {', '.join(SUFFIXES)}"
        )
    return suffix


def load(path: str | os.PathLike, *, repair: bool = False, triangulate: bool = True) -> HalfedgeMesh:
    """Read a mesh file into a ``HalfedgeMesh``.

    Args:
        path: a ``.obj``, ``.ply``, ``.stl``, ``.off``, ``.glb`` or ``.gltf`` file.
        repair: first make the triangles loadable with ``repair_faces`` (drop degenerate
            and duplicate faces, orient consistently, split non-manifold edges and
            vertices). The mesh then has an attribute ``repair_report``, and if anything
            changed the report is also given as a ``MeshWarning``.
        triangulate: for ``.obj``, cut polygons into triangles (False: reject them).
            trimesh always triangulates the other formats. ``.stl`` has no shared
            vertices, so corners at exactly the same position are merged into one.

    Returns:
        A new ``HalfedgeMesh``. Vertices no face uses are dropped with a ``MeshWarning``.

    Raises:
        FileNotFoundError: the file does not exist (the standard error for that).
        MeshInputError: an unknown suffix, a file that cannot be read, or triangles
            that cannot form a halfedge mesh (for ``.obj`` the message names the line).
    """
    path = Path(path)
    suffix = _suffix(path)
    if not path.exists():
        raise FileNotFoundError(f"no such file: {str(path)!r}")

    face_lines = None
    if suffix == ".obj":
        data = read_obj(path, triangulate=triangulate)
        vertices, faces, face_lines = data.vertices, data.faces, data.face_lines
    else:
        vertices, faces = _load_with_trimesh(path)

    if not repair:
        return HalfedgeMesh.from_faces(vertices, faces, face_lines=face_lines, source=path.name)

    vertices, faces, report = repair_faces(vertices, faces)
    if face_lines is not None:
        face_lines = face_lines[report.face_origin]
    mesh = HalfedgeMesh.from_faces(vertices, faces, face_lines=face_lines, source=path.name)
    mesh.repair_report = report
    if report:
        warnings.warn(f"{path.name}: {report}", MeshWarning, stacklevel=2)
    return mesh


def _load_with_trimesh(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of a non-OBJ file, with trimesh's failures as MeshInputError."""
    import trimesh

    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except Exception as error:  # trimesh raises many kinds; all mean "cannot read this file"
        raise MeshInputError(f"{path.name}: trimesh could not read the file ({type(error).__name__}: {error})") from error
    faces = np.asarray(getattr(loaded, "faces", np.zeros((0, 3))), dtype=np.int64)
    if len(faces) == 0:
        raise MeshInputError(f"{path.name}: the file has no triangles")
    vertices = np.asarray(loaded.vertices, dtype=np.float64)
    if path.suffix.lower() == ".stl":
        # STL stores each triangle's three corners by value, with no shared vertices:
        # corners at exactly the same position are one vertex.
        vertices, faces = _merge_identical_vertices(vertices, faces)
    return vertices, faces


def _merge_identical_vertices(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Make vertices with exactly equal positions one vertex, in order of first use."""
    _, first, inverse = np.unique(vertices, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)  # unique rows, renumbered by where they first appear
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return vertices[first[order]], rank[inverse.reshape(-1)][faces]


def save(mesh: HalfedgeMesh, path: str | os.PathLike) -> None:
    """Write ``mesh`` to ``path``; the suffix picks the format (as for ``load``).

    The file is written beside ``path`` and moved into place, so a failure leaves no
    partial file (and an existing file is untouched).

    Attention: only ``.obj`` (and ``.glb``/``.gltf``) keep float64 positions exactly;
    trimesh writes ``.ply`` and ``.stl`` positions as float32, ``.off`` with 17 digits.

    Raises:
        MeshInputError: an unknown suffix.
    """
    path = Path(path)
    suffix = _suffix(path)
    vertices, faces = mesh.to_arrays()
    if suffix == ".obj":
        write_obj(path, vertices, faces)
        return
    if suffix == ".gltf":  # one self-contained file: buffers embedded as base64
        exported = mesh.to_trimesh().export(file_type="gltf", embed_buffers=True)["model.gltf"]
    elif suffix == ".off":  # trimesh's default is 10 digits
        exported = mesh.to_trimesh().export(file_type="off", digits=17)
    else:
        exported = mesh.to_trimesh().export(file_type=suffix[1:])
    if isinstance(exported, str):
        exported = exported.encode("utf-8")
    with atomic_output(path, "wb") as file:
        file.write(exported)
