# %% [markdown]
# # 02 · Building the halfedge structure
#
# Chapter 01 ended with a polygon soup: faces that know their corners and nothing
# else. This chapter turns a soup into halfedges, once, so that every later question
# ("who is next to whom?") is a few pointer steps.
#
# **By the end of this chapter you can**
#
# - say which three halfedges a face `[i, j, k]` makes, and in which order;
# - say when a halfedge becomes the **twin** of an earlier one, and why
#   `twin = h ^ 1` and `edge = h >> 1`;
# - explain where the **boundary halfedges** come from and how they are linked;
# - check that the readable loop and the fast numpy build give identical arrays;
# - write the build yourself, and have `check_build` tell you what is off.

# %%
import numpy as np

import halfedge_edu as hx
from halfedge_edu.viz import HalfedgeExplorer, HalfedgeScene
from IPython.display import Image

# %% [markdown]
# ## The picture
#
# Two triangles sharing one edge, `faces = [[0, 1, 2], [0, 2, 3]]`. Every edge is drawn
# as two arrows, one on each side; each arrow is a **halfedge**, set into the face it
# belongs to. The dark arrows outside run along the boundary: they belong to no face.

# %%
faces = [[0, 1, 2], [0, 2, 3]]
square = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
two = hx.HalfedgeMesh.from_faces(square, faces)

scene = HalfedgeScene(two, window_size=(600, 420))
Image(scene.screenshot())

# %% [markdown]
# The convention in one sentence: **each face `[i, j, k]` makes the halfedges
# `(i, j)`, `(j, k)`, `(k, i)`; an edge seen for the first time gets the next edge
# number `e` and its halfedge is `2e`; when the same edge shows up again, running the
# other way, that halfedge is the twin `2e + 1`; an edge seen only once gets a
# boundary halfedge `2e + 1` with no face.**
#
# Read the picture with that rule: face 0 makes halfedges 0, 2, 4; face 1 meets edge
# `(0, 2)` a second time and makes its twin 5, then 6 and 8 for two new edges. The odd
# numbers that no face made (1, 3, 7, 9) are the boundary.

# %% [markdown]
# ## Positions are not needed
#
# Nothing in that rule looks at where a vertex is. Topology comes from the faces
# alone, which is why `hx.build_reference`, the course's loop, takes only faces:

# %%
arrays = hx.build_reference(faces)
print("origin of each halfedge:", arrays.halfedge_vertex.tolist())
print("face of each halfedge:  ", arrays.halfedge_face.tolist())
print("next of each halfedge:  ", arrays.halfedge_next.tolist())

# %% [markdown]
# Move the vertices anywhere you like: the arrays stay the same.

# %%
elsewhere = hx.HalfedgeMesh.from_faces(np.random.default_rng(0).normal(size=(4, 3)), faces)
print("same topology:", all(np.array_equal(a, b) for a, b in [
    (two.halfedge_vertex, elsewhere.halfedge_vertex),
    (two.halfedge_next, elsewhere.halfedge_next),
    (two.halfedge_face, elsewhere.halfedge_face),
]))

# %% [markdown]
# ## The build, step by step
#
# Here is every decision the build makes for the two triangles, in order. We read the
# steps off the finished arrays: a face's halfedges come in corner order starting at
# `face_halfedge[f]`, an even halfedge is the first sighting of its edge, an odd one
# inside a face is a twin, and an odd one with no face is a boundary halfedge.

# %%
def build_story(faces):
    """The build of `faces` as a list of (halfedge, sentence), in the order it happens."""
    arrays = hx.build_reference(faces)
    origin, face_of, next_of = arrays.halfedge_vertex, arrays.halfedge_face, arrays.halfedge_next
    story = []
    for f, h in enumerate(arrays.face_halfedge.tolist()):
        for corner in range(3):
            a, b = int(origin[h]), int(origin[h ^ 1])
            if h % 2 == 0:
                why = f"edge ({min(a, b)}, {max(a, b)}) is new: edge {h >> 1}, halfedge {h} = 2*{h >> 1}"
            else:
                why = f"edge ({min(a, b)}, {max(a, b)}) seen before: the twin of {h ^ 1}, halfedge {h}"
            story.append((h, f"face {f} {list(faces[f])}, corner ({a}, {b}): {why}"))
            h = int(next_of[h])
    for h in np.flatnonzero(face_of < 0).tolist():
        a, b = int(origin[h]), int(origin[h ^ 1])
        story.append((h, f"edge {h >> 1} has one face: boundary halfedge {h} runs {a} -> {b}, face -1"))
    for h in np.flatnonzero(face_of < 0).tolist():
        n = int(next_of[h])
        story.append((h, f"boundary halfedge {h} ends at {int(origin[h ^ 1])}; the boundary halfedge "
                         f"leaving {int(origin[n])} is {n}, so next[{h}] = {n}"))
    return story


story = build_story(faces)
for step, (h, sentence) in enumerate(story, start=1):
    print(f"{step:>2}. {sentence}")

# %% [markdown]
# Steps 1 to 6 are the face loop: three halfedges per face. Step 4 is the moment that
# matters: face 1 walks `0 -> 2`, edge `(0, 2)` already exists (face 0 walked it
# `2 -> 0`), so instead of a new edge we get the twin, number `4 + 1 = 5`.
#
# Steps 7 to 10 fill the gaps: each odd halfedge that no face claimed runs the other
# way along its edge, starting where its twin ends. Steps 11 to 14 link those boundary
# halfedges into a loop: a boundary halfedge's `next` is the boundary halfedge that
# leaves the vertex where it ends. (Each boundary vertex has exactly one; chapter 04 is
# about what happens when it does not.)
#
# ### Step through it
#
# Drag the slider to watch the halfedges appear: the one made at this step is
# vermillion, the ones made before it green, the ones still to come grey. You do not
# need to read the code of this cell.

# %%
import ipywidgets as widgets

from halfedge_edu.viz import on_main_thread


def step_through():
    """A slider over the steps of ``story`` with the step's text and picture.

    Returns (slider, text, scene, box): ``box`` is what is displayed.
    """
    scene = HalfedgeScene(two, window_size=(560, 400))
    slider = widgets.IntSlider(value=1, min=1, max=len(story), description="step",
                               layout=widgets.Layout(width="560px"))
    text = widgets.Textarea(disabled=True, rows=2, layout=widgets.Layout(width="560px"))
    picture = widgets.Image(format="png")

    def show_step(change=None):
        """Highlight the halfedge of this step and those made before it."""
        k = slider.value
        current = story[k - 1][0]
        made = sorted({h for h, _ in story[: k - 1]} - {current})
        scene.set_roles({"current": [current], "created": made})
        text.value = f"{k}. {story[k - 1][1]}"
        picture.value = scene.screenshot()

    # A slider move from the browser arrives on another thread; the redraw runs on the main one.
    slider.observe(on_main_thread(show_step), names="value")
    show_step()
    return slider, text, scene, widgets.VBox([slider, text, picture])


step_slider, step_text, step_scene, step_box = step_through()
step_box

# %% [markdown]
# The slider can also be moved from code, which is how this notebook checks itself. The
# check moves a second slider of its own (never shown), so the one above stays where
# you leave it:

# %%
check_slider, check_text, check_scene, _ = step_through()
check_slider.value = 4
print(check_text.value)
print(check_scene.describe())

# %% [markdown]
# ## Twins and edges for free
#
# Because an edge's two halfedges are numbered `2e` and `2e + 1`, no twin array and
# no edge array are needed. In binary, the two halves of an edge differ only in the
# last bit:
#
# - `h ^ 1` flips the last bit: the **twin** (0 ↔ 1, 4 ↔ 5, ...);
# - `h >> 1` drops the last bit: the **edge** (4 and 5 are both edge 2).
#
# A twin can therefore never be missing or point somewhere odd.

# %%
print(" h   bits   twin = h ^ 1   edge = h >> 1")
for h in range(two.n_halfedges):
    print(f"{h:>2}   {h:04b}   {h ^ 1:>12}   {h >> 1:>13}")

# %% [markdown]
# The handles say the same: `h.twin` is `h ^ 1` and `h.edge` is `h >> 1`.

# %%
h = two.halfedge(4)
print(h, "| twin:", h.twin, "| edge:", h.edge)

# %% [markdown]
# ## The whole table
#
# Here is everything the build stored for the two triangles, one row per halfedge.
# `prev` is the inverse of `next`, and each vertex keeps one outgoing halfedge: its
# outgoing **boundary** halfedge if it has one, so `v.is_boundary` is one look.

# %%
print(" h  origin -> tip   face   next   prev   twin   edge")
for h in two.halfedges:
    face = "-" if h.face is None else h.face.index
    print(f"{h.index:>2}  {h.vertex.index:>6} -> {h.tip.index:<3} {face:>6} {h.next.index:>6} "
          f"{h.prev.index:>6} {h.twin.index:>6} {h.edge.index:>6}")
print()
for v in two.vertices:
    print(f"vertex {v.index}: halfedge {v.halfedge.index} ({v.halfedge.vertex.index} -> {v.halfedge.tip.index}), "
          f"boundary: {v.is_boundary}")

# %% [markdown]
# ## Two layouts of the same halfedges
#
# The course notes (UChicago's build among them) allocate three halfedges per face as
# they go: face `f` gets `3f`, `3f + 1`, `3f + 2` for its sides (i, j), (j, k), (k, i),
# and the twins are found afterwards, when an edge is seen a second time. This package,
# like pmp-library and OpenMesh, gives each *edge* a pair: `2e` and `2e + 1`, so the
# twin is never stored, it is `h ^ 1`, and a side that no other face shares still gets
# its twin, a boundary halfedge with no face. Here are both for the two triangles:

# %%
def per_face_layout(faces: np.ndarray) -> list[tuple[int, int, int, int | None]]:
    """(halfedge, from, to, twin) with three halfedges per face, twins found afterwards."""
    rows, first_seen = [], {}
    for f, (i, j, k) in enumerate(faces.tolist()):
        for c, (a, b) in enumerate(((i, j), (j, k), (k, i))):
            h = 3 * f + c
            rows.append([h, a, b, None])
            key = (min(a, b), max(a, b))
            if key in first_seen:
                rows[h][3], rows[first_seen[key]][3] = first_seen[key], h
            else:
                first_seen[key] = h
    return [tuple(row) for row in rows]


two_triangles = np.array([[0, 1, 2], [0, 2, 3]])
paired = hx.build_reference(two_triangles)
per_face = per_face_layout(two_triangles)
print("per face (course notes)        paired twins (pmp, OpenMesh, this package)")
for h in range(len(paired.halfedge_vertex)):
    left = per_face[h] if h < len(per_face) else None
    left_text = f"h {left[0]}: {left[1]} -> {left[2]}, twin {left[3]}" if left else ""
    tip = paired.halfedge_vertex[h ^ 1]
    face = paired.halfedge_face[h]
    print(f"{left_text:30s} h {h}: {paired.halfedge_vertex[h]} -> {tip}, twin {h ^ 1}, "
          f"face {face if face >= 0 else 'none (boundary)'}")

# %% [markdown]
# The per-face layout needs no boundary halfedges and follows the loop the notes write,
# but it stores a twin per halfedge and leaves `None` where a side has no neighbour, so
# every walk around a boundary vertex has to test for it. Libraries pick the pairs: the
# twin costs nothing (one bit), an edge is just `h >> 1`, every halfedge has a twin so
# walks never stop at a hole, and the boundary loops are there to follow with `next`.
# `check_build` accepts either layout (return `"twin"` with the per-face one).

# %% [markdown]
# ## Walk the result
#
# The explorer below starts at halfedge 0. Press **next**, **prev** and **twin** and
# watch the pointer table: after three `next`s you are back where you started (a face
# is a loop of three), and `twin` jumps across the edge. Chapter 03 is all about this
# walking; here it is a way to check the table above with your own eyes.

# %%
explorer = HalfedgeExplorer(two, halfedge=0)
explorer

# %% [markdown]
# Driven from code, the same moves as three clicks on **next** and then one on
# **twin** and one on **next** (the boundary loop), on a second explorer of our own
# (never shown), so the one above stays at halfedge 0 until you click:

# %%
walker = HalfedgeExplorer(two, halfedge=0, mode="static")   # never shown: no live view
walker.go("next.next.next")
print(walker.describe())
walker.go("twin")
walker.go("next")
print(walker.describe())

# %% [markdown]
# ## The readable loop and the fast build agree
#
# `hx.build_reference` is the course's loop: one face at a time, one corner at a
# time, with dictionaries, as in the exercise below (it is that exercise's answer, so
# read its source only after you have written your own). `HalfedgeMesh.from_faces` does
# the same work with whole-array numpy operations: it sorts all directed edges by their
# vertex pair at once, so that
# the two sightings of each edge sit side by side. The numbering is chosen so that
# both give **identical** arrays, index for index:

# %%
def same_arrays(mesh):
    """True when build_reference and from_faces agree on every array of `mesh`."""
    _, mesh_faces = mesh.to_arrays()
    loop = hx.build_reference(mesh_faces)
    fast = hx.HalfedgeMesh.from_faces(*mesh.to_arrays())
    return all(np.array_equal(getattr(loop, name), getattr(fast, name)) for name in [
        "vertex_halfedge", "halfedge_next", "halfedge_prev", "halfedge_vertex", "halfedge_face", "face_halfedge"])


for name in ["strip", "open_patch", "cube", "octahedron", "spot"]:
    mesh = hx.sample(name)
    print(f"{name:>10}: {mesh.n_faces:>5} faces, {mesh.n_halfedges:>6} halfedges, identical: {same_arrays(mesh)}")

# %% [markdown]
# The loop is for reading; the numpy build is for the bunny (70 thousand faces) and
# beyond, where a Python loop per corner would make you wait.

# %% [markdown]
# ## Check yourself
#
# These lines would change if the build, or the rule above, were different.

# %%
print("two triangles: origins", two.halfedge_vertex.tolist())
print("               next   ", two.halfedge_next.tolist())
print("               boundary halfedges", np.flatnonzero(two.halfedge_face < 0).tolist())
print("               vertex halfedges  ", two.vertex_halfedge.tolist())
cube = hx.sample("cube")
print(f"cube: {cube.n_faces} faces -> {cube.n_edges} edges -> {cube.n_halfedges} halfedges, "
      f"boundary halfedges: {int((cube.halfedge_face < 0).sum())}")
patch = hx.sample("open_patch")
print(f"open patch: {patch.n_faces} faces -> {patch.n_edges} edges -> {patch.n_halfedges} halfedges, "
      f"boundary halfedges: {int((patch.halfedge_face < 0).sum())}")

# %% [markdown]
# On a closed mesh every edge has two faces, so `3F = 2E` and there is no boundary
# halfedge. On the open patch, `3 × 18 = 54` halfedges come from faces and the other
# `66 - 54 = 12` run around the rim.

# %% [markdown]
# ## Exercise: write `build` yourself
#
# Fill in the five blanks marked `...` so that `build(faces)` returns a dictionary of
# three lists, one entry per halfedge, in the course's numbering:
#
# - `"vertex"`: the vertex each halfedge leaves;
# - `"face"`: its face, or `-1` for a boundary halfedge;
# - `"next"`: the next halfedge around its face (or along the boundary).
#
# No twin list: the twin of `h` is `h ^ 1`. (You may also return `"prev"` and
# `"vertex_halfedge"`; if you do, they are checked too.) Then run the check cell: it
# tries your function on nine meshes (two triangles, a lone triangle, a strip, a
# tetrahedron, a cube, the open patch, a ring with two boundary loops, and two meshes
# with shuffled numbering) and stops at the first difference, telling you which
# halfedge and why.

# %%
def build(faces):
    """faces (m, 3) -> {"vertex": [...], "face": [...], "next": [...]}, one entry per halfedge."""
    edge_of = {}                       # (smaller, larger) vertex pair -> edge number
    vertex, face, next_ = {}, {}, {}   # halfedge -> its origin, its face, its next

    for f, (i, j, k) in enumerate(faces):
        made = []                      # this face's three halfedges, in order
        for a, b in ((i, j), (j, k), (k, i)):
            key = (min(a, b), max(a, b))
            if key not in edge_of:
                edge_of[key] = len(edge_of)
                ### BEGIN SOLUTION
                h = 2 * edge_of[key]   # 1. first sighting of the edge: which halfedge?
                ### END SOLUTION
            else:
                ### BEGIN SOLUTION
                h = 2 * edge_of[key] + 1   # 2. second sighting: which halfedge?
                ### END SOLUTION
            vertex[h] = a
            face[h] = f
            made.append(h)
        for n in range(3):
            ### BEGIN SOLUTION
            next_[made[n]] = made[(n + 1) % 3]   # 3. the next halfedge around this face
            ### END SOLUTION

    n_halfedges = 2 * len(edge_of)
    boundary = [h for h in range(n_halfedges) if h not in vertex]   # no face made these
    for h in boundary:
        ### BEGIN SOLUTION
        vertex[h] = vertex[next_[h ^ 1]]   # 4. where does it start? (hint: where its twin ends)
        ### END SOLUTION
        face[h] = -1
    leaving = {vertex[h]: h for h in boundary}   # boundary vertex -> its outgoing boundary halfedge
    for h in boundary:
        ### BEGIN SOLUTION
        next_[h] = leaving[vertex[h ^ 1]]   # 5. the boundary halfedge leaving the vertex where h ends
        ### END SOLUTION

    return {
        "vertex": [vertex[h] for h in range(n_halfedges)],
        "face": [face[h] for h in range(n_halfedges)],
        "next": [next_[h] for h in range(n_halfedges)],
    }

# %%
from halfedge_edu.exercises import check_build

result = check_build(build)
result

# %% [markdown]
# ### What a mistake looks like
#
# To see how the check talks about a real mistake, here is a build with one planted
# bug: it takes the library's arrays but lets every boundary halfedge claim face 0.
# The check names the first halfedge that is wrong, and `result.show()` draws it
# (vermillion) with its twin, next and prev, on the mesh where the check stopped.

# %%
def build_with_a_bug(faces):
    arrays = hx.build_reference(faces)
    face = arrays.halfedge_face.copy()
    face[face < 0] = 0                      # the planted bug
    return {"vertex": arrays.halfedge_vertex, "face": face, "next": arrays.halfedge_next}


buggy = check_build(build_with_a_bug)
buggy

# %%
buggy.show()

# %% [markdown]
# ## Summary
#
# - Face `[i, j, k]` makes halfedges `(i, j)`, `(j, k)`, `(k, i)`, in that order, and
#   they are each other's `next` in a loop.
# - The first sighting of an edge makes halfedge `2e`; the second sighting, running
#   the other way, is its twin `2e + 1`. So `twin = h ^ 1` and `edge = h >> 1`.
# - An edge seen once gets a boundary halfedge (face `-1`) that starts where its twin
#   ends; boundary halfedges are linked by "next = the boundary halfedge leaving my
#   tip", which closes each hole into a loop.
# - Only faces are needed; positions ride along.
# - `hx.build_reference` (a loop you can read) and `HalfedgeMesh.from_faces` (numpy)
#   produce identical arrays.
#
# **Next:** chapter 03 walks on what we built: around faces, around vertices, and along
# the boundary.

# %% [markdown] tags=["solution"]
# ## Answer
#
# The answers are in the exercise cell above. The five blanks:
#
# 1. `2 * edge_of[key]`: the first sighting is the even halfedge of the new edge;
# 2. `2 * edge_of[key] + 1`: the second sighting is its twin;
# 3. `made[(n + 1) % 3]`: around the face, and from the last corner back to the first;
# 4. `vertex[next_[h ^ 1]]`: the twin `h ^ 1` runs `a -> b` inside its face, so `h`
#    starts at `b`, which is where the twin's `next` starts;
# 5. `leaving[vertex[h ^ 1]]`: `h` ends where its twin starts.
