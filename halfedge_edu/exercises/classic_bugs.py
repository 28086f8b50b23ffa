"""Classic wrong implementations of halfedge code, each beside the right one (the debugging lab).

    from halfedge_edu.exercises.classic_bugs import BUGS, catch
    bug = BUGS["flip_forgetting_vertex_halfedge"]
    mesh = bug.demo(bug.wrong)      # run the wrong function on its demonstration mesh
    mesh.validate()                 # MeshInvariantError: [vertex-halfedge-origin] vertex 0 ...
    catch(bug)                      # the same, as a Caught: rule, element, message, mesh

Every function named after a mistake here is **wrong on purpose**: it is the bug
learners write most often in the courses this package follows (Scotty3D, CS184,
geometry-central's and pmp-library's exercises), kept short, next to the right
version it differs from in one step. Chapter 08b runs each, lets ``validate()`` (or the
``check_*`` helper, where the mesh stays valid) name the rule and the element, draws the
element and explains why it happens and the fix. The tests hold every bug to that:
caught, with a message that names the rule.

The pointer arrays are written directly, as the chapters' exercises do, so that each
mistake is visible in one line.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace
from typing import Callable

import numpy as np

from halfedge_edu.core.build import INDEX, HalfedgeArrays
from halfedge_edu.core.errors import MeshInvariantError
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.core.ops import flip, split
from halfedge_edu.data import sample

__all__ = [
    "BUGS", "Caught", "ClassicBug", "picture", "build_closed_pairing_twins_by_sorted_ends", "build_closed_right", "catch",
    "check_loop_split", "collapse_forgetting_vertex_halfedges", "collapse_leaving_outer_next_stale",
    "collapse_reading_neighbours_too_early", "collapse_right", "flip_forgetting_face_halfedge",
    "flip_forgetting_vertex_halfedge", "flip_right", "loop_split_flipping_old_edges", "loop_split_right",
    "one_ring_endless_at_the_boundary", "one_ring_right", "split_boundary_forgetting_boundary_halfedges",
    "split_boundary_right",
]


def _link(mesh: HalfedgeMesh, a: int, b: int) -> None:
    """Make ``b`` the next of ``a`` (and ``a`` the prev of ``b``): always both."""
    mesh.halfedge_next[a], mesh.halfedge_prev[b] = b, a


# --------------------------------------------------------------------------------------
# Flip (chapter 06)
# --------------------------------------------------------------------------------------

def _flip_gather(mesh: HalfedgeMesh, e: int) -> SimpleNamespace:
    """The names of chapter 06's picture: h0 ... h5, v0 ... v3, f0, f1."""
    nxt, prv, origin, face = mesh.halfedge_next, mesh.halfedge_prev, mesh.halfedge_vertex, mesh.halfedge_face
    h0, h1 = 2 * e, 2 * e + 1
    return SimpleNamespace(h0=h0, h1=h1, h2=int(nxt[h0]), h3=int(prv[h0]), h4=int(nxt[h1]), h5=int(prv[h1]),
                           v0=int(origin[h0]), v1=int(origin[h1]), v2=int(origin[prv[h0]]),
                           v3=int(origin[prv[h1]]), f0=int(face[h0]), f1=int(face[h1]))


def _flip_relink(mesh: HalfedgeMesh, n: SimpleNamespace) -> None:
    """Steps 1 and 2 of the flip: turn the edge and relink the two triangles."""
    mesh.halfedge_vertex[n.h0], mesh.halfedge_vertex[n.h1] = n.v3, n.v2
    for a, b in ((n.h0, n.h3), (n.h3, n.h4), (n.h4, n.h0), (n.h1, n.h5), (n.h5, n.h2), (n.h2, n.h1)):
        _link(mesh, a, b)
    mesh.halfedge_face[n.h4], mesh.halfedge_face[n.h2] = n.f0, n.f1


def _flip_vertex_halfedges(mesh: HalfedgeMesh, n: SimpleNamespace) -> None:
    """Step 4: v0 and v1 no longer leave along h0 and h1."""
    if mesh.vertex_halfedge[n.v0] == n.h0:
        mesh.vertex_halfedge[n.v0] = n.h4
    if mesh.vertex_halfedge[n.v1] == n.h1:
        mesh.vertex_halfedge[n.v1] = n.h2


def flip_right(mesh: HalfedgeMesh, e: int) -> None:
    """Flip interior edge ``e`` in place (chapter 06's answer)."""
    n = _flip_gather(mesh, e)
    _flip_relink(mesh, n)
    mesh.face_halfedge[n.f0], mesh.face_halfedge[n.f1] = n.h0, n.h1
    _flip_vertex_halfedges(mesh, n)
    mesh.topology_changed()


def flip_forgetting_vertex_halfedge(mesh: HalfedgeMesh, e: int) -> None:
    """WRONG: step 4 is missing, so v0 (or v1) may still point at h0, which now leaves v3."""
    n = _flip_gather(mesh, e)
    _flip_relink(mesh, n)
    mesh.face_halfedge[n.f0], mesh.face_halfedge[n.f1] = n.h0, n.h1
    mesh.topology_changed()


def flip_forgetting_face_halfedge(mesh: HalfedgeMesh, e: int) -> None:
    """WRONG: f0 and f1 keep their old halfedge; if that was h2 or h4, it now lies in the other face."""
    n = _flip_gather(mesh, e)
    _flip_relink(mesh, n)
    _flip_vertex_halfedges(mesh, n)
    mesh.topology_changed()


# --------------------------------------------------------------------------------------
# Collapse (chapter 07)
# --------------------------------------------------------------------------------------

def _collapse_gather(mesh: HalfedgeMesh, h: int) -> SimpleNamespace:
    """The names of chapter 07's picture; ``h`` runs from vB (goes) to vA (stays)."""
    nxt, prv, origin, face = mesh.halfedge_next, mesh.halfedge_prev, mesh.halfedge_vertex, mesh.halfedge_face
    h_BA, h_AB = h, h ^ 1
    h_L_B, h_B_R = int(prv[h_BA]), int(nxt[h_AB])
    ring_B = [h_BA]                                     # the halfedges leaving vB, before any change
    g = int(prv[h_BA]) ^ 1
    while g != h_BA:
        ring_B.append(g)
        g = int(prv[g]) ^ 1
    return SimpleNamespace(h_BA=h_BA, h_AB=h_AB, vB=int(origin[h_BA]), vA=int(origin[h_AB]),
                           h_A_L=int(nxt[h_BA]), h_L_B=h_L_B, h_B_R=h_B_R, h_R_A=int(prv[h_AB]),
                           h_B_L=h_L_B ^ 1, h_R_B=h_B_R ^ 1, vL=int(origin[h_L_B]), vR=int(origin[prv[h_AB]]),
                           fL=int(face[h_BA]), fR=int(face[h_AB]), ring_B=ring_B)


def _collapse_move(mesh: HalfedgeMesh, n: SimpleNamespace) -> None:
    """Steps 1 and 2: vA to the midpoint; vB's other halfedges now leave vA."""
    mesh.positions[n.vA] = 0.5 * (mesh.positions[n.vA] + mesh.positions[n.vB])
    for g in n.ring_B:
        if g not in (n.h_BA, n.h_B_L, n.h_B_R):
            mesh.halfedge_vertex[g] = n.vA


def _neighbours(mesh: HalfedgeMesh, old: int) -> tuple[int, int, int]:
    """``old``'s prev, next and face, as they are at this moment."""
    return int(mesh.halfedge_prev[old]), int(mesh.halfedge_next[old]), int(mesh.halfedge_face[old])


def _take_place(mesh: HalfedgeMesh, old: int, new: int, before: int, after: int, face: int) -> None:
    """Steps 3 and 4: ``new`` takes ``old``'s place between ``before`` and ``after`` in ``face``."""
    _link(mesh, before, new)
    _link(mesh, new, after)
    mesh.halfedge_face[new] = face
    if mesh.face_halfedge[face] == old:
        mesh.face_halfedge[face] = new


def _collapse_vertex_halfedges(mesh: HalfedgeMesh, n: SimpleNamespace) -> None:
    """Step 5: vL, vR and vA may point at halfedges that are about to be deleted."""
    if mesh.vertex_halfedge[n.vL] == n.h_L_B:
        mesh.vertex_halfedge[n.vL] = n.h_A_L ^ 1
    if mesh.vertex_halfedge[n.vR] == n.h_R_B:
        mesh.vertex_halfedge[n.vR] = n.h_R_A
    if mesh.vertex_halfedge[n.vA] == n.h_AB:
        mesh.vertex_halfedge[n.vA] = n.h_R_A ^ 1


def _collapse_delete(mesh: HalfedgeMesh, n: SimpleNamespace) -> None:
    """Step 6: the two faces, three edges and vB go."""
    mesh.delete_face(n.fL)
    mesh.delete_face(n.fR)
    for g in (n.h_BA, n.h_L_B, n.h_B_R):
        mesh.delete_edge(g >> 1)
    mesh.delete_vertex(n.vB)
    mesh.topology_changed()


def collapse_right(mesh: HalfedgeMesh, h: int) -> None:
    """Collapse the edge of halfedge ``h`` (vB -> vA) in place (chapter 07's answer)."""
    n = _collapse_gather(mesh, h)
    _collapse_move(mesh, n)
    for old, new in ((n.h_B_L, n.h_A_L), (n.h_R_B, n.h_R_A)):
        _take_place(mesh, old, new, *_neighbours(mesh, old))      # read each side's neighbours NOW
    _collapse_vertex_halfedges(mesh, n)
    _collapse_delete(mesh, n)


def collapse_reading_neighbours_too_early(mesh: HalfedgeMesh, h: int) -> None:
    """WRONG at a degree-3 vertex: both sides' neighbours are read before either side is relinked.

    When vB has degree 3, the faces beyond h_B_L and h_R_B are one face, so relinking
    the left side changes what the right side must read; read early, the right side
    merges the wrong halfedges into that face.
    """
    n = _collapse_gather(mesh, h)
    _collapse_move(mesh, n)
    sides = [(old, new, *_neighbours(mesh, old)) for old, new in ((n.h_B_L, n.h_A_L), (n.h_R_B, n.h_R_A))]
    for side in sides:
        _take_place(mesh, *side)
    _collapse_vertex_halfedges(mesh, n)
    _collapse_delete(mesh, n)


def collapse_leaving_outer_next_stale(mesh: HalfedgeMesh, h: int) -> None:
    """WRONG: the halfedge just outside the removed faces (before h_B_L) keeps h_B_L as its next."""
    n = _collapse_gather(mesh, h)
    _collapse_move(mesh, n)
    for old, new in ((n.h_B_L, n.h_A_L), (n.h_R_B, n.h_R_A)):
        before, after, face = _neighbours(mesh, old)
        mesh.halfedge_prev[new] = before                    # only half of _link(before, new)
        _link(mesh, new, after)
        mesh.halfedge_face[new] = face
        if mesh.face_halfedge[face] == old:
            mesh.face_halfedge[face] = new
    _collapse_vertex_halfedges(mesh, n)
    _collapse_delete(mesh, n)


def collapse_forgetting_vertex_halfedges(mesh: HalfedgeMesh, h: int) -> None:
    """WRONG: step 5 is missing, so vA (or vL, vR) may still point at a deleted halfedge."""
    n = _collapse_gather(mesh, h)
    _collapse_move(mesh, n)
    for old, new in ((n.h_B_L, n.h_A_L), (n.h_R_B, n.h_R_A)):
        _take_place(mesh, old, new, *_neighbours(mesh, old))
    _collapse_delete(mesh, n)


# --------------------------------------------------------------------------------------
# Split of a boundary edge (chapter 06)
# --------------------------------------------------------------------------------------

def _split_boundary_inside(mesh: HalfedgeMesh, e: int) -> SimpleNamespace:
    """The part of a boundary split inside the face: a new vertex m, edges m-b and m-c, a new face.

    ``e``'s interior halfedge h runs a -> b in face f with c opposite; its twin t is on
    the boundary. Afterwards h runs a -> m, t runs m -> a, and the new face is m, b, c.
    """
    h = 2 * e if mesh.halfedge_face[2 * e] >= 0 else 2 * e + 1
    t = h ^ 1
    h_bc, h_ca = int(mesh.halfedge_next[h]), int(mesh.halfedge_prev[h])
    a, b, c = int(mesh.halfedge_vertex[h]), int(mesh.halfedge_vertex[t]), int(mesh.halfedge_vertex[h_ca])
    f = int(mesh.halfedge_face[h])
    m = mesh.add_vertex(0.5 * (mesh.positions[a] + mesh.positions[b]))
    g = 2 * mesh.add_edge(m, b)                             # g: m -> b, g ^ 1: b -> m (on the boundary)
    k = 2 * mesh.add_edge(m, c)                             # k: m -> c, k ^ 1: c -> m
    mesh.halfedge_vertex[t] = m
    for x, y in ((h, k), (k, h_ca), (h_ca, h)):
        _link(mesh, x, y)
    mesh.halfedge_face[k] = f
    f2 = mesh.add_face(g)
    for x, y in ((g, h_bc), (h_bc, k ^ 1), (k ^ 1, g)):
        _link(mesh, x, y)
        mesh.halfedge_face[x] = f2
    mesh.face_halfedge[f] = h
    mesh.vertex_halfedge[m] = t                             # a boundary vertex keeps its boundary halfedge
    return SimpleNamespace(t=t, g=g, b=b, m=m)


def split_boundary_right(mesh: HalfedgeMesh, e: int) -> int:
    """Split boundary edge ``e`` at its midpoint; returns the new vertex."""
    n = _split_boundary_inside(mesh, e)
    _link(mesh, int(mesh.halfedge_prev[n.t]), n.g ^ 1)     # the boundary loop: ... -> b -> m -> a
    _link(mesh, n.g ^ 1, n.t)
    if mesh.vertex_halfedge[n.b] == n.t:                    # b's boundary halfedge now runs b -> m
        mesh.vertex_halfedge[n.b] = n.g ^ 1
    mesh.topology_changed()
    return n.m


def split_boundary_forgetting_boundary_halfedges(mesh: HalfedgeMesh, e: int) -> int:
    """WRONG: the new boundary halfedge b -> m is never linked into the boundary loop."""
    n = _split_boundary_inside(mesh, e)
    mesh.topology_changed()
    return n.m


# --------------------------------------------------------------------------------------
# Build (chapter 02), closed meshes
# --------------------------------------------------------------------------------------

def _build_closed(vertices, faces, origin_of: Callable[[int, int, bool], int]) -> HalfedgeMesh:
    """Build a closed mesh; ``origin_of(a, b, second)`` is the origin stored for the face's side a -> b
    (``second``: the edge was seen before, so this side is halfedge 2e + 1)."""
    faces = np.asarray(faces, dtype=np.int64)                 # (F, 3)
    n_halfedges = 3 * len(faces)                              # closed: every halfedge is in a face
    origin, face, nxt = (np.full(n_halfedges, -1, dtype=INDEX) for _ in range(3))
    face_halfedge = np.full(len(faces), -1, dtype=INDEX)
    edge_of: dict[tuple[int, int], int] = {}                  # (smaller, larger) vertex -> edge
    for f, (i, j, k) in enumerate(faces.tolist()):
        corners = []
        for a, b in ((i, j), (j, k), (k, i)):
            key = (min(a, b), max(a, b))
            second = key in edge_of
            if not second:
                edge_of[key] = len(edge_of)
            h = 2 * edge_of[key] + second                     # the second sighting is the twin 2e + 1
            origin[h], face[h] = origin_of(a, b, second), f
            corners.append(h)
        for h, g in zip(corners, corners[1:] + corners[:1]):
            nxt[h] = g
        face_halfedge[f] = corners[0]
    prv = np.empty_like(nxt)
    prv[nxt] = np.arange(n_halfedges, dtype=INDEX)
    vertex_halfedge = np.full(len(vertices), -1, dtype=INDEX)
    vertex_halfedge[origin[::-1]] = np.arange(n_halfedges, dtype=INDEX)[::-1]   # the smallest leaving each
    return HalfedgeMesh(HalfedgeArrays(np.asarray(vertices, dtype=np.float64), vertex_halfedge, nxt, prv,
                                       origin, face, face_halfedge))


def build_closed_right(vertices, faces) -> HalfedgeMesh:
    """Build a closed mesh: halfedge a -> b leaves a, whichever sighting of its edge it is."""
    return _build_closed(vertices, faces, lambda a, b, second: a)


def build_closed_pairing_twins_by_sorted_ends(vertices, faces) -> HalfedgeMesh:
    """WRONG: 2e is made to run from the smaller vertex to the larger and 2e + 1 back, whatever the faces say."""
    return _build_closed(vertices, faces, lambda a, b, second: max(a, b) if second else min(a, b))


# --------------------------------------------------------------------------------------
# One-ring (chapter 03)
# --------------------------------------------------------------------------------------

def one_ring_right(mesh: HalfedgeMesh, v) -> list[int]:
    """The neighbours of ``v``, counter-clockwise from the tip of ``v.halfedge`` (chapter 03's answer)."""
    start = mesh.vertex(int(v)).halfedge
    ring, h = [], start
    while True:
        ring.append(h.tip.index)
        h = h.prev.twin                           # the next halfedge leaving v, boundary ones included
        if h == start:
            return ring


def one_ring_endless_at_the_boundary(mesh: HalfedgeMesh, v) -> list[int]:
    """WRONG at the boundary: it steps over boundary halfedges, so it never meets its boundary start again."""
    start = mesh.vertex(int(v)).halfedge
    ring, h = [], start
    while True:
        ring.append(h.tip.index)
        h = h.prev.twin
        if h.face is None:                        # "skip the hole": the start is such a halfedge
            h = h.prev.twin
        if h == start:
            return ring


# --------------------------------------------------------------------------------------
# Loop subdivision's 4-to-1 split from operations (chapter 09)
# --------------------------------------------------------------------------------------

def _split_every_edge(mesh: HalfedgeMesh) -> tuple[int, set[tuple[int, int]]]:
    """Split every edge of ``mesh`` in place; returns the old vertex count and the halves of the old edges."""
    n_old = mesh.n_vertices
    halves: set[tuple[int, int]] = set()
    for e in [edge.index for edge in mesh.edges]:
        a, b = (int(v) for v in mesh.edge(e).vertices)
        m = int(split(mesh, e))
        halves |= {(min(a, m), max(a, m)), (min(b, m), max(b, m))}
    return n_old, halves


def _old_new_edges(mesh: HalfedgeMesh, n_old: int) -> list[tuple[int, tuple[int, int]]]:
    """Every edge joining an old vertex (index below ``n_old``) and a new one, with its ends sorted."""
    found = []
    for edge in mesh.edges:
        a, b = sorted(int(v) for v in edge.vertices)
        if (a < n_old) != (b < n_old):
            found.append((edge.index, (a, b)))
    return found


def loop_split_right(mesh: HalfedgeMesh) -> HalfedgeMesh:
    """Loop's 4-to-1 split in place: split every edge, then flip each new edge that joins an old and a new vertex."""
    n_old, halves = _split_every_edge(mesh)
    for e, ends in _old_new_edges(mesh, n_old):
        if ends not in halves:                    # a cross edge drawn by a split, not half of an old edge
            flip(mesh, e)
    return mesh


def loop_split_flipping_old_edges(mesh: HalfedgeMesh) -> HalfedgeMesh:
    """WRONG: it flips every edge between an old and a new vertex, the halves of the old edges too."""
    n_old, _ = _split_every_edge(mesh)
    for e, _ in _old_new_edges(mesh, n_old):
        if mesh.can_flip(e):
            flip(mesh, e)
    return mesh


def _loop_split_problem(loop_split: Callable) -> tuple[str, int | None, HalfedgeMesh]:
    """Run ``loop_split`` on an octahedron: (message, the old vertex it is about, the result)."""
    mesh = sample("octahedron")
    degrees = mesh.vertex_degrees().copy()
    result = loop_split(mesh.copy())
    after = result.vertex_degrees()
    for v in range(len(degrees)):
        if after[v] != degrees[v]:
            return (f"[old-vertex-degree] vertex {v} is an old vertex of degree {degrees[v]}, but after the split "
                    f"it has degree {after[v]}: a flip turned one of the halves of an old edge. Flip only the "
                    f"new edges that cross an old triangle, never the halves of an old edge.", v, result)
    new = after[len(degrees):result.n_vertices]
    if np.any(new != 6):
        return f"[new-vertex-degree] a new vertex has degree {int(new[new != 6][0])}, not 6.", None, result
    return "", None, result


def check_loop_split(loop_split: Callable) -> str:
    """Run ``loop_split(mesh)`` on an octahedron and hold it to Loop's rule; "" when it keeps it.

    Rule ``old-vertex-degree``: the 4-to-1 split keeps every old vertex's degree (each old
    edge becomes two, one of which stays at the old vertex), and gives every new vertex
    degree 6. A flipped half of an old edge changes an old vertex's degree.
    """
    return _loop_split_problem(loop_split)[0]


# --------------------------------------------------------------------------------------
# The lab's table: each bug with its demonstration and how it is caught
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ClassicBug:
    """One classic mistake: the wrong function, the right one, where to watch it and what to learn.

    ``demo(function)`` runs ``function`` (``wrong`` or ``right``) on a fresh copy of a
    mesh chosen so that the mistake shows, and returns the mesh it left; for the two
    bugs that leave a valid mesh (``caught_by`` is not ``"validate"``) it returns the
    mesh the check ran on. ``rule`` is the rule that catches it.
    """

    wrong: Callable
    right: Callable
    demo: Callable[[Callable], HalfedgeMesh]
    rule: str
    caught_by: str
    why: str
    fix: str

    @property
    def name(self) -> str:
        return self.wrong.__name__


@dataclass(frozen=True)
class Caught:
    """How a bug was caught: the rule, the element (``("vertex", 3)``), the message and the mesh."""

    rule: str
    element: tuple | None
    message: str
    mesh: HalfedgeMesh | None


def _first_edge(mesh: HalfedgeMesh, wanted: Callable[[HalfedgeMesh, int], bool]) -> int:
    return next(e.index for e in mesh.edges if wanted(mesh, e.index))


def _flip_demo(wanted: Callable[[HalfedgeMesh, int], bool]) -> Callable[[Callable], HalfedgeMesh]:
    """Flip, on an icosphere, the first flippable edge where ``wanted(mesh, e)`` holds."""
    def demo(operation: Callable) -> HalfedgeMesh:
        mesh = sample("icosphere", subdivisions=1)
        operation(mesh, _first_edge(mesh, lambda m, e: bool(m.can_flip(e)) and wanted(m, e)))
        return mesh
    return demo


def _collapse_demo(make: Callable[[], HalfedgeMesh],
                   wanted: Callable[[HalfedgeMesh, int], bool]) -> Callable[[Callable], HalfedgeMesh]:
    """Collapse, on ``make()``, the first halfedge (of a collapsible edge) where ``wanted(mesh, h)`` holds."""
    def demo(operation: Callable) -> HalfedgeMesh:
        mesh = make()
        h = next(h for h in range(2 * mesh.n_edges) if mesh.can_collapse(h >> 1) and wanted(mesh, h))
        operation(mesh, h)
        return mesh
    return demo


def _split_demo(operation: Callable) -> HalfedgeMesh:
    mesh = sample("strip")
    operation(mesh, _first_edge(mesh, lambda m, e: m.edge(e).is_boundary))
    return mesh


def _build_demo(build: Callable) -> HalfedgeMesh:
    return build(*sample("octahedron").to_arrays())


def _one_ring_demo(one_ring: Callable) -> HalfedgeMesh:
    return sample("open_patch")


def _loop_demo(loop_split: Callable) -> HalfedgeMesh:
    return loop_split(sample("octahedron"))


def _leaves_along(mesh: HalfedgeMesh, vertex: int, h: int) -> bool:
    return int(mesh.vertex_halfedge[vertex]) == h


BUGS: dict[str, ClassicBug] = {bug.name: bug for bug in (
    ClassicBug(
        flip_forgetting_vertex_halfedge, flip_right,
        _flip_demo(lambda m, e: _leaves_along(m, int(m.halfedge_vertex[2 * e]), 2 * e)),
        "vertex-halfedge-origin", "validate",
        "After the flip, h0 leaves v3, not v0. If v0 used h0 as its halfedge, v0 now names a halfedge "
        "that starts somewhere else; one-ring walks from v0 go round v3 instead.",
        "Step 4: if v0's halfedge is h0, give it h4 (still leaving v0); if v1's is h1, give it h2."),
    ClassicBug(
        flip_forgetting_face_halfedge, flip_right,
        _flip_demo(lambda m, e: int(m.face_halfedge[m.halfedge_face[2 * e]]) == int(m.halfedge_next[2 * e])),
        "face-halfedge", "validate",
        "A flip moves h4 into f0 and h2 into f1. A face that used h2 (or h4) as its halfedge now names a "
        "halfedge of the other face: walking that face's loop goes round its neighbour.",
        "Let f0 point at h0 and f1 at h1: those two stay in their faces."),
    ClassicBug(
        collapse_leaving_outer_next_stale, collapse_right,
        _collapse_demo(lambda: sample("single_collapse"), lambda m, h: True),
        "deleted-reference", "validate",
        "h_A_L takes the place of h_B_L in the face beyond it. The halfedge before h_B_L lies outside "
        "the two removed faces, so it is easy to forget: its next still names h_B_L, which is deleted.",
        "Link both ways, always: nxt[before] = new and prv[new] = before (and the same after new)."),
    ClassicBug(
        collapse_forgetting_vertex_halfedges, collapse_right,
        _collapse_demo(lambda: sample("icosphere", subdivisions=1), lambda m, h: _leaves_along(m, int(m.halfedge_vertex[h ^ 1]), h ^ 1)),
        "deleted-reference", "validate",
        "The collapse deletes h_AB, h_L_B and h_R_B with their edges. A vertex that kept one of them as "
        "its halfedge (vA, vL or vR) now points at a deleted halfedge.",
        "Step 5: repoint vL to h_L_A, vR to h_R_A and vA to h_A_R when they used a deleted halfedge."),
    ClassicBug(
        collapse_reading_neighbours_too_early, collapse_right,
        _collapse_demo(lambda: sample("cube"), lambda m, h: m.vertex(int(m.halfedge_vertex[h])).degree == 3),
        "deleted-reference", "validate",
        "When vB has degree 3, the faces beyond h_B_L and h_R_B are the same face. Relinking the left "
        "side changes the prev and next the right side must use; read before that, they are stale and "
        "the right side merges the wrong halfedges into the face.",
        "Read each side's prev, next and face just before relinking that side, not both at the start."),
    ClassicBug(
        split_boundary_forgetting_boundary_halfedges, split_boundary_right,
        _split_demo, "deleted-reference", "validate",
        "Splitting a boundary edge makes one new boundary halfedge, b -> m. add_edge leaves its next "
        "and prev at -1 (no halfedge); the boundary loop must be relinked through it.",
        "Link prev(t) -> (b -> m) -> t, and give b that new halfedge if its boundary halfedge was t."),
    ClassicBug(
        build_closed_pairing_twins_by_sorted_ends, build_closed_right,
        _build_demo, "next-origin", "validate",
        "An edge is looked up by its sorted vertex pair, and the twins were oriented by that key: 2e "
        "from the smaller vertex, 2e + 1 back. Where a face runs its side from the larger vertex, its "
        "halfedge now points against the face, and the face's loop no longer joins up.",
        "Store the origin the face gives, a for the side a -> b, whichever sighting it is."),
    ClassicBug(
        one_ring_endless_at_the_boundary, one_ring_right,
        _one_ring_demo, "ring-returns-to-start", "check_one_ring",
        "A boundary vertex's halfedge is its outgoing boundary halfedge, the walk's start. Skipping "
        "boundary halfedges skips the start too, so the loop never ends: the check stops it after its "
        "time limit.",
        "Step with h = h.prev.twin and stop when h == start; the boundary halfedge needs no special case."),
    ClassicBug(
        loop_split_flipping_old_edges, loop_split_right,
        _loop_demo, "old-vertex-degree", "check_loop_split",
        "After every edge is split, two kinds of edges join an old and a new vertex: the cross edges "
        "the splits drew to an old corner, and the halves of the old edges. Flipping a half cuts an old "
        "edge: the old vertex loses a neighbour and the mesh is no longer Loop's. It stays valid, so "
        "only a check of Loop's rule sees it.",
        "Remember the halves of every old edge while splitting, and flip only the other old-new edges."),
)}


def catch(bug: ClassicBug, function: Callable | None = None) -> Caught | None:
    """Run ``function`` (default: the bug's wrong one) the way the lab does; how it was caught, or None.

    ``validate`` bugs: the demonstration's mesh is validated. The one-ring runs through
    ``check_one_ring`` (its time limit stops the endless walk); the Loop split through
    :func:`check_loop_split`. The right function gives None.
    """
    function = bug.wrong if function is None else function
    if bug.caught_by == "check_one_ring":
        from .checks import check_one_ring

        result = check_one_ring(function)
        return None if result else Caught(bug.rule, result.element, f"[{bug.rule}] {result.message}", result.mesh)
    if bug.caught_by == "check_loop_split":
        message, vertex, result = _loop_split_problem(function)
        return Caught(bug.rule, ("vertex", vertex), message, result) if message else None
    mesh = bug.demo(function)
    try:
        mesh.validate()
    except MeshInvariantError as error:
        return Caught(error.rule, error.element, str(error), mesh)
    return None


def picture(caught: Caught, **scene_options) -> bytes:
    """PNG bytes of the mesh the bug left, with the element that breaks the rule highlighted.

    A halfedge is drawn with its twin, next and prev; a vertex with its ``halfedge`` as
    the current (orange) arrow when that halfedge is live, a face alone (walking a
    broken vertex's one-ring might not end). Needs pyvista (``halfedge_edu[notebooks]``).
    """
    from halfedge_edu.viz import scene_picture

    kind, index = caught.element
    mesh = caught.mesh

    def highlight(scene) -> None:
        if kind == "halfedge":
            scene.show_halfedge(index)
        elif kind == "vertex":
            h = int(mesh.vertex_halfedge[index])
            live = 0 <= h < mesh.n_halfedge_slots and not mesh.halfedge_deleted[h]
            scene.set_roles({"origin": [index], "current": [h] if live else []})
        else:
            scene.set_roles({"face": [index]})

    return scene_picture(mesh, highlight, **scene_options)
