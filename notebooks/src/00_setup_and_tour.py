# %% [markdown]
# # 00 · Setup and tour
#
# Welcome. This course teaches the **halfedge mesh**, the data structure behind most
# programs that edit triangle meshes, one small step at a time. This first notebook
# makes sure everything runs on your machine and takes you on a short tour: a real
# mesh on screen, a few questions it answers instantly, and one edit.
#
# **By the end of this notebook you**
#
# - know your setup works: the package imports, and pictures and widgets appear;
# - have seen the Stanford bunny as a halfedge mesh, and asked it a few questions;
# - know what a halfedge mesh is *for*: answering "who is next to whom?" in a few
#   steps, and editing a mesh in place without rebuilding it;
# - know how the notebooks are laid out, and how to drive a widget from code.

# %% [markdown]
# ## Does everything import?
#
# Run the cell below (click it, then press **Shift + Enter**). Each line should say
# `ok`. If one raises an error instead, the package it names is missing: install the
# course's requirements (`make lab` in the repository does it for you) and try again.

# %%
import importlib

for name in ["numpy", "scipy", "trimesh", "pyvista", "ipywidgets", "halfedge_edu"]:
    importlib.import_module(name)
    print(f"{name:<13} ok")

# %%
import pyvista as pv

import halfedge_edu as hx
from halfedge_edu.viz import OneRingViewer, choose_mode, show

# %% [markdown]
# ## The bunny on screen
#
# This is the Stanford bunny, scanned from a clay figure in 1994 and a test subject of
# geometry processing ever since: 34,834 vertices and 69,451 triangles. If you see it
# below, 3D pictures work.

# %%
bunny = hx.sample("bunny")

plotter = pv.Plotter(window_size=(600, 450))
plotter.add_mesh(bunny.to_pyvista(), color="#E9E6DF", smooth_shading=True)
plotter.camera_position = "xy"
plotter.camera.zoom(1.3)
show(plotter)

# %% [markdown]
# Widgets (the panels with buttons further down) come in two kinds. In JupyterLab with
# the course's packages they are **live**: you can turn the 3D view with the mouse.
# Everywhere else (a plain notebook viewer, GitHub's preview, the course's automatic
# tests) they show a **static** picture that still follows every button press. This
# notebook was last run with:

# %%
print("widgets are", choose_mode())

# %% [markdown]
# ## What a halfedge mesh is for
#
# A mesh file is a list of triangles. That is enough to draw it, but not to *work* on
# it: to smooth a surface, simplify it or refine it, an algorithm keeps asking local
# questions ("what are this vertex's neighbours?", "which triangle is across this
# edge?") and making local edits ("merge these two vertices"). The halfedge mesh
# stores the pointers that make each such question a few steps, and each edit a few
# pointer changes, however large the mesh.
#
# The convention in one sentence: **every edge is split into two halfedges running
# opposite ways, and each halfedge knows its next halfedge around its face, its twin
# across the edge, the vertex it leaves and its face.** Chapters 02 and 03 build and
# walk exactly that. For now, just ask:

# %%
print(bunny)
v = bunny.vertex(100)
print("vertex 100 is at", v.position)
print("its neighbours, counter-clockwise:", [u.index for u in v.neighbors()])
print("its faces:", [f.index for f in v.faces()])
print("on the boundary:", v.is_boundary)

# %% [markdown]
# Each of those answers took six steps around vertex 100, not a search through 69
# thousand triangles. The bunny also has a few holes in its base (the scanner could not
# see under it); the boundary halfedges find them:

# %%
print("holes:", bunny.n_boundary_loops, "| edges around each:", [len(loop) for loop in bunny.boundary_loops()])
print("V - E + F =", bunny.euler_characteristic, "| genus:", bunny.genus)

# %% [markdown]
# So `V - E + F = 2` is not the sanity check for the bunny: a closed surface of genus 0
# has 2, and every hole lowers it by one, so five holes give `2 - 5 = -3`. Here are the
# five boundary loops, each drawn over the surface:

# %%
from IPython.display import Image

from halfedge_edu.viz import surface_png

Image(surface_png(bunny, view=(0.3, -1.0, 0.4), boundary_color="#D1495B", size=(480, 380)))  # seen from below

# %% [markdown]
# ## Look around a vertex
#
# The one-ring viewer shows a vertex (orange), its outgoing halfedges (blue), its
# neighbours and faces. Press **ccw** to turn to the next halfedge counter-clockwise,
# **to tip** to move to a neighbour, or type a vertex number and press **go to**. On a
# mesh this large it draws only the arrows near the vertex.

# %%
viewer = OneRingViewer(bunny, vertex=100)
viewer

# %% [markdown]
# Every widget in the course can also be driven from code, and says what it shows in
# words with `describe()`. That is how a lecture demo can be scripted, and how the
# course's tests check that the notebooks still work. Here a second viewer is driven, so
# the one above stays where you left it:

# %%
scripted = OneRingViewer(bunny, vertex=100, mode="static")   # never shown: no live view
scripted.go("ccw")
scripted.go("tip")
print(scripted.describe())
scripted.close()

# %% [markdown]
# ## One edit
#
# Now a change: **collapse** one edge, merging its two ends into one vertex. On a list
# of triangles you would rebuild everything around the change; on a halfedge mesh the
# collapse rewires a handful of pointers and flags the removed elements as deleted.
# `validate()` then checks every rule of the structure.

# %%
edge = bunny.vertex(100).halfedge.edge
print("collapsing", edge, "-", bunny.can_collapse(edge).reason)
survivor = bunny.collapse(edge)
bunny.validate()
print("survivor:", survivor.index, "| now", bunny)

# %% [markdown]
# One vertex, three edges and two triangles fewer, and the mesh is still sound. (The
# viewer above keeps showing the bunny as it was: every widget holds its own copy of
# the mesh it was given.)
# Chapter 07 explains exactly which pointers changed, and chapters 09 to 11 build whole
# algorithms (subdivision, simplification, remeshing) from such edits.

# %% [markdown]
# ## How the course is laid out
#
# | # | Chapter | You will |
# |---|---|---|
# | 00 | Setup and tour | check your setup (this notebook) |
# | 01 | Polygon soup and OBJ | read and write mesh files by hand |
# | 02 | Building the halfedge structure | build the pointers from a list of triangles |
# | 03 | Navigating | walk next / prev / twin, around faces and vertices |
# | 04 | Manifold or not | meet the meshes halfedges cannot hold |
# | 05 | Geometry on the mesh | normals, areas, smoothing |
# | 06 | Edge flip and edge split | the first local edits |
# | 07 | Edge collapse | the edit behind simplification |
# | 08 | The link condition | when a collapse would break the mesh |
# | 08b | Debugging lab | nine classic halfedge bugs, and how `validate()` finds them |
# | 09 | Loop subdivision | smoother meshes from coarser ones |
# | 10 | Quadric error simplification | coarser meshes that keep the shape |
# | 11 | Isotropic remeshing | even, well-shaped triangles |
# | 12 | Bezier curves and surfaces | smooth shapes from control points |
# | 13 | Putting it together | everything on one mesh |
#
# Every chapter has the same shape: **learning goals**, a **picture** first, the idea
# in a few short cells, code you can change, at least one **widget**, a **check
# yourself** cell, **exercises** with a `check_...` helper that tells you in words what
# is off, a short **summary**, and the **answers** at the very end (in the solution
# edition; the student edition, which `halfedge-edu course` hands out, leaves them out).
#
# **Instructors:** every widget takes `preset="large"` (bigger labels and arrows, for a
# projector), e.g. `OneRingViewer(bunny, vertex=100, preset="large")`.
#
# **On a course hub** the live 3D view may be drawn by your browser instead of the
# kernel (the hub sets this; rotating is then smooth however many students are logged
# in). That view draws **no number labels**, and vertices are squares: when the text
# says "vertex 4" or "halfedge 7", read the numbers in the widget's table beside the
# view (the current halfedge, its origin, tip, twin, next, prev, edge and face) or in
# the pictures of the course website. On your own machine (`make lab`) the kernel
# draws the view, labels included.

# %% [markdown]
# ## Check yourself
#
# Run this cell: it prints facts about the bunny that the rest of the course relies
# on. If the package were broken, they would change.

# %%
fresh = hx.sample("bunny")
print("bunny:", fresh.n_vertices, "vertices,", fresh.n_edges, "edges,", fresh.n_faces, "faces")
print("closed:", fresh.is_closed, "| holes:", fresh.n_boundary_loops, "| genus:", fresh.genus)
print("vertex 100: degree", fresh.vertex(100).degree, "| neighbours", [u.index for u in fresh.vertex(100).neighbors()])
print("after one collapse:", bunny.n_vertices, "vertices,", bunny.n_edges, "edges,", bunny.n_faces, "faces")
print("samples:", ", ".join(hx.samples()))

# %% [markdown]
# ## Exercise: tour another mesh
#
# `hx.sample("spot")` is Spot the cow. Find out, with what you saw above:
#
# 1. how many vertices, edges and faces Spot has, and whether it has holes;
# 2. which vertex has the **most** neighbours, and who they are.
#
# (Hint for 2: `max(mesh.vertices, key=lambda v: v.degree)`.)

# %%
spot = hx.sample("spot")
# your code here

# %% [markdown]
# ## Summary
#
# - The package imports, pictures appear, and widgets work, live or static.
# - A halfedge mesh answers local questions (neighbours, faces, holes) in a few steps
#   and makes local edits (like a collapse) by changing a few pointers.
# - Every widget can be driven from code (`go`, `step`, `pick`) and tells its state
#   with `describe()`.
#
# **Next:** chapter 01 starts where every mesh starts: a file of triangles.

# %% [markdown] tags=["solution"]
# ## Answers

# %% tags=["solution"]
print(spot, "| closed:", spot.is_closed)
busiest = max(spot.vertices, key=lambda v: v.degree)
print("vertex", busiest.index, "has", busiest.degree, "neighbours:", [u.index for u in busiest.neighbors()])
