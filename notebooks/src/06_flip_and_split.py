# %% [markdown]
# # 06 · Edge flip and edge split
#
# So far we have built meshes and walked on them. From here on we *edit* them. The two
# simplest edits change one edge and the two triangles beside it, and nothing else:
# the **flip** turns an edge inside its two triangles, the **split** cuts it in half.
# Every later algorithm in this course (subdivision, remeshing) is built from these two
# and the collapse of chapter 07.
#
# **By the end of this chapter you can**
#
# - name the six halfedges, four vertices and two faces a flip gathers, and say which
#   pointers it rewrites;
# - say why a flip keeps every count, and why a split adds 1 vertex, 3 edges and 2 faces;
# - say when a flip must be refused (boundary edge, an edge that already exists, the
#   tetrahedron), and read the reason the library gives;
# - explain why both operations take the same time on a 10-triangle mesh and on a cow;
# - write `flip` yourself and have `check_flip` tell you what is off.

# %%
import numpy as np

import halfedge_edu as hx
from halfedge_edu.core.ops import OperationLog, can_flip, can_split, flip, split
from halfedge_edu.viz import FlipStepper, SplitStepper, created_roles, named_picture, side_by_side

strip = hx.sample("strip")
log = OperationLog()
flipped = strip.copy()
flip(flipped, 1, log=log)
quad = [index for name, (kind, index) in log.named.items() if kind == "halfedge"]
side_by_side(
    [named_picture(strip, log, {"named": quad}), named_picture(flipped, log, {"named": quad})],
    ["before: edge 1 joins v0 and v1", "after flip(1): edge 1 joins v2 and v3"],
)

# %% [markdown]
# The `strip` sample: three triangles in a row. Edge 1 is the diagonal between the
# first two; the flip turns it to the other diagonal of the quadrilateral they make.
# The blue arrows are the six halfedges the flip works on; every label keeps its name
# from before to after, so you can follow where each halfedge went. A label such as
# `v0 (1)` reads "the flip calls it v0; in the mesh it is vertex 1", and `h0 (2)` is
# halfedge 2. Only the flip's names are written, so `h1` always means the flip's `h1`
# (halfedge 3), never halfedge 1; a plain `v4` is vertex 4, which the flip does not touch
# (and `v3` is both the flip's `v3` and vertex 3).

# %% [markdown]
# ## 1. The flip
#
# **Convention: the two triangles beside edge `v0 – v1` form a quadrilateral
# `v0 v3 v1 v2`; a flip replaces the diagonal `v0 – v1` by the other diagonal
# `v2 – v3`, reusing the same edge, its two halfedges and both faces.**
#
# The names are those of `halfedge_edu/core/ops/flip.py`, which you can read top to bottom:
#
# ```
#             before                               after
#
#               v2                                   v2
#             /    ^                               / ^|  ^
#         h3 /      \ h2                        h3 / h0|h1 \ h2
#           v   f0   \                            v   ||v   \
#        v0 --- h0 ---> v1                     v0  f0 ||  f1  v1
#           <-- h1 ----                           \   ||    ^
#           \   f1   ^                          h4 \  ||   / h5
#         h4 v      / h5                           v |v  /
#               v3                                   v3
#
#     h0 = 2e runs v0 -> v1, h1 = 2e + 1 is its twin; f0 = face(h0), f1 = face(h1)
#     h2 = next(h0), h3 = prev(h0), h4 = next(h1), h5 = prev(h1)
#     after: h0 runs v3 -> v2 in f0 = (h0, h3, h4); h1 runs v2 -> v3 in f1 = (h1, h5, h2)
# ```
#
# A flip is done in two moves. First **gather**: read every element the flip needs
# into a named variable, before anything changes. Then **rewire**: write the new
# pointers. The library records both in an `OperationLog`:

# %%
print(log.describe())

# %% [markdown]
# Read the pointer diff against the picture:
#
# - `h0` and `h1` change the vertex they leave: the edge now runs between `v3` and `v2`.
# - The two triangles are relinked: `f0` is now `h0 → h3 → h4` and `f1` is
#   `h1 → h5 → h2`. Each `next` write comes with the matching `prev` write.
# - `h4` has moved from `f1` into `f0` and `h2` the other way, so their `face` changes.
# - `v0` and `v1` each lose an edge. If a vertex's `halfedge` was the one that just
#   left it, it must point at another outgoing halfedge. On the strip neither was, so
#   the last phase has nothing to do; on other meshes it does (the exercise will find
#   out whether you remembered).
#
# Nothing is created and nothing is deleted, so the counts stay, and so does V − E + F:

# %%
for name, mesh in (("before", strip), ("after", flipped)):
    print(f"{name:6s}: V = {mesh.n_vertices}, E = {mesh.n_edges}, F = {mesh.n_faces}, "
          f"V - E + F = {mesh.euler_characteristic}")
flipped.validate()
print("valid after the flip; edge 1 now joins", [int(v) for v in flipped.edge(1).vertices])

# %% [markdown]
# ### Step through it
#
# The stepper below replays the same log one pointer change at a time: step 0 shows
# the gathered elements; every step after that highlights the pointer that changes,
# its old target and its new one. In the middle of the flip the mesh is *not* valid
# (a triangle may briefly be a loop of two halfedges): that is normal; only the end
# result has to be.

# %%
stepper = FlipStepper(strip, 1, window_size=(480, 360))
stepper

# %% [markdown]
# Every widget here can also be driven from code, which is how this notebook checks
# itself. A second stepper of the same flip (so the one above stays at step 0): step
# twice, then jump to the start of the next phase:

# %%
driven = FlipStepper(strip, 1, mode="static")   # never shown: no live view
driven.step()
driven.step()
print(driven.describe())
print()
driven.go("phase")
print(driven.describe())
driven.close()

# %% [markdown]
# ## 2. When a flip is refused
#
# **Convention: `can_flip(mesh, e)` looks without touching; it is falsy when the flip
# would break the mesh, and its `.reason` says why, naming the elements.**
#
# Three cases, each on a sample mesh:
#
# - a **boundary edge** has a triangle on one side only, so there is no quadrilateral;
# - on the cube, edge 0 touches vertex 0, which has only 3 edges. Its two opposite
#   vertices, 1 and 2, are *already* joined, so the flip would make a second edge
#   between them (and leave vertex 0 with 2 edges);
# - on a **tetrahedron** every pair of vertices is already joined, so no edge can flip.

# %%
cube = hx.sample("cube")
tetrahedron = hx.sample("tetrahedron")
for name, mesh, e in (("strip", strip, 0), ("cube", cube, 0), ("tetrahedron", tetrahedron, 0)):
    check = can_flip(mesh, e)
    print(f"{name}, edge {e}: allowed = {bool(check)}, rule = {check.rule}")
    print(f"  {check.reason}")

# %% [markdown]
# Calling `flip` anyway raises `hx.TopologyError` with the same reason, and leaves the
# mesh exactly as it was:

# %% tags=["raises-exception"]
strip.flip(0)

# %%
strip.validate()
print("strip after the refused flip:", strip)

# %% [markdown]
# ## 3. The split
#
# **Convention: a split puts a new vertex `m` on the edge (at its midpoint unless you
# say otherwise) and joins it to the vertices opposite the edge: an interior edge gains
# 1 vertex, 3 edges and 2 faces, a boundary edge 1 vertex, 2 edges and 1 face.**

# %%
split_inside, split_boundary = strip.copy(), strip.copy()
log_inside, log_boundary = OperationLog(), OperationLog()
split(split_inside, 1, log=log_inside)
split(split_boundary, 0, log=log_boundary)


side_by_side(
    [named_picture(mesh, log, created_roles(log), size=(420, 320), only_created=True)
     for mesh, log in ((split_inside, log_inside), (split_boundary, log_boundary))],
    ["split(1): interior edge 1", "split(0): boundary edge 0"],
)

# %% [markdown]
# Both start from the strip of the first picture. The new halfedges, vertex and faces
# are green. On the left, interior edge 1 has become two edges (the old index keeps the
# `v0` half) and `m` is joined to both opposite vertices: two triangles became four. On
# the right, boundary edge 0 had one triangle, which became two, and the boundary loop
# now runs through `m`.
#
# The names follow the flip's, plus `m` and the new halfedges `h_mX` (from `m` to `vX`)
# and their twins `h_Xm`; the picture is at the top of `halfedge_edu/core/ops/split.py`.

# %%
for name, mesh, log in (("interior edge 1", split_inside, log_inside), ("boundary edge 0", split_boundary, log_boundary)):
    made = {kind: sum(1 for k, _ in log.created if k == kind) for kind in ("vertex", "edge", "face")}
    print(f"split of {name}: new vertices {made['vertex']}, new edges {made['edge']}, new faces {made['face']}; "
          f"V - E + F = {strip.euler_characteristic} -> {mesh.euler_characteristic}")
    mesh.validate()

# %% [markdown]
# Why +1 − 3 + 2 = 0? The vertex and the two faces are balanced by exactly three new
# edges: the second half of the old edge and the two cuts towards the opposite
# vertices. (At the boundary: +1 − 2 + 1.) Local edits that keep V − E + F are exactly
# the ones that do not change the kind of surface.
#
# The split stepper shows the same log one step at a time; here it is driven to the
# end; its text says what the last step did:

# %%
split_stepper = SplitStepper(strip, 1, window_size=(480, 360))
split_stepper.go("end")
split_stepper

# %% [markdown]
# ## 4. Constant work
#
# **Convention: a local operation reads and writes a fixed handful of pointers near
# the edge, so its cost does not depend on the size of the mesh.**
#
# You can see it in the logs: flipping or splitting an edge of Spot (5,856 faces) makes
# about as many pointer changes as on the 3-triangle strip. (The exact number varies by
# one or two, depending on whether a vertex's `halfedge` had to move.)

# %%
spot = hx.sample("spot")
rng = np.random.default_rng(0)
flips, splits = set(), set()
for e in rng.permutation(spot.n_edges)[:30]:
    log = OperationLog()
    if can_flip(spot, int(e)):
        flip(spot, int(e), log=log)
        flips.add(len(log.changes))
    log = OperationLog()
    split(spot, int(e), log=log)
    splits.add(len(log.changes))
spot.validate()

log = OperationLog()
flip(strip.copy(), 1, log=log)
print("pointer changes per flip:  strip", len(log.changes), "| spot", sorted(flips))
log = OperationLog()
split(strip.copy(), 1, log=log)
print("pointer changes per split: strip", len(log.changes), "| spot", sorted(splits))

# %% [markdown]
# ## Check yourself
#
# Predict before you run: after flipping edge 1 of the strip, what are the degrees of
# `v0, v1, v2, v3`? Which rule refuses a flip of the cube's edge 0? How many vertices,
# edges and faces does the cube have after splitting edge 1, and after splitting that
# edge's half again?

# %%
before = hx.sample("strip")
after = before.copy()
log = OperationLog()
flip(after, 1, log=log)
for name in ("v0", "v1", "v2", "v3"):
    v = log.named[name][1]
    print(f"{name} = vertex {v}: degree {before.vertex(v).degree} -> {after.vertex(v).degree}")
print("cube edge 0:", can_flip(hx.sample("cube"), 0).rule)

cube = hx.sample("cube")
m = split(cube, 1)
print("cube after one split:  V, E, F =", cube.n_vertices, cube.n_edges, cube.n_faces)
split(cube, cube.find_edge(m, 2))
print("cube after two splits: V, E, F =", cube.n_vertices, cube.n_edges, cube.n_faces,
      "| V - E + F =", cube.euler_characteristic)

# %% [markdown]
# A flip takes one edge from each end of the old edge and gives one to each opposite
# vertex, so `v0` and `v1` lose a degree and `v2` and `v3` gain one. The cube's edge 0
# is refused by `edge-exists`. Each interior split adds 1, 3 and 2: from (8, 18, 12) to
# (9, 21, 14) to (10, 24, 16), with V − E + F = 2 all along.

# %% [markdown]
# ## Exercise: write the flip
#
# Fill in `my_flip(mesh, e)`: it flips interior edge `e` (an int) in place by writing
# the arrays `mesh.halfedge_next`, `halfedge_prev`, `halfedge_vertex`, `halfedge_face`,
# `vertex_halfedge` and `face_halfedge`. The gathering is done for you with the names of
# the picture above; the rewiring is yours, in four steps. (The check only gives you
# edges that may be flipped, so you need not test `can_flip`.)
#
# `check_flip(my_flip)` runs your function on copies of the strip, the cube,
# `single_collapse` and six random flips on an icosphere, compares each result with the
# library's flip, and at the first difference tells you what is wrong and with which
# element, by its name in the picture.

# %%
def my_flip(mesh, e):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face

    # gather (done for you)
    h0, h1 = 2 * e, 2 * e + 1
    h2, h3 = nxt[h0], prv[h0]
    h4, h5 = nxt[h1], prv[h1]
    v0, v1, v2, v3 = origin[h0], origin[h1], origin[h3], origin[h5]
    f0, f1 = face[h0], face[h1]

    # 1. turn the edge: h0 now leaves v3, h1 now leaves v2
    # 2. relink: f0 = (h0, h3, h4) and f1 = (h1, h5, h2); set next AND prev
    # 3. h4 now lies in f0, h2 in f1; let f0 and f1 point at h0 and h1
    # 4. if v0's halfedge was h0 (or v1's was h1), give it another outgoing halfedge
    ### BEGIN SOLUTION
    origin[h0], origin[h1] = v3, v2                                         # 1
    for a, b in ((h0, h3), (h3, h4), (h4, h0), (h1, h5), (h5, h2), (h2, h1)):
        nxt[a], prv[b] = b, a                                               # 2
    face[h4], face[h2] = f0, f1                                             # 3
    mesh.face_halfedge[f0], mesh.face_halfedge[f1] = h0, h1
    if mesh.vertex_halfedge[v0] == h0:                                      # 4
        mesh.vertex_halfedge[v0] = h4
    if mesh.vertex_halfedge[v1] == h1:
        mesh.vertex_halfedge[v1] = h2
    ### END SOLUTION

# %%
from halfedge_edu.exercises import check_flip

check_flip(my_flip)

# %% [markdown]
# ### Exercise 2: write the split
#
# The split is CS184's and CMU's second local operation. Write `my_split(mesh, e)` for an
# **interior** edge `e`, with the names of the picture in section 3. New elements come
# from `mesh.add_vertex(position)`, `mesh.add_edge(a, b)` (halfedge `2e` runs a -> b,
# `2e + 1` is its twin) and `mesh.add_face(halfedge)`. Adding may grow the arrays, so
# read `mesh.halfedge_next` and the others only after the last `add_`. `check_split`
# runs it on the strip, the cube and random splits on an icosphere.

# %%
from halfedge_edu.exercises import check_split


def my_split(mesh, e):
    # gather (done for you): the flip's names
    h0, h1 = 2 * e, 2 * e + 1
    h2, h3 = int(mesh.halfedge_next[h0]), int(mesh.halfedge_prev[h0])
    h4, h5 = int(mesh.halfedge_next[h1]), int(mesh.halfedge_prev[h1])
    v0, v1 = int(mesh.halfedge_vertex[h0]), int(mesh.halfedge_vertex[h1])
    v2, v3 = int(mesh.halfedge_vertex[h3]), int(mesh.halfedge_vertex[h5])
    f0, f1 = int(mesh.halfedge_face[h0]), int(mesh.halfedge_face[h1])

    # 1. allocate m (at the midpoint), the edges m-v1, m-v2, m-v3 and the faces f2, f3
    # 2. read the pointer arrays only now
    # 3. h1 now leaves m; relink f0 = (h0, h_m2, h3), f2 = (h_m1, h2, h_2m),
    #    f1 = (h1, h4, h_3m), f3 = (h_1m, h_m3, h5): next, prev and face; f0, f1 keep h0, h1
    # 4. m leaves along h_m1; if v1's halfedge was h1 (which now leaves m), give it h2
    ### BEGIN SOLUTION
    m = mesh.add_vertex(0.5 * (mesh.positions[v0] + mesh.positions[v1]))       # 1
    h_m1, h_m2, h_m3 = (2 * mesh.add_edge(m, v) for v in (v1, v2, v3))
    h_1m, h_2m, h_3m = h_m1 + 1, h_m2 + 1, h_m3 + 1
    f2, f3 = mesh.add_face(h_m1), mesh.add_face(h_1m)
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev                          # 2
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    origin[h1] = m                                                             # 3
    for loop, f in (((h0, h_m2, h3), f0), ((h_m1, h2, h_2m), f2), ((h1, h4, h_3m), f1), ((h_1m, h_m3, h5), f3)):
        for a, b in zip(loop, loop[1:] + loop[:1]):
            nxt[a], prv[b] = b, a
            face[a] = f
    mesh.face_halfedge[f0], mesh.face_halfedge[f1] = h0, h1
    mesh.vertex_halfedge[m] = h_m1                                             # 4
    if mesh.vertex_halfedge[v1] == h1:
        mesh.vertex_halfedge[v1] = h2
    ### END SOLUTION
    return m


check_split(my_split)

# %% [markdown] tags=["solution"]
# ### What a mistake looks like (solution edition: it holds most of the answer)
#
# Here is a flip with one step forgotten: it does everything except step 4. The check
# finds the vertex whose `halfedge` no longer leaves it and says which name it has in
# the picture of the operation (`result.show()` draws that element with its one-ring on
# the mesh as it was before; below, the wrong pointer itself is drawn after the flip).

# %% tags=["solution"]
def flip_without_step_4(mesh, e):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h0, h1 = 2 * e, 2 * e + 1
    h2, h3, h4, h5 = nxt[h0], prv[h0], nxt[h1], prv[h1]
    v2, v3 = origin[h3], origin[h5]
    f0, f1 = face[h0], face[h1]
    origin[h0], origin[h1] = v3, v2
    for a, b in ((h0, h3), (h3, h4), (h4, h0), (h1, h5), (h5, h2), (h2, h1)):
        nxt[a], prv[b] = b, a
    face[h4], face[h2] = f0, f1
    mesh.face_halfedge[f0], mesh.face_halfedge[f1] = h0, h1


buggy = check_flip(flip_without_step_4)
buggy

# %% tags=["solution"]
learner, reference, reference_log = hx.sample("cube"), hx.sample("cube"), OperationLog()
flip_without_step_4(learner, 1)
flip(reference, 1, log=reference_log)
vertex = buggy.element[1]
wrong_pointer = {"wrong_vertex": [vertex], "wrong": [learner.vertex_halfedge[vertex]],
                 "right": [reference.vertex_halfedge[vertex]]}
side_by_side([named_picture(learner, reference_log, wrong_pointer, size=(440, 330), legend=True)],
             ["after flip_without_step_4(1) on the cube"])

# %% [markdown] tags=["solution"]
# `v1` (vertex 2) still points at `h1`, which the flip has turned to leave `v2`; the
# library's flip moves that pointer to `h2`, which leaves `v1`.
#
# On the strip the missing step did not matter: no vertex there pointed at `h0` or
# `h1`. On the cube it did. That is why the check runs several meshes: some mistakes
# only show when a particular pointer happens to be involved.

# %% [markdown]
# ## Summary
#
# - A flip gathers six halfedges `h0 … h5`, four vertices `v0 … v3` and two faces, then
#   rewires: `h0` and `h1` change their vertex, the two triangles are relinked, `h2`
#   and `h4` change face, and `v0`/`v1` may need a new `halfedge`. Counts stay.
# - A flip is refused on a boundary edge and where the new edge already exists (which
#   covers a vertex of degree 3 and every edge of a tetrahedron). A refused operation
#   raises `TopologyError` and leaves the mesh untouched.
# - A split adds a vertex at the midpoint and cuts each neighbouring triangle in two:
#   +1 vertex, +3 edges, +2 faces inside; +1, +2, +1 on the boundary. V − E + F stays.
# - Both are constant work: a fixed handful of pointers, whatever the mesh size.
#
# **Next:** chapter 07 does the opposite of a split, the edge collapse, and meets its
# two cases.

# %% [markdown] tags=["solution"]
# ## Answer
#
# The answer is in the exercise cell above. Step 4 picks `h4` for `v0` because after
# the flip `h4` still leaves `v0` (it runs `v0 → v3`), and `h2` for `v1` for the same
# reason. Any other halfedge leaving the vertex would do, except at the boundary, where
# a vertex must keep its outgoing boundary halfedge; since `h0` and `h1` are interior, a
# boundary vertex never points at them, so step 4 never moves a boundary vertex's
# halfedge.
