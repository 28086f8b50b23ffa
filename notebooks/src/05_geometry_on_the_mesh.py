# %% [markdown]
# # 05 · Geometry on the mesh
#
# Until now the halfedge structure has been pure connectivity: who is next to whom.
# This chapter puts the positions back in and computes things you can *see*: which way
# each triangle faces, how a vertex can have a direction of its own, and how to make a
# surface smoother by moving every vertex towards its neighbours.
#
# **After this chapter you can**
#
# - compute edge vectors from the halfedges: tip minus origin;
# - compute a face normal with the right-hand rule, and say why its length is twice the area;
# - average face normals into area-weighted vertex normals, and explain flat versus smooth shading;
# - write one step of uniform Laplacian smoothing, Jacobi style (new positions only from old ones),
#   and say what happens over many steps.

# %%
import numpy as np
import pyvista as pv

import halfedge_edu as hx
from halfedge_edu import face_normals, smooth, vertex_normals
from halfedge_edu.viz import SmoothingViewer, show

spot = hx.sample("spot")
V, F = spot.to_arrays()

picture = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(760, 360), border=False)
for column, shading in enumerate(["flat", "smooth"]):
    surface = pv.PolyData.from_regular_faces(V, F)
    if shading == "smooth":
        surface.point_data["Normals"] = vertex_normals(spot)   # our normals, one per vertex
        surface.point_data.active_normals_name = "Normals"
    picture.subplot(0, column)
    picture.add_mesh(surface, color="#E8B96A", interpolation="flat" if shading == "flat" else "gouraud")
    picture.add_text(f"{shading} shading", font_size=11)
picture.link_views()
picture.camera_position = [(2.6, 0.9, -2.2), (0.0, 0.1, 0.1), (0.0, 1.0, 0.0)]
show(picture)

# %% [markdown]
# The same 5,856 triangles twice. On the left every triangle is lit as one flat piece;
# on the right the light changes smoothly across each triangle, and the cow looks
# round. The difference is nothing but *which normals* the renderer was given. By the
# end of this chapter you will have computed both sets yourself.

# %% [markdown]
# ## 1. Edge vectors
#
# **Convention: a halfedge's vector is its tip minus its origin, `h.tip.position - h.vertex.position`; its twin's vector is the same arrow reversed.**
#
# Every geometric quantity in this chapter starts from these vectors. With handles you
# ask one halfedge; with the arrays you get all of them at once.

# %%
cube = hx.sample("cube")
h = cube.halfedge(0)
print(h, "vector:", h.vector)
print(h.twin, "vector:", h.twin.vector)

# %%
P = cube.positions                                        # (V, 3) float
vectors = P[cube.halfedge_tip()] - P[cube.halfedge_vertex]  # (H, 3): tip minus origin, every halfedge
lengths = np.linalg.norm(vectors[0::2], axis=1)           # (E,): one halfedge per edge is enough

print("twin vectors are reversed:", np.allclose(vectors[0::2], -vectors[1::2]))
for length, count in zip(*np.unique(lengths.round(4), return_counts=True)):
    print(f"{count:2d} edges of length {length}")

# %% [markdown]
# The cube has 12 edges of length 1 (its sides) and 6 of length $\sqrt 2 \approx 1.4142$:
# the diagonal that cuts each square into two triangles.

# %% [markdown]
# ## 2. Face normals
#
# **Convention: for a face with corners `a, b, c` in counter-clockwise order seen from
# outside, `(b - a) × (c - a)` points outwards, and its length is twice the triangle's area.**
#
# That is the right-hand rule: curl the fingers of your right hand along
# `a → b → c` and your thumb points out of the surface. This is why the order of a
# face's vertices matters, and why the halfedges of a face all run counter-clockwise.
# The unit normal is that vector divided by its length.
#
# First one face at a time, with handles, the way you would write it on paper:

# %%
def face_normal_by_hand(face):
    a, b, c = (v.position for v in face.vertices())
    n = np.cross(b - a, c - a)          # outwards, length = 2 * area
    return n / np.linalg.norm(n)


for f in (0, 1, 4):
    face = cube.face(f)
    print(face, "normal", face_normal_by_hand(face) + 0.0, "area", face.area)

# %% [markdown]
# Faces 0 and 1 are the two halves of the square at x = 0, so both point along −x.
# Face 4 lies in the square at y = 0 and points along −y. (The `+ 0.0` only turns a
# printed `-0.` into `0.`.)
#
# Now every face at once. `mesh.face_vertices()` gives the three corners of each face
# in counter-clockwise order, so the whole loop becomes three array lookups and one
# `np.cross`:

# %%
def face_normals_numpy(mesh):
    P = mesh.positions
    corners = mesh.face_vertices()                  # (F, 3) vertex indices, CCW
    a, b, c = P[corners[:, 0]], P[corners[:, 1]], P[corners[:, 2]]
    cross = np.cross(b - a, c - a)                  # (F, 3), length 2 * area
    return cross / np.linalg.norm(cross, axis=1, keepdims=True)


print("cube: loop == numpy:", np.allclose([face_normal_by_hand(f) for f in cube.faces], face_normals_numpy(cube)))
print("spot: numpy == library:", np.allclose(face_normals_numpy(spot), face_normals(spot)))

# %% [markdown]
# `hx.face_normals` is the same computation, with one extra care:
# a triangle of zero area gets a zero normal instead of a division by zero.

# %% [markdown]
# ## 3. Vertex normals
#
# **Convention: a vertex's normal is the sum of `(b - a) × (c - a)` over the faces
# around it, scaled to length 1; since each of those vectors is twice its face's area
# long, bigger faces count more.**
#
# A vertex is a point, and a point has no direction. But the faces around it do, and
# their average is a good guess of the direction the surface would have there if it
# were smooth. Area weighting comes for free: simply *do not* normalize the face
# vectors before adding them.
#
# In the picture, the short red arrows are face normals (one per triangle, from its
# centre) and the blue arrows are the vertex normals of the cube.

# %%
P = cube.positions                                    # (8, 3)
centres = P[cube.face_vertices()].mean(axis=1)        # (12, 3) face centres
face_arrows = pv.PolyData(centres)
face_arrows["n"] = face_normals(cube)
vertex_arrows = pv.PolyData(P.copy())
vertex_arrows["n"] = vertex_normals(cube)

picture = pv.Plotter(off_screen=True, window_size=(520, 420))
picture.add_mesh(cube.to_pyvista(), color="#EDEAE3", show_edges=True, edge_color="#8A8680")
picture.add_mesh(face_arrows.glyph(orient="n", scale=False, factor=0.35), color="#D55E00")
picture.add_mesh(vertex_arrows.glyph(orient="n", scale=False, factor=0.6), color="#0072B2")
picture.add_mesh(pv.Arrow(start=P[1], direction=np.array([1, -1, -1]) / np.sqrt(3), scale=0.6), color="#B0B0B0")
picture.add_point_labels(P[[0, 1]], ["vertex 0", "vertex 1"], font_size=14, text_color="#000000",
                         shape_color="#FFFFFF", shape_opacity=0.8, show_points=False, always_visible=True)
picture.camera_position = [(1.6, -3.2, 2.0), (0.5, 0.5, 0.3), (0.0, 0.0, 1.0)]
picture.camera.zoom(0.85)
show(picture)

# %% [markdown]
# Look at the two labelled corners. Vertex 0 touches three triangles, one from each of
# its three squares, so its normal points straight out along the cube's diagonal.
# Vertex 1 touches one triangle of the square at x = 1 but *two* of the squares at
# y = 0 and z = 0, so those squares count twice and its normal (blue) leans away from
# the cube's diagonal (the grey arrow) towards them. Area weighting sees triangles, not
# squares.
#
# The loop, with handles: for each face around the vertex, add its cross product.

# %%
def vertex_normal_by_hand(vertex):
    total = np.zeros(3)
    for face in vertex.faces():
        a, b, c = (v.position for v in face.vertices())
        total += np.cross(b - a, c - a)      # not normalized: length 2 * area is the weight
    return total / np.linalg.norm(total)


for v in (0, 1):
    vertex = cube.vertex(v)
    print(f"vertex {v}: degree {vertex.degree}, {len(vertex.faces())} faces, normal {vertex_normal_by_hand(vertex).round(4) + 0.0}")

# %% [markdown]
# Vertex 1's normal is $(1, -2, -2)/3$: two parts −y, two parts −z, one part +x.
#
# All vertices at once: every face adds its cross product to each of its three corners.
# Because several faces share a corner, the adding must accumulate; `np.add.at` does
# exactly that (a plain `summed[corners[:, k]] += cross` would keep only one face per vertex).

# %%
def vertex_normals_numpy(mesh):
    P = mesh.positions
    corners = mesh.face_vertices()                      # (F, 3)
    a, b, c = P[corners[:, 0]], P[corners[:, 1]], P[corners[:, 2]]
    cross = np.cross(b - a, c - a)                      # (F, 3), length 2 * area
    summed = np.zeros_like(P)                           # (V, 3)
    for k in range(3):
        np.add.at(summed, corners[:, k], cross)         # each face to its k-th corner
    return summed / np.linalg.norm(summed, axis=1, keepdims=True)


print("cube: loop == numpy:", np.allclose([vertex_normal_by_hand(v) for v in cube.vertices], vertex_normals_numpy(cube)))
print("spot: numpy == library:", np.allclose(vertex_normals_numpy(spot), vertex_normals(spot)))

# %% [markdown]
# The library's `hx.vertex_normals(mesh)` is area-weighted by default. It also offers
# `weighting="angle"`, where each face counts by its corner angle at the vertex; then
# cutting a square into two triangles does not change anything, and vertex 1 of the
# cube points symmetrically outwards again:

# %%
print("area-weighted :", vertex_normals(cube)[1].round(4) + 0.0)
print("angle-weighted:", vertex_normals(cube, weighting="angle")[1].round(4) + 0.0)

# %% [markdown]
# ## 4. Flat versus smooth shading
#
# **Convention: flat shading lights each triangle with its face normal; smooth shading
# gives each vertex its vertex normal and blends the normals across the triangle.**
#
# That is all the picture at the top was: on the left the renderer used one normal per
# face, so neighbouring triangles meet at a visible crease; on the right it used
# `vertex_normals(spot)` and interpolated, so the light changes gradually. The
# triangles are identical. Smooth shading does not change the shape, only how light
# falls on it: look at the outline of the cow on the right and you can still see
# straight segments.

# %% [markdown]
# ## 5. Uniform Laplacian smoothing
#
# **Convention: one iteration moves every vertex to the mean of its neighbours'
# positions, and every mean is computed from the *old* positions (Jacobi); boundary
# vertices stay where they are.**
#
# The "uniform Laplacian" of a vertex is the vector from the vertex to the average of
# its neighbours. Adding it to the vertex lands the vertex on that average. Do that for
# every vertex and small bumps, which stick out from their neighbours, flatten out.
#
# The important word is *old*. Here is the course's loop, written with handles:

# %%
def smooth_once_by_hand(mesh):
    old = mesh.positions.copy()                # read only from here
    new = old.copy()                           # write only to here
    for v in mesh.vertices:
        if v.is_boundary:
            continue                           # the rim keeps its place
        neighbours = [u.index for u in v.neighbors()]
        new[v.index] = old[neighbours].mean(axis=0)
    return new

# %% [markdown]
# What goes wrong if you write into the same array you read from? Then a vertex
# visited late sees some neighbours already moved, and the answer depends on the order
# the vertices are numbered in. That variant is called Gauss-Seidel. Let us run both
# on Spot, once in the numbering order and once backwards:

# %%
def smooth_once_in_place(mesh, order):
    P = mesh.positions.copy()                  # read AND write here: the mistake
    for i in order:
        v = mesh.vertex(i)
        if not v.is_boundary:
            P[i] = P[[u.index for u in v.neighbors()]].mean(axis=0)
    return P


def smooth_once_jacobi(mesh, order):
    old = mesh.positions.copy()
    new = old.copy()
    for i in order:
        v = mesh.vertex(i)
        if not v.is_boundary:
            new[i] = old[[u.index for u in v.neighbors()]].mean(axis=0)
    return new


forwards = range(spot.n_vertices)
backwards = range(spot.n_vertices - 1, -1, -1)
print("Jacobi, forwards == backwards:      ", np.allclose(smooth_once_jacobi(spot, forwards), smooth_once_jacobi(spot, backwards)))
print("Gauss-Seidel, forwards == backwards:", np.allclose(smooth_once_in_place(spot, forwards), smooth_once_in_place(spot, backwards)))

# %% [markdown]
# Jacobi gives one answer; Gauss-Seidel gives a different answer for each numbering.
# A mesh loaded from another file format, or renumbered by `garbage_collect()`, would
# smooth differently. That is why the course asks for Jacobi.
#
# The library's `hx.smooth(mesh, iterations)` runs the same Jacobi step as one sparse
# matrix product for all vertices, and returns a *new* mesh (the input is left alone):

# %%
once = smooth(spot, iterations=1)
print("library == loop:", np.allclose(once.positions, smooth_once_by_hand(spot)))
print("spot itself unchanged:", np.array_equal(spot.positions, V))
print("same connectivity, V - E + F:", spot.euler_characteristic, "->", once.euler_characteristic)

# %% [markdown]
# ## 6. Many iterations
#
# One iteration removes small wiggles. Many iterations keep going: every vertex keeps
# moving towards its neighbours' average, so sharp features round off, and since the
# average of points on a convex bump lies *inside* the bump, the whole surface shrinks.

# %%
def volume(mesh):
    """Enclosed volume of a closed mesh: sum over faces of a · (b × c) / 6."""
    P = mesh.positions
    corners = mesh.face_vertices()
    a, b, c = P[corners[:, 0]], P[corners[:, 1]], P[corners[:, 2]]
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


steps = [0, 5, 25, 125]
picture = pv.Plotter(off_screen=True, shape=(1, 4), window_size=(900, 260), border=False)
for column, n in enumerate(steps):
    smoothed = smooth(spot, iterations=n)
    surface = smoothed.to_pyvista()
    surface.point_data["Normals"] = vertex_normals(smoothed)
    surface.point_data.active_normals_name = "Normals"
    picture.subplot(0, column)
    picture.add_mesh(surface, color="#E8B96A", interpolation="gouraud")
    picture.add_text(f"{n} iterations", font_size=10)
    print(f"{n:3d} iterations: volume {volume(smoothed):.4f}")
picture.link_views()
picture.camera_position = [(2.6, 0.9, -2.2), (0.0, 0.1, 0.1), (0.0, 1.0, 0.0)]
show(picture)

# %% [markdown]
# After 5 iterations Spot has lost its facets but kept its shape. After 25 the legs
# and ears are melting, and after 125 they are gone: the volume is down to less than a
# fifth, and the thin horns have shrunk to spikes. Uniform
# Laplacian smoothing is a good eraser of noise and a poor keeper of shape; later
# chapters (remeshing) use it in small doses, and only along the surface.

# %% [markdown]
# ## 7. Try it: a slider over the iterations
#
# Here Spot gets some noise first (every vertex pushed a random distance along its
# normal, with a fixed seed so the run is repeatable). Drag the slider and watch the
# noise vanish within a few iterations while the shape survives, then watch the shape
# go too. Switch between flat and smooth shading: flat shading shows the noise much
# more than smooth shading does.
#
# The viewer (`SmoothingViewer`, in `halfedge_edu/viz/smoothing_viewer.py`) is a small
# ipywidgets panel drawing off screen into an image, so it works in JupyterLab, in VS Code
# and, as a still picture, on GitHub.

# %%
rng = np.random.default_rng(5)
noisy = spot.copy()
noisy.positions[:] += 0.012 * rng.standard_normal((noisy.n_vertices, 1)) * vertex_normals(spot)
viewer = SmoothingViewer(noisy)
viewer

# %% [markdown]
# The panel can also be driven from code, which is how this notebook checks itself. The
# cell drives a panel of its own, so the one above stays as you leave it:

# %%
by_code = SmoothingViewer(noisy)
for n in (0, 2, 10, 60):
    by_code.iterations.value = n
    print(by_code.describe())
by_code.shading.value = "smooth"
print(by_code.describe())

# %% [markdown]
# ## Check yourself
#
# Before running the cell, predict: the normal of cube vertex 0; how many vertices of
# the flat 4 × 4 `open_patch` move in one smoothing iteration (its rim is fixed); where
# its interior vertex 5 goes after one iteration once vertex 0 has been lifted to
# height 1; and whether smoothing changes V − E + F.

# %%
cube = hx.sample("cube")
print("cube vertex 0 normal:", vertex_normals(cube)[0].round(4) + 0.0)
print("cube face 0 normal:  ", face_normals(cube)[0].round(4) + 0.0, " area", cube.face(0).area)

patch = hx.sample("open_patch")
patch.vertex(0).position = [0.0, 0.0, 1.0]          # lift one corner of the rim
after = smooth(patch, iterations=1)
moved = np.flatnonzero(np.linalg.norm(after.positions - patch.positions, axis=1) > 1e-12)
print("open_patch: boundary vertices", int(patch.vertex_is_boundary().sum()), "of", patch.n_vertices)
print("vertices that moved:", moved.tolist())
print("vertex 5:", patch.vertex(5).position.tolist(), "->", after.vertex(5).position.round(4).tolist(),
      "neighbours", [u.index for u in patch.vertex(5).neighbors()])
print("V - E + F before and after:", patch.euler_characteristic, after.euler_characteristic)

# %% [markdown]
# Vertex 5 has six neighbours (1, 6, 10, 9, 4 and the lifted corner 0, listed
# counter-clockwise), so it rises by one sixth. Its x and y stay put: on this grid the
# six neighbours of an interior vertex sit symmetrically around it, so their mean is the
# vertex itself. That is also why 6, 9 and 10 do not move in this first iteration: none
# of them is next to vertex 0. (The `> 1e-12` ignores rounding in the last digit: a mean
# of six numbers is rarely *exactly* the number you started with.) In the second
# iteration, vertex 5's rise would reach its neighbours 6, 9 and 10.

# ## Exercises
#
# **1. One Jacobi step.** Write `laplacian_step(mesh)` that returns a new `(V, 3)`
# array of positions after one uniform Laplacian iteration: each interior vertex goes to
# the mean of its neighbours' *old* positions, boundary vertices keep theirs. Use
# handles (`mesh.vertices`, `v.neighbors()`, `v.is_boundary`) or arrays, as you like.
# The check below compares your function with `smooth(mesh, 1)` on three meshes and
# tells you about the first vertex that differs.

# %%
def laplacian_step(mesh):
    positions = mesh.positions.copy()
    # move every interior vertex to the mean of its neighbours' old positions
    ### BEGIN SOLUTION
    old = mesh.positions                     # only read
    for v in mesh.vertices:
        if not v.is_boundary:
            positions[v.index] = old[[u.index for u in v.neighbors()]].mean(axis=0)
    return positions
    ### END SOLUTION

# %% [markdown]
# The check is `halfedge_edu.exercises.chapter_checks.check_laplacian_step` (you may
# read it, but you need not):

# %%
from halfedge_edu.exercises.chapter_checks import check_laplacian_step

check_laplacian_step(laplacian_step)

# %% [markdown]
# Here is what it says about the in-place (Gauss-Seidel) version from above:

# %%
check_laplacian_step(lambda mesh: smooth_once_in_place(mesh, range(mesh.n_vertices)))

# %% [markdown]
# **2. Think about it.** Smoothing Spot 125 times halved its volume. Which part of the
# uniform Laplacian makes a round sphere shrink, even though it has no noise at all?
# (Hint: where is the mean of a vertex's neighbours on a sphere, compared with the
# vertex itself?)
#
# **3. Area or angle?** Cut one square face of the cube into four triangles instead of
# two (around its centre). Which of the cube's vertex normals change with area
# weighting? Which with angle weighting?

# %% [markdown] tags=["solution"]
# ### Answers
#
# **1.** The answer is in the exercise cell. Note the two arrays: `old` is only read,
# `positions` only written.
#
# **2.** On a sphere every vertex's neighbours lie on the sphere around it, so their
# mean lies slightly *inside* the sphere, below the vertex. Each iteration pulls every
# vertex inwards by a little, and the sphere shrinks; the finer the mesh, the smaller
# that little, but it never vanishes. The uniform Laplacian points partly along the
# normal (that part shrinks the shape) and partly along the surface (that part evens
# out the triangles).
#
# **3.** Cutting the square at, say, x = 0 into four triangles gives each of its four
# corners one triangle of area 1/4 in that square instead of one or two triangles of
# area 1/2. With area weighting that changes how much the −x direction counts, so the
# normals of those four corners tilt. With angle weighting each corner still sees a
# right angle (two 45° angles, or one 90° angle) from that square, so nothing changes.

# %% [markdown]
# ## Summary
#
# - A halfedge's vector is tip minus origin; the twin's is its negative.
# - A face normal is `(b - a) × (c - a)` for counter-clockwise corners; its length is
#   twice the area, so summing those vectors around a vertex *is* the area-weighted
#   vertex normal.
# - Flat shading uses face normals, smooth shading interpolates vertex normals; the
#   triangles are the same.
# - Uniform Laplacian smoothing moves each interior vertex to the mean of its
#   neighbours, all computed from the old positions (Jacobi), so the result does not
#   depend on the numbering. A few iterations remove noise; many iterations shrink the
#   shape.
#
# Next, in chapter 06, we stop moving vertices and start changing the connectivity
# itself: flipping and splitting edges.
