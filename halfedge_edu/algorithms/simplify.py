"""Quadric error simplification (Garland and Heckbert, 1997), in rounds of collapses.

The idea, in four sentences:

1. Every face lies in a plane ``n . x + d = 0``; the squared distance of a point ``x`` to
   that plane is ``[x, 1] K [x, 1]^T`` with the 4x4 matrix ``K = p p^T``, ``p = [n, d]``.
2. A vertex starts with the sum ``Q`` of the ``K`` of its faces (weighted by area), so
   ``[x, 1] Q [x, 1]^T`` measures how far ``x`` is from the vertex's original planes.
3. Collapsing edge ``(a, b)`` to a point ``x`` costs ``[x, 1] (Q_a + Q_b) [x, 1]^T``; the
   best ``x`` solves a 3x3 linear system (with a tiny pull towards the edge's midpoint,
   which decides where flat or nearly flat regions leave the system undecided: see
   :func:`optimal_points`). If that point would turn a face over, an endpoint may do.
4. Collapse the cheapest edges first; the merged vertex keeps ``Q_a + Q_b``.

The course's version (see ``simplify_sequential``) pops one edge at a time from a priority
queue. This default version does the same work in *rounds*: each round prices, all at
once, the edges whose ends changed in the last round (the other prices are kept), then
collapses a set of cheap edges that are far enough apart not to disturb each other (no
two within one ring of each other), all at once, with numpy. An edge is taken only if
it comes first in its neighbourhood, in cost order between sixteen classes of about
equal cost and a fixed shuffle within one (:func:`~.collapse_rounds.spread_ties`: strict
cost order leaves few local minima on smooth or symmetric meshes), so the order stays
close to the queue's, and about twenty rounds, at any mesh size, replace tens of
thousands of Python steps. A round can take at
most about one face in seven (the collapses must stay apart), so the rounds cannot get
much fewer; what a round costs is kept down instead: two sorts of the face array per
round (:func:`~.collapse_rounds.round_tables`), the quadrics as ten packed numbers,
and checks that gather only what the picked edges touch.

Every collapse must pass the same checks as :func:`halfedge_edu.core.ops.can_collapse`: the
link condition (the endpoints share exactly the two opposite vertices, one on the
boundary), no interior edge between two boundary vertices, no opposite vertex left with
too few edges; and a geometric check the topology does not see: no face the collapse
moves may turn over (its normal may not swing by more than ``max_normal_angle``, nor its
area vanish), and no two neighbouring faces may fold shut (normals more than
:data:`~.collapse_rounds.FOLD_ANGLE` degrees apart), not even two faces moved by two
different collapses of one round. The check covers the fallback placements too.
Both checks run only on the edges a round picks, not on every candidate: a round
collapses about one candidate in ten. The checks and the choice of a round live in
:mod:`.collapse_rounds`, shared with ``remesh``; the array tools (edge keys, CSR
adjacency) in :mod:`halfedge_edu.core.arrays`.
"""

from __future__ import annotations

import inspect
import warnings
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..core.arrays import compact, face_cross, merge_vertices
from ..core.errors import MeshWarning
from ..core.mesh import HalfedgeMesh
from .arguments import check_simplify
from .collapse_rounds import (
    COST_CLASSES, SPREAD_KEY_IDS, choose_round, collapse_topology_ok, drop_folding_neighbours, no_turned_faces,
    round_tables, spread_ties, spread_ties_keys,
)


@dataclass
class SimplifyReport:
    """What :func:`simplify` did: faces before and after, rounds, and whether it reached the target."""

    faces_before: int
    faces_after: int
    target_faces: int
    rounds: int
    reached_target: bool

    def __str__(self) -> str:
        status = "reached" if self.reached_target else "could not reach"
        return (
            f"{self.faces_before} -> {self.faces_after} faces in {self.rounds} rounds "
            f"({status} the target of {self.target_faces})"
        )


class SimplifyResult(NamedTuple):
    """What :func:`simplify_with_report` returns: the simplified mesh and its report.

    A named tuple, so ``mesh, report = simplify_with_report(...)`` works as well as
    ``result.mesh`` and ``result.report``.
    """

    mesh: HalfedgeMesh
    report: SimplifyReport


# ----------------------------------------------------------------------------------------
# Quadrics
# ----------------------------------------------------------------------------------------

def face_quadrics(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(m, 4, 4) area-weighted plane quadric ``area * p p^T`` of each face, ``p = [n, d]``.

    Area weighting makes a big face count for more than a sliver, so the error does
    not depend on how finely a flat region happens to be triangulated.
    """
    area, plane = _face_planes(vertices, faces)
    return area[:, None, None] * plane[:, :, None] * plane[:, None, :]


def _face_planes(vertices: np.ndarray, faces: np.ndarray, *,
                 columns: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Each face's area (m,) and plane ``p = [n, d]`` (m, 4): :func:`face_quadrics` is ``area * p p^T``.

    The same numbers as ``face_cross(vertices[faces])`` and its length, computed one
    coordinate at a time: each corner's x, y and z gathered from a contiguous column
    (``np.take``), then products of contiguous rows: about a third less time than on
    the (m, 3, 3) corner array. ``columns`` (3, n), if the caller has them: ``vertices``
    by coordinate.
    """
    if columns is None:
        columns = np.ascontiguousarray(vertices.T)                   # (3, n)
    a, b, c = (np.take(columns, faces[:, corner], axis=1) for corner in range(3))   # (3, m) each
    ab, ac = b - a, c - a
    cross = (ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0])
    double_area = np.sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2])
    scale = np.maximum(double_area, 1e-300)
    normal = [coordinate / scale for coordinate in cross]
    offset = -((normal[0] * a[0] + normal[2] * a[2]) + normal[1] * a[1])     # in np.einsum's order: see _dot
    return 0.5 * double_area, np.stack([*normal, offset], axis=1)     # (m,), (m, 4)


def _face_quadric_rows(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(m, 10) each face's packed quadric (:func:`_packed_outer` of :func:`_face_planes`), in blocks of faces.

    Each face's numbers depend on that face alone, so blocks of :data:`PRICING_BLOCK`
    faces give the same rows as one pass; their temporaries (some twenty arrays of one
    number per face) stay in the processor's cache instead of being hundreds of MiB,
    which on a big mesh the system hands out afresh, page by page.
    """
    columns = np.ascontiguousarray(vertices.T)                       # (3, n)
    rows = np.empty((len(faces), len(_PACKED_ENTRIES)))
    for start in range(0, len(faces), PRICING_BLOCK):
        block = slice(start, start + PRICING_BLOCK)
        rows[block] = _packed_outer(*_face_planes(vertices, faces[block], columns=columns))
    return rows


def boundary_quadrics(vertices: np.ndarray, faces: np.ndarray, boundary_edges: np.ndarray,
                      boundary_faces: np.ndarray, weight: float) -> np.ndarray:
    """(k, 4, 4) quadrics of planes through each boundary edge, perpendicular to its face.

    They make moving a boundary vertex off its boundary line expensive, so holes keep
    their shape. ``weight`` scales them against the surface quadrics.
    """
    scale, plane = _boundary_planes(vertices, faces, boundary_edges, boundary_faces, weight)
    return scale[:, None, None] * plane[:, :, None] * plane[:, None, :]


def _boundary_planes(vertices, faces, boundary_edges, boundary_faces, weight) -> tuple[np.ndarray, np.ndarray]:
    """The scale (k,) and plane (k, 4) of each :func:`boundary_quadrics` quadric."""
    start, end = vertices[boundary_edges[:, 0]], vertices[boundary_edges[:, 1]]
    face_normal = face_cross(vertices[faces[boundary_faces]])
    direction = end - start
    normal = np.cross(direction, face_normal)
    length = np.linalg.norm(normal, axis=1)
    normal = normal / np.maximum(length, 1e-300)[:, None]
    plane = np.concatenate([normal, -np.einsum("ij,ij->i", normal, start)[:, None]], axis=1)
    return weight * np.einsum("ij,ij->i", direction, direction), plane


def accumulate(quadrics: np.ndarray, owners: np.ndarray, n: int) -> np.ndarray:
    """(n, 4, 4) sum of the quadrics each vertex owns.

    ``owners`` is (k,), one vertex per quadric, or (k, c): quadric ``i`` is added to
    every vertex of ``owners[i]`` (pass the (m, 3) face array to give each face's
    quadric to its three corners). The sum is one sparse product: a vertex-by-quadric
    incidence matrix (a 1 where the vertex owns the quadric) times the quadrics
    flattened to 16 columns.
    """
    return _accumulate_rows(quadrics.reshape(len(quadrics), 16), owners, n).reshape(n, 4, 4)


def _accumulate_rows(rows: np.ndarray, owners: np.ndarray, n: int) -> np.ndarray:
    """(n, c) sum of the rows (k, c) each vertex owns: :func:`accumulate` for any row length."""
    from scipy import sparse      # here, not at the top: `import halfedge_edu` stays light

    owners = owners.reshape(len(owners), -1)                             # (k, c)
    vertex = owners.reshape(-1)
    columns = np.repeat(np.arange(len(owners)), owners.shape[1])
    incidence = sparse.csr_matrix((np.ones(len(vertex)), (vertex, columns)), shape=(n, len(owners)))
    return np.asarray(incidence @ rows)


def quadric_cost(quadric: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(k,) ``[x, 1] Q [x, 1]^T`` for k quadrics (k, 4, 4) and points (k, 3)."""
    homogeneous = np.concatenate([points, np.ones((len(points), 1))], axis=1)
    return np.einsum("ki,kij,kj->k", homogeneous, quadric, homogeneous)


#: How hard the best point is pulled towards the edge's midpoint, as a fraction of
#: trace(A), and how often the pull is then taken back out (see :func:`optimal_points`).
PULL_TO_MIDPOINT = 1e-4
REFINEMENT_STEPS = 2


# A symmetric 3x3 matrix has six distinct entries. The functions below keep them as six
# 1-D arrays ``(m00, m11, m22, m01, m02, m12)``, one entry of k matrices each: whole-array
# arithmetic on contiguous rows is several times faster than on (k, 3, 3) slices, and
# numpy's batched ``np.linalg.solve`` calls LAPACK once per matrix, which for 3x3
# systems is slower still.

def _symmetric_entries(matrix: np.ndarray) -> tuple[np.ndarray, ...]:
    """The six distinct entries ``(m00, m11, m22, m01, m02, m12)`` of (k, 3, 3) symmetric matrices."""
    k = len(matrix)
    return tuple(matrix.reshape(k, 9)[:, [0, 4, 8, 1, 2, 5]].T.copy())


def _symmetric_inverse(m00, m11, m22, m01, m02, m12) -> tuple[np.ndarray, ...]:
    """The inverse's six entries, by the adjugate: ``adj(M) / det(M)``.

    The adjugate of a symmetric matrix is symmetric, so six cofactors are enough. The
    caller makes sure every matrix is invertible.
    """
    c00 = m11 * m22 - m12 * m12
    c01 = m02 * m12 - m01 * m22
    c02 = m01 * m12 - m02 * m11
    c11 = m00 * m22 - m02 * m02
    c12 = m01 * m02 - m00 * m12
    c22 = m00 * m11 - m01 * m01
    det = m00 * c00 + m01 * c01 + m02 * c02
    return c00 / det, c11 / det, c22 / det, c01 / det, c02 / det, c12 / det


def _symmetric_times(entries, x0, x1, x2) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``M x`` for k symmetric matrices given by their six entries, and k vectors by coordinate."""
    m00, m11, m22, m01, m02, m12 = entries
    return (m00 * x0 + m01 * x1 + m02 * x2,
            m01 * x0 + m11 * x1 + m12 * x2,
            m02 * x0 + m12 * x1 + m22 * x2)


def solve_symmetric_3x3(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """(k, 3) solutions of k symmetric 3x3 systems ``matrix[i] x = rhs[i]``, by the adjugate."""
    inverse = _symmetric_inverse(*_symmetric_entries(matrix))
    return np.stack(_symmetric_times(inverse, *rhs.T), axis=1)


def optimal_points(quadric: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Best collapse point and its cost for each edge: (k, 3) points, (k,) costs.

    Minimizing ``[x, 1] Q [x, 1]^T`` means solving ``A x = -q``, with ``A`` the top-left
    3x3 block of Q and ``q`` its last column. That fails in two ways:

    * in a flat or straight region ``A`` is singular: a whole plane or line of points
      costs the same, and no single one is "the" solution;
    * in a *nearly* flat region ``A`` can be inverted, but its solution may lie far off
      the edge (where nearly parallel planes meet), and moving a vertex there folds
      the thin triangles around it.

    So we minimize the cost plus a small pull towards the midpoint ``m``,
    ``eps |x - m|^2`` with ``eps = PULL_TO_MIDPOINT * trace(A)``, which means solving
    ``(A + eps I) x = -q + eps m``. ``A + eps I`` is always invertible (``A`` is a sum
    of ``n n^T``, so its eigenvalues are >= 0). Then ``REFINEMENT_STEPS`` times
    ``x += (A + eps I)^-1 (-q - A x)``: each step shrinks what is left of the pull, in
    a direction where ``A`` has eigenvalue ``lambda``, by a factor
    ``eps / (lambda + eps)``. Where the planes pin ``x`` down that factor is tiny, and
    ``x`` is the exact solution (a corner where three planes meet stays exactly the
    corner); where they do not, it is close to 1, and ``x`` stays at the midpoint.
    For two planes meeting along a crease: at 2 degrees or more ``x`` goes onto the
    crease line, at 0.6 degrees halfway, below 0.1 degrees it stays at the midpoint as
    if the region were flat.
    """
    packed = _pack_quadrics(quadric)
    points, cost = _packed_optimal_points(packed, np.ascontiguousarray((0.5 * (a + b)).T))
    return np.ascontiguousarray(points.T), cost


# The rounds keep the quadrics as their ten distinct entries (the matrix is symmetric):
# summing and gathering 10 numbers a vertex instead of 16 is most of the work of
# re-pricing edges. The arithmetic wants one row per entry, ``packed[:, v]`` being vertex
# v's quadric, so that every product runs on contiguous rows. The vertices' quadrics
# are stored the other way round, (n, 10), one row per vertex: ``np.take`` of whole
# 80-byte rows reads one or two cache lines per vertex, where gathering from ten rows
# of an (10, n) array reads ten; the gathered block (t, 10) is then turned round,
# a cheap copy that stays in cache (a block of 8192 edges prices about 15% faster).
# Packed entries, in order: (00, 01, 02, 03, 11, 12, 13, 22, 23, 33).
_PACKED_ENTRIES = [0, 1, 2, 3, 5, 6, 7, 10, 11, 15]        # their places in the flattened 4x4


def _packed_outer(weight: np.ndarray, plane: np.ndarray) -> np.ndarray:
    """(k, 10) the packed entries of ``weight * p p^T`` for weights (k,) and planes p (k, 4)."""
    rows, columns = np.divmod(_PACKED_ENTRIES, 4)
    return weight[:, None] * plane[:, rows] * plane[:, columns]


def _pack_quadrics(quadric: np.ndarray) -> np.ndarray:
    """(10, k) the distinct entries of k symmetric quadrics (k, 4, 4), one row per entry."""
    return np.ascontiguousarray(quadric.reshape(len(quadric), 16)[:, _PACKED_ENTRIES].T)


def _packed_cost(packed: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(k,) ``[x, 1] Q [x, 1]^T`` for packed quadrics (10, k) and points (3, k): :func:`quadric_cost`."""
    q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = packed
    x, y, z = points
    return (x * (q00 * x + 2.0 * (q01 * y + q02 * z + q03))
            + y * (q11 * y + 2.0 * (q12 * z + q13))
            + z * (q22 * z + 2.0 * q23) + q33)


#: How many edges :func:`_packed_optimal_points` prices at a time (see there).
PRICING_BLOCK = 8192


def _packed_optimal_points(packed: np.ndarray, midpoint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`optimal_points` for packed quadrics (10, k) and edge midpoints (3, k): points (3, k), costs (k,).

    The work is some eighty whole-array products and sums, each making a temporary
    array. In blocks of :data:`PRICING_BLOCK` edges those temporaries stay in the
    processor's cache instead of going out to memory and back, which takes about a
    fifth off the pricing; every edge gets the same numbers either way.
    """
    k = packed.shape[1]
    if k <= PRICING_BLOCK:
        return _packed_optimal_points_block(packed, midpoint)
    points, cost = np.empty((3, k)), np.empty(k)
    for start in range(0, k, PRICING_BLOCK):
        block = slice(start, start + PRICING_BLOCK)
        points[:, block], cost[block] = _packed_optimal_points_block(packed[:, block], midpoint[:, block])
    return points, cost


def _packed_optimal_points_block(packed: np.ndarray, midpoint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_packed_optimal_points` for one block of edges."""
    q00, q01, q02, q03, q11, q12, q13, q22, q23, _ = packed        # ten (k,) rows
    trace = q00 + q11 + q22
    # A quadric with no planes at all (zero-area faces) has A = 0 and q = 0: with
    # eps = 1 the solve below gives the midpoint, as it should.
    eps = np.where(trace > 0, PULL_TO_MIDPOINT * trace, 1.0)
    pulled_inverse = _symmetric_inverse(q00 + eps, q11 + eps, q22 + eps, q01, q02, q12)
    x = _symmetric_times(pulled_inverse, *(eps * midpoint[i] - q_i for i, q_i in enumerate((q03, q13, q23))))
    # Taking the pull back out, x += (A + eps I)^-1 (-q - A x), is the same as
    # x = (A + eps I)^-1 (eps x - q): one product a step instead of two.
    for _ in range(REFINEMENT_STEPS):
        x = _symmetric_times(pulled_inverse, eps * x[0] - q03, eps * x[1] - q13, eps * x[2] - q23)
    x = np.array(x)                                               # (3, k)
    return x, np.maximum(_packed_cost(packed, x), 0.0)


def _price_edges(a: np.ndarray, b: np.ndarray, on_boundary: np.ndarray, boundary_vertex: np.ndarray,
                 vertices: np.ndarray, quadrics: np.ndarray):
    """Collapse point (t, 3), cost (t,) and kept end (t,) of the t edges ``a[i] - b[i]``.

    ``on_boundary`` (t,) marks the boundary edges among them, ``boundary_vertex`` (n,)
    the boundary vertices; ``quadrics`` (n, 10) are packed, one row per vertex.
    """
    quadric = np.ascontiguousarray((np.take(quadrics, a, axis=0) + np.take(quadrics, b, axis=0)).T)     # (10, t)
    midpoint = np.ascontiguousarray((0.5 * (np.take(vertices, a, axis=0) + np.take(vertices, b, axis=0))).T)   # (3, t)
    x, c = _packed_optimal_points(quadric, midpoint)
    p = np.ascontiguousarray(x.T)                                                 # (t, 3)
    kept = a
    # An interior edge with one boundary end collapses onto that end, keeping the outline.
    a_on, b_on = boundary_vertex[a], boundary_vertex[b]
    one_on = np.flatnonzero(a_on != b_on)                      # few: the rest skips this
    if len(one_on):
        pinned = one_on[~on_boundary[one_on]]
        kept = a.copy()
        kept[pinned] = np.where(b_on[pinned], b[pinned], a[pinned])
        p[pinned] = vertices[kept[pinned]]
        c[pinned] = _packed_cost(quadric[:, pinned], p[pinned].T)
    return p, c, kept


def cheapest_first(cost: np.ndarray) -> np.ndarray:
    """(k,) the order ``np.argsort(cost, kind="stable")`` gives, for float costs (k,), found by a plain sort.

    A stable argsort of floats is a merge sort, one element at a time; ``np.sort`` of
    64-bit integers runs on the processor's vector units, several times faster (a
    round's 35,000 candidates: about a tenth of the time). So each cost becomes an
    integer in the same order (a non-negative double's bits, read as an integer, order
    like the double; a negative one's low 63 bits are flipped so it orders too), its
    lowest ``bits`` bits are overwritten with the candidate's position, and the integers
    are sorted: the low bits then give the order back, ties in position order.

    Overwriting low bits can put two costs that differ only there (a relative
    difference below about 1e-11) in position order instead of cost order. That is
    checked: if the sorted costs do not come out non-decreasing, the stable argsort
    does the work. When they do, the order *is* the stable argsort's: costs
    non-decreasing, and equal costs (equal in every bit, so in the same group) in
    position order. NaN costs fail the check too. Costs already in order (on a
    piecewise flat mesh every candidate may cost 0) need no sort at all.
    """
    k = len(cost)
    if (cost[1:] >= cost[:-1]).all():                 # already in order (all equal, say): a merge sort's best case
        return np.arange(k)
    bits = max(1, int(k - 1).bit_length())
    key = (cost + 0.0).view(np.int64)                 # a copy; + 0.0 turns -0.0 (== 0.0) into 0.0
    key ^= (key >> 63) & np.int64(0x7FFFFFFFFFFFFFFF)   # negative doubles: flip all but the sign bit
    key >>= bits                                      # floor division by 2**bits keeps the order
    key <<= bits
    key |= np.arange(k, dtype=np.int64)
    key.sort()
    order = key & ((1 << bits) - 1)
    ordered = cost[order]
    if not (ordered[1:] >= ordered[:-1]).all():
        return np.argsort(cost, kind="stable")
    return order


class _EdgePrices:
    """Collapse point and cost of every edge, kept from round to round.

    An edge's price depends only on its two vertices' quadrics and positions (and on
    which of them are on the boundary, which collapses do not change). So each round
    re-prices just the edges at a vertex that changed (moved, or merged into another);
    the others are the previous round's edges with no changed end, in the same order:
    both lists are sorted by key and hold the same edges, so they match one to one.

    Only the costs are wanted for every edge (the round picks the cheapest); points and
    kept ends are read for the few candidates a round checks. So an edge carries its
    cost and a *slot*, its row in a store of points and kept ends that a new price is
    appended to: a round copies two numbers per unchanged edge forward instead of five
    (the point's three, the cost, the kept end). The store is compacted to the live
    rows when it fills up, a few times a run.
    """

    def __init__(self):
        self.edges = np.empty((0, 2), dtype=np.int64)            # (E, 2) the edges priced last time
        self.cost = np.empty(0)                                   # (E,) each edge's cost
        self.slot = np.empty(0, dtype=np.int64)                   # (E,) each edge's row in the store
        self._points = np.empty((0, 3))                           # (capacity, 3) the store: points ...
        self._keep = np.empty(0, dtype=np.int64)                  # (capacity,) ... and kept ends
        self._used = 0                                            # rows of the store written so far

    def update(self, edges, boundary_edge, boundary_vertex, vertices, quadrics, changed) -> np.ndarray:
        """Price ``edges`` (E, 2, key order) and return their costs (E,); read the rest with :meth:`points` etc.

        ``changed`` (n,) marks the vertices moved or merged away since the last call;
        ``quadrics`` (n, 10) are the vertices' packed quadrics.
        """
        stale = changed[edges[:, 0]] | changed[edges[:, 1]]
        cost = np.empty(len(edges))
        slot = np.empty(len(edges), dtype=np.int64)
        if len(self.edges):
            unchanged = np.flatnonzero(~(changed[self.edges[:, 0]] | changed[self.edges[:, 1]]))
            fresh = np.flatnonzero(~stale)               # indices and np.take: faster than boolean masks
            cost[fresh] = np.take(self.cost, unchanged)
            slot[fresh] = np.take(self.slot, unchanged)
        else:
            fresh = np.empty(0, dtype=np.int64)
        todo = np.flatnonzero(stale)
        if self._used + len(todo) > len(self._keep):
            self._compact(slot, fresh, room=len(todo))
        # The new prices go PRICING_BLOCK edges at a time: on a big mesh a whole-round
        # temporary (ten quadric rows of every stale edge, say) is hundreds of MiB, which
        # the system hands out afresh, page by page, every time; a block's stays in cache.
        for start in range(0, len(todo), PRICING_BLOCK):
            rows = todo[start:start + PRICING_BLOCK]
            a, b = np.take(edges, rows, axis=0).T.copy()     # not np.take(edges[:, 0], ...): it copies the column
            p, c, kept = _price_edges(a, b, np.take(boundary_edge, rows), boundary_vertex, vertices, quadrics)
            stored = slice(self._used, self._used + len(rows))
            self._points[stored], self._keep[stored] = p, kept
            cost[rows] = c
            slot[rows] = np.arange(stored.start, stored.stop)
            self._used = stored.stop
        self.edges, self.cost, self.slot = edges, cost, slot
        return cost

    def _compact(self, slot: np.ndarray, live: np.ndarray, room: int) -> None:
        """Move the rows of the ``live`` edges' slots to the front of a new store with ``room`` rows to spare and more."""
        rows = np.take(slot, live)
        capacity = 2 * (len(live) + room)            # room for a few more rounds before the next compaction
        points, keep = np.empty((capacity, 3)), np.empty(capacity, dtype=np.int64)
        points[:len(live)] = np.take(self._points, rows, axis=0)
        keep[:len(live)] = np.take(self._keep, rows)
        slot[live] = np.arange(len(live))
        self._points, self._keep, self._used = points, keep, len(live)

    def points(self, edges: np.ndarray) -> np.ndarray:
        """(k, 3) the collapse points of the edges with indices ``edges`` (k,)."""
        return np.take(self._points, np.take(self.slot, edges), axis=0)

    def ends(self, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(keep, remove)``, each (k,), of the edges with indices ``edges`` (k,): the end
        each keeps (the vertex that moves to the point) and the one it removes (merged
        into the kept one)."""
        keep = np.take(self._keep, np.take(self.slot, edges))
        ends = np.take(self.edges, edges, axis=0)                         # (k, 2)
        return keep, np.where(keep == ends[:, 0], ends[:, 1], ends[:, 0])

    def move(self, edges: np.ndarray, points: np.ndarray) -> None:
        """Set the collapse points (k, 3) of the edges ``edges`` (k,): kept for later rounds while they stay unchanged."""
        self._points[np.take(self.slot, edges)] = points


def simplify(
    mesh: HalfedgeMesh,
    target_faces: int,
    *,
    boundary_weight: float = 100.0,
    max_normal_angle: float = 80.0,
    candidate_fraction: float = 0.25,
    progress: bool = False,
) -> HalfedgeMesh:
    """Simplify ``mesh`` to about ``target_faces`` faces by quadric-error edge collapses.

    Args:
        mesh: the input; it is not modified.
        target_faces: how many faces to keep. The result has exactly this many, or one
            fewer (an interior collapse removes two faces), or more when no allowed
            collapse is left (a :class:`MeshWarning` says so).
        boundary_weight: how strongly boundaries keep their shape.
        max_normal_angle: largest allowed swing of a face normal in one collapse, degrees.
        candidate_fraction: each round considers only this cheapest fraction of edges,
            which keeps the order close to the one-at-a-time priority queue.
        progress: show a progress bar (tqdm) of faces removed.

    Returns:
        A new :class:`HalfedgeMesh`. To learn how many rounds it took and whether it
        reached the target, call :func:`simplify_with_report` instead.
    """
    check_simplify(mesh, target_faces, boundary_weight, max_normal_angle, candidate_fraction, progress)
    if mesh.n_faces == 0:
        return _empty_result(mesh, target_faces).mesh
    return _simplify(mesh, target_faces, boundary_weight, max_normal_angle, candidate_fraction, progress).mesh


def simplify_with_report(mesh: HalfedgeMesh, target_faces: int, **options) -> SimplifyResult:
    """:func:`simplify`, and what it did: a :class:`SimplifyResult` ``(mesh, report)``.

    Takes exactly the arguments of :func:`simplify` (``options`` are its keyword
    arguments, with its defaults) and does the same work, so the mesh is the same; the
    :class:`SimplifyReport` adds the face counts, the number of rounds and whether the
    target was reached. Two functions instead of a flag, so that each one always
    returns the same type.
    """
    # Bind to simplify's own signature: one place holds the options and their defaults,
    # and a misspelt option is a TypeError naming it.
    arguments = inspect.signature(simplify).bind(mesh, target_faces, **options)
    arguments.apply_defaults()
    check_simplify(**arguments.arguments)
    if mesh.n_faces == 0:
        return _empty_result(mesh, target_faces)
    return _simplify(**arguments.arguments)


def _empty_result(mesh: HalfedgeMesh, target_faces: int) -> SimplifyResult:
    """The empty mesh simplifies to itself: nothing to collapse, and no face above the target."""
    empty = mesh.copy()
    empty.garbage_collect()
    return SimplifyResult(empty, SimplifyReport(0, 0, int(target_faces), rounds=0, reached_target=True))


def _simplify(mesh: HalfedgeMesh, target_faces: int, boundary_weight: float, max_normal_angle: float,
              candidate_fraction: float, progress: bool) -> SimplifyResult:
    """The work of :func:`simplify` and :func:`simplify_with_report`."""
    vertices, faces = mesh.to_arrays()
    vertices = vertices.copy()
    n = len(vertices)
    faces_before = len(faces)
    target_faces = int(target_faces)
    if target_faces < 1:
        raise ValueError(f"target_faces must be at least 1, got {target_faces}")
    max_normal_cos = float(np.cos(np.radians(max_normal_angle)))

    # The vertex quadrics, packed (see _PACKED_ENTRIES) from the start: ten columns, not sixteen.
    quadrics = _accumulate_rows(_face_quadric_rows(vertices, faces), faces, n)       # (n, 10)
    this_round = round_tables(faces, n)                                # the first round's tables
    if this_round.boundary.any():
        boundary_edges = this_round.edges[this_round.boundary]
        boundary_faces = this_round.boundary_halfedge // 3            # the one face of each
        planes = _boundary_planes(vertices, faces, boundary_edges, boundary_faces, boundary_weight)
        quadrics += _accumulate_rows(_packed_outer(*planes), boundary_edges, n)   # each to both ends

    # Costs are area x distance^2 (length^4); below this they count as nothing.
    cost_floor = 1e-12 * float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0))) ** 4
    bar = _progress_bar(progress, faces_before - target_faces)
    rounds = 0
    priced = _EdgePrices()
    changed = np.ones(n, dtype=bool)           # vertices moved or merged away: their edges need new prices
    # The checks read the vertices by coordinate, (3, n): kept up to date beside them
    # (a round moves a few thousand) rather than transposed anew every round.
    positions = np.ascontiguousarray(vertices.T)
    while len(faces) > target_faces:
        rounds += 1
        edges, boundary_edge, face_across = this_round.edges, this_round.boundary, this_round.face_across
        boundary_vertex = np.zeros(n, dtype=bool)
        boundary_vertex[edges[boundary_edge].reshape(-1)] = True
        degree = np.diff(this_round.neighbours[0])                     # (n,) a row lists each neighbour once
        cost = priced.update(edges, boundary_edge, boundary_vertex, vertices, quadrics, changed)   # (E,)

        # Consider the cheapest edges only, and not many more than the faces still to go.
        faces_to_remove = len(faces) - target_faces
        n_candidates = int(max(64, candidate_fraction * len(edges)))
        n_candidates = min(n_candidates, max(64, 4 * faces_to_remove), len(edges))
        if n_candidates < len(edges):
            candidates = np.argpartition(cost, n_candidates - 1)[:n_candidates]
        else:
            candidates = np.arange(len(edges))
        candidates = candidates[cheapest_first(cost[candidates])]
        # Sixteen classes of equal size, cheapest first, for spread_ties (the same order
        # as keys, without its sort, up to a billion edges).
        rank_class = np.arange(len(candidates)) * COST_CLASSES // len(candidates)
        spread = spread_ties_keys if len(edges) <= SPREAD_KEY_IDS else spread_ties

        faces_around, neighbours = this_round.faces_around, this_round.neighbours
        corners_around = this_round.corners_around                      # faces_around's rows as corners 3 f + k

        def check_topology(indices: np.ndarray):
            chosen_edges = candidates[indices]
            ok, owner, vertex = collapse_topology_ok(n, edges[chosen_edges], boundary_edge[chosen_edges],
                                                     boundary_vertex, degree, neighbours)
            return ok, indices[owner], vertex


        def check_turned_faces(indices: np.ndarray) -> np.ndarray:
            chosen_edges = candidates[indices]
            ok = no_turned_faces(vertices, faces, faces_around, priced.points(chosen_edges),
                                 *priced.ends(chosen_edges), max_normal_cos,
                                 face_across=face_across, positions=positions, corners_around=corners_around)
            # Where the best point turns a face over, an endpoint may not: in a flat
            # region all three cost nothing, and moving onto a neighbour folds less
            # often than moving to the middle of a long edge. Accept an endpoint only
            # if it costs at most twice as much (or next to nothing).
            retry = chosen_edges[~ok]                                  # (r,)
            if len(retry) == 0:
                return ok
            # Both endpoints in one check, the kept end's rows first; the kept end wins where both pass.
            twice = np.concatenate([retry, retry])                     # (2r,)
            keep_twice, remove_twice = priced.ends(twice)
            option = vertices[np.concatenate([keep_twice[:len(retry)], remove_twice[:len(retry)]])]
            quadric = (np.take(quadrics, keep_twice, axis=0) + np.take(quadrics, remove_twice, axis=0)).T
            option_cost = _packed_cost(quadric, option.T)
            passes = option_cost <= 2.0 * cost[twice] + cost_floor
            cheap = np.flatnonzero(passes)
            if len(cheap) == 0:
                return ok
            passes[cheap] = no_turned_faces(vertices, faces, faces_around, option[cheap], keep_twice[cheap],
                                            remove_twice[cheap], max_normal_cos, face_across=face_across,
                                            positions=positions, corners_around=corners_around)
            r = len(retry)
            pick = np.where(passes[:r], np.arange(r), np.arange(r) + r)    # (r,) the kept end if it passes
            good = passes[pick]
            priced.move(retry[good], option[pick[good]])
            cost[retry[good]] = option_cost[pick[good]]
            ok[np.flatnonzero(~ok)[good]] = True
            return ok

        chosen_mask = choose_round(edges, candidates, np.ones(len(candidates), dtype=bool), n,
                                   check_topology, check_turned_faces, neighbours=neighbours,
                                   priority=spread(rank_class, candidates))
        chosen = candidates[chosen_mask]
        # Stop exactly at the target: take chosen edges in cost order until enough faces go.
        removes_faces = np.where(boundary_edge[chosen], 1, 2)
        chosen = chosen[np.cumsum(removes_faces) <= faces_to_remove]
        chosen = chosen[drop_folding_neighbours(vertices, faces, faces_around, priced.points(chosen),
                                                *priced.ends(chosen), face_across=face_across,
                                                positions=positions, corners_around=corners_around)]
        if len(chosen) == 0:
            # Nothing passed the geometric check, or only interior collapses are left with
            # one face to go (then one more collapse is the nearest we can get).
            everything = np.arange(len(candidates))
            allowed = everything[check_topology(everything)[0]]
            allowed = allowed[check_turned_faces(allowed)][:1]
            if len(allowed) == 0:
                break
            chosen = candidates[allowed]

        keep_c, remove_c = priced.ends(chosen)
        vertices[keep_c] = priced.points(chosen)
        positions[:, keep_c] = vertices[keep_c].T
        quadrics[keep_c] = np.take(quadrics, keep_c, axis=0) + np.take(quadrics, remove_c, axis=0)
        changed[:] = False
        changed[keep_c] = True
        changed[remove_c] = True
        faces_left = len(faces)
        faces = merge_vertices(faces, remove_c, keep_c, n)
        if len(faces) > target_faces:          # the next round's tables; none after the last round
            this_round = round_tables(faces, n)
        if bar is not None:
            bar.update(faces_left - len(faces))

    if bar is not None:
        bar.close()
    reached = len(faces) <= target_faces
    if not reached:
        warnings.warn(
            f"simplify stopped at {len(faces)} faces: no allowed collapse is left "
            f"(target was {target_faces})",
            MeshWarning,
            stacklevel=3,            # the caller of simplify or simplify_with_report
        )
    result = HalfedgeMesh.from_faces(*compact(vertices, faces)[:2])
    return SimplifyResult(result, SimplifyReport(faces_before, len(faces), target_faces, rounds, reached))


def _progress_bar(enabled: bool, total: int):
    if not enabled:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, desc="simplify", unit="face")
