# %% [markdown]
# # 08b · Debugging lab: nine classic halfedge bugs
#
# The hardest part of writing halfedge code is not the idea of an operation, it is the
# one pointer you forgot. This lab collects the mistakes learners make most often in
# courses like this one, each as a short function **beside the right one**, and shows
# how to find them: run the wrong function, let `validate()` name the rule it broke and
# the element that breaks it, look at that element, read why it happens and the fix.
#
# **By the end of this lab you can**
#
# - read a `MeshInvariantError`: its `.rule` says which rule, its `.element` which
#   vertex, halfedge or face, its message what is wrong with it;
# - recognise the nine classic bugs below from their message alone;
# - fix the three you are given at the end, and have the checks confirm it.
#
# Every wrong function lives in `halfedge_edu.exercises.classic_bugs`, named after its
# mistake (`flip_forgetting_vertex_halfedge`, ...), next to the right version
# (`flip_right`, ...). They are wrong on purpose: never copy them into your own code.

# %%
import inspect

from IPython.display import Image

import halfedge_edu as hx
from halfedge_edu.exercises.classic_bugs import BUGS, catch, picture


#: The bugs you fix yourself at the end of the lab: their right version stays hidden until then.
YOUR_FIXES = {"flip_forgetting_face_halfedge", "one_ring_endless_at_the_boundary",
              "collapse_reading_neighbours_too_early"}


def lab(name):
    """Run bug ``name`` the way this lab does: the wrong code beside the right one (unless fixing it
    is one of your exercises), what catches it, why, the fix; returns the picture of the element
    that breaks the rule."""
    bug = BUGS[name]
    print(inspect.getsource(bug.wrong))
    if name in YOUR_FIXES:
        print(f"# The right version is yours to write at the end of this lab ({bug.right.__name__} is kept out of sight).\n")
    else:
        print(inspect.getsource(bug.right))
    caught = catch(bug)
    print(f"caught by {bug.caught_by}: rule {caught.rule!r}, element {caught.element}")
    print(caught.message)
    print()
    print("Why:", bug.why)
    print("Fix:", bug.fix)
    print("The right function is", bug.right.__name__, "and it passes:", catch(bug, bug.right) is None)
    return Image(picture(caught, window_size=(480, 340)))

# %% [markdown]
# ## How a broken mesh is reported
#
# `mesh.validate()` checks every rule of the halfedge structure (chapter 02 built them;
# chapter 03 walked them) and stops at the first element that breaks one. It raises
# `hx.MeshInvariantError` with three things to act on. Here is a cube with one pointer
# broken by hand: vertex 0's halfedge set to a halfedge that does not leave it.

# %%
cube = hx.sample("cube")
cube.vertex_halfedge[0] = 1          # halfedge 1 runs towards vertex 0, it does not leave it
try:
    cube.validate()
except hx.MeshInvariantError as error:
    print("rule:   ", error.rule)
    print("element:", error.element)
    print("message:", error)

# %% [markdown]
# The rules, with the names `validate()` uses: `deleted-reference` (a live element
# points at a deleted or missing one), `vertex-halfedge-origin` (a vertex's halfedge
# must leave it), `next-prev-inverse`, `twin-involution` (twins run opposite ways),
# `next-origin` (a halfedge's next starts where it ends), `next-cycle` (a face's loop
# has three halfedges), `face-halfedge`, `edge-halfedge`, `boundary-vertex-halfedge`,
# `vertex-manifold` and `duplicate-edge`.
#
# Debugging is then always the same three steps: **which rule** (it says what kind of
# pointer is wrong), **which element** (draw it), **which step of my code** wrote, or
# forgot to write, that pointer.

# %% [markdown]
# ## 1. A flip that forgets the vertices
#
# Chapter 06's step 4: after a flip, `h0` leaves `v3`, no longer `v0`.

# %%
lab("flip_forgetting_vertex_halfedge")

# %% [markdown]
# The orange arrow is vertex 0's halfedge: it starts at another vertex. Any one-ring
# walk from vertex 0 would now circle that other vertex.

# %% [markdown]
# ## 2. A face whose halfedge points into another face

# %%
lab("flip_forgetting_face_halfedge")

# %% [markdown]
# ## 3. A neighbour just outside the edited region, left pointing at the old halfedge
#
# A collapse removes two faces; the halfedges around them are relinked. The one
# *before* the removed halfedge lies in a face the collapse otherwise does not touch,
# so it is the pointer most often forgotten.

# %%
lab("collapse_leaving_outer_next_stale")

# %% [markdown]
# ## 4. A vertex left pointing at a deleted halfedge

# %%
lab("collapse_forgetting_vertex_halfedges")

# %% [markdown]
# ## 5. The degree-3 collapse that merges the wrong faces
#
# Chapter 07's cube edge 0: when the vertex that goes has degree 3, the faces beyond
# both removed edges are one and the same face.

# %%
lab("collapse_reading_neighbours_too_early")

# %% [markdown]
# This one passes on every vertex of higher degree, which is why chapter 07's check
# runs the cube: a bug that only shows in one case is only caught by a test of that case.

# %% [markdown]
# ## 6. A split that forgets the boundary halfedges

# %%
lab("split_boundary_forgetting_boundary_halfedges")

# %% [markdown]
# ## 7. Twins paired with the wrong orientation in a build

# %%
lab("build_closed_pairing_twins_by_sorted_ends")

# %% [markdown]
# ## 8. A one-ring loop that never ends at the boundary
#
# This one does not break the mesh at all: it never returns. `check_one_ring` runs
# each call under a time limit (one second) and stops the walk, naming the vertex.

# %%
lab("one_ring_endless_at_the_boundary")

# %% [markdown]
# ## 9. Loop subdivision flipping an old edge
#
# A flip never breaks the structure, so `validate()` passes here. Only a check of
# Loop's own rule sees it: every old vertex keeps its degree.

# %%
lab("loop_split_flipping_old_edges")

# %% [markdown]
# ## Check yourself
#
# Without running anything: which rule does each message below point to, and which
# step of which operation would you read first?
#
# 1. `[next-origin] halfedge 12 ends at vertex 3, but its next (14) starts at vertex 5`
# 2. `[deleted-reference] vertex 9: its halfedge is halfedge 40, which was deleted`
# 3. A one-ring function that never returns, but only on the open patch.

# %% [markdown]
# 1. `next-origin`: the loop of a face does not join up. After a flip or collapse,
#    read the relinking step (`next`/`prev`); in a build, the origins you stored.
# 2. `deleted-reference` on a vertex: a collapse's step 5 (repoint the vertices that
#    used a deleted halfedge).
# 3. The boundary: the walk treats boundary halfedges specially and misses its start.

# %% [markdown]
# ## Exercises: fix three of them
#
# Write the fixed versions. Each is checked by the same helper as in its own chapter,
# and grading (`halfedge-edu grade`) runs those checks on these three names.
#
# **1.** `fixed_flip(mesh, e)`: `flip_forgetting_face_halfedge` with every step.

# %%
def fixed_flip(mesh, e):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h0, h1 = 2 * e, 2 * e + 1                     # gather (done for you)
    h2, h3, h4, h5 = nxt[h0], prv[h0], nxt[h1], prv[h1]
    v0, v1, v2, v3 = origin[h0], origin[h1], origin[h3], origin[h5]
    f0, f1 = face[h0], face[h1]
    ### BEGIN SOLUTION
    origin[h0], origin[h1] = v3, v2
    for a, b in ((h0, h3), (h3, h4), (h4, h0), (h1, h5), (h5, h2), (h2, h1)):
        nxt[a], prv[b] = b, a
    face[h4], face[h2] = f0, f1
    mesh.face_halfedge[f0], mesh.face_halfedge[f1] = h0, h1      # the forgotten step
    if mesh.vertex_halfedge[v0] == h0:
        mesh.vertex_halfedge[v0] = h4
    if mesh.vertex_halfedge[v1] == h1:
        mesh.vertex_halfedge[v1] = h2
    ### END SOLUTION

# %%
from halfedge_edu.exercises import check_collapse, check_flip, check_one_ring

check_flip(fixed_flip)

# %% [markdown]
# **2.** `fixed_one_ring(mesh, v)`: `one_ring_endless_at_the_boundary` without its
# endless loop.

# %%
def fixed_one_ring(mesh, v):
    start = mesh.vertex(int(v)).halfedge
    ring, h = [], start
    while True:
        ring.append(h.tip.index)
        ### BEGIN SOLUTION
        h = h.prev.twin                           # the next halfedge leaving v
        ### END SOLUTION
        if h == start:
            return ring

# %%
check_one_ring(fixed_one_ring)

# %% [markdown]
# **3.** `fixed_collapse(mesh, h)`: `collapse_reading_neighbours_too_early`, right at a
# degree-3 vertex too. The gathering is done for you, with chapter 07's names.

# %%
def fixed_collapse(mesh, h):
    nxt, prv = mesh.halfedge_next, mesh.halfedge_prev
    origin, face = mesh.halfedge_vertex, mesh.halfedge_face
    h_BA, h_AB = h, h ^ 1                          # gather (done for you)
    vB, vA = origin[h_BA], origin[h_AB]
    h_A_L, h_L_B = nxt[h_BA], prv[h_BA]
    h_B_R, h_R_A = nxt[h_AB], prv[h_AB]
    h_B_L, h_R_B = h_L_B ^ 1, h_B_R ^ 1
    vL, vR = origin[h_L_B], origin[h_R_A]
    fL, fR = face[h_BA], face[h_AB]
    ring_B = [h_BA]
    g = prv[h_BA] ^ 1
    while g != h_BA:
        ring_B.append(g)
        g = prv[g] ^ 1
    ### BEGIN SOLUTION
    mesh.positions[vA] = 0.5 * (mesh.positions[vA] + mesh.positions[vB])
    for g in ring_B:
        if g not in (h_BA, h_B_L, h_B_R):
            origin[g] = vA
    for old, new in ((h_B_L, h_A_L), (h_R_B, h_R_A)):
        before, after, f = prv[old], nxt[old], face[old]       # read each side just before relinking it
        nxt[before], prv[new] = new, before
        nxt[new], prv[after] = after, new
        face[new] = f
        if mesh.face_halfedge[f] == old:
            mesh.face_halfedge[f] = new
    if mesh.vertex_halfedge[vL] == h_L_B:
        mesh.vertex_halfedge[vL] = h_A_L ^ 1
    if mesh.vertex_halfedge[vR] == h_R_B:
        mesh.vertex_halfedge[vR] = h_R_A
    if mesh.vertex_halfedge[vA] == h_AB:
        mesh.vertex_halfedge[vA] = h_R_A ^ 1
    mesh.delete_face(fL)
    mesh.delete_face(fR)
    for g in (h_BA, h_L_B, h_B_R):
        mesh.delete_edge(g >> 1)
    mesh.delete_vertex(vB)
    ### END SOLUTION

# %%
check_collapse(fixed_collapse)

# %% [markdown]
# ## Summary
#
# - `validate()` names the **rule** and the **element**; the rule tells you which kind
#   of pointer, the element where to look, and the step of your code that writes that
#   pointer is the one to read.
# - Most bugs are a pointer *not written*: a vertex or face that kept a halfedge that
#   moved or was deleted, a `next` set without its `prev`, a new boundary halfedge
#   never linked in. Write every pointer pair both ways, and after an operation ask
#   of every vertex and face you touched: does its halfedge still belong to it?
# - Read neighbours just before you change them, not at the start: the degree-3
#   collapse changes them under you.
# - Some bugs leave a valid mesh (Loop's old-edge flip) or never return (a ring walk):
#   only a check of the operation's own rule, with a time limit, catches those.
#
# **Next:** chapter 09 builds Loop subdivision from the splits and flips you can now
# debug.

# %% [markdown] tags=["solution"]
# ## Answers
#
# The answers are in the exercise cells: the flip sets `f0`'s and `f1`'s halfedge to
# `h0` and `h1`; the ring steps with `h = h.prev.twin` and needs no boundary case; the
# collapse reads `prv[old]`, `nxt[old]` and `face[old]` inside the loop, just before
# relinking each side.
