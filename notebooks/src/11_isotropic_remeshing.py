# %% [markdown]
# # 11 · Isotropic remeshing
#
# Simplification (chapter 10) keeps the *shape* of a surface with few triangles, but it
# does not care what those triangles look like: some come out long and thin, some
# tiny, and vertices end up with 3 or 11 neighbours. Many algorithms downstream
# (smoothing, simulation, parametrization) work best on triangles that are all about
# the same size and close to equilateral. **Isotropic remeshing** rebuilds a mesh that
# way, with only the local operations you already know: split, collapse, flip, and a
# careful kind of smoothing.
#
# **By the end of this chapter you can**
#
# - state the four phases of Botsch and Kobbelt's algorithm and the rule of each:
#   split above 4/3 L, collapse below 4/5 L (without creating an edge above 4/3 L),
#   flip toward degree 6 (4 on a boundary), smooth tangentially;
# - explain where 4/3 comes from, and why a collapse must not create long edges;
# - say why the smoothing moves vertices only in the tangent plane, and why every
#   centroid is computed before any vertex moves;
# - read edge-length, degree and angle histograms before and after;
# - step through the phases with `RemeshStepper`;
# - write the tangential smoothing step yourself and have `check_tangential_smoothing`
#   check it.

# %%
import numpy as np
from IPython.display import Image

import halfedge_edu as hx
from halfedge_edu.algorithms.remesh import PHASES, closest_points_on_segments, remesh_step_by_step
from halfedge_edu.viz.remesh_stepper import RemeshStepper, histogram_png, phase_quality
from halfedge_edu.viz import side_by_side, surface_png

SPOT_VIEW = (2.6, 0.8, -2.3)        # from Spot toward the camera: the cow seen from the front left


def mesh_png(mesh, size=(380, 320), view=SPOT_VIEW, boundary_colour=None, zoom=1.35):
    """A picture of ``mesh`` with its edges drawn (and its boundary in a colour, if given)."""
    return surface_png(mesh, size=size, view=view, zoom=zoom, boundary_color=boundary_colour)


spot = hx.sample("spot")
rough = hx.simplify(spot, 1500)              # chapter 10's output: right shape, uneven triangles
L = 0.08                                     # the target edge length
even = hx.remesh(rough, target_length=L, iterations=3)
side_by_side([mesh_png(rough), mesh_png(even)],
             [f"after simplification: {rough.n_faces} faces", f"remeshed, L = {L}: {even.n_faces} faces"])

# %% [markdown]
# Left: Spot simplified to 1,500 faces by quadric error collapses. The shape is right,
# but look at the triangles: long slivers along the flanks, crowds of small ones around
# the eyes and horns. Right: the same surface after three iterations of isotropic
# remeshing with target length L = 0.08. Nearly every triangle is close to equilateral
# and nearly every vertex has six neighbours, like a sheet of graph paper laid over
# the cow.

# %% [markdown]
# ## 1. The idea
#
# **Convention: pick a target edge length `L`; one iteration is four phases, each a
# sweep of one local operation over the whole mesh.**
#
# 1. **Split** every edge longer than 4/3 L at its midpoint (chapter 06).
# 2. **Collapse** every edge shorter than 4/5 L (chapters 07 and 08), but only if no
#    edge around the merged vertex ends up longer than 4/3 L.
# 3. **Flip** an edge (chapter 06) when that brings the degrees of its four vertices
#    closer to 6 (4 for a vertex on a boundary).
# 4. **Smooth tangentially**: move each vertex toward the centroid of its neighbours,
#    but only sideways, in the surface's tangent plane.
#
# Splits and collapses even out the *lengths*; flips even out the *degrees*; smoothing
# evens out the *shapes*. A few iterations are usually enough. The library runs one
# more phase after the smoothing, **project**, which puts every vertex back on the
# input surface (section 6). `remesh_step_by_step` hands you the mesh after each phase:

# %%
print("phases:", PHASES)
print(f"{'':18s}{'V':>6s}{'F':>6s}{'short':>7s}{'long':>6s}{'|deg - 6|':>11s}{'min angle':>11s}")
history = list(remesh_step_by_step(rough, target_length=L, iterations=2))
for iteration, phase, mesh in history:
    q = phase_quality(mesh, L)
    print(f"{iteration} {phase:16s}{q.n_vertices:6d}{q.n_faces:6d}{q.n_short:7d}{q.n_long:6d}"
          f"{q.degree_deviation:11.3f}{q.min_angle_mean:11.1f}")

# %% [markdown]
# Read the table column by column. *short* counts edges below 4/5 L, *long* those
# above 4/3 L; `|deg - 6|` is the mean distance of the degrees from the ideal; the
# last column is the mean, over all faces, of each face's smallest angle (60° for an
# equilateral triangle).
#
# - The split removes every long edge, and creates many short ones (the halves).
# - The collapse removes most short edges, and still no edge is long.
# - The flip halves the degree error without touching a single vertex position.
# - Over both iterations, the smoothing raises the smallest angles more than any other
#   phase (the first collapse comes close).
#
# The sections below take the phases one at a time.

# %% [markdown]
# ## 2. Split above 4/3 L
#
# **Convention: split an edge of length `l` when `l > 4/3 L`.**
#
# Why 4/3? Splitting trades one edge of length `l` for two of length `l/2`. That is an
# improvement exactly when `l/2` is nearer to L than `l` was: `L - l/2 < l - L`, that
# is `l > 4/3 L`. At `l = 4/3 L` both are off by `L/3`, a tie.

# %%
for l in (1.2, 4 / 3, 1.5, 2.0):
    print(f"l = {l:.3f} L: off by {abs(l - 1):.3f} L before, halves off by {abs(l / 2 - 1):.3f} L -> "
          f"{'split' if l > 4 / 3 + 1e-12 else 'leave it'}")

# %% [markdown]
# An edge longer than 8/3 L leaves halves that are still too long; the library simply
# splits again until no edge is long. A split adds one vertex, and three edges and two
# faces for an interior edge (chapter 06), so the table's first split phase took Spot
# from 1,500 to 3,550 faces.

# %% [markdown]
# ## 3. Collapse below 4/5 L, but never create a long edge
#
# **Convention: collapse an edge shorter than 4/5 L into its midpoint, unless a vertex
# that would then be joined to the merged vertex lies more than 4/3 L from it.**
#
# The second half of the rule is what keeps the phases from fighting. A collapse
# swings all the edges of the removed vertex over to the kept one; some of them get
# longer. Without the check, the next split would cut them again, and the two phases
# could undo each other forever. 4/5 is Botsch and Kobbelt's partner threshold to 4/3:
# an edge slightly under L is left alone.
#
# When the midpoint does not fit, the library tries each end of the edge in turn; an
# edge that fits nowhere (or breaks the link condition of chapter 08, or would turn a
# face over) waits for the next iteration, when the smoothing may have given it room.
# Right after every split phase and every collapse phase, no edge is longer than 4/3 L:

# %%
for iteration, phase, mesh in history:
    if phase in ("split", "collapse"):
        longest = phase_quality(mesh, L).lengths.max()
        print(f"iteration {iteration}, after {phase:8s}: longest edge {longest:.3f} L  (<= 4/3 L: {longest <= 4 / 3 + 1e-9})")

# %% [markdown]
# ## 4. Flip toward degree 6
#
# **Convention: flip edge `a – b` (with opposite corners `c` and `d`) when that lowers
# `|deg a - 6| + |deg b - 6| + |deg c - 6| + |deg d - 6|`; a boundary vertex aims for 4.**
#
# A flip takes one edge away from `a` and `b` and gives one to `c` and `d`, so it is
# easy to compute what it gains before doing it. Why 6? In a grid of equilateral
# triangles, six meet at every corner (6 × 60° = 360°). On a boundary, three triangles
# fill the half-turn, so four edges meet there.
#
# Here is the gain written with handles, tried on the mesh right after the first
# collapse phase. The best edge is flipped with `mesh.flip` from chapter 06:

# %%
def ideal(v):
    return 4 if v.is_boundary else 6


def flip_gain(mesh, e):
    """How much flipping interior edge ``e`` lowers the four vertices' distance from the ideal degree."""
    h = mesh.edge(e).halfedge
    a, b, c, d = h.vertex, h.tip, h.prev.vertex, h.twin.prev.vertex
    before = sum(abs(v.degree - ideal(v)) for v in (a, b, c, d))
    after = (abs(a.degree - 1 - ideal(a)) + abs(b.degree - 1 - ideal(b))
             + abs(c.degree + 1 - ideal(c)) + abs(d.degree + 1 - ideal(d)))
    return before - after


collapsed = next(mesh for iteration, phase, mesh in history if (iteration, phase) == (1, "collapse"))
gains = {e.index: flip_gain(collapsed, e.index) for e in collapsed.edges if not e.is_boundary}
best = max(gains, key=gains.get)                       # the first edge with the largest gain
h = collapsed.edge(best).halfedge
names = {"a": h.vertex, "b": h.tip, "c": h.prev.vertex, "d": h.twin.prev.vertex}
print(f"edges that a flip would improve: {sum(g > 0 for g in gains.values())} of {len(gains)}")
print(f"best: edge {best}, gain {gains[best]}; degrees before:",
      {k: v.degree for k, v in names.items()})
flipped = collapsed.copy()
flipped.flip(best)
print("degrees after flipping it:           ", {k: flipped.vertex(v.index).degree for k, v in names.items()})

# %% [markdown]
# The flip takes one edge from `a` and `b` and gives one to `c` and `d`. Here each of
# the four moves one step towards 6: a gain of 4, the most a single flip can give. The library computes the gain of every edge at
# once, and flips a set of improving edges that share no vertex together (two flips at
# one vertex could otherwise both take an edge from it), repeating until nothing
# improves. It also refuses flips across a sharp crease and flips that would fold a
# triangle over.

# %% [markdown]
# > **Sidebar: the fast version uses the same halfedges, with `next` by arithmetic.**
# > `remesh` and `simplify` flip and collapse thousands of edges at once on a plain face
# > array `F`, through a *corner table* (`halfedge_edu/core/corner_table.py`). Its
# > halfedges are the ones of chapter 02, numbered `3f + k`: halfedge `3f + k` leaves
# > corner `k` of face `f`. The three halfedges of a face sit side by side, so `next`
# > needs no array: `next(h) = 3 * (h // 3) + (h + 1) % 3`. The mesh does it the other
# > way round: it stores `next` and gets `twin` by arithmetic (`h ^ 1`). The corner
# > table finds every `twin` with one sort of all halfedges by their edge. Same
# > halfedges, same twins:

# %%
from halfedge_edu.core.corner_table import CornerTable, next_halfedge

V, F = hx.sample("spot").to_arrays()          # V: (2930, 3) positions, F: (5856, 3) corners
table = CornerTable(F, len(V))                # one sort of all 3F halfedges by their edge
h = 1                                         # face 0, corner 1: runs F[0, 1] -> F[0, 2]
print("corner table: next", next_halfedge(h), "| twin", table.twin[h], "in face", table.twin[h] // 3)
g = hx.HalfedgeMesh.from_faces(V, F).face(0).halfedge.next   # the same halfedge on the mesh
print("HalfedgeMesh: twin in face", g.twin.face.index)

# %% [markdown]
# ## 5. Smooth, but only in the tangent plane
#
# **Convention: for every vertex `p`, compute the centroid `c` of its neighbours, all
# of them first, from the old positions. Then move each interior vertex by
# `s - (s · n) n`, where `s = c - p` and `n` is the unit, area-weighted vertex normal.
# Boundary vertices stay put.** (The library's remesher does one better and slides
# them along the boundary; section 10.)
#
# Chapter 05's Laplacian smoothing moves `p` all the way to `c`. On a curved surface
# `c` lies *inside* the surface (the centroid of points on a sphere is inside the
# sphere), so every step shrinks the mesh. Splitting `s` into a part along `n` and a
# part in the tangent plane, and dropping the first, keeps the part that spreads the
# vertices out evenly and removes the part that pulls the surface in.
#
# "All centroids first" (Jacobi, as in chapter 05) makes the result independent of the
# order of the vertices. Here is one vertex of the collapsed mesh, by hand:

# %%
mesh = collapsed
P = mesh.positions
normals = hx.vertex_normals(mesh)                  # unit, area-weighted (chapter 05)
v = mesh.vertex(100)
c = np.mean([P[u.index] for u in v.neighbors()], axis=0)
n = normals[v.index]
s = c - P[v.index]
tangential = s - (s @ n) * n
print(f"vertex {v.index}: degree {v.degree}, boundary: {v.is_boundary}")
print(f"step to the centroid s = {np.round(s, 4)}, length {np.linalg.norm(s) / L:.3f} L")
print(f"its normal part (s.n) n = {np.round((s @ n) * n, 4)}")
print(f"the tangential step     = {np.round(tangential, 4)}, length {np.linalg.norm(tangential) / L:.3f} L")
print(f"tangential step . n = {tangential @ n:.1e}  (zero: it stays in the tangent plane)")

# %% [markdown]
# How much does the normal part matter? Take a sphere of radius 1, let the remesher
# run up to its smoothing phase without projection, and compare one step of plain
# Laplacian smoothing (`hx.smooth`, chapter 05) with the tangential step the remesher
# takes:

# %%
sphere = hx.sample("icosphere", subdivisions=3)
steps = {(i, phase): m for i, phase, m in remesh_step_by_step(sphere, 0.12, iterations=1, project=False)}
before = steps[(1, "flip")]


def mean_radius(mesh):
    return np.linalg.norm(mesh.to_arrays()[0], axis=1).mean()


print(f"mean radius before smoothing:       {mean_radius(before):.5f}")
print(f"after one tangential step:          {mean_radius(steps[(1, 'smooth')]):.5f}")
print(f"after one plain Laplacian step:     {mean_radius(hx.smooth(before)):.5f}")
print(f"after 20 plain Laplacian steps:     {mean_radius(hx.smooth(before, 20)):.5f}")

# %% [markdown]
# One plain step pulls the sphere in by almost 1% of its radius; the tangential step
# by a hundredth of that (a step along a curved surface leaves the tangent plane only
# to second order). Twenty plain steps would make a visibly smaller ball.

# %% [markdown]
# ## 6. Project back onto the input
#
# Two things still nudge vertices off the original surface: a split puts the new
# vertex at the midpoint of a *chord*, and a tangential step is straight, not curved.
# Each step is small, but over many iterations the mesh would drift. So after each
# smoothing, the library moves every vertex to the nearest point of the *input*
# mesh (a boundary vertex to the nearest point of the input's boundary, a vertex on a
# crease to the nearest point of that crease: section 10). That is
# why the `project` rows of the table barely change: the moves are a few hundredths
# of L.

# %% [markdown]
# ## 7. Step through it
#
# `RemeshStepper` runs the phases once and lets you walk through them: **step** goes
# one phase on, **iteration** jumps to the same phase one iteration later. The picture
# marks edges longer than 4/3 L (vermillion: the next split's work), edges shorter than
# 4/5 L (blue: the next collapse's) and vertices whose degree is 2 or more from the
# ideal (purple dots: the flips' work). Below it, the histograms compare the input
# (grey) with the mesh now; the table on the right lists every phase.
#
# Driven here to the first flip. The flips have evened out the degrees (few purple dots
# are left), at a price: a flipped edge joins the two far corners, and some of those are
# long (vermillion). One step on, the smoothing has shortened most of them; the next
# split takes care of the rest.

# %%
stepper = RemeshStepper(rough, target_length=L, iterations=2, window_size=(460, 340), view_direction=SPOT_VIEW,
                        zoom=1.25)
stepper.go((1, "flip"))
stepper

# %%
print(stepper.describe())
print()
print(stepper.describe(stepper.step_index + 1))   # the next step, read without moving the stepper

# %% [markdown]
# ## 8. Quality before and after
#
# The three histograms are the point of the whole algorithm. Edge lengths gather in a
# narrow hump around L; the degrees pile up at 6; and the smallest angles, spread from
# 5° to 60° after simplification, crowd between 40° and 60°:

# %%
Image(histogram_png([rough, even], ["after simplification", f"remeshed (L = {L}, 3 iterations)"], L))

# %% [markdown]
# `iterations` is a parameter. The first iteration does most of the work; later ones
# polish. Here is the quality after 0 to 5 iterations (`phase_quality` measures
# against L; *spread* is the standard deviation of the lengths divided by their mean):

# %%
print(f"{'iterations':>10s}{'faces':>7s}{'in [4/5 L, 4/3 L]':>19s}{'spread':>8s}{'|deg - 6|':>11s}{'min angle':>11s}{'< 30 deg':>10s}")
for iterations in range(6):
    q = phase_quality(hx.remesh(rough, L, iterations), L)
    print(f"{iterations:10d}{q.n_faces:7d}{100 * q.in_range:18.0f}%{q.lengths.std() / q.lengths.mean():8.3f}"
          f"{q.degree_deviation:11.3f}{q.min_angle_mean:11.1f}{int((q.min_angles < 30).sum()):10d}")

# %% [markdown]
# ## 9. Boundaries stay where they are
#
# On a surface with holes, the boundary is part of the shape, so the remesher keeps
# it: boundary vertices never leave the input's boundary, boundary edges are split at
# their midpoints and only collapse *along* the boundary, and the smoothing moves a
# boundary vertex only along the boundary (a corner, where the boundary turns
# sharply, not at all). Flips aim for degree 4 there. Here is the front half of
# Spot, an open surface with one boundary loop (orange), seen from behind:

# %%
V, F = spot.to_arrays()
front_faces = F[V[F].mean(axis=1)[:, 2] < 0.0]          # faces whose centre has z < 0
used = np.unique(front_faces)
renumber = np.full(len(V), -1)
renumber[used] = np.arange(len(used))
front = hx.HalfedgeMesh.from_faces(V[used], renumber[front_faces])
front_even = hx.remesh(front, target_length=0.06, iterations=3)
side_by_side([mesh_png(front, (360, 300), (0.8, 0.4, 1), "#E69F00", zoom=1.1),
              mesh_png(front_even, (360, 300), (0.8, 0.4, 1), "#E69F00", zoom=1.1)],
             [f"front of Spot: {front.n_faces} faces", f"remeshed, L = 0.06: {front_even.n_faces} faces"])

# %%
rim = np.array([[h.vertex.position, h.tip.position] for h in front.halfedges if h.is_boundary])   # (S, 2, 3)
on_rim = front_even.vertex_is_boundary()
points = front_even.positions[on_rim]
nearest = np.min([np.linalg.norm(closest_points_on_segments(points, np.repeat(a[None], len(points), 0),
                                                            np.repeat(b[None], len(points), 0)) - points, axis=1)
                  for a, b in rim], axis=0)
print("boundary loops before and after:", front.n_boundary_loops, front_even.n_boundary_loops)
print("every new boundary vertex lies on the old boundary (closer than 1e-12):", bool(nearest.max() < 1e-12))
degrees, counts = np.unique(front_even.vertex_degrees()[on_rim], return_counts=True)
print("degrees of the boundary vertices after:", {int(d): int(k) for d, k in zip(degrees, counts)})

# %% [markdown]
# The boundary vertices sit exactly on the old boundary (up to rounding): even the
# saw-teeth of the cut are still there, because the remesher cannot know they are not
# meant. Degree 4 is the most common one on the boundary; the sharp teeth keep some
# vertices at 2 or 3, where a single triangle or two fill the corner.

# %% [markdown]
# ## 10. Creases stay sharp
#
# A boundary is one kind of **feature line**; a crease is the other: an edge whose two
# faces meet at a sharp angle, like the twelve edges of a cube. Smoothing and
# projecting onto the nearest surface point would round it off. So `remesh` first
# marks as feature edges the boundary and every edge whose face normals differ by
# more than `feature_angle` degrees (45 by default), and then keeps four rules: a
# feature edge is never flipped, a collapse never pulls a feature vertex off its
# line, a split of a feature edge gives two feature halves, and a feature vertex is
# smoothed only along its line. A **corner** (three creases meet, or a line turns
# sharply) does not move at all. Here is the cube, remeshed with the rules switched
# off (`feature_angle=None`) and on:

# %%
cube = hx.sample("cube")                                    # 12 triangles, from (0, 0, 0) to (1, 1, 1)
CUBE_VIEW = (1.6, 1.2, 2.0)
rounded = hx.remesh(cube, target_length=0.15, iterations=5, feature_angle=None)
kept = hx.remesh(cube, target_length=0.15, iterations=5)
side_by_side([mesh_png(rounded, (340, 300), CUBE_VIEW, zoom=1.2), mesh_png(kept, (340, 300), CUBE_VIEW, zoom=1.2)],
             ["feature_angle=None: creases rounded", "feature_angle=45 (default): creases kept"])

# %%
def distance_to_cube_edges(points):
    """(n,) how far each point is from the nearest of the cube's 12 edges."""
    off_face = np.sort(np.abs(np.abs(points - 0.5) - 0.5), axis=1)   # (n, 3): off each pair of opposite faces
    return np.linalg.norm(off_face[:, :2], axis=1)                 # on an edge: two of them are 0


for name, result in (("off", rounded), ("on", kept)):
    corners = np.abs(np.abs(result.positions - 0.5) - 0.5).max(axis=1) < 1e-12   # (n,) exactly at a corner
    sharp = distance_to_cube_edges(result.positions) < 1e-12
    print(f"features {name:3s}: {result.n_faces:4d} faces, {int(corners.sum())} of 8 corners kept, "
          f"{int(sharp.sum()):3d} vertices exactly on the cube's edges")

# %% [markdown]
# With the rules off, nothing stops the corners from sliding into the faces: the
# smoothing pulls every vertex toward the middle of its neighbours, and the nearest
# surface point of a point near a crease is on one of the two faces, so the creases are
# cut off. With the rules on, the eight corners stay where they are and every vertex
# that started on a crease is still exactly on it. The price is a few triangles near
# the corners that are less even, because those vertices may not move freely.

# %% [markdown]
# ## Check yourself
#
# Predict before you run. With L = 0.3, which of these edges does a split phase cut,
# which may a collapse phase remove, and which are left alone: lengths 0.2, 0.25, 0.3,
# 0.39, 0.41, 0.9? For the 0.9 edge, how many pieces are there once no piece is long?
# Then: remesh the icosphere with 1,280 faces (radius 1) with L = 0.3 and 3 iterations.
# Does the number of faces go up or down (its edges are about 0.15 long)? Is the result
# still a closed surface of genus 0?

# %%
for l in (0.2, 0.25, 0.3, 0.39, 0.41, 0.9):
    verdict = "split" if l > 4 / 3 * 0.3 else "collapse" if l < 4 / 5 * 0.3 else "leave"
    pieces = 1
    while l / pieces > 4 / 3 * 0.3:
        pieces *= 2
    print(f"length {l}: {verdict}" + (f" (into {pieces} pieces)" if pieces > 1 else ""))
ball = hx.sample("icosphere", subdivisions=3)
result = hx.remesh(ball, target_length=0.3, iterations=3)
result.validate()
print(f"faces: {ball.n_faces} -> {result.n_faces}; V - E + F = {result.euler_characteristic}; "
      f"genus {result.genus}; boundary loops {result.n_boundary_loops}")
print(phase_quality(result, 0.3).summary())

# %% [markdown]
# 4/3 × 0.3 = 0.4 and 4/5 × 0.3 = 0.24: 0.2 may collapse; 0.25, 0.3 and 0.39 are left
# alone; 0.41 and 0.9 are split, the 0.9 edge into 4 pieces of 0.225 (two pieces of
# 0.45 are still too long). Edges of about 0.15 are *shorter* than 4/5 L, so the
# remesher collapses, and the face count drops to about a quarter (edges twice as long
# cover the same area with a quarter as many triangles). The topology is kept: V − E + F = 2, genus 0,
# no boundary.

# %% [markdown]
# ## Exercise: write the tangential smoothing step
#
# Fill in `my_tangential_smoothing(mesh)`: return a new `(n_vertices, 3)` array of
# positions after one step of tangential smoothing, and do not change `mesh`. Use the
# handles (`mesh.vertices`, `v.neighbors()`, `v.is_boundary`, `v.index`) and the
# area-weighted unit normals `hx.vertex_normals(mesh)`.
#
# `check_tangential_smoothing` runs yours on an octahedron, an icosphere, a flat patch
# with a boundary and a cube (each a little bumpy, so that no mistake hides behind a
# symmetry), compares with the library's smoothing phase, and at the first vertex that
# differs tells you what the right position was and, if it recognises the slip, which
# one.

# %%
def my_tangential_smoothing(mesh):
    P = mesh.positions
    normals = hx.vertex_normals(mesh)
    centroids = np.zeros_like(P)
    for v in mesh.vertices:
        ### BEGIN SOLUTION
        centroids[v.index] = np.mean([P[u.index] for u in v.neighbors()], axis=0)   # the mean of v's neighbours' positions
        ### END SOLUTION
    new = P.copy()
    for v in mesh.vertices:
        if v.is_boundary:
            continue
        ### BEGIN SOLUTION
        s = centroids[v.index] - P[v.index]   # the step from v to its centroid
        ### END SOLUTION
        n = normals[v.index]
        ### BEGIN SOLUTION
        new[v.index] = P[v.index] + s - (s @ n) * n   # the step without its normal part
        ### END SOLUTION
    return new

# %%
from halfedge_edu.exercises.remesh_checks import check_tangential_smoothing

check_tangential_smoothing(my_tangential_smoothing)

# %% [markdown]
# ### What a mistake looks like
#
# This version is almost right: it moves each vertex as soon as its centroid is known,
# in one loop. But then the centroids of later vertices use neighbours that have
# *already* moved (Gauss-Seidel instead of Jacobi):

# %%
def smoothing_while_moving(mesh):
    new = mesh.positions.copy()
    normals = hx.vertex_normals(mesh)
    for v in mesh.vertices:
        if v.is_boundary:
            continue
        s = np.mean([new[u.index] for u in v.neighbors()], axis=0) - new[v.index]
        n = normals[v.index]
        new[v.index] += s - (s @ n) * n
    return new


buggy = check_tangential_smoothing(smoothing_while_moving)
buggy

# %%
buggy.show(window_size=(420, 320))

# %% [markdown]
# The picture shows the vertex where the first difference appeared, with its one-ring.
# Its neighbours with smaller numbers moved before its centroid was taken, so the
# centroid was not the one of the old mesh.

# %% [markdown]
# ### Exercise 2: the normal you projected with
#
# `hx.vertex_normals(mesh)` gave the smoothing its `n`. Write it for one vertex, as
# CS184's `Vertex::normal()` and UChicago's P4 ask: sum the cross products
# `(b - a) x (c - a)` of the faces around `v` (corners in each face's own order; each
# is twice its face's area long, so big faces count more), then divide by the length
# once. `check_vertex_normal` compares yours with the library's at every vertex of a
# cube, a bent patch and a nudged icosphere, and names the slip it recognises.

# %%
from halfedge_edu.exercises.remesh_checks import check_vertex_normal


def my_vertex_normal(mesh, v):
    total = np.zeros(3)
    for f in v.faces():
        a, b, c = (u.position for u in f.vertices())
        ### BEGIN SOLUTION
        total += np.cross(b - a, c - a)   # this face's normal, as long as twice its area
        ### END SOLUTION
    ### BEGIN SOLUTION
    return total / np.linalg.norm(total)   # unit length, divided once at the end
    ### END SOLUTION


check_vertex_normal(my_vertex_normal)

# %% [markdown]
# ### Exercise 3: when does the flip phase flip?
#
# CMU's step 3 flips an edge when that brings the degrees closer to 6. Write
# `my_flip_improves(mesh, e)`: a flip takes one edge from each end of `e` and gives one to
# each vertex opposite it; return True exactly when the summed distance of those four
# vertices from their ideal degree (6 inside, 4 on the boundary, section 9) drops.

# %%
from halfedge_edu.exercises.remesh_checks import check_flip_improves


def my_flip_improves(mesh, e):
    h = mesh.edge(e).halfedge
    four = [(h.vertex, -1), (h.tip, -1), (h.prev.vertex, +1), (h.twin.prev.vertex, +1)]   # (vertex, change)
    ### BEGIN SOLUTION
    ideal = {v.index: 4 if v.is_boundary else 6 for v, _ in four}
    before = sum(abs(v.degree - ideal[v.index]) for v, _ in four)
    after = sum(abs(v.degree + change - ideal[v.index]) for v, change in four)
    return after < before
    ### END SOLUTION


check_flip_improves(my_flip_improves)

# %% [markdown]
# ### Exercise 4: the split phase
#
# CMU's step 1. Write `my_split_long_edges(mesh, L)`: split (with `split(mesh, e)` from
# chapter 06) every edge longer than 4/3 L, in place. The two halves of a long edge may
# still be too long, so go round again until a round splits nothing.
# `check_split_long_edges` judges the result, whatever order you split in.

# %%
from halfedge_edu.core.ops import split
from halfedge_edu.exercises.remesh_checks import check_split_long_edges


def my_split_long_edges(mesh, L):
    ### BEGIN SOLUTION
    while True:
        ends = mesh.edge_vertices()                                        # (E, 2)
        long = [e for e in range(mesh.n_edge_slots) if not mesh.edge_deleted[e]
                and np.linalg.norm(mesh.positions[ends[e, 0]] - mesh.positions[ends[e, 1]]) > 4 / 3 * L]
        if not long:
            return
        for e in long:
            split(mesh, e)
    ### END SOLUTION


check_split_long_edges(my_split_long_edges)

# %% [markdown]
# ### Exercise 5: the collapse phase
#
# CMU's step 2, with section 3's rule. Write `my_collapse_short_edges(mesh, L)`: collapse
# (with `mesh.collapse(e)`, chapter 07) every interior edge shorter than 4/5 L, in place,
# but skip an edge when
#
# - it is on the boundary (`mesh.edge(e).is_boundary`: CMU's collapse ignores those, and
#   the outline stays where it is);
# - the link condition refuses it (`mesh.can_collapse(e)`, chapter 08);
# - a neighbour of either end would be more than 4/3 L from the merged vertex, the
#   edge's midpoint.
#
# One collapse can make room for another, so go round again until a round collapses
# nothing. `check_collapse_short_edges` judges the result, whatever order you collapse in.

# %%
from halfedge_edu.exercises.remesh_checks import check_collapse_short_edges


def my_collapse_short_edges(mesh, L):
    while True:
        collapsed = 0
        for e in range(mesh.n_edge_slots):
            if mesh.edge_deleted[e]:
                continue
            a, b = mesh.edge(e).vertices
            ### BEGIN SOLUTION
            if mesh.edge(e).is_boundary or np.linalg.norm(a.position - b.position) >= 4 / 5 * L:
                continue
            if not mesh.can_collapse(e):
                continue
            middle = (a.position + b.position) / 2
            around = {u.index for u in (*a.neighbors(), *b.neighbors())} - {a.index, b.index}
            if any(np.linalg.norm(mesh.positions[u] - middle) > 4 / 3 * L for u in around):
                continue
            mesh.collapse(e)
            collapsed += 1
            ### END SOLUTION
        if collapsed == 0:
            return


check_collapse_short_edges(my_collapse_short_edges)

# %% [markdown]
# ## Summary
#
# - Isotropic remeshing aims for edges of length about L and degrees near 6, with four
#   phases per iteration: split above 4/3 L, collapse below 4/5 L, flip toward degree 6
#   (4 on a boundary), smooth tangentially.
# - 4/3 is where splitting starts to help: the halves are nearer to L than the edge.
#   A collapse may not create an edge longer than 4/3 L, so splits and collapses never
#   undo each other.
# - A flip's gain is computed from four degrees before it is done.
# - Tangential smoothing computes every centroid first, then drops the normal part of
#   each step: the vertices spread out evenly and the surface does not shrink.
#   Projecting onto the input removes the small drift that is left.
# - Boundaries and creases (faces meeting at more than `feature_angle`) stay where
#   they are: feature edges are never flipped, feature vertices move only along their
#   line, corners not at all. The topology never changes.
# - The histograms say it all: lengths gather around L, degrees at 6, smallest angles
#   near 60°.

# %% [markdown] tags=["solution"]
# ## Answer
#
# The answer is in the exercise cell above: every centroid first, from the old
# positions, then each interior vertex takes the step to its centroid without its
# normal part, `s - (s @ n) * n`.
