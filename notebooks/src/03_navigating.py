# %% [markdown]
# # 03 · Navigating: next, twin, prev, and one-rings
#
# Chapter 02 built the pointers. This chapter walks on them. Every question a mesh
# algorithm asks ("what are this vertex's neighbours?", "which face is across this
# edge?", "where are the holes?") is answered by a short walk from one halfedge.
#
# **By the end of this chapter you can**
#
# - move from a halfedge to its `next`, `prev` and `twin`, and say where each one is;
# - walk around a face, around a vertex (counter-clockwise *and* clockwise), and along a
#   boundary loop, and stop at the right moment;
# - tell `h = h.prev.twin` (counter-clockwise) from `h = h.twin.next` (clockwise);
# - write `one_ring` yourself and have `check_one_ring` check it on every vertex of
#   seven meshes.

# %%
import halfedge_edu as hx
from halfedge_edu.viz import HalfedgeExplorer, HalfedgeScene, OneRingViewer
from IPython.display import Image

# %% [markdown]
# ## The picture
#
# The open patch, a flat 4 × 4 grid of vertices, with one halfedge picked out
# (vermillion): halfedge 7, from vertex 4 to vertex 5, inside face 6. Its `next`
# (green) and `prev` (purple) close the triangle; its `twin` (blue) runs back along the
# same edge in the neighbouring face.

# %%
patch = hx.sample("open_patch")
scene = HalfedgeScene(patch, window_size=(600, 430))
scene.show_halfedge(7)
Image(scene.screenshot())

# %% [markdown]
# The convention in one sentence: **from a halfedge `h` you can reach everything:
# `h.next` and `h.prev` go around its face counter-clockwise and back, `h.twin` crosses
# to the other side of its edge, `h.vertex` is where it starts, `h.tip` where it ends,
# and `h.face` is the face on its left.**

# %%
h = patch.halfedge(7)
print("h      ", h)
print("h.next ", h.next)
print("h.prev ", h.prev)
print("h.twin ", h.twin)
print("h.vertex", h.vertex.index, "| h.tip", h.tip.index, "| h.face", h.face)

# %% [markdown]
# Pointers compose, and read left to right: `h.next.twin` is "go to the next halfedge,
# then cross its edge". A few identities hold for **every** halfedge, and they make good
# sanity checks:

# %%
print("h.twin.twin == h:      ", h.twin.twin == h)
print("h.next.prev == h:      ", h.next.prev == h)
print("h.next.next.next == h: ", h.next.next.next == h, "(a triangle has three sides)")
print("h.prev == h.next.next: ", h.prev == h.next.next)
print("h.next.vertex == h.tip:", h.next.vertex == h.tip)

# %% [markdown]
# ## Walk it yourself
#
# The explorer starts at halfedge 7. Press **next**, **prev** and **twin**; the pointer
# table on the right always shows where each pointer of the current halfedge goes, and
# the trail below it remembers your path. Walk off the patch with `twin` at the rim and
# you land on a **boundary** halfedge: its face is `None`, and `next` then follows the
# rim.

# %%
explorer = HalfedgeExplorer(patch, halfedge=7)
explorer

# %% [markdown]
# The same moves from code, on a second explorer of our own (never shown), so the one
# above stays where your clicks leave it. Three `next`s bring you back, because a face
# is a loop of three halfedges:

# %%
walker = HalfedgeExplorer(patch, halfedge=7, mode="static")   # never shown: no live view
walker.go("next")
walker.go("next")
walker.go("next")
print(walker.describe())

# %% [markdown]
# Now down to the rim. Face 0 is the bottom-left triangle `[0, 1, 5]`; its bottom side
# runs along the edge of the patch, so its `twin` has nowhere to go but outside:

# %%
walker.go(2)               # jump to halfedge 2: vertex 1 -> 5, in face 0
walker.go("prev")          # the bottom side of face 0: 0 -> 1
walker.go("twin")          # across the edge: nothing there but the outside
print(walker.describe())
walker.go("next")          # along the rim
print(walker.describe())

# %% [markdown]
# ## Around a face
#
# A face is a loop of `next` pointers. Start at `face.halfedge`, step `next` until you
# are back: you meet its three halfedges and, at their origins, its three corners,
# counter-clockwise.

# %%
face = patch.face(6)
start = face.halfedge
h = start
while True:
    print(f"halfedge {h.index}: {h.vertex.index} -> {h.tip.index}")
    h = h.next
    if h == start:
        break
print("face.vertices():", [v.index for v in face.vertices()])

# %% [markdown]
# Note the test `h == start` **after** the step: the loop body runs once for the start
# halfedge, then for every other one, and stops when the walk closes. Compare halfedges
# with `==`, never with `is`: each `h.next` is a fresh little handle object, so `is`
# would never be true and the loop would never end.

# %% [markdown]
# ## Around a vertex: the one-ring
#
# The **one-ring** of a vertex `v` is its neighbours, in order around it. To walk
# around `v` you need, at every step, another halfedge *leaving* `v`:
#
# - `h.prev` is the halfedge of the same face that comes *into* `v`;
# - its twin leaves `v` again, in the next face **counter-clockwise**.
#
# So **`h = h.prev.twin` turns counter-clockwise around `v`**, seen from outside. Start
# at `v.halfedge` and stop when you are back:

# %%
v = patch.vertex(5)
start = v.halfedge
h = start
ccw = []
while True:
    ccw.append(h.tip.index)
    h = h.prev.twin
    if h == start:
        break
print("counter-clockwise (h = h.prev.twin):", ccw)
print("v.neighbors():                      ", [u.index for u in v.neighbors()])

# %% [markdown]
# The course notes print a vertex's neighbours with the other classic step,
# `h = h.twin.next`: `h.twin` comes *into* `v`, and its `next` leaves `v` in the
# neighbouring face. That works just as well, but it turns the **other way**,
# clockwise:

# %%
h = start
cw = []
while True:
    cw.append(h.tip.index)
    h = h.twin.next
    if h == start:
        break
print("clockwise (h = h.twin.next):", cw)
print("same neighbours:", sorted(cw) == sorted(ccw), "| reversed order after the first:", cw[1:] == ccw[1:][::-1])

# %% [markdown]
# Both visit every neighbour exactly once. Which one you use matters only when the order
# matters, and in this package rings are **counter-clockwise** (as in pmp-library and
# geometry-central): `v.outgoing()`, `v.neighbors()` and `v.faces()` all walk
# `h.prev.twin`.
#
# Vertex 5 on the picture: the ring starts at vertex 1 (below), then 6 (right), 10, 9
# (above), 4 (left), 0, counter-clockwise when you look down at the patch.
#
# ### Turn around a vertex yourself
#
# The one-ring viewer below shows a vertex, its outgoing halfedges (blue), its
# neighbours and faces. **ccw** steps `h = h.prev.twin`, **cw** steps
# `h = h.twin.next`, **to tip** moves to the neighbour the current halfedge points at.

# %%
ring_viewer = OneRingViewer(patch, vertex=5)
ring_viewer

# %% [markdown]
# From code, on a second viewer of our own (never shown), so the one above stays at
# vertex 5 until you turn it: two steps counter-clockwise, then one back.

# %%
ring_walker = OneRingViewer(patch, vertex=5, mode="static")   # never shown: no live view
ring_walker.go("ccw")
ring_walker.go("ccw")
print(ring_walker.describe())
ring_walker.go("cw")
print(ring_walker.describe().splitlines()[-1])

# %% [markdown]
# ## On the boundary
#
# A vertex on the rim has a gap in its ring: the outside. Boundary halfedges make that
# gap harmless. A boundary vertex's `halfedge` is its outgoing **boundary** halfedge, so
# the counter-clockwise walk starts on the rim, crosses the hole first, and then turns
# through the faces until it is back. Nothing special is needed in the loop:

# %%
corner = patch.vertex(1)
print("vertex 1 is on the boundary:", corner.is_boundary)
print("its halfedge:", corner.halfedge)
print("outgoing, counter-clockwise:", corner.outgoing())
print("neighbours:", [u.index for u in corner.neighbors()], "| faces:", [f.index for f in corner.faces()])

# %% [markdown]
# Four neighbours but only three faces: the step from neighbour 0 to neighbour 2
# crosses the outside, where the boundary halfedge has no face.
#
# ## Boundary loops
#
# The boundary halfedges link into loops by their `next` pointers (chapter 02 built
# them that way). To walk a hole, start at any boundary halfedge and follow `next`:

# %%
start = corner.halfedge
h = start
rim = []
while True:
    rim.append(h.vertex.index)
    h = h.next
    if h == start:
        break
print("the rim of the open patch:", rim)
print("boundary loops:", patch.n_boundary_loops, "| halfedges in each:", [len(loop) for loop in patch.boundary_loops()])

# %% [markdown]
# The rim runs clockwise seen from above: the boundary halfedges are the twins of the
# faces' outer sides, so they run the opposite way around. Seen from the hole's side,
# a boundary loop is a face that is not really there.

# %% [markdown]
# ## A large mesh: the bunny
#
# The same walks work on a mesh of 70 thousand faces, and each costs the same few
# steps. The bunny stands on a base with holes: five boundary loops.

# %%
bunny = hx.sample("bunny")
print(bunny)
print("halfedges in each hole:", [len(loop) for loop in bunny.boundary_loops()])

# %% [markdown]
# On a mesh this size the explorer draws only the arrows near the current halfedge and
# follows it with the camera. Here it starts on the rim of the first hole, and walks
# ten steps along it (`go` takes a chain of moves, read left to right like
# `h.next.next...`, and draws once at the end):

# %%
hole_start = int(bunny.boundary_loops()[0][0])
bunny_explorer = HalfedgeExplorer(bunny, halfedge=hole_start)
bunny_explorer.go(".".join(["next"] * 10))
print(bunny_explorer.describe().splitlines()[0])
bunny_explorer

# %% [markdown]
# ## Check yourself
#
# These lines would change if the pointers, or the directions of the walks, were
# different.

# %%
h = patch.halfedge(7)
print("halfedge 7: next", h.next.index, "prev", h.prev.index, "twin", h.twin.index, "face", h.face.index)
print("vertex 5 ring, ccw (h.prev.twin):", ccw)
print("vertex 5 ring, cw  (h.twin.next):", cw)
print("vertex 1 (boundary) ring:", [u.index for u in corner.neighbors()])
print("open patch rim:", rim)
cube = hx.sample("cube")
print("cube degrees:", [v.degree for v in cube.vertices])
print("bunny: boundary loops", bunny.n_boundary_loops, "| degree of vertex 100:", bunny.vertex(100).degree)

# %% [markdown]
# ## Exercise: write `one_ring` yourself
#
# Write `one_ring(mesh, v)` that returns the neighbours of vertex `v` as a list of
# vertex indices, **counter-clockwise, starting with the tip of `v.halfedge`**. `v` is a
# vertex handle (so `v.halfedge` works; `mesh.vertex(v)` works too). Use only the
# pointers `halfedge`, `prev`, `next`, `twin`, `tip`, not `v.neighbors()`!
#
# `check_one_ring` runs your function on every vertex of seven meshes (the open patch,
# the strip, a tetrahedron, the cube, a patch around two vertices, a shuffled
# octahedron and a ring with two holes) and explains the first ring that differs. A
# walk that never comes back is stopped after a second.

# %%
def one_ring(mesh, v):
    """The neighbours of v, counter-clockwise, starting with the tip of v.halfedge."""
    start = v.halfedge
    ring = []
    h = start
    while True:
        ### BEGIN SOLUTION
        neighbour = h.tip.index   # 1. the neighbour this halfedge points to
        h = h.prev.twin           # 2. turn counter-clockwise to the next halfedge leaving v
        ### END SOLUTION
        ring.append(neighbour)
        if h == start:
            return ring

# %%
from halfedge_edu.exercises import check_one_ring

result = check_one_ring(one_ring)
result

# %% [markdown]
# ### The other way round, and what a mistake looks like
#
# A ring walked with the CMU notes' `h = h.twin.next` has the same neighbours from the
# same start, clockwise. That is correct in that course's convention, so the check
# accepts it, and its answer says why this chapter turns the other way.

# %%
def one_ring_clockwise(mesh, v):
    start = v.halfedge
    ring, h = [], start
    while True:
        ring.append(h.tip.index)
        h = h.twin.next
        if h == start:
            return ring


check_one_ring(one_ring_clockwise)

# %% [markdown]
# A walk that steps with `h = h.next.twin` instead circles around the *tip* of the first
# halfedge, not around `v`. The check stops at the first vertex where that shows, says
# what happened, and `result.show()` draws that vertex with its ring.

# %%
def one_ring_around_the_tip(mesh, v):
    start = v.halfedge
    ring, h = [], start
    for _ in range(mesh.n_vertices):   # a bounded walk: this one never gets back to start
        ring.append(h.tip.index)
        h = h.next.twin
        if h == start:
            break
    return ring


wrong_way = check_one_ring(one_ring_around_the_tip)
wrong_way

# %%
wrong_way.show()

# %% [markdown]
# ## Summary
#
# - `h.next`, `h.prev`: around the face (counter-clockwise, and back); `h.twin`: across
#   the edge; `h.vertex` / `h.tip`: where it starts / ends; `h.face`: `None` on the
#   boundary.
# - Around a face: step `next` until back at the start.
# - Around a vertex: `h = h.prev.twin` turns **counter-clockwise**; the course's
#   `h = h.twin.next` turns **clockwise**. Both see every neighbour once, and
#   `check_one_ring` accepts either.
# - A boundary vertex starts its ring at its boundary halfedge, so the same loop works
#   on the rim; boundary halfedges chain into loops by `next`.
# - Compare halfedges with `==`, and stop when you are back at the start.
#
# **Next:** chapter 04 asks what the halfedge structure *cannot* hold, and why.

# %% [markdown] tags=["solution"]
# ## Answer
#
# The answer is in the exercise cell above: the two blanks are `h.tip.index` (or
# `h.tip`; vertex handles are accepted) and `h.prev.twin`.
