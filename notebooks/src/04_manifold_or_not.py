# %% [markdown]
# # 04 · Manifold or not
#
# Chapters 02 and 03 built and walked halfedges on meshes that behaved. Some triangle
# lists do not: three faces hinge on one edge, or two cones touch at a single point.
# You can draw them, and a polygon soup stores them happily, but the halfedge
# structure **cannot hold them**. This chapter shows both cases, finds them with
# `hx.manifold_report`, shows the error construction gives, and repairs them.
#
# **By the end of this chapter you can**
#
# - say what makes an edge and a vertex *manifold*, in one sentence each;
# - recognise a non-manifold edge (three faces on one edge) and a non-manifold vertex
#   (two fans meeting at one point), and say exactly which pointer cannot be written;
# - find them in any face list with `hx.manifold_report`, and read the error that
#   `HalfedgeMesh.from_faces` raises for them;
# - repair a face list with `hx.repair_faces` or `hx.load(..., repair=True)`, and say
#   what the repair changed.

# %%
import tempfile
import warnings
from pathlib import Path

import numpy as np
import pyvista as pv

import halfedge_edu as hx
from halfedge_edu.viz import OneRingViewer

# %% [markdown]
# ## The picture
#
# Left: **three pages on one spine**. Three triangles share the edge between vertices 0
# and 1 (vermillion). Right: **two cones touching at their tips**. Two closed
# tetrahedra share vertex 0 (vermillion) and nothing else.

# %%
pages = hx.sample("nonmanifold_edge")
cones = hx.sample("nonmanifold_vertex")
print(type(pages).__name__, "| vertices", len(pages.vertices), "| faces", pages.faces.tolist())
print(type(cones).__name__, "| vertices", len(cones.vertices), "| faces", cones.faces.tolist())

# %%
colours = ["#E69F00", "#56B4E9", "#009E73", "#F0E442", "#CC79A7", "#0072B2", "#999999", "#E9E6DF"]
plotter = pv.Plotter(shape=(1, 2), window_size=(800, 400), border=False)

plotter.subplot(0, 0)
plotter.add_text("three faces on edge (0, 1)", font_size=11, color="black")
soup = pv.PolyData.from_regular_faces(pages.vertices, pages.faces)
plotter.add_mesh(soup, scalars=np.arange(3), cmap=colours[:3], show_scalar_bar=False,
                 show_edges=True, edge_color="#333333", ambient=0.5, diffuse=0.5)
plotter.add_mesh(pv.Line(pages.vertices[0], pages.vertices[1]), color="#D55E00", line_width=10,
                 render_lines_as_tubes=True)
plotter.add_point_labels(pages.vertices, [f"{i}" for i in range(len(pages.vertices))], font_size=16,
                         always_visible=True, shape_color="#333333", text_color="white", point_size=1)
plotter.camera_position = [(2.2, 1.0, 2.2), (0, 0, 0.4), (0, 0, 1)]
plotter.camera.zoom(0.7)

plotter.subplot(0, 1)
plotter.add_text("two fans at vertex 0", font_size=11, color="black")
two_cones = pv.PolyData.from_regular_faces(cones.vertices, cones.faces)
plotter.add_mesh(two_cones, scalars=np.repeat([0, 1], 4), cmap=colours[:2], show_scalar_bar=False,
                 show_edges=True, edge_color="#333333", ambient=0.5, diffuse=0.5)
plotter.add_points(cones.vertices[:1], color="#D55E00", point_size=22, render_points_as_spheres=True)
plotter.add_point_labels(cones.vertices, [f"{i}" for i in range(len(cones.vertices))], font_size=16,
                         always_visible=True, shape_color="#333333", text_color="white", point_size=1)
plotter.camera_position = [(4.2, -3.6, 1.4), (0, 0, 0), (0, 0, 1)]
plotter.camera.zoom(0.85)
plotter.show()

# %% [markdown]
# `hx.sample` gives these two back as a `RawMesh`, plain arrays of vertices and faces,
# and not as a `HalfedgeMesh`: as you will see, no `HalfedgeMesh` can hold them.
#
# The convention in two sentences: **an edge is manifold when one or two faces use it
# (running along it in opposite directions); a vertex is manifold when its faces form
# a single fan, so that you can go from any of them to any other by crossing edges
# that touch the vertex.** A halfedge mesh needs both, everywhere.

# %% [markdown]
# ## Finding them: `manifold_report`
#
# `hx.manifold_report(faces)` looks at a raw face array, builds nothing, raises
# nothing, and lists every place that breaks the rules. `bool(report)` is True when the
# faces can become a halfedge mesh.

# %%
report = hx.manifold_report(pages.faces)
print(report)
print("manifold:", bool(report))

# %%
report = hx.manifold_report(cones.faces)
print(report)
print("manifold:", bool(report))

# %% [markdown]
# The two samples are one of each kind, and only that kind:
#
# - the pages are **edge-non-manifold but vertex-manifold**: edge `(0, 1)` has three
#   faces, yet around each vertex the faces still form one fan (the three pages hang
#   together through the spine). Three faces on one edge also mean two of them must run
#   along it the same way, so the report lists the directed edge `1 -> 0` as used twice;
# - the cones are **vertex-non-manifold but edge-manifold**: every edge has exactly two
#   faces, yet vertex 0 has two separate fans.
#
# A good mesh gives a short, happy report:

# %%
print(hx.manifold_report(hx.sample("cube").to_arrays()[1]))
print(hx.manifold_report(hx.sample("bunny").to_arrays()[1]))

# %% [markdown]
# ## Why an edge cannot have three faces
#
# In chapter 02, edge `e` owns exactly two halfedges, `2e` and `2e + 1`, and each is the
# other's twin. A face that uses the edge needs one of them. Two faces: one each. A
# third face would need a third halfedge along the same edge, and then `twin` would
# have to point to *two* places at once. There is no such pointer, so construction
# stops and names the edge and its faces:

# %% tags=["raises-exception"]
hx.HalfedgeMesh.from_faces(pages.vertices, pages.faces)

# %% [markdown]
# The error is an `hx.MeshInputError` (a `ValueError`), and it carries the element, so
# a program can act on it:

# %%
try:
    hx.HalfedgeMesh.from_faces(pages.vertices, pages.faces)
except hx.MeshInputError as error:
    print("element:", error.element)

# %% [markdown]
# ## Why a vertex cannot have two fans
#
# A vertex stores **one** outgoing halfedge, and its one-ring is the walk
# `h = h.prev.twin` from there (chapter 03). That walk only ever crosses edges that
# touch the vertex, so it stays in one fan. Around vertex 0 of the cones, start in the
# lower cone and you go round the lower cone and come back; the upper cone's faces are
# never reached, and no single `halfedge` pointer could reach both.
#
# Here is that walk done on the raw faces: group the faces at a vertex into fans, where
# two faces are in the same fan when they share an edge at the vertex.

# %%
def fans_at(faces, v):
    """The faces around vertex v, grouped into fans (faces joined across edges at v)."""
    around = [f for f, face in enumerate(faces.tolist()) if v in face]
    fans, seen = [], set()
    for first in around:
        if first in seen:
            continue
        fan, todo = [], [first]
        seen.add(first)
        while todo:
            f = todo.pop()
            fan.append(f)
            for g in around:
                shares_an_edge = len(set(faces[f]) & set(faces[g])) == 2   # both contain v, plus one more
                if g not in seen and shares_an_edge:
                    seen.add(g)
                    todo.append(g)
        fans.append(sorted(fan))
    return fans


print("cones, vertex 0:", fans_at(cones.faces, 0))
print("cones, vertex 4:", fans_at(cones.faces, 4))
print("pages, vertex 0:", fans_at(pages.faces, 0))

# %% [markdown]
# Two fans at the tip, one everywhere else. Construction finds the same thing (it walks
# each vertex's ring and counts the halfedges the walk missed):

# %% tags=["raises-exception"]
hx.HalfedgeMesh.from_faces(cones.vertices, cones.faces)

# %% [markdown]
# ## Repairing: cut them apart
#
# The cure for both is to **give each fan its own copy of the vertex**.
# `hx.repair_faces(vertices, faces)` does that, and also drops degenerate and duplicate
# faces and turns faces round so that neighbours agree. It returns new arrays and a
# report of what it changed.

# %%
vertices, faces, changes = hx.repair_faces(cones.vertices, cones.faces)
print(changes)
print("new faces:", faces.tolist())

# %% [markdown]
# Vertex 0 kept the lower cone; the upper cone's corners at the tip now use a new
# vertex 7, at the same position. Now it builds: two closed pieces, each a sphere in
# the eyes of topology.

# %%
repaired_cones = hx.HalfedgeMesh.from_faces(vertices, faces)
print(repaired_cones)
print("pieces:", repaired_cones.n_components, "| V - E + F:", repaired_cones.euler_characteristic,
      "| same position:", np.array_equal(repaired_cones.vertex(7).position, repaired_cones.vertex(0).position))

# %% [markdown]
# Walk around the two copies of the tip. The viewer starts at vertex 0 (three
# neighbours: the lower cone); `pick(7)` moves to the copy (the upper cone).

# %%
tip_viewer = OneRingViewer(repaired_cones, vertex=0)
tip_viewer

# %%
print(tip_viewer.describe())
tip_viewer.pick(7)
print(tip_viewer.describe())

# %% [markdown]
# The pages need more cutting. All three run along the spine the same way (`1 -> 0`),
# so no two of them can be twins without turning one round, and there is no good
# reason to prefer a pair. The repair cuts the spine into three: vertices 0 and 1 each
# get two copies, and the pages come apart as three separate triangles.

# %%
vertices, faces, changes = hx.repair_faces(pages.vertices, pages.faces)
print(changes)
repaired_pages = hx.HalfedgeMesh.from_faces(vertices, faces)
print(repaired_pages)

# %% [markdown]
# ### From a file: `hx.load(..., repair=True)`
#
# Files are where broken meshes usually come from. Loading one fails with the error
# you have seen, now with the file's lines. With `repair=True`, `hx.load` repairs first,
# keeps the report on the mesh as `mesh.repair_report`, and warns you that it changed
# something (we catch the warning here to print it).

# %%
scratch = tempfile.TemporaryDirectory()   # a folder that is deleted at the end of this section
folder = Path(scratch.name)
hx.write_obj(folder / "pages.obj", pages.vertices, pages.faces)
print((folder / "pages.obj").read_text())

# %% tags=["raises-exception"]
hx.load(folder / "pages.obj")

# %%
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    mesh = hx.load(folder / "pages.obj", repair=True)
for warning in caught:
    print(f"{warning.category.__name__}: {warning.message}")
print(mesh)
print("vertex copies (original, copy):", mesh.repair_report.vertex_copies.tolist())
scratch.cleanup()

# %% [markdown]
# A repair is a decision made for you. Read its report: on a scanned statue, a few
# split vertices are harmless; on a CAD model, a hundred may mean the file should be
# fixed at its source.

# %% [markdown]
# ## Check yourself
#
# These lines would change if the detection, the errors or the repair were different.

# %%
pages_report, cones_report = hx.manifold_report(pages.faces), hx.manifold_report(cones.faces)
print("pages: non-manifold edges", pages_report.nonmanifold_edges.tolist(),
      "with faces", [f.tolist() for f in pages_report.nonmanifold_edge_faces],
      "| non-manifold vertices", pages_report.nonmanifold_vertices.tolist())
print("cones: non-manifold edges", cones_report.nonmanifold_edges.tolist(),
      "| non-manifold vertices", cones_report.nonmanifold_vertices.tolist())
for name, raw in [("pages", pages), ("cones", cones)]:
    try:
        hx.HalfedgeMesh.from_faces(raw.vertices, raw.faces)
    except hx.MeshInputError as error:
        print(f"{name} cannot be built; the error names", error.element)
print("cones repaired:", repaired_cones, "| tip ring sizes:", repaired_cones.vertex(0).degree,
      repaired_cones.vertex(7).degree)
print("pages repaired:", repaired_pages)

# %% [markdown]
# ## Exercises
#
# **1. Predict, then check.** For each face list below, decide: manifold, a
# non-manifold edge, a non-manifold vertex, or faces that disagree about direction?
# Write your guesses down, then check each with `hx.manifold_report(soups[name])`.
#
# - `bowtie`: two triangles that share only vertex 0;
# - `book`: four triangles on the edge `(0, 1)`;
# - `turned`: two triangles sharing an edge, one of them turned round;
# - `square`: two triangles sharing an edge, both counter-clockwise.

# %%
soups = {
    "bowtie": [[0, 1, 2], [0, 3, 4]],
    "book": [[0, 2, 1], [0, 1, 3], [0, 4, 1], [0, 1, 5]],
    "turned": [[0, 1, 2], [0, 3, 2]],
    "square": [[0, 1, 2], [0, 2, 3]],
}

# %% [markdown]
# **2. Cut the bowtie by hand.** Give the second triangle its own copy of vertex 0, so
# that the bowtie becomes two separate triangles. Fill in `cut_bowtie`: one new vertex,
# number 5, at the position of vertex 0, is already added; change the faces so that
# the second triangle uses it. `check_cut` builds your mesh and compares it with what
# `repair_faces` does.

# %%
from halfedge_edu.exercises.chapter_checks import check_cut


def cut_bowtie(vertices, faces):
    """The bowtie with its second fan on a copy of vertex 0: (vertices, faces)."""
    cut_vertices = np.vstack([vertices, vertices[0]])    # vertex 5: a copy of vertex 0 (done for you)
    ### BEGIN SOLUTION
    cut_faces = [[0, 1, 2], [5, 3, 4]]
    ### END SOLUTION
    return cut_vertices, cut_faces


check_cut(cut_bowtie)

# %% [markdown]
# **3. Ask a soup what is wrong with it.** `from_faces` refuses these face lists, so
# to *ask* them anything we need a structure that builds for any face list.
# `hx.SoupTopology(faces)` is one (UChicago's P3 asks for exactly this: "build topology
# for non-manifold objs without breaking"): three halfedges per face, and each edge keeps
# every face that uses it. You answer with its queries:
# `soup.edges()`, `soup.faces_of_edge(a, b)`, `soup.faces_of_vertex(v)`,
# `soup.faces[f]` and `soup.n_vertices`. Here is the book of exercise 1 as one:

# %%
book = hx.SoupTopology(soups["book"])
print(book)
print("faces on edge (0, 1):", book.faces_of_edge(0, 1))
print("faces at vertex 0:   ", book.faces_of_vertex(0))

# %% [markdown]
# Write both questions. An edge is manifold with one face or two. A vertex is manifold
# when its faces form one fan: starting from one of them, you reach all the others by
# crossing edges **that touch the vertex**. (The methods `soup.has_nonmanifold_edges()`
# and `soup.fans(v)` exist too; answer without them, then compare.)

# %%
from halfedge_edu.exercises.chapter_checks import check_nonmanifold


def has_nonmanifold_edges(soup):
    """True when some edge of the soup has more than two faces."""
    ### BEGIN SOLUTION
    return any(len(soup.faces_of_edge(a, b)) > 2 for a, b in soup.edges())
    ### END SOLUTION


def has_nonmanifold_vertices(soup):
    """True when the faces around some vertex form more than one fan."""
    ### BEGIN SOLUTION
    for v in range(soup.n_vertices):
        faces = soup.faces_of_vertex(v)
        if not faces:
            continue
        fan, stack = {faces[0]}, [faces[0]]          # grow one fan across edges at v
        while stack:
            f = stack.pop()
            for u in soup.faces[f]:
                if u != v:
                    for g in soup.faces_of_edge(v, int(u)):
                        if g not in fan:
                            fan.add(g)
                            stack.append(g)
        if len(fan) < len(faces):                  # a face left over: a second fan
            return True
    return False
    ### END SOLUTION


check_nonmanifold(has_nonmanifold_edges, has_nonmanifold_vertices)

# %% [markdown]
# ## Summary
#
# - **Manifold edge:** one or two faces, running along it in opposite directions.
#   **Manifold vertex:** its faces form a single fan.
# - A halfedge mesh needs both: an edge has exactly two halfedges (so at most two
#   faces), and a vertex has one `halfedge` from which one ring walk must reach all its
#   faces.
# - `hx.manifold_report(faces)` finds every problem without building anything;
#   `HalfedgeMesh.from_faces` raises `hx.MeshInputError` naming the edge or vertex (and
#   the file's line, when there is one).
# - `hx.repair_faces` and `hx.load(..., repair=True)` give each fan its own copy of the
#   vertex (and drop or turn bad faces); read the report to know what changed.
# - `hx.SoupTopology(faces)` builds for any face list, so you can ask a non-manifold
#   soup where it is non-manifold before you repair it.
#
# **Next:** chapter 05 puts geometry on the mesh: normals, areas and smoothing.

# %% [markdown] tags=["solution"]
# ## Answers
#
# **1.** The bowtie has a non-manifold vertex (0: two fans, each with its own piece of
# boundary); the book has a non-manifold edge `(0, 1)` with four faces; `turned` has
# two faces running the same way along `(2, 0)` (turn one round and it is fine); the
# square is manifold.

# %% tags=["solution"]
for name, soup_faces in soups.items():
    print(f"--- {name}")
    print(hx.manifold_report(soup_faces))

# %% [markdown] tags=["solution"]
# **2.** The answer is in the exercise cell: the second triangle uses the copy,
# `[[0, 1, 2], [5, 3, 4]]`.
