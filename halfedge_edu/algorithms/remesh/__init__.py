"""Isotropic remeshing (Botsch and Kobbelt, 2004): make every edge about ``L`` long.

Each iteration runs five phases, one file each; read them in this order:

1. **Split** (:mod:`.split`, :func:`split_long_edges`): every edge longer than
   ``4/3 L`` at its midpoint.
2. **Collapse** (:mod:`.collapse`, :func:`collapse_short_edges`): every edge shorter
   than ``4/5 L`` to its midpoint (or, failing that, to one of its ends), unless that
   would create an edge longer than ``4/3 L``. Why 4/3 and 4/5: :mod:`.lengths`.
3. **Flip** (:mod:`.flip`, :func:`flip_to_regular_degrees`): edges where that brings
   the degrees of the four vertices involved closer to 6 (4 on the boundary), the
   degree of a vertex in a regular triangle grid.
4. **Smooth tangentially** (:mod:`.smooth`, :func:`tangential_smoothing`): compute the
   centroid of every vertex's neighbours first (all of them, from the old positions),
   then move each vertex towards its centroid *only in its tangent plane*, so the
   vertices spread out evenly without the surface shrinking. Boundary vertices stay put.
5. **Project** (:mod:`.project`, :func:`project_to_surface`): every vertex back onto
   the input surface (boundary vertices onto the input's boundary polyline): splitting
   at chord midpoints and smoothing in a plane both step a little off a curved
   surface. A vertex that lands within ``SNAP_TO_INPUT_VERTEX * L`` of an input vertex
   goes onto it: the input's vertices are the points where its surface was measured
   (a scan) or modelled, and a triangle resting on them follows it more closely than
   one whose corners lie between them.

**Features** (``feature_angle``, :mod:`..features`): creases sharper than the angle, and
the boundary, are feature lines, found once on the input and carried through every
phase. A feature edge is split into two feature edges, collapses only along its line
(never across from one line to another, never removing a corner), and is never
flipped; in phase 4 a vertex on a line moves only along it, on its own two edges
(corners not at all), and in phase 5 it goes back onto its own line of the input.
With ``feature_angle=None`` only the boundary is kept, as described above.

Each phase works on whole arrays (vertices (n, 3), faces (m, 3)) with numpy, not one
edge at a time as the course's exercises do; each file's docstring says how.
:mod:`.quality` measures what remeshing is for (edge lengths, degrees, angles).

This file is the driver: :func:`remesh` returns the result; :func:`remesh_step_by_step`
yields the mesh after each phase, for a stepper, and :func:`remesh_history` lists them
all.
"""

from __future__ import annotations

import inspect
import math
from typing import Iterator, NamedTuple

import numpy as np

from ...core.arrays import compact
from ...core.corner_table import edge_table
from ...core.mesh import HalfedgeMesh
from .._progress import progress_range
from ..arguments import check_remesh, real_number
from ..features import DEFAULT_FEATURE_ANGLE, Features, feature_arrays
from .collapse import collapse_short_edges
from .flip import flip_to_regular_degrees
from .lengths import COLLAPSE_BELOW, SPLIT_ABOVE, edge_lengths
from .project import InputSurface, closest_points_on_segments, closest_points_on_triangles, project_to_surface
from .quality import MeshQuality, quality_report
from .smooth import tangential_smoothing
from .split import split_long_edges

__all__ = [
    "COLLAPSE_BELOW", "PHASES", "SNAP_TO_INPUT_VERTEX", "SPLIT_ABOVE", "InputSurface", "MeshQuality", "RemeshStep",
    "closest_points_on_segments", "closest_points_on_triangles", "collapse_short_edges", "edge_lengths",
    "flip_to_regular_degrees", "project_to_surface", "quality_report", "remesh", "remesh_history",
    "remesh_step_by_step", "split_long_edges", "tangential_smoothing",
]

#: The projection puts a vertex (off the lines) onto an input vertex within this times
#: L of the point it found (0 turns it off). What it gains on a scan, and what it costs
#: in evenness: docs/performance.md, "Quality".
SNAP_TO_INPUT_VERTEX = 0.1

#: The phases of one iteration, in the order they run (the names a :class:`RemeshStep` carries).
PHASES = ("split", "collapse", "flip", "smooth", "project")


class RemeshStep(NamedTuple):
    """One snapshot of :func:`remesh_step_by_step`: the mesh after ``phase`` of ``iteration``."""

    iteration: int
    phase: str
    mesh: HalfedgeMesh


def _check_arguments(target_length, iterations) -> tuple[float | None, int]:
    """``target_length`` as a positive float or None (the input's mean edge length), and
    ``iterations`` as a whole number >= 0; a ValueError naming the argument otherwise."""
    if int(iterations) != iterations or iterations < 0:
        raise ValueError(f"iterations must be a whole number >= 0, got {iterations!r}")
    if target_length is not None:
        target_length = float(target_length)
        if not math.isfinite(target_length) or target_length <= 0:
            raise ValueError(f"target_length must be a positive number, got {target_length!r}")
    return target_length, int(iterations)


def _check_feature_options(feature_angle, smoothing_step) -> tuple[float | None, float]:
    """``feature_angle`` as a float from 0 to 180 degrees or None (no creases), and
    ``smoothing_step`` as a float from 0 to 1."""
    if feature_angle is not None:
        feature_angle = real_number(feature_angle, "feature_angle", minimum=0.0, maximum=180.0)
    return feature_angle, real_number(smoothing_step, "smoothing_step", minimum=0.0, maximum=1.0)


def _phases(mesh: HalfedgeMesh, target_length, iterations, project, progress, feature_angle: float | None,
            smoothing_step: float = 1.0) -> Iterator[tuple[int, str, np.ndarray, np.ndarray, Features | None]]:
    """Yield ``(iteration, phase, vertices, faces, features)`` after every phase (arrays,
    not meshes; ``features`` None without ``feature_angle``): the five phases, in order."""
    vertices, faces = mesh.to_arrays()                 # (n, 3) float, (m, 3) int
    table = edge_table(faces, len(vertices))           # the input's edges, sorted once for the next three uses
    if target_length is None:
        target_length = float(edge_lengths(vertices, table.edges).mean())
    features = feature_arrays(vertices, faces, feature_angle, table=table) if feature_angle is not None else None
    surface = InputSurface(vertices, faces, features) if project else None
    rng = np.random.default_rng(0)
    for iteration in progress_range(iterations, progress, "remesh"):
        # 1. split.py: no edge longer than 4/3 L.
        vertices, faces, features = split_long_edges(vertices, faces, target_length, features,
                                                     table if iteration == 0 else None)
        yield iteration + 1, "split", vertices, faces, features
        # 2. collapse.py: few edges shorter than 4/5 L.
        vertices, faces, features = collapse_short_edges(vertices, faces, target_length, features)
        yield iteration + 1, "collapse", vertices, faces, features
        # 3. flip.py: degrees nearer 6 (table: the flipped faces' edges, for phases 4 and 5).
        faces, table = flip_to_regular_degrees(vertices, faces, rng, features)
        yield iteration + 1, "flip", vertices, faces, features
        # 4. smooth.py: vertices evenly spread, each in its tangent plane.
        vertices = tangential_smoothing(vertices, faces, features, smoothing_step, table=table)
        yield iteration + 1, "smooth", vertices, faces, features
        # 5. project.py: back onto the input.
        if surface is not None:
            vertices = project_to_surface(vertices, faces, surface, features, table.boundary_vertices(len(vertices)),
                                          SNAP_TO_INPUT_VERTEX * target_length)
            yield iteration + 1, "project", vertices, faces, features


def remesh(
    mesh: HalfedgeMesh,
    target_length: float | None = None,
    iterations: int = 5,
    *,
    project: bool = True,
    progress: bool = False,
    feature_angle: float | None = DEFAULT_FEATURE_ANGLE,
    smoothing_step: float = 1.0,
) -> HalfedgeMesh:
    """Isotropic remeshing: edges of about ``target_length``, vertex degrees near 6.

    Args:
        mesh: the input; it is not modified.
        target_length: the edge length ``L`` to aim for; default: the input's mean edge length.
        iterations: how many rounds of split / collapse / flip / smooth / project.
        project: put the vertices back on the input surface after each smoothing (the
            boundary ones on the input's boundary polyline, the ones on a feature line
            on that line of the input). Each vertex goes to the nearest point of a few
            input triangles near it (a k-d tree of centroids, then the triangles beside
            the nearest; of the four segments of its line nearest, on a line), which is
            the true nearest point almost always; one that lands within
            ``SNAP_TO_INPUT_VERTEX * L`` (0.1 L) of an input vertex off the lines goes
            onto that vertex. Without it, midpoints of splits and tangential moves drift
            slightly inside curved regions.
        progress: show a progress bar (tqdm) over the iterations.
        feature_angle: keep the creases: edges whose two faces' normals differ by more
            than this many degrees (default :data:`~halfedge_edu.algorithms.features.DEFAULT_FEATURE_ANGLE`),
            together with the boundary, are feature edges (see
            :func:`~halfedge_edu.algorithms.features.detect_features`). None: no
            creases, only the boundary is kept (and its vertices do not move at all).
        smoothing_step: how much of the tangential step to its neighbours' centroid each
            vertex takes per smoothing phase, from 0 to 1. 1 (Botsch and Kobbelt) makes
            the most even triangles; smaller values leave the vertices nearer where
            splits and collapses put them, and nearer the input's vertices (where the
            projection puts those within ``SNAP_TO_INPUT_VERTEX * L``), which follows a
            noisy input (a scan) more closely at the price of less even triangles (what
            0.5 does on a scan: docs/performance.md, "Quality").

    Returns:
        A new :class:`HalfedgeMesh`. For the mesh after every phase, call
        :func:`remesh_history` (all at once) or :func:`remesh_step_by_step` (one by one).

    What is kept: the genus, the number of boundary loops and components, orientation;
    boundary vertices only move along the input's boundary (boundary edges are split at
    their midpoints and collapse only along the boundary, onto one of their ends).
    With ``feature_angle``, every feature line likewise: a feature edge is never
    flipped, is split into two feature edges and collapses only along its line, its
    vertices move only along the line and go back onto the input's feature lines, and
    corners (where lines meet, end or turn by more than ``feature_angle``) stay exactly
    where they are.
    Right after each split phase and each collapse phase no edge is longer than 4/3 L.
    What is aimed for, not guaranteed: edges between 4/5 L and 4/3 L at the end (a
    collapse that would make a long edge, fold a face or break the link condition is
    skipped, and smoothing moves vertices afterwards), degree 6 inside and 4 on the
    boundary.

    Attention: with ``feature_angle=None`` creases are not kept. An edge whose faces meet
    at more than 20 degrees is still never flipped, and no collapse may swing a face by
    more than 30 degrees, but smoothing may move vertices across a crease and round it off.
    """
    check_remesh(mesh, target_length, iterations, project, progress)
    feature_angle, smoothing_step = _check_feature_options(feature_angle, smoothing_step)
    if mesh.n_faces == 0:
        return _to_mesh(*mesh.to_arrays())
    target_length, iterations = _check_arguments(target_length, iterations)
    vertices, faces = mesh.to_arrays()
    for _, _, vertices, faces, _ in _phases(mesh, target_length, iterations, project, progress, feature_angle,
                                            smoothing_step):
        pass
    return _to_mesh(vertices, faces)


def remesh_history(mesh: HalfedgeMesh, target_length: float | None = None, **options) -> list[RemeshStep]:
    """Every :class:`RemeshStep` of :func:`remesh_step_by_step`, as one list.

    Takes exactly the arguments of :func:`remesh` (``options`` are its other keyword
    arguments, with its defaults); the last step's mesh is what :func:`remesh` returns
    for them. A separate function rather than a flag on :func:`remesh`, so that each
    function always returns one type.
    """
    # Bind to remesh's own signature: one place holds the options and their defaults,
    # and a misspelt option is a TypeError naming it.
    arguments = inspect.signature(remesh).bind(mesh, target_length, **options)
    arguments.apply_defaults()
    given = dict(arguments.arguments)
    feature_angle, smoothing_step = _check_feature_options(given.pop("feature_angle"), given.pop("smoothing_step"))
    check_remesh(**given)
    if mesh.n_faces == 0:
        return [RemeshStep(0, "input", mesh.copy())]
    target_length, iterations = _check_arguments(given["target_length"], given["iterations"])
    return list(_steps(mesh, target_length, iterations, given["project"], given["progress"], feature_angle,
                       smoothing_step))


def remesh_step_by_step(
    mesh: HalfedgeMesh,
    target_length: float | None = None,
    iterations: int = 5,
    *,
    project: bool = True,
    feature_angle: float | None = DEFAULT_FEATURE_ANGLE,
    smoothing_step: float = 1.0,
) -> Iterator[RemeshStep]:
    """Yield a :class:`RemeshStep` ``(iteration, phase, mesh)`` after every phase.

    First ``(0, "input", a copy of mesh)``; then, for each iteration from 1, the phases
    ``"split"``, ``"collapse"``, ``"flip"``, ``"smooth"`` and (with ``project=True``)
    ``"project"``. Each mesh is new. The work happens as you ask for the next step, so a
    stepper can stop whenever it likes. The arguments are those of :func:`remesh`.
    """
    check_remesh(mesh, target_length, iterations, project)
    feature_angle, smoothing_step = _check_feature_options(feature_angle, smoothing_step)
    if mesh.n_faces == 0:
        return iter([RemeshStep(0, "input", mesh.copy())])
    target_length, iterations = _check_arguments(target_length, iterations)
    return _steps(mesh, target_length, iterations, project, False, feature_angle, smoothing_step)


def _steps(mesh, target_length, iterations, project, progress, feature_angle, smoothing_step) -> Iterator[RemeshStep]:
    yield RemeshStep(0, "input", mesh.copy())
    for iteration, phase, vertices, faces, _ in _phases(mesh, target_length, iterations, project, progress,
                                                        feature_angle, smoothing_step):
        yield RemeshStep(iteration, phase, _to_mesh(vertices, faces))


def _to_mesh(vertices: np.ndarray, faces: np.ndarray) -> HalfedgeMesh:
    vertices, faces, _ = compact(vertices, faces)
    return HalfedgeMesh.from_faces(vertices, faces)
