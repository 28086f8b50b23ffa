"""Would numba let one readable loop be both the teaching path and the fast path? (issue 15)

    PYTHONPATH=$PWD:/tmp/numba-site python benchmarks/numba_trial.py
    PYTHONPATH=$PWD:/tmp/numba-site python benchmarks/numba_trial.py --quick   # icosphere(6), no CI case

numba is not a dependency of halfedge_edu; install it somewhere apart first, e.g.
``pip install --target /tmp/numba-site numba==0.68.1`` (it needs llvmlite, not a new
numpy). The script exits with a message if ``import numba`` fails.

Two kernels are written here the way a student reads them, as plain loops over the
mesh's flat arrays (``for h in range(n_h): ...``), each under ``@numba.njit(cache=True)``:

* ``check_rules``: the pointer rules of :mod:`halfedge_edu.core.validate` (next/prev
  inverse, twin runs the other way, next starts where h ends, faces are closed loops
  of three, face and vertex halfedges, boundary vertex halfedge, one fan per vertex,
  no duplicate edge), timed on the 1.3M-face icosphere of ``bench_build.py`` beside
  ``mesh.validate()`` and ``HalfedgeMesh.from_faces``.
* ``simplify_in_place``: ``simplify_sequential``'s algorithm (area-weighted quadrics,
  boundary quadrics, the pulled optimal point, a heap of edge prices with lazy
  deletion, the link condition and the turned-face check, one halfedge collapse at a
  time on the flat arrays), simplifying the bunny to 10% beside ``hx.simplify``,
  openmesh's decimater with ModQuadric and ``hx.simplify_sequential`` (the teaching
  path in Python), all in the same process.

What the table reports for each kernel, each in its own fresh process:
* compile + 1 run: the first call with an empty on-disk cache (``NUMBA_CACHE_DIR`` a new
  temporary folder), i.e. the cost in a fresh clone or CI run;
* first call, warm cache: the first call in a later process (loads the cached machine
  code), the cost a student pays after the first run;
* steady: the median of 5 calls, with the peers timed in turns in the same process.
Also ``import numba`` and ``import halfedge_edu`` (median of 5 fresh processes), the
kernels run as plain Python (``NUMBA_DISABLE_JIT=1``, the same source), and two fresh
processes compiling both kernels at once into one empty cache (two pytest workers in a
fresh clone), then a third process loading both from that cache. The machine is shared and noisy: read the ratios within one run.
"""

from __future__ import annotations

import argparse
import heapq
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

_import_start = time.perf_counter()
try:
    import numba
except ImportError:
    sys.exit(
        "numba_trial.py measures numba, which is not installed here (halfedge_edu does not depend on it).\n"
        "Install it apart, e.g. `pip install --target /tmp/numba-site numba==0.68.1`, and run\n"
        "`PYTHONPATH=$PWD:/tmp/numba-site python benchmarks/numba_trial.py`."
    )

#: Seconds this process took to import numba: the first call of a library that imported
#: numba only when needed would pay it too.
NUMBA_IMPORT_SECONDS = time.perf_counter() - _import_start

import halfedge_edu as hx  # noqa: E402 (after the numba check)
from _common import surface_distance, timed  # noqa: E402 (this folder: python puts it on sys.path)
from bench_build import icosphere, interleaved_medians  # noqa: E402
from bench_simplify import run_openmesh  # noqa: E402

# ---------------------------------------------------------------------------------------
# Kernel 1: the pointer rules, one loop per kind of element
# ---------------------------------------------------------------------------------------

#: What ``check_rules`` returns first: an index into this tuple (0 means every rule holds).
RULES = ("ok", "deleted-reference", "next-prev-inverse", "twin-involution", "next-origin",
         "next-cycle", "edge-halfedge", "face-halfedge", "vertex-halfedge-origin",
         "boundary-vertex-halfedge", "vertex-manifold", "duplicate-edge")


@numba.njit(cache=True)
def check_rules(nxt, prv, origin, face, vertex_he, face_he, vertex_deleted, edge_deleted, face_deleted):
    """(rule, element) for the first broken rule of the table in ``validate.py``, or (0, -1).

    Twin is ``h ^ 1``. Deleted slots are skipped; live ones may point only at live
    ones. The element is a halfedge, face or vertex index, as the rule names it.
    """
    n_h, n_v, n_f = len(nxt), len(vertex_he), len(face_he)
    degree = np.zeros(n_v, np.int64)                   # live halfedges leaving each vertex

    # deleted-reference: every pointer of a live element is in range and live
    for h in range(n_h):
        if edge_deleted[h >> 1]:
            continue
        for other in (nxt[h], prv[h]):
            if other < 0 or other >= n_h or edge_deleted[other >> 1]:
                return 1, h
        v, f = origin[h], face[h]
        if v < 0 or v >= n_v or vertex_deleted[v] or f < -1 or f >= n_f or (f >= 0 and face_deleted[f]):
            return 1, h
        degree[v] += 1
    for f in range(n_f):
        h = face_he[f]
        if not face_deleted[f] and (h < 0 or h >= n_h or edge_deleted[h >> 1]):
            return 1, f
    for v in range(n_v):
        h = vertex_he[v]
        if not vertex_deleted[v] and (h < -1 or h >= n_h or (h >= 0 and edge_deleted[h >> 1])):
            return 1, v

    # the halfedge rules: each live halfedge with its twin, next and prev
    for h in range(n_h):
        if edge_deleted[h >> 1]:
            continue
        tip = origin[h ^ 1]                            # where h ends: its twin's origin
        if prv[nxt[h]] != h or nxt[prv[h]] != h:
            return 2, h
        if origin[h] == tip:
            return 3, h
        if origin[nxt[h]] != tip:
            return 4, h
        if face[nxt[h]] != face[h] or (face[h] >= 0 and (nxt[nxt[nxt[h]]] != h or nxt[h] == h)):
            return 5, h
        if face[h] < 0 and face[h ^ 1] < 0:
            return 6, h
        own = vertex_he[origin[h]]                     # the halfedge the origin keeps
        if own == -1:
            return 8, origin[h]
        if face[h] < 0 and face[own] >= 0:
            return 9, origin[h]

    # face-halfedge and vertex-halfedge-origin: the element's own halfedge comes back to it
    for f in range(n_f):
        if not face_deleted[f] and face[face_he[f]] != f:
            return 7, f
    for v in range(n_v):
        if not vertex_deleted[v] and vertex_he[v] >= 0 and origin[vertex_he[v]] != v:
            return 8, v

    # vertex-manifold and duplicate-edge: walk around each vertex (h -> twin(prev(h))),
    # marking the neighbours met; the walk must meet every edge of the vertex, each
    # neighbour once
    last_met_from = np.full(n_v, -1, np.int64)         # the last vertex whose walk met this one
    for v in range(n_v):
        if vertex_deleted[v] or vertex_he[v] == -1:
            continue
        h, steps = vertex_he[v], 0
        while True:
            neighbour = origin[h ^ 1]
            if last_met_from[neighbour] == v:
                return 11, v
            last_met_from[neighbour] = v
            steps += 1
            h = prv[h] ^ 1
            if h == vertex_he[v]:
                break
        if steps != degree[v]:
            return 10, v
    return 0, -1


def check_mesh_rules(mesh: hx.HalfedgeMesh) -> tuple[str, int]:
    """(rule name, element) of the first rule ``check_rules`` finds broken in ``mesh``."""
    rule, element = check_rules(
        mesh.halfedge_next, mesh.halfedge_prev, mesh.halfedge_vertex, mesh.halfedge_face,
        mesh.vertex_halfedge, mesh.face_halfedge, mesh.vertex_deleted, mesh.edge_deleted, mesh.face_deleted)
    return RULES[rule], int(element)


# ---------------------------------------------------------------------------------------
# Kernel 2: quadric simplification, one collapse at a time (simplify_sequential's steps)
# ---------------------------------------------------------------------------------------

PULL_TO_MIDPOINT = 1e-4     # as halfedge_edu.algorithms.simplify
REFINEMENT_STEPS = 2


@numba.njit(cache=True)
def dot(u, w):
    """u . w for (3,) arrays (written out: numba's np.dot would need scipy's BLAS)."""
    return u[0] * w[0] + u[1] * w[1] + u[2] * w[2]


@numba.njit(cache=True)
def cross_vectors(u, w):
    """u x w for (3,) arrays."""
    return np.array([u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]])


@numba.njit(cache=True)
def cross(p0, p1, p2):
    """(p1 - p0) x (p2 - p0): twice the triangle's area times its unit normal."""
    return cross_vectors(p1 - p0, p2 - p0)


@numba.njit(cache=True)
def add_plane(quadrics, v, weight, normal, point):
    """quadrics[v] += weight * p p^T for the plane p = [n, -n.point] through ``point``."""
    plane = np.array([normal[0], normal[1], normal[2], -dot(normal, point)])
    for i in range(4):
        for j in range(4):
            quadrics[v, i, j] += weight * plane[i] * plane[j]


@numba.njit(cache=True)
def vertex_quadrics(positions, nxt, origin, face, face_he, boundary_weight):
    """(n_v, 4, 4): each vertex's sum of its faces' area-weighted plane quadrics, and of the
    planes through its boundary edges, perpendicular to their face (weight * length^2)."""
    quadrics = np.zeros((len(positions), 4, 4))
    for f in range(len(face_he)):
        h = face_he[f]
        a, b, c = origin[h], origin[nxt[h]], origin[nxt[nxt[h]]]
        normal = cross(positions[a], positions[b], positions[c])
        double_area = np.sqrt(dot(normal, normal))
        if double_area > 0:
            for v in (a, b, c):
                add_plane(quadrics, v, 0.5 * double_area, normal / double_area, positions[a])
    for h in range(len(nxt)):
        if face[h] < 0:                                # a boundary halfedge; its twin has the face
            start, end = origin[h], origin[h ^ 1]
            inside = h ^ 1
            face_normal = cross(positions[origin[inside]], positions[origin[nxt[inside]]],
                                positions[origin[nxt[nxt[inside]]]])
            direction = positions[end] - positions[start]
            normal = cross_vectors(direction, face_normal)
            length = np.sqrt(dot(normal, normal))
            if length > 0:
                weight = boundary_weight * dot(direction, direction)
                for v in (start, end):
                    add_plane(quadrics, v, weight, normal / length, positions[start])
    return quadrics


@numba.njit(cache=True)
def quadric_cost(quadric, x):
    """[x, 1] Q [x, 1]^T."""
    homogeneous = np.array([x[0], x[1], x[2], 1.0])
    total = 0.0
    for i in range(4):
        for j in range(4):
            total += homogeneous[i] * quadric[i, j] * homogeneous[j]
    return total


@numba.njit(cache=True)
def determinant(c0, c1, c2):
    """det of the 3x3 matrix with columns c0, c1, c2: c0 . (c1 x c2)."""
    return (c0[0] * (c1[1] * c2[2] - c1[2] * c2[1])
            + c0[1] * (c1[2] * c2[0] - c1[0] * c2[2])
            + c0[2] * (c1[0] * c2[1] - c1[1] * c2[0]))


@numba.njit(cache=True)
def solve_3x3(m, rhs):
    """x with m @ x = rhs, by Cramer's rule (m is positive definite here: det > 0)."""
    c0, c1, c2 = m[:, 0], m[:, 1], m[:, 2]
    det = determinant(c0, c1, c2)
    return np.array([determinant(rhs, c1, c2), determinant(c0, rhs, c2), determinant(c0, c1, rhs)]) / det


@numba.njit(cache=True)
def best_point(quadric, a, b):
    """The point minimizing the quadric, pulled towards the midpoint of ab (as ``_best_point``)."""
    A, q = quadric[:3, :3], quadric[:3, 3]
    midpoint = 0.5 * (a + b)
    eps = PULL_TO_MIDPOINT * (A[0, 0] + A[1, 1] + A[2, 2])
    if eps <= 0:
        return midpoint
    pulled = A + eps * np.eye(3)
    x = solve_3x3(pulled, -q + eps * midpoint)
    for _ in range(REFINEMENT_STEPS):
        x = x + solve_3x3(pulled, -q - (A * x).sum(axis=1))
    return x


@numba.njit(cache=True)
def is_boundary_vertex(v, face, vertex_he):
    """A boundary vertex keeps its outgoing boundary halfedge (rule boundary-vertex-halfedge)."""
    return face[vertex_he[v]] < 0


@numba.njit(cache=True)
def price(e, positions, origin, face, vertex_he, quadrics):
    """(cost, point) of collapsing edge e: interior edges with one boundary end go onto that end."""
    a, b = origin[2 * e], origin[2 * e + 1]
    quadric = quadrics[a] + quadrics[b]
    interior_edge = face[2 * e] >= 0 and face[2 * e + 1] >= 0
    a_on, b_on = is_boundary_vertex(a, face, vertex_he), is_boundary_vertex(b, face, vertex_he)
    if interior_edge and a_on and not b_on:
        point = positions[a].copy()
    elif interior_edge and b_on and not a_on:
        point = positions[b].copy()
    else:
        point = best_point(quadric, positions[a], positions[b])
    return max(quadric_cost(quadric, point), 0.0), point


@numba.njit(cache=True)
def link_condition_holds(h, nxt, prv, origin, face, vertex_he, mark):
    """The topology checks of ``can_collapse`` for the edge of h (``mark``: zeros, left zero)."""
    o = h ^ 1
    a, b = origin[h], origin[o]
    left, right = face[h], face[o]
    opposite_left = origin[prv[h]] if left >= 0 else -1
    opposite_right = origin[prv[o]] if right >= 0 else -1
    interior_edge = left >= 0 and right >= 0
    if interior_edge and opposite_left == opposite_right:
        return False                                   # back to back
    if interior_edge and is_boundary_vertex(a, face, vertex_he) and is_boundary_vertex(b, face, vertex_he):
        return False                                   # both ends on the boundary
    for side in (h, o):
        if face[side] >= 0 and face[nxt[side] ^ 1] < 0 and face[prv[side] ^ 1] < 0:
            return False                               # a lone triangle
    # shared neighbours: only the opposite vertices may be in both rings
    degree_a = 0
    g = vertex_he[a]
    while True:
        mark[origin[g ^ 1]] = 1
        degree_a += 1
        g = prv[g] ^ 1
        if g == vertex_he[a]:
            break
    shared_other, degree_b = False, 0
    g = vertex_he[b]
    while True:
        neighbour = origin[g ^ 1]
        if mark[neighbour] == 1 and neighbour != opposite_left and neighbour != opposite_right:
            shared_other = True
        degree_b += 1
        g = prv[g] ^ 1
        if g == vertex_he[b]:
            break
    g = vertex_he[a]
    while True:
        mark[origin[g ^ 1]] = 0
        g = prv[g] ^ 1
        if g == vertex_he[a]:
            break
    if shared_other:
        return False
    return not (interior_edge and degree_a == 3 and degree_b == 3)  # a tetrahedron


@numba.njit(cache=True)
def turns_a_face(h, point, positions, nxt, prv, origin, face, vertex_he, max_normal_cos):
    """True if moving both ends of h's edge to ``point`` swings a remaining face's normal too far."""
    doomed_left, doomed_right = face[h], face[h ^ 1]
    for end in (origin[h], origin[h ^ 1]):
        g = vertex_he[end]
        while True:
            f = face[g]
            if f >= 0 and f != doomed_left and f != doomed_right:
                b, c = positions[origin[nxt[g]]], positions[origin[prv[g]]]
                before = cross(positions[end], b, c)
                after = cross(point, b, c)
                lengths = np.sqrt(dot(before, before) * dot(after, after))
                if lengths <= 1e-300 or dot(before, after) < max_normal_cos * lengths:
                    return True
            g = prv[g] ^ 1
            if g == vertex_he[end]:
                break
    return False


@numba.njit(cache=True)
def link(h, then, nxt, prv):
    """Make ``then`` follow h."""
    nxt[h] = then
    prv[then] = h


@numba.njit(cache=True)
def keep_boundary_halfedge(v, face, prv, vertex_he):
    """Point v at its outgoing boundary halfedge, if it has one."""
    g = vertex_he[v]
    while True:
        if face[g] < 0:
            vertex_he[v] = g
            return
        g = prv[g] ^ 1
        if g == vertex_he[v]:
            return


@numba.njit(cache=True)
def remove_two_gon(h0, nxt, prv, origin, face, vertex_he, face_he, edge_deleted, face_deleted):
    """Remove the loop h0 -> h1 -> h0 left of a triangle by a collapse; h1 takes twin(h0)'s place.

    Returns the number of faces removed (0 if the loop was a boundary).
    """
    h1 = nxt[h0]
    twin0 = h0 ^ 1
    start, end = origin[h1], origin[h0]                # h1 runs start -> end, as twin0 does
    gone, other_side = face[h0], face[twin0]
    link(prv[twin0], h1, nxt, prv)
    link(h1, nxt[twin0], nxt, prv)
    face[h1] = other_side
    vertex_he[start] = h1
    keep_boundary_halfedge(start, face, prv, vertex_he)
    vertex_he[end] = h1 ^ 1
    keep_boundary_halfedge(end, face, prv, vertex_he)
    if other_side >= 0 and face_he[other_side] == twin0:
        face_he[other_side] = h1
    edge_deleted[h0 >> 1] = True
    if gone < 0:
        return 0
    face_he[gone] = -1
    face_deleted[gone] = True
    return 1


@numba.njit(cache=True)
def collapse(h, nxt, prv, origin, face, vertex_he, face_he, vertex_deleted, edge_deleted, face_deleted):
    """Collapse h's edge: origin(h) is removed, h's tip kept. Returns the faces removed (1 or 2)."""
    o = h ^ 1
    removed, kept = origin[h], origin[o]
    after_h, before_h, after_o, before_o = nxt[h], prv[h], nxt[o], prv[o]
    left, right = face[h], face[o]
    g = vertex_he[removed]                             # every halfedge leaving `removed` now leaves `kept`
    while True:
        origin[g] = kept
        g = prv[g] ^ 1
        if g == vertex_he[removed]:
            break
    link(before_h, after_h, nxt, prv)                  # h and o leave their loops
    link(before_o, after_o, nxt, prv)
    if left >= 0:
        face_he[left] = after_h
    if right >= 0:
        face_he[right] = after_o
    if vertex_he[kept] == o:
        vertex_he[kept] = after_h
    keep_boundary_halfedge(kept, face, prv, vertex_he)
    vertex_he[removed] = -1
    vertex_deleted[removed] = True
    edge_deleted[h >> 1] = True
    faces_removed = 0                                  # each face beside h is now a loop of two
    if nxt[nxt[after_h]] == after_h:
        faces_removed += remove_two_gon(after_h, nxt, prv, origin, face, vertex_he, face_he, edge_deleted, face_deleted)
    if nxt[nxt[after_o]] == after_o:
        faces_removed += remove_two_gon(after_o, nxt, prv, origin, face, vertex_he, face_he, edge_deleted, face_deleted)
    return faces_removed


@numba.njit(cache=True)
def simplify_in_place(positions, nxt, prv, origin, face, vertex_he, face_he, target_faces,
                      boundary_weight, max_normal_cos):
    """Collapse the cheapest allowed edge until ``target_faces`` remain; the arrays change in place.

    Returns (faces left, vertex_deleted, face_deleted).
    """
    n_v, n_e, n_faces = len(positions), len(nxt) // 2, len(face_he)
    vertex_deleted = np.zeros(n_v, np.bool_)
    edge_deleted = np.zeros(n_e, np.bool_)
    face_deleted = np.zeros(n_faces, np.bool_)
    mark = np.zeros(n_v, np.int64)
    quadrics = vertex_quadrics(positions, nxt, origin, face, face_he, boundary_weight)
    stamp = np.zeros(n_e, np.int64)                    # an edge's price is current if its stamp matches
    point = np.zeros((n_e, 3))
    heap = [(0.0, 0, 0)]                               # (cost, edge, stamp when pushed); the first
    heap.pop()                                         # entry only tells numba the type
    for e in range(n_e):
        cost, point[e] = price(e, positions, origin, face, vertex_he, quadrics)
        stamp[e] += 1
        heap.append((cost, e, stamp[e]))
    heapq.heapify(heap)
    while n_faces > target_faces and len(heap) > 0:
        cost, e, pushed = heapq.heappop(heap)
        if edge_deleted[e] or pushed != stamp[e]:
            continue                                   # stale: deleted or re-priced since
        h = 2 * e
        if not link_condition_holds(h, nxt, prv, origin, face, vertex_he, mark):
            continue
        if turns_a_face(h, point[e], positions, nxt, prv, origin, face, vertex_he, max_normal_cos):
            continue                                   # re-priced later if a neighbour's collapse changes its ring
        removed, kept = origin[h], origin[h ^ 1]
        quadrics[kept] += quadrics[removed]
        positions[kept] = point[e]
        n_faces -= collapse(h, nxt, prv, origin, face, vertex_he, face_he, vertex_deleted, edge_deleted, face_deleted)
        g = vertex_he[kept]                            # re-price the edges around the kept vertex
        while True:
            around = g >> 1
            cost, point[around] = price(around, positions, origin, face, vertex_he, quadrics)
            stamp[around] += 1
            heapq.heappush(heap, (cost, around, stamp[around]))
            g = prv[g] ^ 1
            if g == vertex_he[kept]:
                break
    return n_faces, vertex_deleted, face_deleted


def simplify_numba(mesh: hx.HalfedgeMesh, target_faces: int, boundary_weight: float = 100.0,
                   max_normal_angle: float = 80.0) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of ``mesh`` simplified to ``target_faces`` by ``simplify_in_place``."""
    positions = mesh.positions.copy()
    nxt, prv, origin, face, vertex_he, face_he = (     # int64 copies: one integer type in the heap's tuples
        index.astype(np.int64) for index in (mesh.halfedge_next, mesh.halfedge_prev, mesh.halfedge_vertex,
                                             mesh.halfedge_face, mesh.vertex_halfedge, mesh.face_halfedge))
    _, vertex_deleted, face_deleted = simplify_in_place(
        positions, nxt, prv, origin, face, vertex_he, face_he, target_faces, boundary_weight,
        math.cos(math.radians(max_normal_angle)))
    first = face_he[~face_deleted]                     # compact: live faces and vertices only
    corners = np.stack([origin[first], origin[nxt[first]], origin[prv[first]]], axis=1)
    new_index = np.cumsum(~vertex_deleted) - 1
    return positions[~vertex_deleted], new_index[corners]


# ---------------------------------------------------------------------------------------
# Measuring
# ---------------------------------------------------------------------------------------

def first_call(function) -> float:
    """Seconds of one call (the first in its process: compiling or loading included)."""
    return timed(function)[0]


def loaded_from_cache(kernel) -> int:
    """How many compiled versions of ``kernel`` this process loaded from the on-disk cache.

    0 also when the JIT is off (``NUMBA_DISABLE_JIT``: the kernel is then the plain function).
    """
    stats = getattr(kernel, "stats", None)
    return 0 if stats is None else sum(stats.cache_hits.values())


def import_seconds(module: str, repeats: int = 5) -> float:
    """Median seconds of ``import module`` over ``repeats`` fresh interpreters."""
    code = f"import time; t = time.perf_counter(); import {module}; print(time.perf_counter() - t)"
    return float(np.median([
        float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)
        for _ in range(repeats)]))


def child_validate(data: Path, steady: bool) -> dict:
    """In a fresh process: first call of check_rules, then (steady) its median beside validate and build."""
    arrays = np.load(data)
    vertices, faces = arrays["vertices"], arrays["faces"]
    mesh = hx.HalfedgeMesh.from_faces(vertices, faces)
    result = {"first": first_call(lambda: check_mesh_rules(mesh)), "faces": len(faces),
              "import_numba": NUMBA_IMPORT_SECONDS, "cache_hits": loaded_from_cache(check_rules)}
    if steady:
        result.update(interleaved_medians(
            5, kernel=lambda: check_mesh_rules(mesh), validate=mesh.validate,
            build=lambda: hx.HalfedgeMesh.from_faces(vertices, faces)))
        result["verdict"] = check_mesh_rules(mesh)
        broken = mesh.copy()                           # one wrong pointer must be caught
        h = broken.n_halfedge_slots // 3
        broken._halfedge_next[h] = broken.halfedge_next[broken.halfedge_next[h]]
        result["corrupted_verdict"] = check_mesh_rules(broken)
    return result


def child_simplify(steady: bool) -> dict:
    """In a fresh process: first call of simplify_in_place on the bunny, then (steady) the peers."""
    mesh = hx.sample("bunny")
    vertices, faces = mesh.to_arrays()
    target = mesh.n_faces // 10
    result = {"first": first_call(lambda: simplify_numba(mesh, target)), "faces": mesh.n_faces,
              "import_numba": NUMBA_IMPORT_SECONDS, "cache_hits": loaded_from_cache(simplify_in_place)}
    if not steady:
        return result
    result.update(interleaved_medians(
        5, kernel=lambda: simplify_numba(mesh, target), simplify=lambda: hx.simplify(mesh, target),
        openmesh=lambda: run_openmesh(vertices, faces, target)))
    start = time.perf_counter()
    sequential = hx.simplify_sequential(mesh, target)
    result["sequential"] = time.perf_counter() - start
    diagonal = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
    outputs = {
        "kernel": simplify_numba(mesh, target),
        "simplify": hx.simplify(mesh, target).to_arrays(),
        "openmesh": run_openmesh(vertices, faces, target),
        "sequential": sequential.to_arrays(),
    }
    for name, (v, f) in outputs.items():
        v, f = np.asarray(v), np.asarray(f)
        try:
            hx.HalfedgeMesh.from_faces(v, f).validate()
            valid = "yes"
        except (hx.MeshInputError, hx.MeshInvariantError) as error:
            valid = f"no ({type(error).__name__})"
        mean, worst = surface_distance(vertices, faces, v, f)
        result[f"{name}_quality"] = (len(f), mean / diagonal, worst / diagonal, valid)
    return result


def child_both() -> dict:
    """In a fresh process: the first calls of both kernels on the bunny (a CI worker's compile)."""
    mesh = hx.sample("bunny")
    return {"first": first_call(lambda: (check_mesh_rules(mesh), simplify_numba(mesh, mesh.n_faces // 10))),
            "import_numba": NUMBA_IMPORT_SECONDS}


def spawn(kernel: str, cache: Path, steady: bool = False, data: Path | None = None,
          disable_jit: bool = False) -> subprocess.Popen:
    """Start this script as a child measuring ``kernel`` with its numba cache in ``cache``."""
    environment = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    if disable_jit:
        environment["NUMBA_DISABLE_JIT"] = "1"
    command = [sys.executable, str(Path(__file__).resolve()), "--child", kernel]
    if steady:
        command.append("--steady")
    if data is not None:
        command += ["--data", str(data)]
    return subprocess.Popen(command, env=environment, stdout=subprocess.PIPE, text=True)


def collect(process: subprocess.Popen) -> dict:
    """The JSON a child printed last."""
    out, _ = process.communicate()
    if process.returncode != 0:
        raise RuntimeError(f"child {process.args} failed with exit code {process.returncode}")
    return json.loads(out.strip().splitlines()[-1])


def measure(kernel: str, scratch: Path, data: Path | None = None) -> tuple[dict, dict]:
    """(cold, warm): a child with an empty cache, then a second child reusing what it saved."""
    cache = scratch / f"cache-{kernel}"
    cold = collect(spawn(kernel, cache, data=data))
    warm = collect(spawn(kernel, cache, steady=True, data=data))
    return cold, warm


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="icosphere(6) instead of (8); skip the CI case")
    parser.add_argument("--child", choices=["validate", "simplify", "both"], help=argparse.SUPPRESS)
    parser.add_argument("--steady", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--data", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        result = {"validate": lambda: child_validate(args.data, args.steady),
                  "simplify": lambda: child_simplify(args.steady),
                  "both": child_both}[args.child]()
        print(json.dumps(result))
        return

    print(f"numba {numba.__version__}, numpy {np.__version__}, python {sys.version.split()[0]}", flush=True)
    numba_import, hx_import = import_seconds("numba"), import_seconds("halfedge_edu")
    with tempfile.TemporaryDirectory(prefix="numba-trial-") as folder:
        scratch = Path(folder)
        level = 6 if args.quick else 8
        data = scratch / "icosphere.npz"
        vertices, faces = icosphere(level)
        np.savez(data, vertices=vertices, faces=faces)
        small = scratch / "icosphere5.npz"
        np.savez(small, **dict(zip(("vertices", "faces"), icosphere(5))))

        v_cold, v_warm = measure("validate", scratch, data)
        s_cold, s_warm = measure("simplify", scratch)
        python_validate = collect(spawn("validate", scratch / "unused", data=small, disable_jit=True))
        python_simplify = collect(spawn("simplify", scratch / "unused", disable_jit=True))
        if not args.quick:
            shared = scratch / "cache-ci"
            workers = [spawn("both", shared) for _ in range(2)]
            ci = [collect(worker)["first"] for worker in workers]
            alone = collect(spawn("both", scratch / "cache-ci-alone"))["first"]
            again = collect(spawn("both", scratch / "cache-ci-alone"))

    print()
    print(f"{'what':<72}{'seconds':>10}{'vs peer':>10}")
    print("-" * 92)
    rows = [
        ("import numba (median of 5 fresh processes)", numba_import, None),
        ("import halfedge_edu (median of 5 fresh processes)", hx_import, None),
        (f"check_rules, {v_warm['faces']:,} faces: compile + 1 run (empty cache)", v_cold["first"], None),
        ("  first call in a new process, warm on-disk cache", v_warm["first"], None),
        ("  import numba + that first call", v_warm["import_numba"] + v_warm["first"], None),
        ("  steady (median of 5)", v_warm["kernel"], None),
        ("  mesh.validate() (median of 5, same process)", v_warm["validate"], v_warm["kernel"] / v_warm["validate"]),
        ("  HalfedgeMesh.from_faces (median of 5, same process)", v_warm["build"], v_warm["kernel"] / v_warm["build"]),
        ("  the same source as Python (NUMBA_DISABLE_JIT), 20,480 faces", python_validate["first"], None),
        (f"simplify_in_place, bunny {s_warm['faces']:,} -> 10%: compile + 1 run (empty cache)", s_cold["first"], None),
        ("  first call in a new process, warm on-disk cache", s_warm["first"], None),
        ("  import numba + that first call", s_warm["import_numba"] + s_warm["first"], None),
        ("  steady (median of 5)", s_warm["kernel"], None),
        ("  hx.simplify (median of 5, same process)", s_warm["simplify"], s_warm["kernel"] / s_warm["simplify"]),
        ("  openmesh TriMeshDecimater + ModQuadric (median of 5)", s_warm["openmesh"], s_warm["kernel"] / s_warm["openmesh"]),
        ("  hx.simplify_sequential, the teaching path (1 run)", s_warm["sequential"], s_warm["kernel"] / s_warm["sequential"]),
        ("  the same source as Python (NUMBA_DISABLE_JIT), 1 run", python_simplify["first"], s_warm["kernel"] / python_simplify["first"]),
    ]
    if not args.quick:
        rows += [
            ("both kernels on the bunny, first calls, empty cache, 1 process", alone, None),
            ("  the same, 2 processes at once on one empty cache (the slower)", max(ci), None),
            ("  import numba + both first calls, a new process, warm cache", again["import_numba"] + again["first"], None),
        ]
    for label, seconds, ratio in rows:
        print(f"{label:<72}{seconds:>10.3f}{'' if ratio is None else f'{ratio:.2f}x':>10}")
    print("(vs peer: the kernel's steady time over the peer's, below 1 the kernel is faster)")
    print()
    print(f"loaded from the on-disk cache: check_rules {v_cold['cache_hits']} then {v_warm['cache_hits']}, "
          f"simplify_in_place {s_cold['cache_hits']} then {s_warm['cache_hits']} (empty cache, then warm)")
    print(f"check_rules on the icosphere: {tuple(v_warm['verdict'])}; "
          f"after breaking one next pointer: {tuple(v_warm['corrupted_verdict'])}")
    print(f"{'bunny -> 10%':<26}{'faces':>8}{'mean dist':>11}{'max dist':>10}  valid (HalfedgeMesh(...).validate())")
    for name in ("kernel", "simplify", "openmesh", "sequential"):
        count, mean, worst, valid = s_warm[f"{name}_quality"]
        print(f"{name:<26}{count:>8,}{mean:>11.2e}{worst:>10.2e}  {valid}")
    print("(distances: symmetric, at the vertices, over the bounding-box diagonal; _common.surface_distance)")


if __name__ == "__main__":
    main()
