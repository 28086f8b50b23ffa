# %% [markdown]
# # 09 · Loop subdivision
#
# Chapters 06 to 08 changed a mesh one edge at a time. This chapter puts those local
# operations to work on the whole mesh at once: every triangle becomes four, and the
# vertices move a little, so that a coarse, faceted shape turns into a smooth one. The
# method is Charles Loop's (1987), and it is one of the most used ideas in geometry
# processing: film studios model characters as coarse meshes and let subdivision make
# them smooth.
#
# **After this chapter you can**
#
# - say what the 4-to-1 split does and count its result: `V' = V + E`, `F' = 4F`;
# - build the split from the operations you know: split every edge, then flip every
#   new edge that joins an old vertex and a new one;
# - state Loop's weights: `3/8, 3/8, 1/8, 1/8` for a new vertex on an edge, Warren's
#   `beta` for an old vertex, and the rules on the boundary;
# - explain why every new position is computed from the *old* mesh, before anything
#   changes;
# - explain why a subdivided cube can come out lopsided, and predict where a corner ends
#   up: halfway to the average of its ring, 3/5 of the way at valence 3;
# - say what valence the old and the new vertices have after a level, and why the number
#   of extraordinary vertices (valence other than 6) never changes;
# - write the two rules yourself and have `check_loop_rules` check them.

# %%
import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

import halfedge_edu as hx
from halfedge_edu.algorithms import loop_subdivide
from halfedge_edu.algorithms.loop import loop_positions, loop_subdivide_by_operations
from halfedge_edu.viz import show
from halfedge_edu.viz.loop_stepper import LoopStepper

octahedron = hx.sample("octahedron")

picture = pv.Plotter(off_screen=True, shape=(1, 4), window_size=(920, 250), border=False)
for column in range(4):
    level = loop_subdivide(octahedron, levels=column)
    picture.subplot(0, column)
    picture.add_mesh(level.to_pyvista(), color="#E8B96A", show_edges=True, edge_color="#6B5B45", line_width=1)
    picture.add_text(f"{column} level{'s' if column != 1 else ''}: {level.n_faces} faces", font_size=9)
picture.link_views()
picture.camera_position = [(2.6, 2.0, 3.2), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
show(picture)

# %% [markdown]
# An octahedron (8 triangles), then one, two and three levels of Loop subdivision. Each
# level has four times the triangles of the one before, and the shape gets rounder.
# It also gets smaller: on a convex shape like this one, every rule pulls vertices
# inwards.
# After a few levels the mesh hardly changes any more; it approaches a smooth *limit
# surface*.

# %% [markdown]
# ## The idea
#
# One level of Loop subdivision has two parts, and it pays to keep them apart.
#
# 1. **Connectivity.** Put a new vertex on every edge (an *edge point*) and join the
#    three new vertices of every triangle: each triangle becomes four.
# 2. **Positions.** Each new vertex goes to a weighted average of the old vertices
#    near its edge; each old vertex moves to a weighted average of itself and its
#    neighbours. **All of these averages are computed from the old mesh**, before any
#    connectivity changes and before any vertex moves.
#
# The weights are chosen so that repeating the two steps converges to a smooth
# surface. The rest of the chapter takes the parts one at a time.

# %% [markdown]
# ## 1. The 4-to-1 split, counted
#
# **Convention: the edge point of edge `e` becomes vertex `V + e`; the old vertices keep
# their numbers `0 .. V-1`.**
#
# Every old edge gets one new vertex, so `V' = V + E`. Every triangle becomes four, so
# `F' = 4F`. For the edges: each old edge is cut in two (`2E`), and each triangle gets
# three new edges inside it (`3F`), so `E' = 2E + 3F`. Let us check these on a few
# meshes, open and closed:

# %%
print(f"{'mesh':12s} {'V':>4s} {'E':>4s} {'F':>4s}   {'V+E':>5s} {'2E+3F':>6s} {'4F':>4s}   {'V1':>4s} {'E1':>4s} {'F1':>4s}  V-E+F")
for name in ["tetrahedron", "octahedron", "cube", "open_patch", "strip"]:
    mesh = hx.sample(name)
    V, E, F = mesh.n_vertices, mesh.n_edges, mesh.n_faces
    finer = loop_subdivide(mesh)
    print(f"{name:12s} {V:4d} {E:4d} {F:4d}   {V + E:5d} {2 * E + 3 * F:6d} {4 * F:4d}   "
          f"{finer.n_vertices:4d} {finer.n_edges:4d} {finer.n_faces:4d}  {mesh.euler_characteristic} -> {finer.euler_characteristic}")

# %% [markdown]
# The predicted columns and the measured ones agree on every line. The last column is
# a bonus: `V' - E' + F' = (V + E) - (2E + 3F) + 4F = V - E + F`, so subdivision never
# changes the Euler characteristic. A sphere stays a sphere, a disc stays a disc.

# %% [markdown]
# ## 2. The split built from operations you know
#
# **Convention (the course's route): split every old edge at its midpoint, then flip
# every new edge that joins an old vertex and a new one.**
#
# Why does this give the 4-to-1 split? Splitting an edge puts a vertex on it and cuts
# each neighbouring triangle in two with a new edge *across* the triangle, from the
# new vertex to the opposite corner. Once every edge is split, each old triangle has
# been cut into four pieces by those cross edges, but not into the right four: some
# cross edges run from a new vertex to an old corner. Flipping exactly those turns
# them into edges between two new vertices, and then every old triangle is a centre
# triangle of three new vertices with three corner triangles around it.
#
# `loop_subdivide_by_operations` does exactly this with the `split` and `flip` of
# chapter 06, and calls a function of ours after every step. Let us count the steps:

# %%
steps = []
by_operations = loop_subdivide_by_operations(octahedron, on_step=lambda step: steps.append(step.phase))
print({phase: steps.count(phase) for phase in ["split", "flip", "reposition"]})

fast = loop_subdivide(octahedron)
same_faces = {tuple(sorted(f)) for f in by_operations.to_arrays()[1].tolist()} == {tuple(sorted(f)) for f in fast.to_arrays()[1].tolist()}
print("same triangles as loop_subdivide:", same_faces)
print("same positions:", np.allclose(by_operations.positions, fast.positions))

# %% [markdown]
# Twelve splits (one per edge), eight flips (one per face) and one step that moves
# every vertex. Why one flip per face? Each triangle gets three cross edges, one for
# each of its sides as that side is split. The first split in a triangle draws its
# cross edge to the opposite corner, an old vertex: that edge must be flipped. By the
# time the second and third sides are split, the corner opposite them is the first
# new vertex, so their cross edges already join two new vertices and stay. The result is the same mesh that `loop_subdivide` builds
# directly from arrays in one go, only in a different order. The operation route is
# the one to understand; the array route is the one to run on a large mesh.

# %% [markdown]
# ## 3. Try it: the Loop stepper
#
# Step through one level on the octahedron. Step 0 shows where every vertex *will*
# go: small orange dots for the edge points (inside the see-through surface: the
# octahedron shrinks) and a black line from each old vertex to its new place. Then
# come the twelve splits, the eight flips and the final move.
#
# Watch the colours: **blue** dots are old vertices, **orange** dots new ones.
# **Vermillion** edges run from an old vertex to a new one across a triangle: these
# are the ones the flip phase turns around. **Green** edges join two new vertices:
# the sides of the centre triangles. **Dark grey** edges are old edges and the halves
# they were split into. The element of the current step is **purple**.

# %%
stepper = LoopStepper(octahedron)
stepper

# %% [markdown]
# The same moves from code, on a stepper of its own (the one above stays where you
# leave it). The first split, then the first flip:

# %%
by_code = LoopStepper(octahedron, mode="static")
by_code.go(1)
print(by_code.describe())
print()
by_code.go("flip")
print(by_code.describe())

# %% [markdown]
# Splitting edge 0 made vertex 6 and two cross edges, 13 and 14, to the corners 4 and 5
# opposite the edge. This was the first split in both triangles, so both corners are
# old vertices and both edges will be flipped. The first flip turns edge 13, from new
# vertex 6 to old vertex 4, into an edge between new vertices 7 and 8: a side of a
# centre triangle.
#
# Just before the flips, the vermillion edges are exactly the ones still to flip:

# %%
by_code.go(by_code.phase_start("flip") - 1)
print("edges to flip:", len(by_code.edge_kinds()["to_flip"]), "(one per face)")
by_code.go("end")
print(by_code.describe())

# %% [markdown]
# ## 4. Where the vertices go: Loop's weights
#
# **Convention: an edge point is `3/8 (a + b) + 1/8 (c + d)`, with `a, b` the ends of
# the edge and `c, d` the corners opposite it; an old vertex of degree `n` moves to
# `(1 - n beta) v + beta (v_1 + ... + v_n)`, with Warren's `beta = 3/16` for `n = 3`
# and `beta = 3/(8n)` otherwise.**
#
# The pictures are called *masks* or *stencils*: which old vertices a new position
# listens to, and how much.

# %%
figure, (left, right) = plt.subplots(1, 2, figsize=(8.4, 3.4))
a, b, c, d = np.array([[-1.0, 0], [1.0, 0], [0, 1.3], [0, -1.3]])
for p, q in [(a, b), (a, c), (b, c), (a, d), (b, d)]:
    left.plot(*np.array([p, q]).T, color="#555555", lw=1.5)
for p, text in [(a, "a: 3/8"), (b, "b: 3/8"), (c, "c: 1/8"), (d, "d: 1/8")]:
    left.plot(*p, "o", color="#0072B2", ms=9)
    left.annotate(text, p, textcoords="offset points", xytext=(8, 6), fontsize=11)
left.plot(0, 0, "o", color="#E69F00", ms=11)
left.annotate("edge point", (0, 0), textcoords="offset points", xytext=(8, -14), fontsize=10)
left.set_title("edge point (interior edge)")
angles = np.linspace(0, 2 * np.pi, 7)[:-1]
ring = np.stack([np.cos(angles), np.sin(angles)], axis=1)
for k in range(6):
    right.plot(*np.array([ring[k], ring[(k + 1) % 6]]).T, color="#555555", lw=1.5)
    right.plot(*np.array([[0, 0], ring[k]]).T, color="#555555", lw=1.5)
    right.plot(*ring[k], "o", color="#0072B2", ms=9)
    right.annotate("beta", ring[k], textcoords="offset points", xytext=(6, 6), fontsize=11)
right.plot(0, 0, "o", color="#0072B2", ms=11)
right.annotate("1 - n beta", (0, 0), textcoords="offset points", xytext=(8, -16), fontsize=11)
right.set_title("old vertex, degree n = 6: beta = 3/48 = 1/16")
for axes in (left, right):
    axes.set_aspect("equal")
    axes.axis("off")
plt.show()

# %% [markdown]
# An edge point is mostly the edge's midpoint (`3/8 + 3/8 = 3/4` of the weight), pulled a
# little towards the two "wings" `c` and `d`. An old vertex keeps the largest share for
# itself and takes a little from each neighbour. In both masks the weights add up to 1:
# `3/8 + 3/8 + 1/8 + 1/8 = 1` and `(1 - n beta) + n beta = 1`. That matters: weights
# that add up to 1 make the rule independent of where the origin is. Move the whole
# mesh and the subdivided mesh moves with it.
#
# Here is Warren's `beta` for the degrees you will meet, and the share a vertex keeps:

# %%
for n in range(3, 9):
    beta = 3 / 16 if n == 3 else 3 / (8 * n)
    print(f"degree {n}: beta = {beta:.4f}, the vertex keeps 1 - n beta = {1 - n * beta:.4f}")

# %% [markdown]
# From degree 4 up, a vertex always keeps `5/8` and shares the other `3/8` evenly among
# its neighbours. For `n = 3` the same formula would give `beta = 1/8`; Warren's special
# value `3/16` comes from the analysis of which weights make the limit surface smooth at
# such a vertex, and with it the vertex keeps only `7/16`. (Warren chose these values as a
# simpler stand-in for Loop's own, which has a cosine in it; `loop_subdivide` has
# `weights="loop"` if you want to compare. For `n = 6`, the common case, both give
# `1/16`.)
#
# On the octahedron the numbers are easy enough to check by hand. Vertex 0 sits at
# `(1, 0, 0)` with degree 4, so `beta = 3/32` and it keeps `1 - 4 * 3/32 = 5/8`; its four
# neighbours `(0, ±1, 0)` and `(0, 0, ±1)` add up to zero. Edge 0 joins vertex 0 and
# vertex 2 at `(0, 1, 0)`; its opposite corners are `(0, 0, 1)` and `(0, 0, -1)`, which
# also cancel.

# %%
vertex_points, edge_points = loop_positions(octahedron)
print("vertex 0:", octahedron.vertex(0).position, "->", vertex_points[0])
print("edge 0 joins", [v.index for v in octahedron.edge(0).vertices], "-> edge point", edge_points[0])

# %% [markdown]
# Vertex 0 moves from 1 to 5/8 = 0.625, and the edge point lands at `3/8 (1, 1, 0)`,
# inside the old edge's midpoint `(0.5, 0.5, 0)`: that is the shrinking you saw in the
# first picture.

# %% [markdown]
# ## 5. Why "from the old mesh"?
#
# **Convention: compute every vertex point and every edge point first, from the old
# positions and the old connectivity; change the connectivity and move the vertices
# only afterwards.**
#
# Two things can go wrong if you do not. After the splits, the old vertices have new
# neighbours (the edge points), so a vertex rule run then would average over the
# wrong ring. And if you move the old vertices first, every edge point computed
# afterwards is built from positions that have *already* been pulled in. Let us make
# the second mistake on purpose:

# %%
hurried = octahedron.copy()
vertex_points, edge_points = loop_positions(hurried)
hurried.positions[:] = vertex_points                  # move the old vertices first ...
_, late_edge_points = loop_positions(hurried)         # ... then compute the edge points
print("edge point of edge 0, from the old mesh: ", edge_points[0])
print("edge point of edge 0, after moving first:", late_edge_points[0])

# %% [markdown]
# The late edge point is pulled in twice: `0.234 = 5/8 * 0.375`. In this symmetric case
# the surface just shrinks more; on a real mesh the mix of old and new positions
# distorts the shape, and the result depends on the order you happened to visit the
# vertices in. `loop_subdivide_by_operations` therefore starts with `loop_positions`
# and ends with the move, exactly as the stepper shows.

# %% [markdown]
# ## 6. The boundary
#
# **Convention: on a boundary edge the edge point is the midpoint `(a + b) / 2`; a
# boundary vertex moves to `3/4 v + 1/8 (b0 + b1)`, with `b0` and `b1` its two
# neighbours along the boundary.**
#
# A boundary edge has only one triangle, so the interior rule's `c + d` does not exist.
# The boundary rules use the boundary vertices *only*: the boundary is subdivided as a
# curve of its own (these are the rules of a cubic B-spline curve). Two meshes that
# share a boundary therefore still share it after subdivision, and nothing inside can
# pull the boundary away.
#
# Here is the open patch of chapter 05 with a bump in the middle, before and after
# three levels. Only the inside moves up; the square boundary becomes a rounded curve
# in the floor.

# %%
bumped = hx.sample("open_patch")
bumped.positions[[5, 6, 9, 10], 2] = 0.8               # lift the four interior vertices

picture = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(820, 300), border=False)
for column, levels in enumerate([0, 3]):
    mesh = loop_subdivide(bumped, levels=levels)
    rim = mesh.halfedge_vertex[np.flatnonzero(mesh.halfedge_face < 0)]
    picture.subplot(0, column)
    picture.add_mesh(mesh.to_pyvista(), color="#E8B96A", show_edges=True, edge_color="#6B5B45", line_width=1)
    picture.add_mesh(pv.PolyData(mesh.positions[rim]), color="#0072B2", point_size=9, render_points_as_spheres=True)
    picture.add_text(f"{levels} levels", font_size=10)
picture.link_views()
picture.camera_position = [(4.6, -3.0, 4.2), (1.5, 1.5, 0.2), (0.0, 0.0, 1.0)]
show(picture)

# %% [markdown]
# The blue dots are the boundary vertices. Do they depend on the inside? Lift the bump
# twice as high and subdivide again: the boundary does not notice.

# %%
taller = bumped.copy()
taller.positions[[5, 6, 9, 10], 2] = 1.6
low, high = loop_subdivide(bumped, levels=3), loop_subdivide(taller, levels=3)
rim = low.vertex_is_boundary()
print("boundary vertices after 3 levels:", int(rim.sum()))
print("boundary unchanged by the taller bump:", np.allclose(low.positions[rim], high.positions[rim]))
print("inside changed:", not np.allclose(low.positions[~rim], high.positions[~rim]))
print("corner vertex 0:", bumped.vertex(0).position, "->", low.vertex(0).position.round(4))

# %% [markdown]
# The corner `(0, 0, 0)` moves inside the square, to about `(0.164, 0.164, 0)` after three
# levels: the B-spline rule rounds corners off. If you want to keep a corner sharp,
# you need extra rules (creases and corners); Loop's basic scheme has none.

# %% [markdown]
# ## 7. The lopsided cube
#
# **Convention: Loop's rules see only the triangles and the positions, not the shape they
# stand for; two triangulations of the same cube are two different inputs.**
#
# The Loop assignment and CS184 both have you subdivide a cube and look at it. Here is
# the sample cube, each square face cut by one diagonal as in most OBJ files, beside the
# same cube with every diagonal split at its midpoint by chapter 06's `split`: now each
# face is four triangles around its centre. Four levels of each, seen from the side, so
# that the diagonal through the cube from corner 0 to corner 7 runs across the picture.
# Corners 0 and 7 are the orange dots, the other six corners blue.

# %%
cube = hx.sample("cube")
ends = cube.edge_vertices()                                                    # (E, 2)
edge_lengths = np.linalg.norm(cube.positions[ends[:, 0]] - cube.positions[ends[:, 1]], axis=1)
centred = cube.copy()
for diagonal in np.flatnonzero(edge_lengths > 1.1):                            # the six face diagonals, length sqrt(2)
    centred.split(diagonal)                                                    # the midpoint: the face's centre


def corner_row(columns, marked=(0, 7)):
    """One row of cubes, ``columns`` = [(mesh, levels, title), ...], the box drawn around each;
    the ``marked`` corners orange, the other corners blue."""
    picture = pv.Plotter(off_screen=True, shape=(1, len(columns)), window_size=(230 * len(columns), 250), border=False)
    box = pv.Box(bounds=(0, 1, 0, 1, 0, 1)).outline()
    others = [v for v in range(8) if v not in marked]
    for column, (mesh, levels, title) in enumerate(columns):
        level = loop_subdivide(mesh, levels=levels)                            # corners keep the numbers 0 .. 7
        picture.subplot(0, column)
        picture.add_mesh(level.to_pyvista(), color="#E8B96A", show_edges=levels == 0, edge_color="#6B5B45",
                         line_width=1)
        picture.add_mesh(box, color="#555555", line_width=1)
        for corners, colour in [(list(marked), "#D55E00"), (others, "#0072B2")]:
            picture.add_mesh(pv.PolyData(level.positions[corners]), color=colour, point_size=11,
                             render_points_as_spheres=True)
        picture.add_text(title, position=(6, 226), font_size=8)
    picture.link_views()
    picture.camera_position = [(3.3, -2.3, 0.5), (0.5, 0.5, 0.5), (-1.0, -1.0, 2.0)]   # up: across the 0-7 diagonal
    show(picture)


corner_row([(cube, 0, "one diagonal: 0 levels"), (cube, 4, "one diagonal: 4 levels"),
            (centred, 0, "face centres: 0 levels"), (centred, 4, "face centres: 4 levels")])

# %% [markdown]
# The cube on the right stays a rounded cube. The one on the left is drawn out towards
# the orange corners, like a lemon.
#
# **Your turn.** Both start from the same eight corners. Count the edges at each corner of
# the left cube (its picture at 0 levels helps): which corners differ from the others,
# and why would Loop's weights care?
#
# The counts, and a number for the lopsidedness: the distance from the cube's centre
# to each corner after five levels, along the 0-7 diagonal and along the other three.

# %%
for name, mesh in [("one diagonal", cube), ("face centres", centred)]:
    finer = loop_subdivide(mesh, levels=5)
    reach = np.linalg.norm(finer.positions[:8] - 0.5, axis=1)                  # (8,) corner distances from the centre
    along, across = reach[[0, 7]].mean(), reach[1:7].mean()
    print(f"{name:13s} corner degrees {mesh.vertex_degrees()[:8].tolist()}: "
          f"corners 0, 7 at {along:.4f}, the other six at {across:.4f}, ratio {along / across:.3f}")

# %% [markdown]
# Each face diagonal ends at two corners: six diagonals, twelve ends, shared by six of the
# eight corners. Corners 0 and 7 get none and keep degree 3; the other six get two each,
# degree 5. A vertex's new place is a weighted average of its own ring, so corners with
# different rings move differently: the degree-5 corners have two far neighbours across
# the faces that pull them further in, and the two degree-3 corners are left standing
# out. The left cube ends up about 11 % longer along its 0-7 diagonal than along the
# other three (the ratio 1.107). Split around the face centres, every corner has the
# same ring (three edges of the cube, three face centres, degree 6), all eight land at
# the same distance (ratio 1.000), and the shape keeps every symmetry of the cube.
#
# Subdivision follows the triangulation, not the shape you meant. To get a symmetric
# result, give it a symmetric triangulation.

# %% [markdown]
# ## 8. Sharp corners, and what valence does to them
#
# **Convention: the *valence* of a vertex is its degree, the number of edges at it; a
# corner is *sharper* after subdivision the less of it is cut off.**
#
# Section 6 ended with Loop rounding corners off. CS184 asks what happens to sharp
# corners, and whether splitting some edges beforehand changes it. Here is the same
# corner 0 of the same cube three ways, each after four levels: valence 3 (the sample
# cube), valence 6 (split around the face centres), and valence 6 with its six edges
# split beforehand a quarter of the way from the corner. Corner 0 is the orange dot on
# the left, the box's corner the place it started.

# %%
presplit = centred.copy()
for neighbour in [v.index for v in presplit.vertex(0).neighbors()]:
    edge = presplit.find_edge(0, neighbour)
    presplit.split(edge, position=0.75 * presplit.positions[0] + 0.25 * presplit.positions[neighbour])

corner_row([(cube, 4, "valence 3"), (centred, 4, "valence 6"), (presplit, 4, "valence 6, split at 1/4")], marked=(0,))

# %% [markdown]
# **Your turn.** Before running the next cell: which of the three corners is cut off the
# most? And by how much should splitting at a quarter shrink the cut?

# %%
start = cube.positions[0]                                                      # (0, 0, 0): the cube's corner
for name, mesh in [("valence 3", cube), ("valence 6", centred), ("valence 6, split at 1/4", presplit)]:
    limit = loop_subdivide(mesh, levels=6).positions[0]
    print(f"{name:24s} corner 0 goes to {limit.round(4)}, cut {np.linalg.norm(limit - start):.4f} deep")

# %% [markdown]
# The valence-3 corner is cut deepest, 0.346; at valence 6 the cut is 0.289; and with its
# edges split at a quarter it is 0.072, exactly a quarter of 0.289. Where do these
# numbers come from? (The valence-3 corner still looks like a tip in the picture only
# because the valence-5 corners around it are cut deeper still.)
#
# Follow one vertex `v` of valence `n >= 4` and the average `a` of its ring. One level
# moves `v` to `5/8 v + 3/8 a`. Its new ring is the edge points around it; averaging
# `3/8 (v + u_i) + 1/8 (u_(i-1) + u_(i+1))` over the ring gives `3/8 v + 5/8 a`. So the
# midpoint `(v + a) / 2` of the new pair is the midpoint of the old pair: it never moves,
# while the gap `a - v` shrinks to a quarter each level. The vertex ends **halfway to
# the average of its first ring**. With Warren's `3/16` at valence 3 the same argument
# gives **3/5 of the way**. Let us predict corner 0 this way, and corner 1 of the sample
# cube (valence 5) too:

# %%
def predicted_limit(mesh, vertex):
    ring = np.array([u.position for u in mesh.vertex(vertex).neighbors()])    # (n, 3)
    share = 3 / 5 if len(ring) == 3 else 1 / 2
    v = mesh.positions[vertex]
    return v + share * (ring.mean(axis=0) - v)


for name, mesh, vertex in [("valence 3", cube, 0), ("valence 5", cube, 1), ("valence 6", centred, 0),
                           ("valence 6, split at 1/4", presplit, 0)]:
    measured = loop_subdivide(mesh, levels=7).positions[vertex]
    print(f"{name:24s} vertex {vertex}: predicted {predicted_limit(mesh, vertex).round(4)}, "
          f"after 7 levels {measured.round(4)}")

# %% [markdown]
# So valence acts twice. It sets the share: 3/5 of the way at valence 3, 1/2 at every
# other valence. And it decides *which* vertices are in the ring, which sets where the
# ring's average is. At valence 3, corner 0's ring is the three far corners, average
# `(1/3, 1/3, 1/3)`, and 3/5 of that is `(0.2, 0.2, 0.2)`. At valence 6 the three face
# centres join, the average is again `(1/3, 1/3, 1/3)`, but only half of it is taken:
# `(1/6, 1/6, 1/6)`. The valence-5 corners of the sample cube have the two far diagonal
# ends in their ring, which pulls the average, and the corner, further in: that is the
# lopsided cube of section 7, in numbers.
#
# Splitting the edges at a quarter puts the whole ring four times closer, so its average
# and the cut shrink four times: the corner looks sharper. It is still round, only on a
# smaller scale, and it costs triangles. Corners that stay truly sharp need extra rules
# for marked *crease* edges and corners (Hoppe and others, 1994), which this basic scheme
# does not have.

# %% [markdown]
# ## 9. Regular and extraordinary vertices
#
# **Convention: an interior vertex of valence 6 is *regular* (every vertex of a flat grid
# of equilateral triangles has six edges; on the boundary, four); a vertex of any other
# valence is *extraordinary*.**
#
# The Loop assignment asks what subdivision does to valences. Here is the sample cube
# after 0, 1 and 2 levels, each vertex a dot coloured by its valence: orange 3, green 4,
# blue 5, and grey (drawn smaller) for the regular 6.

# %%
VALENCE_COLOURS = {3: "#D55E00", 4: "#009E73", 5: "#0072B2", 6: "#AAAAAA"}


def valence_row(mesh, levels=(0, 1, 2)):
    """``mesh`` after each number of ``levels``, every vertex a dot in the colour of its valence."""
    picture = pv.Plotter(off_screen=True, shape=(1, len(levels)), window_size=(260 * len(levels), 260), border=False)
    for column, level in enumerate(levels):
        finer = loop_subdivide(mesh, levels=level)
        valence = finer.vertex_degrees()                                      # (V,) edges at each vertex
        picture.subplot(0, column)
        picture.add_mesh(finer.to_pyvista(), color="#F3E3C3", show_edges=True, edge_color="#9A8A70", line_width=1)
        for n in np.unique(valence):
            picture.add_mesh(pv.PolyData(finer.positions[valence == n]), color=VALENCE_COLOURS.get(int(n), "#CC79A7"),
                             point_size=6 if n == 6 else 13, render_points_as_spheres=True)
        picture.add_text(f"{level} level{'s' if level != 1 else ''}: {finer.n_vertices} vertices", font_size=8)
        picture.camera_position = [(3.0, -2.0, 2.4), (0.5, 0.5, 0.5), (0.0, 0.0, 1.0)]
        picture.reset_camera()                                                # each level fills its view
    show(picture)


valence_row(hx.sample("cube"))

# %% [markdown]
# The cube starts with no regular vertex at all: two corners of valence 3 and six of
# valence 5. Look at where the coloured dots are at one and two levels, and how many
# grey ones there are.
#
# **Your turn** (the Loop assignment's questions 3 and 4). Loop subdivision makes two
# kinds of vertices: "V" vertices, one per old vertex, and "E" vertices, one per old edge.
# Fill in your predictions, then run the cell after, which measures them on the cube, an
# icosphere and the open patch:
#
# 1. an old vertex had valence `n`: what is its valence after one level?
# 2. what is the valence of an edge point inside the mesh, and of one on the boundary?
# 3. a closed mesh has `k` extraordinary vertices: how many after `levels` levels?
# 4. a mesh has `V` vertices and `E` edges: how many vertices after one level?

# %%
def valence_of_old_vertex(n):
    ### BEGIN SOLUTION
    return n
    ### END SOLUTION


def valence_of_edge_point(on_boundary):
    ### BEGIN SOLUTION
    return 4 if on_boundary else 6
    ### END SOLUTION


def extraordinary_after(k, levels):
    ### BEGIN SOLUTION
    return k
    ### END SOLUTION


def vertices_after_one_level(V, E):
    ### BEGIN SOLUTION
    return V + E
    ### END SOLUTION

# %%
def extraordinary(mesh):
    """How many vertices have a valence other than the regular one (6 inside, 4 on the boundary)."""
    regular = np.where(mesh.vertex_is_boundary(), 4, 6)
    return int(np.sum((mesh.vertex_degrees() != regular) & ~mesh.vertex_deleted))


def verdict(predicted, measured):
    """'yes' when the prediction is the measurement, else what was measured."""
    if predicted is Ellipsis or (isinstance(predicted, list) and Ellipsis in predicted):
        return "fill in the blank above"
    return "yes" if np.all(np.asarray(predicted) == np.asarray(measured)) else f"no, measured {measured}"


for name, mesh in [("cube", hx.sample("cube")), ("icosphere", hx.sample("icosphere", subdivisions=1)),
                   ("open patch", hx.sample("open_patch"))]:
    V, E = mesh.n_vertices, mesh.n_edges
    finer = loop_subdivide(mesh)                              # old vertices keep 0 .. V-1, edge e's point is V + e
    valence, new_valence = mesh.vertex_degrees(), finer.vertex_degrees()
    inside = np.array([not edge.is_boundary for edge in mesh.edges])            # (E,) in the order of the edge points
    answers = [("1. old vertices", verdict([valence_of_old_vertex(n) for n in valence], new_valence[:V].tolist()))]
    for where, on_boundary in (("inside", False), ("on the boundary", True)):
        points = new_valence[V:][inside != on_boundary]                         # valences of these edge points
        if len(points):
            answers.append((f"2. edge points {where}", verdict(valence_of_edge_point(on_boundary),
                                                               sorted(set(points.tolist())))))
    counts = [extraordinary(loop_subdivide(mesh, levels=levels)) for levels in (1, 2, 3)]
    answers.append(("3. extraordinary after 1, 2, 3 levels",
                    verdict([extraordinary_after(extraordinary(mesh), levels) for levels in (1, 2, 3)], counts)))
    answers.append(("4. vertices after one level", verdict(vertices_after_one_level(V, E), finer.n_vertices)))
    print(f"{name}: {V} vertices, {extraordinary(mesh)} of them extraordinary")
    for question, said in answers:
        print(f"  {question:38s} {said}")

# %% [markdown] tags=["solution"]
# ### Why (solution edition: it holds the answers)
#
# 1. An old vertex of valence `n` keeps valence `n`: each of its `n` edges is cut in two,
#    and its new neighbour along that edge is the edge point. No edge is added at it.
# 2. An edge point inside has valence 6: the two halves of its edge, and two new edges in
#    each of the two triangles beside it (to the other two edge points of that triangle).
#    On the boundary there is one triangle: the two halves and two new edges, valence 4,
#    the regular valence there.
# 3. So the extraordinary vertices of a closed mesh are the old ones that were
#    extraordinary, and their number never changes: `k` after any number of levels. (Read
#    literally, "valence other than six" would also count every new boundary vertex of an
#    open mesh; with 4 as the boundary's regular valence the count stays too, as the open
#    patch shows.)
# 4. `V + E` (section 1). The vertices grow about fourfold per level while the `k`
#    extraordinary ones stay, so they become rarer and rarer, isolated points in a regular
#    grid. That is why the limit surface is smooth almost everywhere, and why the
#    analysis of Loop's scheme only has to look at one extraordinary vertex at a time
#    (the sharp corners of section 8 are exactly those).

# %% [markdown]
# ## Check yourself
#
# Predict, then run: the counts of the cube after one and after two levels; where
# vertex 0 of the octahedron and the edge point of its edge 0 go; Warren's `beta` for
# degrees 3, 4 and 6; and the new position of corner vertex 0 of the flat open patch
# (neighbours along the boundary: vertices 1 and 4).

# %%
cube = hx.sample("cube")
for levels in (1, 2):
    finer = loop_subdivide(cube, levels=levels)
    print(f"cube, {levels} level(s): {finer.n_vertices} vertices, {finer.n_edges} edges, {finer.n_faces} faces")
vertex_points, edge_points = loop_positions(octahedron)
print("octahedron vertex 0 ->", vertex_points[0], " edge 0 ->", edge_points[0])
print("beta for n = 3, 4, 6:", [3 / 16 if n == 3 else 3 / (8 * n) for n in (3, 4, 6)])
patch = hx.sample("open_patch")
print("open patch corner 0:", patch.vertex(0).position, "->", loop_positions(patch)[0][0])

# %% [markdown]
# The cube (8, 18, 12) becomes 8 + 18 = 26 vertices, 2·18 + 3·12 = 72 edges and 48
# faces; a second level starts from those numbers: 26 + 72 = 98, 2·72 + 3·48 = 288,
# 192. The open patch's corner: `3/4 (0, 0, 0) + 1/8 ((1, 0, 0) + (0, 1, 0))`.

# %% [markdown]
# ## Exercises
#
# **1. The two rules.** Write `edge_point(mesh, edge)`, the new vertex on one edge,
# and `vertex_point(mesh, vertex)`, where one old vertex goes. Both read the old mesh
# and must not change it. Fill in the blanks marked `...`. You need `h.prev`,
# `h.twin`, `h.vertex`, `h.tip` and `.position`; `edge.is_boundary`,
# `vertex.is_boundary` and `vertex.neighbors()` tell you which rule applies.
#
# `check_loop_rules` compares your functions with the library on six meshes
# (degree 3, degree 4, degrees 5 and 6, a mix, a boundary, and a strip that is all
# boundary, each with its vertices nudged so that symmetry cannot hide a wrong
# weight), and explains the first difference.

# %%
def edge_point(mesh, edge):
    h = edge.halfedge
    a, b = h.vertex.position, h.tip.position
    if edge.is_boundary:
        ### BEGIN SOLUTION
        return 0.5 * (a + b)               # 1. the boundary rule
        ### END SOLUTION
    c = h.prev.vertex.position             # the corner opposite the edge in h's triangle
    ### BEGIN SOLUTION
    d = h.twin.prev.vertex.position        # 2. the corner opposite the edge in the twin's triangle
    return 0.375 * (a + b) + 0.125 * (c + d)   # 3. 3/8 of each end, 1/8 of each opposite corner
    ### END SOLUTION


def vertex_point(mesh, vertex):
    v = vertex.position
    if vertex.is_boundary:
        h = vertex.halfedge                # a boundary vertex's halfedge runs along the boundary
        after, before = h.tip.position, h.prev.vertex.position
        ### BEGIN SOLUTION
        return 0.75 * v + 0.125 * (after + before)   # 4. 3/4 of itself, 1/8 of each boundary neighbour
        ### END SOLUTION
    ring = [u.position for u in vertex.neighbors()]
    n = len(ring)
    ### BEGIN SOLUTION
    beta = 3 / 16 if n == 3 else 3 / (8 * n)   # 5. Warren's beta
    return (1 - n * beta) * v + beta * np.sum(ring, axis=0)   # 6. (1 - n beta) v + beta * (the sum of the ring)
    ### END SOLUTION

# %%
from halfedge_edu.exercises.algorithm_checks import check_loop_rules

check_loop_rules(edge_point, vertex_point)

# %% [markdown]
# ### What a mistake looks like
#
# Two classic slips: using the midpoint for every edge point, and using `3/(8n)` for
# every degree, forgetting Warren's special value for `n = 3`.

# %%
def midpoint_only(mesh, edge):
    h = edge.halfedge
    return 0.5 * (h.vertex.position + h.tip.position)


def no_special_case(mesh, vertex):
    ring = [u.position for u in vertex.neighbors()]
    n = len(ring)
    beta = 3 / (8 * n)
    return (1 - n * beta) * vertex.position + beta * np.sum(ring, axis=0)


print(check_loop_rules(edge_point=midpoint_only))
print()
print(check_loop_rules(vertex_point=no_special_case))

# %% [markdown]
# **1b. The connectivity (CS184's and CMU's `upsample`).** Write `my_upsample(mesh)` with
# the `split` and `flip` of chapter 06, by the route of section 2: split every old edge,
# then flip the new edges that join an old vertex and a new one, and return the mesh.
# The new vertices may stay at the midpoints; `check_upsample_connectivity` compares
# the triangles with `loop_subdivide`'s.

# %%
from halfedge_edu.core.ops import flip, split
from halfedge_edu.exercises.algorithm_checks import check_upsample_connectivity


def my_upsample(mesh):
    n_old_vertices = mesh.n_vertices
    ### BEGIN SOLUTION
    across = []                                   # the new edges cutting across old triangles
    for e in range(mesh.n_edges):
        ends = {int(v) for v in mesh.edge(e).vertices}
        m = split(mesh, e)
        across += [h.edge.index for h in m.outgoing() if h.tip.index not in ends]
    for e in across:
        a, b = (int(v) for v in mesh.edge(e).vertices)
        if (a < n_old_vertices) != (b < n_old_vertices):
            flip(mesh, e)
    ### END SOLUTION
    return mesh


check_upsample_connectivity(my_upsample)

# %% [markdown]
# **2. Think about it.** The octahedron shrinks with every level. Would a mesh shaped
# like a saddle (curving up one way and down the other) also shrink everywhere? Where
# does a vertex move when its neighbours lie in a plane around it, evenly spaced?
#
# **3. Counting.** A mesh has 1,000 faces and is closed. How many faces, edges and
# vertices after three levels, if it has genus 0? (Hint: on a closed triangle mesh
# `2E = 3F`.)

# %% [markdown] tags=["solution"]
# ### Answers
#
# **1.** The answers are in the exercise cell: the blanks are `0.5 * (a + b)`,
# `h.twin.prev.vertex.position`, `0.375 * (a + b) + 0.125 * (c + d)`,
# `0.75 * v + 0.125 * (after + before)`, `3 / 16 if n == 3 else 3 / (8 * n)` and
# `(1 - n * beta) * v + beta * np.sum(ring, axis=0)`.

# %% [markdown] tags=["solution"]
# **2.** No. A vertex moves towards the weighted average of its ring. On a convex
# bump that average lies inside, so the surface shrinks there; on a saddle the ring
# curves up on two sides and down on the other two, the average lies close to the
# vertex, and the vertex hardly moves. A vertex whose neighbours are evenly spread in
# a plane around it does not move at all: its ring's average is the vertex itself,
# and `(1 - n beta) v + n beta v = v`.
#
# **3.** Each level multiplies the faces by 4: 64,000 faces. On a closed mesh
# `E = 3F/2` = 96,000 edges, and with `V - E + F = 2` (genus 0), `V = 2 + 96,000 - 64,000`
# = 32,002 vertices.

# %% [markdown]
# ## Summary
#
# - One level of Loop subdivision: a 4-to-1 split of every triangle, and new
#   positions for all vertices. `V' = V + E`, `E' = 2E + 3F`, `F' = 4F`, and `V - E + F`
#   is kept.
# - The course builds the split from local operations: split every edge, then flip
#   each new edge that joins an old vertex and a new one.
# - Edge point: `3/8 (a + b) + 1/8 (c + d)`. Old vertex: `(1 - n beta) v + beta * sum`,
#   `beta = 3/16` for `n = 3`, `3/(8n)` otherwise. Boundary: midpoints, and
#   `3/4 v + 1/8 (b0 + b1)`.
# - Every new position comes from the old mesh, computed before anything changes.
# - Loop follows the triangulation, not the shape: the sample cube (corners of valence 3
#   and 5) comes out 11 % longer along one diagonal; split around the face centres it
#   stays symmetric. A vertex ends halfway to its first ring's average (3/5 of the way at
#   valence 3), so splitting the edges at a corner beforehand keeps it sharper.
#
# Next, chapter 10 runs the other way: instead of adding triangles, it removes them
# while keeping the shape, choosing each collapse by its error.
