# %% [markdown]
# # 10 · Quadric error simplification
#
# Chapter 09 made meshes finer. This one makes them coarser: it removes triangles one
# edge collapse at a time (the collapse of chapter 07, with the link condition of
# chapter 08) and keeps the shape as well as it can. The question is *which* edge to
# collapse next, and *where* to put the vertex that is left. Garland and Heckbert's
# answer (1997) measures, for every candidate, how far the new vertex would be from
# the planes of the original surface, and always takes the cheapest.
#
# **After this chapter you can**
#
# - write the plane quadric `K = p p^T` of a face and use it to measure squared
#   distance to the face's plane;
# - sum face quadrics into vertex quadrics, and price an edge collapse with `Q_a + Q_b`;
# - find the best collapse point from a 3x3 linear system, and say what to do when
#   that system is singular;
# - run the priority queue the course's way: pop the cheapest edge first, collapse,
#   then re-price and re-insert the edges around the new vertex, until a target
#   face count is reached;
# - step through the queue with the QEM stepper and read its cost heat-map.

# %%
import heapq

import numpy as np
import pyvista as pv
from IPython.display import Image

import halfedge_edu as hx
from halfedge_edu.algorithms import simplify, simplify_with_report
from halfedge_edu.algorithms.simplify import face_quadrics, optimal_points, quadric_cost
from halfedge_edu.algorithms.simplify_queue import QuadricQueue, simplify_sequential, turns_a_face
from halfedge_edu.viz.qem_stepper import QEMStepper
from halfedge_edu.viz import show

spot = hx.sample("spot")
spot_camera = [(2.6, 0.9, -2.2), (0.0, 0.1, 0.1), (0.0, 1.0, 0.0)]

picture = pv.Plotter(off_screen=True, shape=(1, 4), window_size=(920, 260), border=False)
for column, target in enumerate([spot.n_faces, 1500, 400, 100]):
    coarse = simplify(spot, target) if target < spot.n_faces else spot
    picture.subplot(0, column)
    picture.add_mesh(coarse.to_pyvista(), color="#E8B96A", show_edges=True, edge_color="#6B5B45", line_width=0.5)
    picture.add_text(f"{coarse.n_faces} faces", font_size=9)
picture.link_views()
picture.camera_position = spot_camera
show(picture)

# %% [markdown]
# Spot the cow with all 5,856 of her triangles, then with 1,500, 400 and 100. Even with
# 100 triangles she is recognisably Spot: the collapses went first where the surface
# is nearly flat (the flanks), and last where it bends sharply (ears, horns, legs).
# Look at where the remaining small triangles are at 400: that is where the shape is.

# %% [markdown]
# ## The idea
#
# 1. Every face lies in a plane. The squared distance of a point `x` to that plane is a
#    quadratic function of `x`, written as a 4x4 matrix `K` (a *quadric*).
# 2. A vertex starts with `Q`, the sum of the quadrics of its faces. `[x, 1] Q [x, 1]^T`
#    then says how far `x` is from all the planes the vertex was on.
# 3. Collapsing edge `a b` to a point `x` costs `[x, 1] (Q_a + Q_b) [x, 1]^T`; the best
#    `x` solves a 3x3 linear system.
# 4. Keep every edge in a priority queue by its cost. Pop the cheapest, collapse it,
#    give the new vertex `Q_a + Q_b`, re-price the edges around it, and repeat until the
#    mesh has the target number of faces.

# %% [markdown]
# ## 1. The plane quadric of one face
#
# **Convention: a plane is `n . x + d = 0` with `n` of length 1, written as
# `p = [n_x, n_y, n_z, d]`; its quadric is `K = p p^T`, and `[x, 1] K [x, 1]^T = (n . x + d)^2`
# is the squared distance from `x` to the plane.**
#
# The unit normal comes from chapter 05: `(b - a) x (c - a)`, divided by its length.
# Then `d = -n . a`, so that every point of the plane, `a` included, gives 0. A
# triangle in the plane `z = 2`:

# %%
a, b, c = np.array([0.0, 0.0, 2.0]), np.array([2.0, 0.0, 2.0]), np.array([0.0, 3.0, 2.0])
n = np.cross(b - a, c - a)
n = n / np.linalg.norm(n)
p = np.append(n, -n @ a)
K = np.outer(p, p)
print("p =", p)
print("K =\n", K + 0.0)                        # + 0.0 turns a printed -0. into 0.
for x in ([1.0, 1.0, 2.0], [1.0, 1.0, 5.0], [-7.0, 4.0, 1.0]):
    h = np.append(x, 1.0)                       # homogeneous: [x, y, z, 1]
    print(f"x = {x}: [x, 1] K [x, 1]^T = {h @ K @ h:g}")

# %% [markdown]
# A point in the plane costs 0; a point 3 above it costs 9; a point 1 below it costs
# 1, however far sideways it is. The quadric measures distance to the whole infinite
# plane, not to the triangle.
#
# The library's `face_quadrics` returns the same matrix for every face at once, with
# one difference: it multiplies each `K` by the face's area, so a big face counts
# more than a sliver and the result does not depend on how finely a flat region was
# triangulated.

# %%
library_K = face_quadrics(np.array([a, b, c]), np.array([[0, 1, 2]]))[0]
area = 0.5 * np.linalg.norm(np.cross(b - a, c - a))
print("area:", area, " library K / area == K:", np.allclose(library_K / area, K))

# %% [markdown]
# ## 2. Vertex quadrics and the price of a collapse
#
# **Convention: a vertex's quadric `Q_v` is the sum of its faces' (area-weighted)
# quadrics; collapsing edge `a b` to `x` costs `[x, 1] (Q_a + Q_b) [x, 1]^T`.**
#
# A vertex lies on the planes of all its faces, so at its own position its quadric
# costs 0. Move it and the cost grows with the squared distance to those planes:

# %%
queue = QuadricQueue(spot.copy())               # builds every vertex quadric (and prices every edge)
Q = queue.quadrics                              # (V, 4, 4)
at_home = quadric_cost(Q, spot.positions)       # (V,) every vertex at its own position
print("every vertex costs (nearly) 0 at its own place:", bool(np.all(np.abs(at_home) < 1e-12)))
v = 100
normal = hx.vertex_normals(spot)[v]
for step in (0.001, 0.01, 0.1):
    moved = spot.positions[v] + step * normal
    print(f"vertex {v} moved {step} along its normal: cost {quadric_cost(Q[[v]], moved[None])[0]:.3g}")

# %% [markdown]
# Ten times further costs a hundred times more: squared distance. ("Nearly" 0 in the
# first line because adding up a few dozen products leaves rounding errors around
# `1e-18`.)
#
# Why *sum* the quadrics? Because `[x, 1] (K_1 + K_2) [x, 1]^T` is the sum of the
# squared distances to plane 1 and plane 2. And when an edge collapses, the new vertex
# gets `Q_a + Q_b`: it remembers the planes of *both* ends, and through them the
# planes of every vertex merged into it before. That memory is what makes the error
# of a long sequence of collapses add up honestly.

# %% [markdown]
# ## 3. The best point, and when there is none
#
# **Convention: write `Q` as `[[A, q], [q^T, r]]` with `A` its top-left 3x3 block; the
# cost is smallest where `A x = -q`. When `A` is singular, use the midpoint of the edge.**
#
# The cost is a quadratic bowl in `x`, and the bottom of a bowl is where its gradient
# `2 (A x + q)` is zero. Take the cube's edge 0, from the corner `(0, 0, 0)` up to
# `(0, 0, 1)`. Its two ends lie on the planes `x = 0` and `y = 0`, on the floor `z = 0`
# (vertex 0) and the ceiling `z = 1` (vertex 4):

# %%
cube = hx.sample("cube")
cube_queue = QuadricQueue(cube.copy())
a, b = (v.index for v in cube.edge(0).vertices)
Q_edge = cube_queue.quadrics[a] + cube_queue.quadrics[b]
A, q = Q_edge[:3, :3], Q_edge[:3, 3]
best = np.linalg.solve(A, -q)
print("edge 0 joins", cube.vertex(a).position, "and", cube.vertex(b).position)
print("det(A) =", np.linalg.det(A).round(4), " best point:", best + 0.0, " cost:", quadric_cost(Q_edge[None], best[None])[0])

# %% [markdown]
# The best point stays on both walls (`x = 0`, `y = 0`) and goes halfway between floor
# and ceiling, because it cannot be on both: the cost 0.25 is the price of cutting
# that corner. The queue prices this edge the same way:

# %%
print("queue's price of edge 0:", cube_queue.price(0)[0], cube_queue.price(0)[1] + 0.0)

# %% [markdown]
# Now a flat region. Every face around an interior edge of the open patch lies in the
# plane `z = 0`, so `A` has rank 1: every point of that plane costs 0, and `A x = -q`
# has no single solution (`np.linalg.solve` would raise `LinAlgError`). The course
# takes the midpoint, and so does the library here.

# %%
patch = hx.sample("open_patch")
patch_queue = QuadricQueue(patch.copy())
edge = patch.find_edge(5, 6)
A = (patch_queue.quadrics[5] + patch_queue.quadrics[6])[:3, :3]
print("rank of A:", np.linalg.matrix_rank(A), " det(A) is 0:", abs(np.linalg.det(A)) < 1e-12)
cost, point = patch_queue.price(edge.index)
print("vertices 5 and 6 at", patch.vertex(5).position, patch.vertex(6).position, "-> point", point, "cost", cost)

# %% [markdown]
# *Nearly* flat is the harder case. Three planes a twentieth of a degree apart can be
# solved, but they meet far from the edge, and a vertex moved there would fold every
# triangle around it:

# %%
def plane(normal, point):
    normal = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    p = np.append(normal, -normal @ point)
    return np.outer(p, p)


tilt = np.radians(0.05)
Q_nearly_flat = (plane([0, 0, 1], [0, 0, 0]) + plane([np.sin(tilt), 0, np.cos(tilt)], [0, 0, 0.01])
                 + plane([0, np.sin(tilt), np.cos(tilt)], [0, 0, -0.01]))
A, q = Q_nearly_flat[:3, :3], Q_nearly_flat[:3, 3]
ends = np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]])
print("edge from (0, 0, 0) to (1, 0, 0)")
print("exact solution of A x = -q:", np.linalg.solve(A, -q).round(2))
print("the library's point:       ", optimal_points(Q_nearly_flat[None], *ends)[0][0].round(3))

# %% [markdown]
# So the library adds a small pull towards the midpoint `m`: it minimizes the cost
# plus `eps |x - m|^2`, with `eps` a ten-thousandth of `A`'s trace, by solving
# `(A + eps I) x = -q + eps m`. Then it takes the pull back out twice,
# `x += (A + eps I)^-1 (-q - A x)`, which leaves the exact answer wherever the planes
# really decide it (the cube's edge above, any corner) and the midpoint wherever they
# do not (a flat region, or planes a fraction of a degree apart). Along a crease it
# gives the point of the crease line nearest the midpoint.

# %% [markdown]
# ## 4. The priority queue
#
# **Convention: pop the cheapest edge *before* changing anything; if it may be
# collapsed, collapse it; then remove the entries of the edges around the new vertex
# and insert them again with their new prices. Stop when the mesh has the target
# number of faces.**
#
# Python's `heapq` keeps a list ordered so that the smallest entry comes out first.
# Entries are tuples, compared element by element, so `(cost, edge)` pops the
# cheapest edge:

# %%
heap = []
for cost, e in [(0.30, 7), (0.02, 3), (0.50, 1), (0.02, 9)]:
    heapq.heappush(heap, (cost, e))
print([heapq.heappop(heap) for _ in range(4)])

# %% [markdown]
# One detail needs care. After a collapse, the edges around the new vertex have new
# prices, but their old entries are still somewhere inside the heap, and a binary heap
# cannot remove an entry from its middle cheaply. The library's `QuadricQueue`
# therefore *marks* them instead: each edge has a stamp that goes up whenever it is
# re-priced, each entry remembers the stamp it was pushed with, and `pop()` drops
# entries whose stamp is out of date (and entries of deleted edges) without looking at
# them. The effect is exactly "remove, then re-insert"; the cost is a few stale
# entries left in the list.
#
# Here is the whole loop, written out with `QuadricQueue`'s pieces. Every line is one
# sentence of the convention above:

# %%
small = simplify(spot, 800)                     # a lighter Spot to work on (the fast version, see below)

work = small.copy()
queue = QuadricQueue(work)
max_normal_cos = np.cos(np.radians(80.0))
done = []
while len(done) < 5:
    cost, e = queue.pop()                       # 1. pop the cheapest edge first
    point = queue.point[e]
    if not work.can_collapse(e) or turns_a_face(work, e, point, max_normal_cos):
        continue                                #    not allowed: drop it, pop the next one
    a, b = (v.index for v in work.edge(e).vertices)
    merged = queue.quadrics[a] + queue.quadrics[b]
    kept = work.collapse(e, point).index        # 2. collapse to the best point
    queue.quadrics[kept] = merged               # 3. the survivor remembers both ends' planes
    for h in work.vertex(kept).outgoing():      # 4. re-price the edges around it and push them again
        queue.push(h.edge.index)
    done.append((e, kept, cost))

records = []
simplify_sequential(small, 1, max_steps=5, on_step=records.append)
for (e, kept, cost), record in zip(done, records):
    print(f"ours: edge {e:4d} into vertex {kept:3d}, cost {cost:.3g}   library: {record.describe()}")

# %% [markdown]
# The five collapses agree with `simplify_sequential`, the library's version of the
# same loop. Besides the link condition of chapter 08 (`can_collapse`), there is a
# geometric check: `turns_a_face` refuses a collapse that would swing a face's normal
# by more than 80 degrees, because a face turned over is a fold in the surface that
# no quadric sees.

# %% [markdown]
# ## 5. Try it: the QEM stepper
#
# The stepper runs `simplify_sequential` from 800 faces down to 100 and lets you walk
# through it. Every edge is coloured by what it would cost to collapse *now* (`log10`
# of the cost): dark edges are cheap, bright ones expensive. The colour bar runs from
# the first collapse's cost to the last one's, so an edge in the brightest yellow will
# still be there at the end.
#
# On top: the edge the queue pops next (**vermillion**), the next few in the queue
# (**purple**), and, after a collapse, the new vertex with the edges around it that were
# re-priced and pushed again (**black**). The panel lists the head of the queue with
# the costs. Spot is seen from behind, because her flat rump is where the first
# collapses happen. Press **step** a few times, then **+10** and **+100**, and watch the
# dark edges disappear first.

# %%
stepper = QEMStepper(small, 100, view_direction=(-1.8, 0.9, 2.4))   # from behind: the first collapses are there
stepper

# %% [markdown]
# From code, on a second stepper of the same run (the one above stays where you leave
# it): two single collapses, then jumps.

# %%
driven = QEMStepper(small, 100, view_direction=(-1.8, 0.9, 2.4), mode="static")   # shown as a picture only
driven.step()
driven.step()
print(driven.describe())
print()
driven.jump(100)
print(driven.describe())

# %%
driven.go("end")
print(driven.describe())
Image(driven.screenshot())

# %% [markdown]
# Read the costs down the run: the first collapse costs less than `1e-7`, the last ones
# nearly `1e-3`. The queue always takes the cheapest edge there is, and a collapse
# usually makes the edges around it more expensive (their vertices now carry more
# planes), so the cost creeps upwards. At the end nearly every edge left is in the
# brightest colour: it would cost at least as much as anything collapsed so far.
#
# Sometimes the head of the queue is *skipped*. `skipped_steps()` lists where:

# %%
skipped = driven.skipped_steps()
print("the queue's cheapest edge is skipped after collapse", ", ".join(str(k) for k in skipped))
driven.go(skipped[0])
print(driven.describe())

# %% [markdown]
# The cheapest edge would turn a face over: its best point lies beyond the fan of
# triangles around one of its ends, so one of them would flip upside down. The queue
# drops the entry and pops the next one. Later, as the mesh gets coarser, the link
# condition of chapter 08 starts to bite too:

# %%
for k in skipped:                          # the first skip that the link condition causes
    driven.go(k)
    if "not allowed" in driven.describe():
        break
print(driven.describe())

# %% [markdown]
# Here the ends of the cheapest edge share a third neighbour, so collapsing it would
# pinch the surface. Either way, a skipped edge is not lost for good: if a later
# collapse next to it changes its ring, it is re-priced and pushed again.

# %% [markdown]
# ## 6. The target is a face count
#
# **Convention: stop as soon as the mesh has at most the target number of faces.**
#
# An interior collapse removes exactly two faces, so the result has the target, or
# one fewer when the count would step over it. If no allowed collapse is left before
# that, the loop stops early and warns.

# %%
for target in (200, 201):
    print(f"target {target}: {simplify_sequential(small, target).n_faces} faces")

# %% [markdown]
# The library has a second, faster implementation, `simplify`, which prices every
# edge at once with numpy and collapses many cheap, well-separated edges per *round*.
# It follows the same rules and checks, though its order of collapses differs a little
# from the queue's, and it is the one to use on large meshes (the picture at the top
# used it, and so did `small`). `simplify_with_report` does the same work and also
# says what it did:

# %%
for target in (1500, 400, 100):
    coarse, report = simplify_with_report(spot, target)
    print(report)

# %% [markdown]
# ## Check yourself
#
# Predict, then run: the quadric of the plane `z = 2` at the point `(1, 1, 5)`; the best
# point and cost of collapsing the cube's edge 0; how many collapses it takes to go
# from 800 faces to 100; and the face count after asking for 201.

# %%
p = np.array([0.0, 0.0, 1.0, -2.0])
x = np.array([1.0, 1.0, 5.0, 1.0])
print("plane z = 2, point (1, 1, 5):", x @ np.outer(p, p) @ x)
cost, point = QuadricQueue(hx.sample("cube")).price(0)
print("cube edge 0: best point", point + 0.0, "cost", cost)
print("collapses from 800 to 100 faces:", stepper.n_steps)
print("faces after asking for 201:", simplify_sequential(small, 201).n_faces)

# %% [markdown]
# `(5 - 2)^2 = 9`. The cube edge goes to `(0, 0, 0.5)` for 0.25. Each collapse removes two
# faces, so 700 faces need 350 collapses; asking for 201 gives 200.

# %% [markdown]
# ## Exercises
#
# **1. The plane quadric.** Write `plane_quadric(a, b, c)`: the 4x4 quadric `K = p p^T` of
# the plane through the triangle `a, b, c`, *without* the area weight. Fill in the
# blanks. `check_plane_quadric` tries five triangles (flat, raised, tilted, away from
# the origin, long and thin) and explains the first difference.

# %%
def plane_quadric(a, b, c):
    ### BEGIN SOLUTION
    n = np.cross(b - a, c - a)               # 1. the normal, by the right-hand rule
    n = n / np.linalg.norm(n)                # 2. ... scaled to length 1
    d = -n @ a                               # 3. so that n . a + d = 0
    ### END SOLUTION
    p = np.append(n, d)
    return np.outer(p, p)

# %%
from halfedge_edu.exercises.algorithm_checks import check_optimal_point, check_plane_quadric

check_plane_quadric(plane_quadric)

# %% [markdown]
# **2. The best point.** Write `optimal_point(Q, a, b)`: the point where the edge `a b`
# should collapse under the quadric `Q`. Solve `A x = -q`; when `A` is singular
# (`abs(np.linalg.det(A))` below `1e-9`, say), return the midpoint. The check tries the
# corner of a box, three tilted planes, an edge of an icosphere, a flat region and a
# ridge.

# %%
def optimal_point(Q, a, b):
    A = Q[:3, :3]
    q = Q[:3, 3]
    ### BEGIN SOLUTION
    singular = abs(np.linalg.det(A)) < 1e-9  # 4. when is A singular?
    ### END SOLUTION
    if singular:
        ### BEGIN SOLUTION
        return 0.5 * (a + b)                 # 5. the fallback
        ### END SOLUTION
    ### BEGIN SOLUTION
    return np.linalg.solve(A, -q)            # 6. the solution of A x = -q
    ### END SOLUTION

# %%
check_optimal_point(optimal_point)

# %% [markdown]
# ### What a mistake looks like
#
# Forgetting to divide the normal by its length, and solving without a fallback:

# %%
def unnormalized(a, b, c):
    n = np.cross(b - a, c - a)
    p = np.append(n, -n @ a)
    return np.outer(p, p)


print(check_plane_quadric(unnormalized))
print()
print(check_optimal_point(lambda Q, a, b: np.linalg.solve(Q[:3, :3], -Q[:3, 3])))

# %% [markdown]
# **2b. The whole loop (CMU's downsampling).** Write `my_downsample(mesh, target_faces)`
# with your `optimal_point`, a heap (`heapq`) and the library's `can_collapse` and
# `collapse(mesh, e, position=x)`. The quadrics, the vertex versions and `push(e)` are
# there; write the loop. An entry is stale when either end of its edge has changed since
# it was pushed. `check_downsample` asks for what the loop must achieve: the target face
# count, a flat-faced cube reduced to its exact corners, a sphere that keeps its shape.

# %%
from halfedge_edu.core.ops import can_collapse, collapse
from halfedge_edu.exercises.algorithm_checks import check_downsample


def my_downsample(mesh, target_faces):
    mesh = mesh.copy()
    corners = mesh.face_vertices()                                       # (F, 3)
    K = face_quadrics(mesh.positions, corners)                           # (F, 4, 4)
    Q = np.zeros((mesh.n_vertex_slots, 4, 4))
    for f in range(len(corners)):
        for v in corners[f]:
            Q[v] += K[f]                                                 # each vertex: the sum of its faces'
    version = np.zeros(mesh.n_vertex_slots, dtype=int)                  # bumped when a vertex changes
    heap, pushed = [], 0

    def push(e):
        nonlocal pushed
        a, b = (int(v) for v in mesh.edge(e).vertices)
        Qe = Q[a] + Q[b]
        x = optimal_point(Qe, mesh.positions[a], mesh.positions[b])
        cost = float(np.append(x, 1.0) @ Qe @ np.append(x, 1.0))
        heapq.heappush(heap, (cost, pushed, e, a, b, version[a], version[b], x))
        pushed += 1

    # 1. every edge into the queue, with its best point and cost
    # 2. pop the cheapest; skip it if it is stale (an end changed since) or may not collapse
    # 3. collapse it to its best point; the survivor's quadric is the sum of both ends'
    # 4. re-insert the edges around the survivor with their new costs
    ### BEGIN SOLUTION
    for edge in mesh.edges:                                              # 1
        push(edge.index)
    while mesh.n_faces > target_faces and heap:
        cost, _, e, a, b, version_a, version_b, x = heapq.heappop(heap)  # 2
        if mesh.edge_deleted[e] or (version[a], version[b]) != (version_a, version_b):
            continue
        if not can_collapse(mesh, e):
            continue
        survivor = collapse(mesh, e, position=x).index                   # 3
        Q[survivor] = Q[a] + Q[b]
        version[a] += 1                                                  # both ends changed: their
        version[b] += 1                                                  # old entries are stale
        for h in mesh.vertex(survivor).outgoing():                       # 4
            push(h.edge.index)
    ### END SOLUTION
    mesh.garbage_collect()
    return mesh


check_downsample(my_downsample)

# %% [markdown]
# **3. Think about it.** Why does the queue need the *stamps* at all? What would go
# wrong if stale entries were popped and collapsed as if they were current?
#
# **4. Area weights.** A flat square is cut into 2 triangles in one mesh and into 200
# in another. Without area weights, how would the vertex quadrics of the two meshes
# differ, and why would that be a problem?

# %% [markdown] tags=["solution"]
# ### Answers
#
# **1 and 2.** The answers are in the exercise cells.

# %% [markdown] tags=["solution"]
# (A fixed `1e-9` is fine for these small cases. The library needs no threshold at all:
# its pull `eps` is a fraction of `A`'s trace, so a mesh measured in millimetres is
# treated like the same mesh in metres, and `A + eps I` can always be solved.)
#
# **3.** A stale entry carries an old cost and an old best point. Collapsing it would
# use a point computed for vertices that have since moved or merged, and its cost
# would put it in the wrong place in the order: an edge that became expensive would
# be collapsed as if it were still cheap. Worse, the edge may no longer exist at all.
# The stamp check throws such entries away; the current entry for the same edge,
# pushed at the re-pricing, comes out at the right time.
#
# **4.** Each vertex quadric would count faces instead of area. A vertex in the finely
# cut square would carry about a hundred times "more plane" than in the coarse one, so
# moving it off the plane would look a hundred times more expensive, and the order of
# collapses would depend on how the mesh happened to be triangulated rather than on
# its shape. With area weights both squares give the same quadrics for the same
# surface.

# %% [markdown]
# ## Summary
#
# - A face's plane `p = [n, d]` (unit `n`, `d = -n . a`) gives the quadric `K = p p^T`, and
#   `[x, 1] K [x, 1]^T` is the squared distance to the plane. The library weights `K` by area.
# - A vertex's `Q` is the sum of its faces' quadrics; a collapse of `a b` to `x` costs
#   `[x, 1] (Q_a + Q_b) [x, 1]^T`, and the survivor keeps `Q_a + Q_b`.
# - The best `x` solves `A x = -q`; when `A` is singular (flat or straight regions), take
#   the midpoint. The library adds a small pull towards the midpoint, so that nearly
#   flat regions do not send the point far off the edge.
# - The queue: pop the cheapest edge first; skip it if the collapse is not allowed;
#   collapse; re-price and re-insert the edges around the new vertex (stamps mark the
#   old entries stale); stop at the target face count.
#
# Next, chapter 11 combines splits, collapses, flips and smoothing to *remesh*: to make
# all triangles about the same size and shape.
