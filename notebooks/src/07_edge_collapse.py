# %% [markdown]
# # 07 · Edge collapse
#
# A split adds a vertex in the middle of an edge. A **collapse** does the opposite: it
# shrinks an edge to a point, so its two ends become one vertex. Simplification
# (chapter 10) and remeshing (chapter 11) are built on it. It is also the local
# operation with the most pointers to get right, and one case that catches almost
# everybody: an end of degree 3.
#
# **By the end of this chapter you can**
#
# - name the elements a collapse gathers: `vA` (stays), `vB` (goes), the faces `fL`
#   and `fR` beside the edge, and the halfedges around them (`h_A_L`, `h_B_R`, ...);
# - list what a collapse deletes (the edge, `vB`, both faces, and one more edge from
#   each face) and check it with V − E + F;
# - tell the two cases apart (removed vertex of degree 3, or more) and say why the
#   degree-3 case needs care;
# - explain why the result does not depend on which of the two merging edges you keep;
# - write `collapse` yourself and have `check_collapse` tell you what is off.

# %%
import numpy as np

import halfedge_edu as hx
from halfedge_edu.core.ops import OperationLog, can_collapse, collapse
from halfedge_edu.viz import CollapseAtlas, CollapseStepper, grid, named_picture


def collapsed(mesh, h):
    """A collapsed copy of ``mesh`` (halfedge ``h``: its origin goes) and the log."""
    result, log = mesh.copy(), OperationLog()
    collapse(result, result.halfedge(h), log=log)
    return result, log


cube, single = hx.sample("cube"), hx.sample("single_collapse")
cube_after, cube_log = collapsed(cube, 0)
single_after, single_log = collapsed(single, 0)
corner_view = [(-1.9, -2.4, -1.6), (0.5, 0.5, 0.5), (0.0, 0.0, 1.0)]   # the cube seen from below vertex 0
small = {"size": (380, 290), "follow": False}
grid(
    [[named_picture(cube, cube_log, camera=corner_view, **small),
      named_picture(cube_after, cube_log, camera=corner_view, **small)],
     [named_picture(single, single_log, **small), named_picture(single_after, single_log, **small)]],
    [["cube, before: vB = vertex 0 has degree 3", "cube, after collapsing halfedge 0"],
     ["single_collapse, before: vB = vertex 0 has degree 6", "single_collapse, after collapsing halfedge 0"]],
)

# %% [markdown]
# Two collapses, before and after. In each, the edge between `vB` and `vA` has shrunk to
# a point: `vB` is gone and `vA` sits at the old midpoint. The two triangles beside the
# edge (`fL`, `fR`) have vanished, and on each side two edges have become one.
#
# Top: the cube's corner vertex 0 has only three edges. Once it merges into `vA`, the
# three faces around it have become one, `(vA, vL, vR)`. Bottom: a vertex of degree 6
# in a flat patch; its other faces simply swing over to `vA`.

# %% [markdown]
# ## 1. What a collapse does
#
# **Convention: collapsing halfedge `h_BA` merges its origin `vB` into its tip `vA`;
# it deletes the edge, `vB`, both faces beside the edge, and one more edge of each of
# those faces; `vA` moves to the midpoint of the edge.**
#
# The names are those of `halfedge_edu/core/ops/collapse.py` (a halfedge `h_X_Y` runs from
# `vX` to `vY`):
#
# ```
#                                vL
#                             /  ^  ^  \
#                      h_L_B /  /    \  \ h_L_A          gL: the face beyond
#                           v  / h_B_L \  v                  vB - vL
#                           / v   fL    \  \
#                      vB  ---- h_BA ---->  vA
#                          <--- h_AB ----
#                           \ ^   fR     / ^
#                      h_B_R v \ h_R_B  / / h_R_A        gR: the face beyond
#                             \ v      v /                   vB - vR
#                                vR
#
#     fL = (h_BA, h_A_L, h_L_B)        fR = (h_AB, h_B_R, h_R_A)
#     h_A_L is the twin of h_L_A; h_A_R the twin of h_R_A
# ```
#
# Why "one more edge of each face"? Face `fL` has three edges: the collapsed one, `vA –
# vL` and `vB – vL`. Once `vB` *is* `vA`, those last two join the same two vertices, so
# one of them must go. The library keeps `vA`'s (`h_A_L`, `h_L_A`) and deletes `vB`'s;
# `h_A_L` takes the place of `h_B_L` in the face `gL` beyond. The same happens on the
# right with `h_R_A` taking the place of `h_R_B` in `gR`.
#
# Count what goes: 1 vertex, 3 edges, 2 faces, so V − E + F changes by −1 + 3 − 2 = 0.

# %%
for name, before, after in (("cube", cube, cube_after), ("single_collapse", single, single_after)):
    after.validate()
    print(f"{name:16s} V, E, F: {before.n_vertices}, {before.n_edges}, {before.n_faces} -> "
          f"{after.n_vertices}, {after.n_edges}, {after.n_faces};  "
          f"V - E + F: {before.euler_characteristic} -> {after.euler_characteristic}")

# %% [markdown]
# ## 2. The case of a vertex of degree 3: the cube's edge 0
#
# Edge 0 of the cube runs from vertex 0 to vertex 4, and vertex 0 is a corner with
# only three edges. Collapsing halfedge 0 removes vertex 0. Here is the whole pointer
# diff, phase by phase, exactly as the library made it:

# %%
print(cube_log.describe())

# %% [markdown]
# Three things to see in it:
#
# - **No halfedge moves to `vA`** in the second phase: apart from the edge itself,
#   `vB`'s only halfedges are `h_B_L` and `h_B_R`, and both are deleted.
# - **`gL` and `gR` are the same face**, face 8, the third face around vertex 0. The
#   `fL` phase rewires its loop (`h_A_L` replaces `h_B_L`), and then the `fR` phase
#   rewires *the same loop again* (`h_R_A` replaces `h_R_B`). Look at halfedge 2: its
#   `prev` is set to 21 in the first phase and to 22 in the second.
# - After the collapse that face is `(vA, vL, vR)`: the three faces around the corner
#   have become one.
#
# That second point is the trap. Code that first reads *all* the neighbour pointers of
# `h_B_L` and `h_R_B` and then writes them all uses a value that the first write has
# already made stale, and leaves a pointer to a deleted halfedge. The library reads
# each pointer right before it writes, so one code path covers both cases. You will
# meet the trap again in the exercise.

# %%
face = cube_after.face(cube_log.named["gL"][1])
print("gL == gR:", cube_log.named["gL"] == cube_log.named["gR"])
print("that face after the collapse:", [int(v) for v in face.vertices()],
      "= (vA, vL, vR) =", [cube_log.named[n][1] for n in ("vA", "vL", "vR")])
print("degree of vA:", cube.vertex(4).degree, "+", cube.vertex(0).degree, "- 4 =", cube_after.vertex(4).degree)

# %% [markdown]
# ## 3. The case of a higher degree: `single_collapse`
#
# The sample `single_collapse` is made for this: two interior vertices of degree 6
# next to each other, and the ring of vertices around them. Collapsing halfedge 0
# removes vertex 0. This time three more halfedges leave `vB`; the second phase moves
# each of them to `vA`, and `gL` and `gR` are two different faces:

# %%
print(single_log.describe())

# %%
print("gL, gR:", single_log.named["gL"][1], single_log.named["gR"][1])
print("degree of vA:", single.vertex(1).degree, "+", single.vertex(0).degree, "- 4 =", single_after.vertex(1).degree)

# %% [markdown]
# The new degree of `vA` is `deg(vA) + deg(vB) − 4`: the two ends' edges are pooled, and
# four are lost (the collapsed edge counted at both ends, and one edge on each side).
# The cube's corner gives 5 + 3 − 4 = 4, the flat patch 6 + 6 − 4 = 8.
#
# ### Step through it
#
# The stepper replays a log one pointer change at a time, with the changed pointer,
# its old target and its new one highlighted. Use **phase** to jump from one phase to
# the next. Here it is on the cube's edge 0, driven to the start of the `fR` phase,
# where the face `gL = gR` is rewired a second time:

# %%
stepper = CollapseStepper(cube, cube.halfedge(0), window_size=(480, 360))
for _ in range(3):
    stepper.go("phase")
stepper

# %% [markdown]
# One step on (a second stepper, so the one above stays at the start of the phase):

# %%
one_on = CollapseStepper(cube, cube.halfedge(0), mode="static")   # never shown: no live view
one_on.go(stepper.step_index + 1)
print(one_on.describe())
one_on.close()

# %% [markdown]
# ### Both cases side by side
#
# The atlas runs the two collapses of the first picture together, one *phase* at a
# time, so you can compare what each phase does in each case. Below them are three
# collapses that are refused, with the reason; they are the subject of chapter 08.

# %%
atlas = CollapseAtlas()
atlas

# %% [markdown]
# Two phases in, the degree-3 case has made one change (the position of `vA`: no
# halfedge moves), the degree-6 case four (the position and three halfedges that now
# leave `vA`). The counts only change in the last phase, when the deletions happen,
# and V − E + F does not change even then.

# %%
driven_atlas = CollapseAtlas(mode="static")  # a second atlas, never shown: the one above stays put
for _ in range(2):
    driven_atlas.step()
print(driven_atlas.describe().split("\nrefused")[0])
print()
driven_atlas.go("end")
print(driven_atlas.describe())
driven_atlas.close()

# %% [markdown]
# ## 4. Which end, which edge: the result does not depend on it
#
# **Convention: up to the numbering of its elements, the mesh after a collapse is the
# same whichever end you remove and whichever of the two merging edges you keep.**
#
# The surviving vertex moves to the midpoint either way, and the two edges that merge
# join the same two vertices, so keeping one or the other is only a matter of which
# index survives. The library lets you choose the end: pass a halfedge and its origin
# goes. To compare two results "up to numbering", describe every face by the positions
# of its three corners:

# %%
def surface(mesh):
    """The set of faces, each as its corner positions, counter-clockwise from the smallest."""
    faces = set()
    for f in mesh.faces:
        corners = [tuple(np.round(v.position, 9) + 0.0) for v in f.vertices()]
        k = corners.index(min(corners))
        faces.add(tuple(corners[k:] + corners[:k]))
    return faces


for name, mesh in (("cube", cube), ("single_collapse", single)):
    remove_B, _ = collapsed(mesh, 0)       # halfedge 0: its origin goes
    remove_A, _ = collapsed(mesh, 1)       # its twin: the other end goes
    print(f"{name}: removing either end gives the same surface: {surface(remove_B) == surface(remove_A)}")

# %% [markdown]
# On the cube that is worth a second look: halfedge 1 removes vertex **4**, which has
# degree 5, and keeps the corner 0. It is the "higher degree" case of the code, yet the
# surface is the same as when the corner goes.
#
# The indices, however, differ: deleted elements are only *flagged*, and their slots
# stay until `garbage_collect()` renumbers everything. That is what keeps a collapse
# constant work:

# %%
after = cube_after.copy()
print("slots before garbage_collect: vertices", after.n_vertex_slots, "edges", after.n_edge_slots,
      "faces", after.n_face_slots, "| live:", after.n_vertices, after.n_edges, after.n_faces)
maps = after.garbage_collect()
print("old vertex -> new vertex:", maps.vertices.tolist())
print("slots after: vertices", after.n_vertex_slots, "edges", after.n_edge_slots, "faces", after.n_face_slots)

# %% [markdown]
# ## 5. Not every edge may collapse
#
# Some collapses would break the surface, and `can_collapse` refuses them with a
# reason. On the cube, the diagonal edge 1 (vertices 4 and 2) is one: its ends share
# a third neighbour that is not opposite the edge. And no edge of a tetrahedron can
# collapse. Chapter 08 is all about why; here is what the library says:

# %%
for name, mesh, e in (("cube", hx.sample("cube"), 1), ("tetrahedron", hx.sample("tetrahedron"), 0)):
    check = can_collapse(mesh, e)
    print(f"{name}, edge {e}: allowed = {bool(check)} ({check.rule})\n  {check.reason}")

# %% [markdown]
# ## Check yourself
#
# Predict before you run: collapse the cube's halfedge 0, then collapse, on the result,
# the edge between `vA` (vertex 4) and vertex 6, removing vertex 6. How many vertices,
# edges and faces are left after each, and what is V − E + F? What is the degree of
# vertex 4 at the end, and where is it?

# %%
mesh = hx.sample("cube")
print("start:              V, E, F =", mesh.n_vertices, mesh.n_edges, mesh.n_faces, "| V - E + F =", mesh.euler_characteristic)
collapse(mesh, mesh.halfedge(0))
print("after halfedge 0:   V, E, F =", mesh.n_vertices, mesh.n_edges, mesh.n_faces, "| V - E + F =", mesh.euler_characteristic)
h = mesh.find_halfedge(6, 4)
print("allowed next?", bool(mesh.can_collapse(h)), "| halfedge", h.index, "runs 6 -> 4")
collapse(mesh, h)
mesh.validate()
print("after halfedge", h.index, ": V, E, F =", mesh.n_vertices, mesh.n_edges, mesh.n_faces, "| V - E + F =", mesh.euler_characteristic)
print("vertex 4: degree", mesh.vertex(4).degree, "at", mesh.vertex(4).position.tolist())

# %% [markdown]
# Each collapse removes 1 vertex, 3 edges and 2 faces: (8, 18, 12) → (7, 15, 10) →
# (6, 12, 8), and V − E + F stays 2. After the first collapse vertex 4 has degree
# 5 + 3 − 4 = 4 and vertex 6 still has 5, so the second leaves vertex 4 with
# 4 + 5 − 4 = 5 edges, at the midpoint of `(0, 0, 0.5)` and `(0, 1, 1)`.

# %% [markdown]
# ## Exercise: write the collapse
#
# Fill in `my_collapse(mesh, h)`: `h` is a halfedge index (an int) of an interior edge
# that may be collapsed; `h` runs from `vB` (goes) to `vA` (stays, at the midpoint).
# Write the arrays `mesh.halfedge_next`, `halfedge_prev`, `halfedge_vertex`,
# `halfedge_face`, `vertex_halfedge`, `face_halfedge` and `mesh.positions`, and delete
# with `mesh.delete_vertex(v)`, `mesh.delete_edge(e)` (an edge index: `h >> 1`) and
# `mesh.delete_face(f)`. The gathering is done for you, with the names of the picture.
#
# `check_collapse(my_collapse)` runs it on `single_collapse`, on the cube's edge 0 in
# both directions (degree 3 and degree 5), and on six random collapses in a row on an
# icosphere. It compares each result with the library's *up to numbering*, so you may
# keep either of the two merging edges.

# %%
def my_collapse(mesh, h):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face

    # gather (done for you)
    h_BA, h_AB = h, h ^ 1
    vB, vA = origin[h_BA], origin[h_AB]
    h_A_L, h_L_B = nxt[h_BA], prv[h_BA]
    h_B_R, h_R_A = nxt[h_AB], prv[h_AB]
    h_B_L, h_R_B = h_L_B ^ 1, h_B_R ^ 1
    vL, vR = origin[h_L_B], origin[h_R_A]
    fL, fR = face[h_BA], face[h_AB]
    ring_B = [h_BA]                          # the halfedges leaving vB, before anything changes
    g = prv[h_BA] ^ 1
    while g != h_BA:
        ring_B.append(g)
        g = prv[g] ^ 1

    # 1. vA moves to the midpoint of the edge
    # 2. every halfedge of ring_B except h_BA, h_B_L, h_B_R now leaves vA
    # 3. h_A_L takes the place of h_B_L: read h_B_L's prev, next and face NOW, link
    #    prev -> h_A_L -> next, set h_A_L's face, and fix that face's halfedge if it was h_B_L
    # 4. the same on the right: h_R_A takes the place of h_R_B
    # 5. vL's halfedge may have been h_L_B, vR's h_R_B, vA's h_AB: point them at live ones
    # 6. delete fL, fR, the edges of h_BA, h_L_B and h_B_R, and vB
    ### BEGIN SOLUTION
    mesh.positions[vA] = 0.5 * (mesh.positions[vA] + mesh.positions[vB])       # 1
    for g in ring_B:                                                           # 2
        if g not in (h_BA, h_B_L, h_B_R):
            origin[g] = vA
    for old, new in ((h_B_L, h_A_L), (h_R_B, h_R_A)):                          # 3 and 4
        before, after, f = prv[old], nxt[old], face[old]                       # read now
        nxt[before], prv[new] = new, before
        nxt[new], prv[after] = after, new
        face[new] = f
        if mesh.face_halfedge[f] == old:
            mesh.face_halfedge[f] = new
    if mesh.vertex_halfedge[vL] == h_L_B:                                      # 5
        mesh.vertex_halfedge[vL] = h_A_L ^ 1         # h_L_A
    if mesh.vertex_halfedge[vR] == h_R_B:
        mesh.vertex_halfedge[vR] = h_R_A
    if mesh.vertex_halfedge[vA] == h_AB:
        mesh.vertex_halfedge[vA] = h_R_A ^ 1         # h_A_R
    mesh.delete_face(fL)                                                       # 6
    mesh.delete_face(fR)
    for g in (h_BA, h_L_B, h_B_R):
        mesh.delete_edge(g >> 1)
    mesh.delete_vertex(vB)
    ### END SOLUTION

# %% [markdown]
# Check each phase as soon as you have written it: `upto=2` after steps 1 and 2, then
# 4, then 5. Each says what the next phase is. (Steps you have not written yet are simply
# not there; the check looks only at what the earlier steps change.)

# %%
from halfedge_edu.exercises.ops_checks import check_collapse_steps

check_collapse_steps(my_collapse, 2)

# %%
from halfedge_edu.exercises import check_collapse

check_collapse(my_collapse)

# %% [markdown] tags=["solution"]
# ### What a mistake looks like (solution edition: it holds most of the answer)
#
# This collapse does everything right except one thing: in steps 3 and 4 it reads the
# neighbours of `h_B_L` and `h_R_B` at the *start*, before the first replacement. It
# works on `single_collapse`. On the cube's corner it does not, and the check says why:

# %% tags=["solution"]
def collapse_reading_too_early(mesh, h):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h_BA, h_AB = h, h ^ 1
    vB, vA = origin[h_BA], origin[h_AB]
    h_A_L, h_L_B, h_B_R, h_R_A = nxt[h_BA], prv[h_BA], nxt[h_AB], prv[h_AB]
    h_B_L, h_R_B = h_L_B ^ 1, h_B_R ^ 1
    vL, vR, fL, fR = origin[h_L_B], origin[h_R_A], face[h_BA], face[h_AB]
    ring_B, g = [h_BA], prv[h_BA] ^ 1
    while g != h_BA:
        ring_B.append(g)
        g = prv[g] ^ 1
    saved = {old: (prv[old], nxt[old], face[old]) for old in (h_B_L, h_R_B)}   # read too early

    mesh.positions[vA] = 0.5 * (mesh.positions[vA] + mesh.positions[vB])
    for g in ring_B:
        if g not in (h_BA, h_B_L, h_B_R):
            origin[g] = vA
    for old, new in ((h_B_L, h_A_L), (h_R_B, h_R_A)):
        before, after, f = saved[old]
        nxt[before], prv[new], nxt[new], prv[after], face[new] = new, before, after, new, f
        if mesh.face_halfedge[f] == old:
            mesh.face_halfedge[f] = new
    if mesh.vertex_halfedge[vL] == h_L_B:
        mesh.vertex_halfedge[vL] = h_A_L ^ 1
    if mesh.vertex_halfedge[vR] == h_R_B:
        mesh.vertex_halfedge[vR] = h_R_A
    if mesh.vertex_halfedge[vA] == h_AB:
        mesh.vertex_halfedge[vA] = h_R_A ^ 1
    for f in (fL, fR):
        mesh.delete_face(f)
    for g in (h_BA, h_L_B, h_B_R):
        mesh.delete_edge(g >> 1)
    mesh.delete_vertex(vB)


buggy = check_collapse(collapse_reading_too_early)
buggy

# %% tags=["solution"]
learner = cube.copy()
collapse_reading_too_early(learner, 0)
halfedge = buggy.element[1]
wrong_pointer = {"wrong_owner": [halfedge], "wrong": [learner.halfedge_next[halfedge]],
                 "right": [cube_after.halfedge_next[halfedge]]}
grid([[named_picture(cube, cube_log, wrong_pointer, size=(440, 330), camera=corner_view, follow=False,
                     legend=True)]],
     [["the cube before the collapse: h_R_A's next"]])

# %% [markdown] tags=["solution"]
# The picture shows halfedge 22 (`h_R_A`) on the cube before the collapse, and its
# `next`: the wrong value `h_B_L` (halfedge 5), which the collapse deletes, and the
# right one. That `next` was copied from `h_R_B` at the start, when it was still `h_B_L`;
# by the time it is written, the first replacement has put `h_A_L` there instead.

# %% [markdown]
# ## Summary
#
# - A collapse merges `vB` into `vA`: `vA` moves to the midpoint; every other halfedge
#   that left `vB` now leaves `vA`; on each side, one of the two edges that become one
#   is deleted and the kept halfedge takes the other's place in the face beyond.
# - It deletes 1 vertex, 3 edges and 2 faces, so V − E + F does not change; the new
#   degree of `vA` is `deg(vA) + deg(vB) − 4`.
# - When `vB` has degree 3, the faces beyond on both sides are one face, rewired twice;
#   read every pointer right before you rewrite it.
# - The result does not depend on which end goes or which merging edge is kept, up to
#   the numbering; deleted slots stay until `garbage_collect()`.
# - Not every edge may collapse: chapter 08 says exactly which.

# %% [markdown] tags=["solution"]
# ## Answer
#
# The answer is in the exercise cell above. Steps 3 and 4 read the neighbours of
# `h_B_L` (and then of `h_R_B`) just before relinking that side: when `vB` has degree
# 3, the face beyond both is the same face, and the left side's relinking changes what
# the right side must read. Step 5 hands `vL`, `vR` and `vA` a halfedge that survives:
# `h_L_A`, `h_R_A` and `h_A_R` all still leave them after the collapse.
