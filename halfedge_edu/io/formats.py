"""``load`` and ``save``: one entry point for every file format.

``.obj`` goes through the package's own reader and writer (``halfedge_edu.io.obj``), so
errors name the line of the file; so does ``.stl`` (``halfedge_edu.io.stl``: trimesh
reads a damaged STL as the empty mesh). ``.ply`` and ``.off`` are read by trimesh after
their header's counts are checked against what the file holds
(``halfedge_edu.io.headers``: trimesh believes the header, so a lying one gave another
mesh); ``.glb``, ``.gltf`` and ``.dae`` go through trimesh as they are. Every format is
written by trimesh but ``.obj``. A file that does not say truthfully what it holds is
refused, never loaded as another mesh.

What each format can hold decides what ``save`` refuses, so that a file never loads
back as a different mesh: no format takes a non-finite coordinate; the float32 formats
(``.ply``, ``.stl``, ``.glb``, ``.gltf``) take no coordinate beyond float32's range;
and ``.stl``, which stores every triangle's corners by value and so is read back with
equal positions merged into one vertex, takes no mesh with two vertices at one
(float32) position, such as a repaired mesh whose non-manifold vertex was split into
copies.
"""

from __future__ import annotations

import errno
import io
import os
import warnings
from pathlib import Path

import numpy as np

from halfedge_edu.core.errors import MeshInputError, MeshWarning
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.repair import repair_faces
from halfedge_edu.io.headers import check_off, check_ply
from halfedge_edu.io.obj import (
    atomic_output, checked_arrays, path_error, read_obj, require_regular_file, shown_path, write_obj,
)
from halfedge_edu.io.stl import read_stl

__all__ = ["load", "load_arrays", "save", "SUFFIXES"]

#: The file suffixes ``load`` and ``save`` understand.
SUFFIXES = (".obj", ".ply", ".stl", ".off", ".glb", ".gltf", ".dae")

#: The formats trimesh writes with float32 positions.
FLOAT32_SUFFIXES = (".ply", ".stl", ".glb", ".gltf")


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise MeshInputError(
            f"{path.name}: unknown file type {suffix or '(no suffix)'!r}; use one of {', '.join(SUFFIXES)}"
        )
    return suffix


def load(path: str | os.PathLike, *, repair: bool = False, triangulate: bool = True,
         drop_unreferenced: bool = False) -> HalfedgeMesh:
    """Read a mesh file into a ``HalfedgeMesh``.

    Args:
        path: a ``.obj``, ``.ply``, ``.stl``, ``.off``, ``.glb``, ``.gltf`` or ``.dae``
            (COLLADA, the CMU and CS184 assignments' format; needs pycollada, in the
            ``io`` extra) file. trimesh's COLLADA reader numbers vertices by their first
            use in the triangle lists, so ``.dae`` vertex ids are not the file's.
        repair: first make the triangles loadable with ``repair_faces`` (drop degenerate
            and duplicate faces, orient consistently, split non-manifold edges and
            vertices). The mesh then has an attribute ``repair_report``, and if anything
            changed the report is also given as a ``MeshWarning``.
        triangulate: for ``.obj``, cut polygons into triangles (False: reject them).
            trimesh always triangulates the other formats. ``.stl`` has no shared
            vertices, so corners at exactly the same position are merged into one.
        drop_unreferenced: False (the default) keeps every vertex of the file at its
            index, so vertex ``i`` of the file is ``mesh.vertex(i)`` (a vertex no face
            uses is isolated: no halfedge), as pmp-library and OpenMesh do; True drops
            those vertices with a ``MeshWarning`` and renumbers the rest in order.

    Returns:
        A new ``HalfedgeMesh``.

    Raises:
        FileNotFoundError: the file does not exist (the standard error for that).
        MeshInputError: an unknown suffix, a path too long for the system, a file that
            cannot be read, a file whose contents do not match what it declares (an
            STL, PLY or OFF count; see the module docstring), or triangles that cannot
            form a halfedge mesh (for ``.obj`` the message names the line).
    """
    path = Path(path)
    vertices, faces, face_lines = load_arrays(path, triangulate=triangulate)
    if not repair:
        return HalfedgeMesh.from_faces(vertices, faces, face_lines=face_lines, source=path.name,
                                   drop_unreferenced=drop_unreferenced)

    vertices, faces, report = repair_faces(vertices, faces)
    if face_lines is not None:
        face_lines = face_lines[report.face_origin]
    mesh = HalfedgeMesh.from_faces(vertices, faces, face_lines=face_lines, source=path.name,
                                   drop_unreferenced=drop_unreferenced)
    mesh.repair_report = report
    if report:
        warnings.warn(f"{path.name}: {report}", MeshWarning, stacklevel=2)
    return mesh


def load_arrays(path: str | os.PathLike, *, triangulate: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """The vertex and face arrays of a mesh file, before any halfedge structure is built.

    What ``load`` builds from, so a tool can look at a file that does not build (the
    command line's ``info`` reports the non-manifold edges of any format from it).
    ``.stl`` corners at exactly the same position are merged into one vertex, as in ``load``.

    Returns:
        ``(vertices, faces, face_lines)``: (n, 3) float64, (m, 3) int64 and, for
        ``.obj``, the (m,) file line of each face (None for the other formats).

    Raises:
        FileNotFoundError: the file does not exist.
        MeshInputError: an unknown suffix, a path that is not a regular file or too long
            for the system, a file that cannot be read, or one whose contents do not
            match what it declares (an STL, PLY or OFF count).
    """
    path = Path(path)
    suffix = _suffix(path)
    try:
        exists = path.exists()
    except OSError as error:  # a path too long for the system, say
        raise path_error(path, error, "read") from error
    if not exists:
        raise FileNotFoundError(f"no such file: {shown_path(path)!r}")
    require_regular_file(path)
    if suffix == ".obj":
        data = read_obj(path, triangulate=triangulate)
        return data.vertices, data.faces, data.face_lines
    vertices, faces = _load_other_format(path)
    return vertices, faces, None


def _load_other_format(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of a non-OBJ file, with every failure as MeshInputError.

    ``.stl`` is read by ``read_stl``; ``.ply`` and ``.off`` are checked against their
    headers first (see the module docstring), then read from the same bytes.
    """
    import trimesh

    suffix = path.suffix.lower()
    if suffix == ".stl":
        # STL stores each triangle's three corners by value, with no shared vertices:
        # corners at exactly the same position are one vertex.
        return _merge_identical_vertices(*read_stl(path))
    source: Path | io.BytesIO = path
    if suffix in (".ply", ".off"):
        data = _read_bytes(path)
        (check_ply if suffix == ".ply" else check_off)(data, path.name)
        source = io.BytesIO(data)
    try:
        loaded = trimesh.load(source, file_type=suffix[1:], force="mesh", process=False)
    except Exception as error:  # trimesh raises many kinds; all mean "cannot read this file"
        raise MeshInputError(
            f"{path.name}: trimesh could not read the file ({type(error).__name__}: {_bounded(str(error))})"
        ) from error
    faces = np.asarray(getattr(loaded, "faces", np.zeros((0, 3))), dtype=np.int64).reshape(-1, 3)
    vertices = np.asarray(getattr(loaded, "vertices", np.zeros((0, 3))), dtype=np.float64).reshape(-1, 3)
    if len(faces) == 0:
        # The same rule as the OBJ reader: a file with neither vertices nor faces is the
        # empty mesh (what ``save`` writes for one), one with points only is not a mesh.
        # ``force="mesh"`` turns a point cloud into an empty mesh, so count its points as read.
        points = len(getattr(trimesh.load(path, process=False), "vertices", ()))
        if points:
            raise MeshInputError(f"{path.name}: {points} vertices but no triangles: a point cloud, not a mesh")
    return vertices, faces


def _read_bytes(path: Path) -> bytes:
    """The whole file, with a failure to read it as ``MeshInputError``."""
    try:
        return path.read_bytes()
    except OSError as error:
        raise MeshInputError(f"{path.name}: cannot read the file ({error.strerror or error})") from error


def _bounded(text: str, limit: int = 300) -> str:
    """``text`` cut to ``limit`` characters: a library's message can quote a whole file."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


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

    Attention: only ``.obj`` keeps float64 positions exactly (and ``.off``, written with
    17 digits); trimesh writes ``.ply``, ``.stl``, ``.glb`` and ``.gltf`` positions as
    float32, rounded to about 7 digits.

    Raises:
        MeshInputError: an unknown suffix, a path too long for the system, or a mesh the
            format cannot hold (see the module docstring): a non-finite coordinate, one
            beyond float32's range, or for ``.stl`` two vertices at the same position.
        OSError: the file cannot be written (no such folder, permission, disk full);
            the message names ``path``.
    """
    path = Path(path)
    suffix = _suffix(path)
    vertices, faces = checked_arrays(*mesh.to_arrays())
    if suffix in FLOAT32_SUFFIXES:
        _check_fits_float32(vertices, suffix)
    if suffix == ".stl":
        _check_no_shared_positions(vertices)
    try:
        _write(mesh, path, suffix, vertices, faces)
    except OSError as error:
        if error.errno == errno.ENAMETOOLONG:
            raise path_error(path, error, "write") from error
        raise


def _write(mesh: HalfedgeMesh, path: Path, suffix: str, vertices: np.ndarray, faces: np.ndarray) -> None:
    """Write the checked arrays (``.obj``) or trimesh's export of ``mesh`` to ``path``, atomically."""
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


def _check_fits_float32(vertices: np.ndarray, suffix: str) -> None:
    """Refuse coordinates that float32 would turn into inf."""
    too_large = np.flatnonzero((np.abs(vertices) > np.finfo(np.float32).max).any(axis=1))
    if len(too_large):
        bad = int(too_large[0])
        raise MeshInputError(
            f"vertex {bad} has a coordinate beyond float32's range (about 3.4e38), which {suffix} stores; "
            f"save as .obj or .off",
            element=("vertex", bad),
        )


def _check_no_shared_positions(vertices: np.ndarray) -> None:
    """Refuse two vertices that STL's float32 corners would merge into one on loading."""
    stored = vertices.astype(np.float32)  # (n, 3), what the file will hold
    _, first, inverse = np.unique(stored, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    merged = np.flatnonzero(first[inverse] != np.arange(len(vertices)))
    if len(merged):
        later = int(merged[0])
        earlier = int(first[inverse[later]])
        raise MeshInputError(
            f"vertices {earlier} and {later} have the same position; .stl stores no shared vertices, "
            f"so they would load back merged into one (another mesh); save as .obj, .ply or .off",
            element=("vertex", later),
        )
