"""Checks of the arguments every public algorithm takes, shared so that each says the same thing.

Each public function calls these in its first lines, before any work, so that a bad
argument is refused by name (``iterations must be a whole number >= 0, got nan``) and
never reaches numpy, where it would become a bare ``IndexError``, an overflow warning, or
a check that ``nan`` silently switches off (every comparison with ``nan`` is False).

* A value of the wrong kind (a string where a number belongs, a list where a mesh
  belongs) raises :class:`ArgumentTypeError`, which is both a
  :class:`~halfedge_edu.MeshInputError` and a ``TypeError``.
* A value of the right kind but out of range (``nan``, a negative count, an unknown
  name) raises :class:`~halfedge_edu.MeshInputError` (a ``ValueError``).

Both carry ``element=("argument", name)``, and the command line reports both as bad
input (exit status 2).
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..core.errors import MeshInputError, TopologyError
from ..core.mesh import HalfedgeMesh

#: Largest coordinate size (absolute value) the algorithms accept. Their formulas
#: multiply up to four coordinates together (quadric costs, cross products of edge
#: vectors, squared areas), and ``(1e40) ** 4 = 1e160`` stays far below the float64
#: limit of about 1.8e308, with room for the sums. The command line uses the same limit.
MAX_COORDINATE = 1e40

#: Smallest extent (the longest side of the bounding box of the live vertices) the
#: algorithms accept for a mesh with faces. The same products of four coordinate
#: differences underflow at the other end: ``(1e-40) ** 4 = 1e-160`` stays far above the
#: smallest normal float64 (about 2.2e-308), while a mesh scaled to 1e-200 has edge
#: lengths whose squares are 0 and normals of (0, 0, 0). The command line uses the same limit.
MIN_EXTENT = 1e-40


class ArgumentTypeError(MeshInputError, TypeError):
    """An argument of the wrong type: a string for a number, a list for a mesh.

    A :class:`~halfedge_edu.MeshInputError` (so ``except MeshInputError`` and the command
    line treat it as bad input) and a ``TypeError`` (what Python code expects for a value
    of the wrong type). ``element`` is ``("argument", name)``.
    """


def _refuse(name: str, message: str) -> MeshInputError:
    return MeshInputError(f"{name} {message}", element=("argument", name))


def _wrong_type(name: str, wanted: str, value) -> ArgumentTypeError:
    return ArgumentTypeError(
        f"{name} must be {wanted}, got {value!r} ({type(value).__name__})", element=("argument", name)
    )


def check_mesh(mesh, name: str = "mesh") -> None:
    """Refuse anything but a :class:`HalfedgeMesh` whose live coordinates the algorithms can compute with.

    Raises:
        ArgumentTypeError: ``mesh`` is not a :class:`HalfedgeMesh`.
        MeshInputError: a live vertex has a coordinate that is not finite (set by hand
            after construction) or larger in size than :data:`MAX_COORDINATE`; the error
            names the vertex, with ``element=("vertex", index)``. Or a mesh with faces
            whose extent is below :data:`MIN_EXTENT` (``element=("argument", name)``).
    """
    if not isinstance(mesh, HalfedgeMesh):
        raise _wrong_type(name, "a HalfedgeMesh (build one with HalfedgeMesh.from_faces or hx.load)", mesh)
    deleted = mesh.vertex_deleted
    live_positions = mesh.positions[~deleted] if deleted.any() else mesh.positions   # (V_live, 3)
    if live_positions.size:
        # Two reductions over all coordinates say "all finite and small enough": NaN
        # carries through min and max, and an infinity is one of the two. Only if they
        # say no is every vertex looked at, to name the first offending one.
        coordinates = live_positions.reshape(-1)                      # (3 V_live,)
        lowest, highest = coordinates.min(), coordinates.max()
        if not (np.isfinite(lowest) and np.isfinite(highest) and max(-lowest, highest) <= MAX_COORDINATE):
            _refuse_coordinates(mesh)
    if mesh.n_faces:
        # A few vertices' extent is at most all of them's, so when the first
        # EXTENT_SAMPLE live vertices already span MIN_EXTENT the whole mesh does, and
        # the whole-mesh measurement (a slow reduction across 3 columns) is only needed
        # for the rare mesh whose sample is that small.
        extent = float(np.ptp(live_positions[:EXTENT_SAMPLE], axis=0).max())
        if extent < MIN_EXTENT:
            extent = float(np.ptp(live_positions, axis=0).max())
        if extent < MIN_EXTENT:
            raise MeshInputError(
                f"the mesh is {extent:.3g} across: too small for the computation (at least {MIN_EXTENT:.0e}, so that "
                f"the products the algorithms take do not round to zero); scale the mesh up",
                element=("argument", name),
            )


#: How many live vertices :func:`check_mesh` measures the extent of before it measures all.
EXTENT_SAMPLE = 1024


def _refuse_coordinates(mesh: HalfedgeMesh) -> None:
    """Raise for the first live vertex with a coordinate that is not finite or too large."""
    live = np.flatnonzero(~mesh.vertex_deleted)                       # (V_live,)
    size = np.abs(mesh.positions[live]).max(axis=1, initial=0.0)      # (V_live,) largest |coordinate|
    finite = np.isfinite(size)
    if not finite.all():
        vertex = int(live[np.flatnonzero(~finite)[0]])
        raise MeshInputError(
            f"vertex {vertex} has a coordinate that is not a finite number: {mesh.positions[vertex].tolist()}",
            element=("vertex", vertex),
        )
    too_large = size > MAX_COORDINATE
    if too_large.any():
        vertex = int(live[np.flatnonzero(too_large)[0]])
        raise MeshInputError(
            f"vertex {vertex} has a coordinate of size {float(size[np.flatnonzero(too_large)[0]]):.3g}: "
            f"coordinates are too large for the computation (at most {MAX_COORDINATE:.0e}, so that the "
            f"products the algorithms take stay finite); scale the mesh down",
            element=("vertex", vertex),
        )


def refuse_pillows(mesh: HalfedgeMesh, what: str) -> None:
    """Raise :class:`~halfedge_edu.TopologyError` if two faces of ``mesh`` are glued back to back.

    ``from_faces`` refuses such a "pillow" (two triangles on the same three vertices),
    but a mesh built from hand-made arrays can hold one. No edge of it can be split
    (the new vertex would be joined to the opposite vertex twice), flipped or collapsed,
    and a result holding it could not be rebuilt, so the algorithms that change
    connectivity (``what``) refuse it up front. Found as an interior edge whose two
    opposite corners are the same vertex, over all live edges at once.
    """
    edges = np.flatnonzero(~mesh.edge_deleted)                           # (E_live,)
    first, second = 2 * edges, 2 * edges + 1
    interior = (mesh.halfedge_face[first] >= 0) & (mesh.halfedge_face[second] >= 0)
    opposite_first = mesh.halfedge_vertex[mesh.halfedge_prev[first]]   # (E_live,)
    opposite_second = mesh.halfedge_vertex[mesh.halfedge_prev[second]]
    glued = np.flatnonzero(interior & (opposite_first == opposite_second))
    if len(glued):
        e = int(edges[glued[0]])
        f, g = int(mesh.halfedge_face[2 * e]), int(mesh.halfedge_face[2 * e + 1])
        raise TopologyError(
            f"{what} cannot work on this mesh: faces {min(f, g)} and {max(f, g)} are glued back to back along "
            f"all three edges (a two-triangle 'pillow' on vertex {int(opposite_first[glued[0]])} and edge {e}, "
            f"which from_faces refuses as a duplicate face), and none of its edges can be split, flipped or "
            f"collapsed; remove one of the two faces"
        )


def whole_number(value, name: str, minimum: int | None = None) -> int:
    """``value`` as an ``int``, refusing booleans, fractions, ``nan`` and anything below ``minimum``.

    Whole floats such as ``2.0`` are accepted, as ``range`` users expect from numpy scalars.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _wrong_type(name, "a whole number", value)
    if not math.isfinite(value) or int(value) != value:
        raise _refuse(name, f"must be a whole number, got {value!r}")
    if minimum is not None and value < minimum:
        raise _refuse(name, f"must be a whole number >= {minimum}, got {value!r}")
    return int(value)


def real_number(
    value,
    name: str,
    *,
    above: float | None = None,
    minimum: float | None = None,
    maximum: float | None = None,
    nonzero: bool = False,
) -> float:
    """``value`` as a finite ``float`` in the allowed range, or an error naming ``name``.

    Args:
        above: the value must be strictly greater than this.
        minimum, maximum: the value must lie in ``[minimum, maximum]``.
        nonzero: the value must not be zero.

    Complex numbers, booleans and strings are refused by type (a complex number's
    imaginary part would otherwise be dropped, and ``True`` would count as 1).
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _wrong_type(name, "a real number", value)
    number = float(value)
    if not math.isfinite(number):
        raise _refuse(name, f"must be a finite number, got {value!r}")
    if above is not None and not number > above:
        raise _refuse(name, f"must be greater than {above:g}, got {value!r}")
    if minimum is not None and number < minimum or maximum is not None and number > maximum:
        low = "-inf" if minimum is None else f"{minimum:g}"
        high = "inf" if maximum is None else f"{maximum:g}"
        raise _refuse(name, f"must lie between {low} and {high}, got {value!r}")
    if nonzero and number == 0:
        raise _refuse(name, "must not be zero")
    return number


def choice(value, name: str, choices: tuple[str, ...]) -> str:
    """``value`` if it is one of the names in ``choices``; an error listing them otherwise."""
    if not isinstance(value, str):
        raise _wrong_type(name, f"one of {choices}", value)
    if value not in choices:
        raise _refuse(name, f"must be one of {choices}, got {value!r}")
    return value


def flag(value, name: str) -> bool:
    """``value`` if it is ``True`` or ``False`` (numpy's too); ``"no"`` or ``0`` are refused."""
    if not isinstance(value, (bool, np.bool_)):
        raise _wrong_type(name, "True or False", value)
    return bool(value)


def callback(value, name: str) -> None:
    """Refuse a ``value`` that is neither ``None`` nor callable."""
    if value is not None and not callable(value):
        raise _wrong_type(name, "a function or None", value)


def check_simplify(mesh, target_faces, boundary_weight=100.0, max_normal_angle=80.0,
                   candidate_fraction=0.25, progress=False) -> None:
    """The checks of :func:`~halfedge_edu.simplify` (and ``simplify_with_report``).

    ``max_normal_angle`` is in degrees, between 0 and 180 (180 allows every swing);
    ``candidate_fraction`` is a fraction of the edges, above 0 and at most 1.
    """
    check_mesh(mesh)
    refuse_pillows(mesh, "simplification")
    whole_number(target_faces, "target_faces", minimum=1)
    real_number(boundary_weight, "boundary_weight", minimum=0.0)
    real_number(max_normal_angle, "max_normal_angle", minimum=0.0, maximum=180.0)
    real_number(candidate_fraction, "candidate_fraction", above=0.0, maximum=1.0)
    flag(progress, "progress")


def check_remesh(mesh, target_length=None, iterations=5, project=True, progress=False) -> None:
    """The checks of :func:`~halfedge_edu.remesh` and its step-by-step forms.

    ``target_length`` is None (the mean edge length) or a positive length.
    """
    check_mesh(mesh)
    refuse_pillows(mesh, "remeshing")
    if target_length is not None:
        real_number(target_length, "target_length", above=0.0)
    whole_number(iterations, "iterations", minimum=0)
    flag(project, "project")
    flag(progress, "progress")


def check_smooth(mesh, iterations, weights, boundary, step, weight_names: tuple[str, ...],
                 boundary_rules: tuple[str, ...]) -> None:
    """The checks of :func:`~halfedge_edu.smooth` and ``smooth_reference``.

    ``step`` may be any finite number but zero (negative steps are Taubin's inflation).
    """
    check_mesh(mesh)
    whole_number(iterations, "iterations", minimum=0)
    choice(weights, "weights", weight_names)
    choice(boundary, "boundary", boundary_rules)
    real_number(step, "step", nonzero=True)
