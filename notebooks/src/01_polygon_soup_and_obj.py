# %% [markdown]
# # 01 · Polygon soup and the OBJ file
#
# Before a mesh can be navigated it has to be read. This chapter opens the simplest
# mesh file there is, the Wavefront OBJ, reads it with the package's own parser, and
# ends with the question that motivates the rest of the course: *a list of triangles
# knows its corners, but who are a vertex's neighbours?*
#
# **By the end of this chapter you can**
#
# - read and write the `v` and `f` lines of an OBJ file by hand;
# - say why `f 1 2 3` means the vertices numbered 0, 1 and 2 in Python;
# - use comments, negative indices and polygons, and say what the reader does with each;
# - read an error message and go straight to the line of the file it names;
# - write a small OBJ reader and writer of your own (the Loop-subdivision assignment's
#   first task);
# - explain why a *polygon soup* (faces only) answers "who are my neighbours?" slowly,
#   and why that is the reason for the halfedge structure of chapter 02.

# %%
import html
import io
import warnings

import numpy as np
import pyvista as pv

import halfedge_edu as hx

# %% [markdown]
# ## A file you can read
#
# Here is a square pyramid, drawn with the numbers its OBJ file uses. Four corners
# stand on the floor, one apex sits on top; the floor is a square, the four sides are
# triangles.

# %%
pyramid_obj = """\
# A square pyramid: four corners on the floor, one apex.
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.5 0.5 0.8   # the apex
f 1 4 3 2       # the floor, a square (counter-clockwise seen from below)
f 1 2 5
f 2 3 5
f 3 4 5
f 4 1 5
"""

# %%
from halfedge_edu.viz import show

pyramid = hx.read_obj(io.StringIO(pyramid_obj))

plotter = pv.Plotter(window_size=(600, 400))
plotter.add_mesh(pv.PolyData.from_regular_faces(pyramid.vertices, pyramid.faces),
                 color="#E9E6DF", opacity=0.75, show_edges=True, edge_color="#333333", line_width=2)
plotter.add_point_labels(pyramid.vertices, [f"v {n}" for n in range(1, 6)], font_size=20, always_visible=True,
                         point_size=14, point_color="#D55E00", shape_color="#333333", text_color="white")
plotter.camera_position = [(2.2, -2.3, 1.5), (0.5, 0.5, 0.3), (0, 0, 1)]
show(plotter)

# %% [markdown]
# The convention in one sentence: **an OBJ file lists the vertices as `v x y z` lines,
# then each face as an `f` line of vertex numbers counted from 1, going
# counter-clockwise when you look at the face from outside.**
#
# That is all a mesh file needs. Everything else in the file (colours, texture
# coordinates, normals, group names) is optional, and our reader skips it; a line that
# is not OBJ at all (a mistyped `vx`, bare numbers) is an error naming its line.

# %% [markdown]
# ## Reading it
#
# `hx.read_obj` takes a path or an open file. A string wrapped in `io.StringIO` is an
# open file too, which is handy for examples like this one.

# %%
print(pyramid.vertices)

# %%
print(pyramid.faces)

# %% [markdown]
# Three things to notice:
#
# 1. **Indices start at 1 in the file and at 0 in Python.** `f 1 2 5` became `[0, 1, 4]`.
#    Every OBJ reader subtracts one; forgetting it is the most common OBJ bug.
# 2. **The square became two triangles.** `f 1 4 3 2` is a polygon with four corners;
#    the reader cut it into `[0, 3, 2]` and `[0, 2, 1]`.
# 3. **The comments are gone.** `#` starts a comment, at the start of a line or after a
#    record.
#
# The reader also remembers which line each triangle came from, so that error messages
# can point into the file:

# %%
for face, line in zip(pyramid.faces.tolist(), pyramid.face_lines.tolist()):
    record = pyramid_obj.splitlines()[line - 1].split("#")[0].strip()
    print(f"line {line:>2}: {record:<10} -> face {face}")
print("polygons cut into triangles:", pyramid.n_polygons_triangulated)

# %% [markdown]
# ## Polygons become fans
#
# A polygon `f a b c d e ...` becomes the triangles `(a, b, c)`, `(a, c, d)`,
# `(a, d, e)`, ...: all of them share the first corner, like the ribs of a folding fan.
# Each triangle keeps the polygon's direction, so the orientation survives. Here is a
# hexagon:

# %%
hexagon_obj = "".join(f"v {np.cos(a):.3f} {np.sin(a):.3f} 0\n" for a in np.linspace(0, 2 * np.pi, 7)[:-1])
hexagon_obj += "f 1 2 3 4 5 6\n"
hexagon = hx.read_obj(io.StringIO(hexagon_obj))
print(hexagon.faces + 1)  # back to the file's 1-based numbers

# %%
plotter = pv.Plotter(window_size=(600, 400))
plotter.add_mesh(pv.PolyData.from_regular_faces(hexagon.vertices, hexagon.faces),
                 scalars=np.arange(4), cmap=["#E69F00", "#56B4E9", "#009E73", "#F0E442"],
                 show_edges=True, edge_color="black", line_width=3, show_scalar_bar=False)
plotter.add_point_labels(hexagon.vertices, [str(n) for n in range(1, 7)], font_size=20,
                         point_size=12, shape_color="#333333", text_color="white")
plotter.view_xy()
show(plotter)

# %% [markdown]
# A fan is only a good cut when the polygon is convex (every fan triangle then lies
# inside it). For a course on triangle meshes that is fine. If you would rather be
# told about polygons than have them cut, pass `triangulate=False`: the reader then
# refuses, and names the line.

# %% tags=["raises-exception"]
hx.read_obj(io.StringIO(pyramid_obj), triangulate=False)

# %% [markdown]
# ## Negative indices, and lines the reader skips
#
# A negative index counts back from the **last vertex defined so far**: `-1` is the
# newest vertex, `-2` the one before. Exporters like it because a face can be written
# right after its own vertices without knowing how many came before.
#
# Real files also carry records we do not need: `vt` (texture coordinates), `vn`
# (normals), `g` and `o` (group and object names), `usemtl` (a material). Face corners
# may then look like `3/7/2` (vertex / texture / normal); only the first number is the
# vertex.

# %%
exported_obj = """\
o two_triangles
v 0 0 0
v 1 0 0
v 0 1 0
f -3 -2 -1          # the three vertices just above
v 1 1 0
vt 0.5 0.5
vn 0 0 1
usemtl red
f 2/1/1 4/1/1 3/1/1 # vertex/texture/normal: only the vertex counts
"""
two = hx.read_obj(io.StringIO(exported_obj))
print(two.faces)

# %% [markdown]
# `f -3 -2 -1` on line 5 comes after three vertices, so it means vertices 1, 2, 3 in
# file numbers, `[0, 1, 2]` in Python.

# %% [markdown]
# ## Writing
#
# `hx.write_obj` does the reverse: 1-based indices, one record per line. Coordinates
# are written with enough digits that reading the file back gives exactly the same
# numbers.

# %%
out = io.StringIO()
hx.write_obj(out, pyramid.vertices, pyramid.faces, header="the pyramid, as triangles")
print(out.getvalue())

# %%
again = hx.read_obj(io.StringIO(out.getvalue()))
print("same vertices:", np.array_equal(again.vertices, pyramid.vertices))
print("same faces:   ", np.array_equal(again.faces, pyramid.faces))

# %% [markdown]
# The square floor comes back as two triangles: once cut, a polygon stays cut.

# %% [markdown]
# ## When the file is wrong
#
# A broken file raises `hx.MeshInputError`. Its message names the file (here
# `<file>`, since a `StringIO` has no name), the line, and quotes the line, and its
# `.line` attribute is the line number. Here face line 7 asks for vertex 9 of a file
# with five:

# %% tags=["raises-exception"]
broken_obj = pyramid_obj.replace("f 1 4 3 2", "f 1 4 3 9")
hx.read_obj(io.StringIO(broken_obj))

# %% [markdown]
# The reader checks everything before it hands anything back, so you never get half a
# mesh. A few more mistakes, each with the line it is found on:

# %%
mistakes = {
    "index 0": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
    "two corners": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n",
    "not a number": "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n",
    "-4 before the start": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n",
}
for name, text in mistakes.items():
    try:
        hx.read_obj(io.StringIO(text))
    except hx.MeshInputError as error:
        print(f"{name:>20} -> .line = {error.line}: {error}")

# %% [markdown]
# Some files are fine line by line and still not a surface, for instance when one face
# is turned the wrong way round. The reader cannot see that: it is a question about
# how faces fit together. Building a mesh can, and with the `face_lines` the reader
# kept, the message still points at the file's line. (`hx.load("file.obj")` passes
# them on for you.)

# %% tags=["raises-exception"]
flipped_obj = pyramid_obj.replace("f 2 3 5", "f 3 2 5")
flipped = hx.read_obj(io.StringIO(flipped_obj))
hx.HalfedgeMesh.from_faces(flipped.vertices, flipped.faces, face_lines=flipped.face_lines, source="pyramid.obj")

# %% [markdown]
# ## Try it: an OBJ playground
#
# Edit the file in the box (click outside it to apply). Below it you see what the
# reader and the halfedge builder make of it: the counts and a picture, or the error
# and its line. Try deleting a `v` line, turning a face around, or adding a sixth
# vertex that no face uses.
#
# You do not need to read the code of this cell; it only wires a text box to
# `read_obj` and `HalfedgeMesh.from_faces`.

# %%
import ipywidgets as widgets

from halfedge_edu.viz import on_main_thread, plotter_png

editor = widgets.Textarea(value=pyramid_obj, rows=13, continuous_update=False,
                          layout=widgets.Layout(width="460px"))
verdict = widgets.HTML(layout=widgets.Layout(width="360px", min_height="4.5em"))
picture = widgets.Image(format="png", width=360, height=270)
playground_plotter = pv.Plotter(off_screen=True, window_size=(360, 270))
SEEN_FROM = (1.0, -1.6, 1.1)   # front right, above: no face is seen edge-on


def show_verdict(text: str, color: str) -> None:
    """Write the verdict in the box, line by line (nothing cut off)."""
    lines = "<br>".join(html.escape(line) for line in text.splitlines())
    verdict.value = f'<div style="color:{color};line-height:1.35">{lines}</div>'


def judge(obj_text: str):
    """What the reader and the builder make of ``obj_text``: ``(verdict, mesh or None)``."""
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            data = hx.read_obj(io.StringIO(obj_text))
            mesh = hx.HalfedgeMesh.from_faces(data.vertices, data.faces, face_lines=data.face_lines)
    except hx.MeshInputError as error:
        return f"Not a mesh yet. {error}", None
    notes = "".join(f"\nNote: {w.message}" for w in caught)
    return (f"A mesh. {mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} "
            f"triangles, {mesh.n_boundary_loops} boundary loop(s).{notes}"), mesh


def read_editor(change=None):
    """Judge the text box and show the verdict with the mesh (or the error, and no mesh)."""
    text, mesh = judge(editor.value)
    playground_plotter.clear()
    if mesh is None:
        show_verdict(text, "#B00020")
        playground_plotter.add_text("no mesh to draw", position="upper_left", font_size=12, color="#B00020")
    else:
        show_verdict(text, "#333333")
        playground_plotter.add_mesh(mesh.to_pyvista(), color="#E9E6DF", show_edges=True, edge_color="#555555")
        playground_plotter.view_vector(SEEN_FROM, viewup=(0, 0, 1))
        playground_plotter.reset_camera()
    picture.value = plotter_png(playground_plotter)


# A text box change from the browser arrives on another thread; the redraw runs on the main one.
editor.observe(on_main_thread(read_editor), names="value")
read_editor()
playground = widgets.HBox([editor, widgets.VBox([verdict, picture])])
playground

# %% [markdown]
# The playground's verdict comes from `judge`, a plain function. Here we break the
# file on purpose and read what it says:

# %%
print(judge(pyramid_obj.replace("v 0 1 0", "v 0 one 0"))[0])
print(judge(pyramid_obj + "v 9 9 9\n")[0])

# %% [markdown]
# ## Soup versus connectivity
#
# What the reader returns is a **polygon soup**: a list of corners for each face and
# nothing else. That is enough to draw the mesh. It is not enough to *walk* on it.
#
# Ask a soup "who are the neighbours of vertex `v`?" and it has only one way to
# answer: look at **every** face, keep those that contain `v`, and collect their other
# corners.

# %%
def soup_neighbours(faces, v):
    """The neighbours of v in a polygon soup, and how many faces we had to look at."""
    touching = faces[(faces == v).any(axis=1)]       # looks at every row of faces
    neighbours = sorted(set(touching.ravel().tolist()) - {v})
    return neighbours, len(faces)


print(soup_neighbours(pyramid.faces, 4))  # the apex

# %% [markdown]
# On five faces that is nothing. On the Stanford bunny it is not:

# %%
bunny = hx.sample("bunny")
bunny_vertices, bunny_faces = bunny.to_arrays()
print(f"{len(bunny_vertices)} vertices, {len(bunny_faces)} faces")

# %%
v = 100
from_soup, faces_looked_at = soup_neighbours(bunny_faces, v)
ring = bunny.vertex(v).outgoing()
print("neighbours from the soup:         ", from_soup)
print("neighbours from the halfedge mesh:", sorted(int(h.tip) for h in ring))
print("faces the soup looked at:          ", faces_looked_at)
print("halfedges the halfedge mesh stepped:", len(ring))

# %% [markdown]
# Same answer, very different work. The soup looked at all 69,451 faces to find six
# neighbours; the halfedge mesh stepped through exactly six halfedges, one per
# neighbour. Asked for *every* vertex (which smoothing, subdivision and remeshing all
# do), the soup's work multiplies:

# %%
V, F, H = len(bunny_vertices), len(bunny_faces), bunny.n_halfedges
print(f"soup, every vertex:          {V} x {F} = {V * F:,} face looks")
print(f"halfedge mesh, every vertex: {H:,} halfedge steps (each halfedge once)")

# %% [markdown]
# That is `V × F` work against work proportional to the mesh's size: about 2.4 billion
# looks against about 200 thousand steps. Two more things the soup
# cannot tell you without such a search:
#
# - **the order** of the neighbours around `v` (our `sorted` threw away any order; the
#   halfedge mesh gives them counter-clockwise);
# - **which face lies across an edge**, the question every walk over a surface asks.
#
# You could build an index once, say a dictionary from each vertex to its faces, and
# reuse it. That is exactly the right idea, and doing it properly, with every pointer a
# walk needs, is the halfedge structure. Chapter 02 builds it.

# %% [markdown]
# ## Check yourself
#
# Run this cell. If the library or your reading of this chapter were wrong, these
# lines would change.

# %%
print("pyramid: vertices", len(pyramid.vertices), "| triangles", len(pyramid.faces),
      "| polygons cut", pyramid.n_polygons_triangulated)
print("file line 7 'f 1 4 3 2' becomes", pyramid.faces[pyramid.face_lines == 7].tolist())
print("'f -3 -2 -1' after three vertices is", two.faces[0].tolist())
try:
    hx.read_obj(io.StringIO(broken_obj))
except hx.MeshInputError as error:
    print("the broken file fails on line", error.line)
print("apex neighbours, soup:", soup_neighbours(pyramid.faces, 4)[0])
pyramid_mesh = hx.HalfedgeMesh.from_faces(pyramid.vertices, pyramid.faces)
print("apex neighbours, halfedges (counter-clockwise):", [int(u) for u in pyramid_mesh.vertex(4).neighbors()])

# %% [markdown]
# ## Exercises
#
# **1. A tetrahedron by hand.** Write the OBJ text of a tetrahedron with corners
# `(0,0,0)`, `(1,0,0)`, `(0,1,0)`, `(0,0,1)`, faces counter-clockwise seen from outside.
# If `HalfedgeMesh.from_faces` accepts it and reports 4 vertices, 6 edges, 4 faces and
# no boundary, your orientation is consistent. (A face turned the wrong way gives the
# "directed edge ... is used by two faces" error you saw above.)

# %%
my_tetrahedron_obj = """\
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
"""  # add the four f lines

try:
    data = hx.read_obj(io.StringIO(my_tetrahedron_obj))
    print(hx.HalfedgeMesh.from_faces(data.vertices, data.faces))
except hx.MeshInputError as error:
    print("Not yet:", error)

# %% [markdown]
# **2. Your own fan.** Write `fan(corners)` that cuts one polygon (a list of 0-based
# vertex indices) into triangles the way the reader does. The check below compares your
# triangles with the reader's for polygons of 3 to 8 corners.

# %%
def fan(corners):
    """[(a, b, c), (a, c, d), ...] for the polygon a, b, c, d, ..."""
    ### BEGIN SOLUTION
    return [(corners[0], corners[k], corners[k + 1]) for k in range(1, len(corners) - 1)]
    ### END SOLUTION

# %%
from halfedge_edu.exercises.chapter_checks import check_fan

check_fan(fan)

# %% [markdown]
# **3. Your own reader and writer.** This is the first task of the Loop-subdivision
# assignment: read and write OBJ files yourself, as a polygon soup.
#
# - `read_obj(source)` takes the file's text (a `str`) or a `pathlib.Path` to the file,
#   and returns `(vertices, faces)`: `vertices` an `(n, 3)` float array, one row per `v`
#   line in the file's order, and `faces` a list with one entry per `f` line, its
#   **0-based** corners in the file's order. **Keep polygons whole**: a quad is a list of
#   four corners. (Cutting it into a fan as `hx.read_obj` does is accepted too; the
#   Loop assignment would let you skip or refuse polygons, but the check's files have a
#   quad, so do not.)
# - Everything this chapter showed must work: comments and blank lines, words separated
#   by any whitespace, records you skip (`vt`, `vn`, `o`, `g`, `usemtl`, `s` ...),
#   corners `v/vt/vn`, `v//vn` and `v/vt` (the vertex is the number before the first
#   `/`), negative indices (counted back from the last vertex defined *above* the line),
#   Windows line ends, and a last line without a line break.
# - `write_obj(vertices, faces)` returns the text of the file: a `v x y z` line per
#   vertex, then an `f` line per face with 1-based indices, corners in the order given.
#
# Skip error handling here: the check's files are all valid. The check reads nine small
# texts and `spot.obj` (as a `Path`) and compares with `hx.read_obj`, reads your
# writer's text back with `hx.read_obj`, and finally sends the pyramid through your
# writer and your reader.

# %%
from pathlib import Path


def read_obj(source):
    """(vertices, faces) of an OBJ file; ``source`` is its text, or a pathlib.Path to it."""
    ### BEGIN SOLUTION
    text = source.read_text() if isinstance(source, Path) else source
    vertices, faces = [], []
    for line in text.splitlines():               # also splits at "\r\n" and keeps a last line without "\n"
        words = line.split("#", 1)[0].split()    # drop the comment, split on any whitespace
        if not words:
            continue
        if words[0] == "v":
            vertices.append([float(x) for x in words[1:4]])
        elif words[0] == "f":
            corners = []
            for corner in words[1:]:
                index = int(corner.split("/")[0])    # "3/7/2", "3//2", "3/7" and "3" are all vertex 3
                corners.append(index - 1 if index > 0 else len(vertices) + index)
            faces.append(corners)
    return np.array(vertices, dtype=float).reshape(-1, 3), faces
    ### END SOLUTION


# %%
def write_obj(vertices, faces):
    """The text of an OBJ file with these vertices ((n, 3) floats) and faces (0-based corner lists)."""
    ### BEGIN SOLUTION
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, dtype=float).tolist()]
    for face in faces:
        lines.append("f " + " ".join(str(int(corner) + 1) for corner in face))
    return "\n".join(lines) + "\n"
    ### END SOLUTION

# %%
from halfedge_edu.exercises.chapter_checks import check_obj_io

check_obj_io(read_obj, write_obj)

# %% [markdown] tags=["solution"]
# ### Answers
#
# **1.** One consistent choice (each face counter-clockwise seen from outside):
#
# ```
# f 1 3 2
# f 1 2 4
# f 1 4 3
# f 2 3 4
# ```
#
# **2.** The answer is in the exercise cell: every triangle shares the first corner.
#
# **3.** The answer is in the exercise cells. `repr(x)` writes the shortest text that
# reads back as exactly the same float, so a file written and read again gives the same
# numbers; the reader turns a negative index into a 0-based one with the count of
# vertices read so far, which is why it must be done while reading, not at the end.

# %% tags=["solution"]
data = hx.read_obj(io.StringIO(my_tetrahedron_obj + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"))
print(hx.HalfedgeMesh.from_faces(data.vertices, data.faces))

# %% [markdown]
# ## Summary
#
# - An OBJ file is `v x y z` lines and `f i j k ...` lines; face numbers start at **1**,
#   negative ones count back from the newest vertex, `#` starts a comment, other OBJ
#   records (`vt`, `vn`, `g`, `usemtl` ...) are skipped, and a line that is not OBJ is
#   an error.
# - Polygons are cut into fans `(a, b, c), (a, c, d), ...`; `triangulate=False` refuses
#   them instead.
# - Errors are `hx.MeshInputError` with the file's line number in `.line` and in the
#   message.
# - What you get is a **polygon soup**: corners of faces, no neighbours. Finding a
#   vertex's neighbours means searching every face, `V × F` work for the whole mesh.
#
# **Next:** chapter 02 turns the soup into halfedges, once, so that every later
# question is a few pointer steps.
