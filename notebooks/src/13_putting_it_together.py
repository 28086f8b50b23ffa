# %% [markdown]
# # 13 · Putting it together
#
# You now have a whole toolbox: a halfedge mesh you can build from any face list, local
# operations (flip, split, collapse) with their safety checks, and the algorithms made
# of them: smoothing, Loop subdivision, quadric simplification and isotropic remeshing.
# This last chapter uses them together, on a mesh you build yourself and on Spot, and
# asks one question throughout: **what does each operation do to the shape, and what
# does it do to the triangles?**
#
# **By the end of this chapter you can**
#
# - build a mesh of your own from numpy arrays and put it through collapses and smoothing,
#   checking the topology after every step;
# - measure two things about any result: how far it is from the surface it should
#   represent, and how good its triangles are (smallest angles, degrees, edge lengths);
# - run round trips (subdivide then simplify, simplify then subdivide, remesh) and say
#   what each costs;
# - choose an order of operations for a given goal, and defend it with numbers.

# %%
import numpy as np
from IPython.display import Image
from scipy.spatial import cKDTree

import halfedge_edu as hx
from halfedge_edu.algorithms.remesh import closest_points_on_triangles
from halfedge_edu.viz.remesh_stepper import RemeshStepper, draw_histograms, histogram_png, phase_quality
from halfedge_edu.viz import side_by_side, surface_png



def histograms(meshes, labels, L) -> bytes:
    """``histogram_png`` of ``meshes``, with the legend to the right of the histograms
    instead of over the bars of the last one."""
    import io

    from matplotlib.figure import Figure

    figure = Figure(figsize=(11.4, 2.6), dpi=80)
    draw_histograms(figure, [phase_quality(mesh, L) for mesh in meshes], labels)
    last = figure.axes[-1]
    legend = last.get_legend()
    handles, texts = legend.legend_handles, [text.get_text() for text in legend.get_texts()]
    legend.remove()
    last.legend(handles, texts, loc="upper left", bbox_to_anchor=(1.03, 1.0), fontsize=9, frameon=False)
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", metadata={"Software": None})
    return buffer.getvalue()


R, r = 1.0, 0.35                                   # the torus: distance to the tube's centre, tube radius


def torus(n_around=72, n_tube=12):
    """A torus with uneven triangles: thin ones on the outside, crowded rings on one side of the tube."""
    t = np.linspace(0, 2 * np.pi, n_tube, endpoint=False)
    u = np.linspace(0, 2 * np.pi, n_around, endpoint=False)
    v = t + 0.6 * np.sin(t)                                      # tube angles bunch up near v = pi
    U, W = np.meshgrid(u, v, indexing="ij")                      # (n_around, n_tube)
    points = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], axis=-1)
    i, j = np.meshgrid(np.arange(n_around), np.arange(n_tube), indexing="ij")
    a, b = i * n_tube + j, (i + 1) % n_around * n_tube + j
    c, d = (i + 1) % n_around * n_tube + (j + 1) % n_tube, i * n_tube + (j + 1) % n_tube
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return hx.HalfedgeMesh.from_faces(points.reshape(-1, 3), faces)


def torus_distance(mesh):
    """(V,) distance of every vertex from the true torus: | distance to the tube's centre circle - r |."""
    P = mesh.to_arrays()[0]
    return np.abs(np.hypot(np.hypot(P[:, 0], P[:, 1]) - R, P[:, 2]) - r)


def mesh_png(mesh, size=(300, 240), view=(0.3, -1.0, 0.9), zoom=1.4):
    return surface_png(mesh, size=size, view=view, view_up=(0, 0, 1) if abs(view[2]) < 0.99 else (0, 1, 0), zoom=zoom)


def collapse_shortest(mesh, count):
    """Collapse the shortest edge that may be collapsed, ``count`` times, in place; returns how many were done."""
    done = 0
    for _ in range(count):
        live = np.flatnonzero(~mesh.edge_deleted)
        ends = mesh.edge_vertices()[live]
        lengths = np.linalg.norm(mesh.positions[ends[:, 0]] - mesh.positions[ends[:, 1]], axis=1)
        for e in live[np.argsort(lengths, kind="stable")]:
            if mesh.can_collapse(int(e)):
                mesh.collapse(int(e))
                done += 1
                break
        else:
            break
    return done


ring = torus()
collapsed = ring.copy()
collapse_shortest(collapsed, 300)
collapsed.garbage_collect()
smoothed = hx.smooth(collapsed, iterations=5)
L_ring = 0.12
remeshed = hx.remesh(ring, target_length=L_ring, iterations=3)
side_by_side([mesh_png(m) for m in (ring, collapsed, smoothed, remeshed)],
             [f"built: {ring.n_faces} faces", f"300 collapses: {collapsed.n_faces}",
              "then 5 x smooth", f"remeshed: {remeshed.n_faces}"])

# %% [markdown]
# A torus you will build yourself below, and three things done to it. Left: as built,
# with long thin triangles around the outside and crowded rings on the far side of the
# tube. Second: after collapsing the 300 shortest edges one by one, the crowded rings
# are thinned out, but the triangles are no better. Third: five steps of Laplacian
# smoothing even them out, and the ring has become thinner. Right: isotropic remeshing
# of the original, with even triangles on the original surface.
#
# The rest of the chapter puts numbers on what you see.

# %% [markdown]
# ## 1. A mesh of your own
#
# **Convention: any surface you can describe by a grid of points and the triangles
# between them is a halfedge mesh: `hx.HalfedgeMesh.from_faces(points, faces)`.**
#
# The torus above comes from two angles: `u` around the big circle (72 steps) and `v`
# around the tube (12 steps). Each grid square `a, b, c, d` becomes two triangles
# `(a, b, c)` and `(a, c, d)`; the indices wrap around with `% n`, so the grid closes
# up in both directions. The tube angles are bunched on purpose (`v = t + 0.6 sin t`),
# so the triangles are uneven. Building from faces alone works out the twins and
# checks that the surface is manifold (chapters 02 and 04):

# %%
ring.validate()
print(f"V = {ring.n_vertices}, E = {ring.n_edges}, F = {ring.n_faces}; V - E + F = {ring.euler_characteristic}; "
      f"genus {ring.genus}; boundary loops {ring.n_boundary_loops}")
print("every vertex has degree 6:", bool(np.all(ring.vertex_degrees() == 6)))
print(f"largest distance of a vertex from the true torus: {torus_distance(ring).max():.1e}")

# %% [markdown]
# A torus has genus 1, so V − E + F = 2 − 2 · 1 = 0. Every vertex has degree 6 (a grid
# cut into triangles always does), so degrees alone do not make good triangles: the
# angles and lengths matter too. And because we know the true surface, we can say
# exactly how far any vertex is from it: `torus_distance` above.

# %% [markdown]
# ## 2. Two measures: shape and triangles
#
# **Convention: judge a mesh by two numbers that do not depend on each other: its
# distance from the surface it stands for (shape), and its smallest angles (triangles).**
#
# `phase_quality(mesh, L)` from chapter 11 measures the triangles; the distance tells
# you about the shape. Here are both for the four meshes of the picture:

# %%
def report(name, mesh, L, distance):
    q = phase_quality(mesh, L)
    return (f"{name:24s}{q.n_faces:7d}{distance.mean():11.4f}{distance.max():10.4f}{q.min_angle_mean:11.1f}"
            f"{100 * (q.min_angles < 30).mean():9.0f}%{q.degree_deviation:11.3f}{q.lengths.std() / q.lengths.mean():8.3f}")


header = f"{'':24s}{'faces':>7s}{'mean dist':>11s}{'max dist':>10s}{'min angle':>11s}{'< 30 deg':>10s}{'|deg - 6|':>11s}{'spread':>8s}"
print(header)
for name, mesh in (("built", ring), ("300 collapses", collapsed), ("collapses + 5 x smooth", smoothed),
                   ("remeshed", remeshed)):
    print(report(name, mesh, L_ring, torus_distance(mesh)))

# %% [markdown]
# - **Collapses** at midpoints leave the new vertex on a chord, a little inside the
#   surface, so the distance grows slightly. They thin out the crowded rings, but they
#   do not choose *which* triangles are left, so the angles improve only a little, and
#   the degrees, all 6 before, now vary.
# - **Laplacian smoothing** gives far better angles and more even lengths, and pays
#   with the shape: every vertex is pulled toward the inside of the tube, and after
#   five steps the vertices are on average 0.16 from the true torus, almost half the
#   tube's radius of 0.35.
# - **Remeshing** gets the best angles and stays close to the surface, because its
#   smoothing is tangential and every vertex is projected back onto the input. Its
#   distance is not zero: the vertices land on the input's *flat* triangles, which
#   pass a little inside the true torus between their corners.

# %% [markdown]
# ## 3. Watch it: your torus through the remesher
#
# The stepper of chapter 11 works on any mesh, including yours. Step through the
# first iteration and watch the thin outside triangles split and the crowded rings
# collapse:

# %%
stepper = RemeshStepper(ring, target_length=L_ring, iterations=2, window_size=(440, 300),
                        view_direction=(0.3, -1.0, 0.9), zoom=1.3)
stepper.go((1, "collapse"))
stepper

# %%
print(stepper.describe())
print()
print(stepper.describe(stepper.n_steps))           # the end, read without moving the stepper

# %% [markdown]
# ## 4. Round trips on Spot
#
# **Convention: a round trip changes the resolution and comes back (up then down, down
# then up, or "resample" at the same size); what it does to the shape and the
# triangles is its cost.**
#
# Three ways to come back to Spot's 5,856 faces:
#
# - **up, then down**: one level of Loop subdivision (4 × the faces), then quadric
#   simplification back down;
# - **down, then up**: simplification to a quarter, then one level of Loop subdivision;
# - **resample**: isotropic remeshing with L chosen for about the same number of faces.
#
# Spot has no exact formula, so the distance is measured between meshes, both ways:
# from each vertex of the result to the nearest point of Spot's triangles (the same
# search the remesher uses for its projection), and from each vertex of Spot to the
# nearest point of the result's triangles. Both directions are needed: a remeshed
# vertex lies exactly on Spot by construction, but its triangles may still cut
# corners, and the second direction sees that.

# %%
def distance_to(reference, mesh, candidates=8):
    """(V,) distance from each vertex of ``mesh`` to the nearest of ``reference``'s triangles."""
    V, F = reference.to_arrays()
    corners = V[F]                                                   # (F, 3, 3)
    points = mesh.to_arrays()[0]
    _, near = cKDTree(corners.mean(axis=1)).query(points, k=candidates)   # (P, k) nearby triangles
    near = near.reshape(-1)
    repeated = np.repeat(points, candidates, axis=0)
    closest = closest_points_on_triangles(repeated, corners[near, 0], corners[near, 1], corners[near, 2])
    return np.linalg.norm(closest - repeated, axis=1).reshape(len(points), candidates).min(axis=1)


def distance_both_ways(reference, mesh):
    """The distances of :func:`distance_to` in both directions, one after the other."""
    return np.concatenate([distance_to(reference, mesh), distance_to(mesh, reference)])


def length_for(mesh, faces):
    """The edge length L at which equilateral triangles of side L cover ``mesh`` with about ``faces`` faces."""
    area = hx.algorithms.face_areas(mesh).sum()
    return float(np.sqrt(4 * area / (np.sqrt(3) * faces)))


spot = hx.sample("spot")
L_spot = length_for(spot, spot.n_faces)
trips = {
    "Spot as it is": spot,
    "up, then down": hx.simplify(hx.loop_subdivide(spot), spot.n_faces),
    "down, then up": hx.loop_subdivide(hx.simplify(spot, spot.n_faces // 4)),
    "resample (remesh)": hx.remesh(spot, target_length=L_spot, iterations=3),
}
print(f"L for {spot.n_faces} equilateral faces: {L_spot:.4f}")
print(header)
for name, mesh in trips.items():
    print(report(name, mesh, L_spot, distance_both_ways(spot, mesh)))

# %%
Image(histograms(list(trips.values()), list(trips), L_spot))

# %% [markdown]
# Grey is Spot as it is; the outlines are the three round trips.
#
# - **Up, then down** keeps the shape well: quadric simplification places its vertices
#   by the shape alone. That is also its weakness: it does not look at the triangles,
#   and 40% of them end up with an angle below 30°, more than Spot had to begin with.
# - **Down, then up** loses the most shape on average. The simplified Spot has lost
#   detail, and subdivision cannot bring back what is gone; being an *approximating*
#   scheme, it also pulls vertices a little inside. Its triangles inherit the angles of
#   the coarse mesh: a 4-to-1 split makes four triangles similar to their parent
#   (before the vertices move).
# - **Resample** makes by far the best triangles (none below 30°, the narrowest spread
#   of lengths), with a mean distance as small as up-then-down. Its *largest* distance
#   is the largest of the three, though: at the tips of the horns and ears the
#   remesher's smoothing rounds the surface off. A tip is a point, not a crease, so the
#   feature rules of chapter 11 do not hold it, and projection cannot restore a tip
#   that no vertex sits on.

# %% [markdown]
# ## 5. What each operation does, in one table
#
# | operation | shape | triangles | topology |
# |---|---|---|---|
# | edge collapse (midpoint) | a little inside on curved parts | no better on its own | kept when the link condition holds |
# | Laplacian smoothing | shrinks, more with every step | much better angles and lengths | kept |
# | Loop subdivision | smoother, a little inside (approximating) | copies the parent's angles at first | kept; V' = V + E, F' = 4F |
# | quadric simplification | best for a given face count | ignored: slivers appear | kept |
# | isotropic remeshing | close to the input (projection); creases kept | near equilateral, degree 6 | kept; boundaries kept |
#
# So when you need *both*, combine: an operation that gets the shape right, then one
# that fixes the triangles without moving off the surface.

# %% [markdown]
# ## Check yourself
#
# Predict before you run. (1) One level of Loop subdivision of the torus as built: how
# many vertices, edges and faces, and what is V − E + F? (2) After the 300 collapses
# above, how many faces are left, and is V − E + F still 0? (3) Which of the four torus
# meshes has the largest *mean* distance from the true torus?

# %%
fine = hx.loop_subdivide(ring)
print(f"(1) {ring.n_vertices} + {ring.n_edges} = {fine.n_vertices} vertices, {fine.n_edges} edges, "
      f"{fine.n_faces} faces; V - E + F = {fine.euler_characteristic}")
collapsed.validate()
print(f"(2) {collapsed.n_faces} faces; V - E + F = {collapsed.euler_characteristic}; genus {collapsed.genus}")
means = {name: torus_distance(m).mean() for name, m in
         (("built", ring), ("300 collapses", collapsed), ("collapses + smooth", smoothed), ("remeshed", remeshed))}
print("(3) largest mean distance:", max(means, key=means.get))

# %% [markdown]
# (1) V' = V + E = 864 + 2,592 = 3,456, E' = 2E + 3F = 10,368, F' = 4F = 6,912; V − E + F
# stays 0, as subdivision never changes the topology. (2) Each interior collapse removes
# two faces, so 1,728 − 600 = 1,128; V − E + F = 0 still, genus 1. (3) The smoothed one:
# Laplacian smoothing shrinks the ring.

# %% [markdown]
# ## Project: Spot at 2,000 faces, with good triangles
#
# A game engine wants Spot with **about 2,000 faces** (within 5%), and triangles as
# close to equilateral as you can make them. You may use any of the operations, in any
# order. Compare at least these three, and try one more of your own:
#
# - **A**: `hx.simplify(spot, 2000)` alone;
# - **B**: `hx.remesh(spot, L)` alone, with `L` chosen for 2,000 faces;
# - **C**: simplify to 2,000, then remesh at the same `L`.
#
# Judge them by the min-angle histogram (`histogram_png`), the share of faces with a
# smallest angle below 30°, and the distance to the original Spot (`distance_both_ways`).
# Which order gives the best triangles? Does that cost any shape?
#
# Hints: `length_for(spot, 2000)` gives a first `L`. Remeshing does not hit a face
# count exactly. If it misses, remember that the number of faces goes with `1 / L²`:
# multiply `L` by `sqrt(faces you got / faces you want)` and run it again.

# %%
def my_pipeline(spot):
    L = length_for(spot, 2000)
    mesh = spot                            # replace with your order of operations
    return mesh


mine = my_pipeline(spot)
print(f"{mine.n_faces} faces, within 5% of 2,000: {abs(mine.n_faces - 2000) <= 100}")

# %% [markdown]
# ## Summary
#
# - Any grid of points with triangles between them is a mesh: build it with
#   `from_faces`, check it with `validate()` and V − E + F.
# - Judge a result by two independent measures: distance to the surface it stands for,
#   and triangle quality (smallest angles, degrees, length spread).
# - Collapses and simplification decide *where the vertices are*; smoothing and flips
#   decide *what the triangles look like*; plain smoothing pays for that with shape,
#   tangential smoothing with projection does not.
# - Round trips show each operation's cost: up-then-down keeps the shape, down-then-up
#   loses detail for good, resampling makes the best triangles.
# - For a target size with good triangles, let one operation find the size and the
#   remesher fix the triangles.

# %% [markdown] tags=["solution"]
# ## Answer
#
# Try the project before you read this. The answer runs the three pipelines and one
# more, D (subdivide once, then simplify to 2,000), with `L` corrected once for the
# face count.

# %% tags=["solution"]
def remesh_to(mesh, faces, iterations=4):
    """Remesh ``mesh`` to about ``faces`` faces: one run, one correction of L by the face count."""
    L = length_for(mesh, faces)
    result = hx.remesh(mesh, target_length=L, iterations=iterations)
    L *= np.sqrt(result.n_faces / faces)
    return hx.remesh(mesh, target_length=L, iterations=iterations), L


B, L_B = remesh_to(spot, 2000)
C_start = hx.simplify(spot, 2000)
C = hx.remesh(C_start, target_length=L_B, iterations=4)
answers = {
    "A: simplify": hx.simplify(spot, 2000),
    "B: remesh": B,
    "C: simplify, remesh": C,
    "D: subdivide, simplify": hx.simplify(hx.loop_subdivide(spot), 2000),
}
print(f"L = {L_B:.4f}")
print(header)
for name, mesh in answers.items():
    print(report(name, mesh, L_B, distance_both_ways(spot, mesh)))

# %% tags=["solution"]
Image(histograms(list(answers.values()), list(answers), L_B))

# %% [markdown] tags=["solution"]
# **B** (remesh alone) and **C** (simplify, then remesh) give near-equilateral
# triangles: hardly a face below 30° (the few are next to the creases the remesher
# keeps, where vertices may not move freely), degrees near 6, lengths near L. Simplification alone
# (**A**) and **D** keep the shape best, but leave close to 40% of the faces below 30°.
# The triangles are what the game engine asked for, so the remeshed versions win.
#
# They are not free: their mean distance to Spot is about three times that of A, and
# the largest (at the tip of a horn or an ear, rounded off by the smoothing) is a good
# part of L: about 0.8 L for B, 0.3 L for C. B projects onto the original Spot, C onto
# the simplified one, whose error it inherits; here C still comes out nearer, because
# simplification has already put its vertices where the shape needs them. On a huge input C is the practical order: simplification is cheap and
# gets the size right, and a few remeshing iterations then fix the triangles. If the horns mattered more than the triangles, you would now try a
# smaller L near them, which is where this course hands over to the research papers.

# %% [markdown]
# ## Project: edit your own mesh
#
# The last task of two of the courses this book follows: UChicago's P7 ("load a mesh of
# your choosing, apply a few edge collapses and Laplacian smoothing, hand in the original
# and the edited OBJ") and CMU's Task 7 (make the most interesting model you can with
# the operations and the vertex-drag tool). The **mesh editor** below is the viewer those
# courses give you, for this package's mesh:
#
# - **select** an element: choose vertex, edge, halfedge or face and type its index, or,
#   in the live view, right-click the mesh;
# - **flip**, **split**, **collapse** the selected edge (or halfedge: its origin is the
#   vertex a collapse removes), **smooth** the selection and its neighbours (one uniform
#   Laplacian step, boundary vertices stay); **upsample** (Loop), **downsample**
#   (quadrics, to a quarter of the faces) and **remesh** the whole mesh; **info** on the
#   selection; **undo**. The keys are CMU's, typed into the "keys" box: f, s, c, l; u, d,
#   r; i; and z for undo;
# - **drag** the ball on a selected vertex (live view) or use its x, y, z sliders.
#
# After every edit the panel shows the **pointer diff** (every pointer and position the
# operation wrote, old → new) and whether `validate()` still passes. An operation the
# mesh refuses says why and changes nothing: try flipping an edge at a vertex of
# degree 3.
#
# Start from one of your own meshes: `mine = hx.load("p7.obj")` (any OBJ, PLY, STL, OFF
# or glTF; a few thousand faces keep the editor quick). Here it starts from the cube,
# subdivided once so there is room to edit.

# %%
from halfedge_edu.viz.editor import MeshEditor

mine = hx.loop_subdivide(hx.sample("cube"))          # your own: hx.load("p7.obj")
editor = MeshEditor(mine, select=("edge", 5))
editor

# %% [markdown]
# The editor can also be driven from code. The cells below drive an editor of their own,
# `scripted`, so the one above stays as you leave it. A refused edit comes back falsy
# with the reason, and the mesh stays as it was. Vertex 0 is a corner of the cube with
# only three edges; flip one of them:

# %%
scripted = MeshEditor(mine, select=("edge", 5), mode="static")
scripted.select("edge", scripted.mesh.vertex(0).halfedge.edge.index)
check = scripted.apply("flip")
print(bool(check), "-", check.reason)
print(scripted.can_undo, "edits to undo: nothing changed")

# %% [markdown]
# Code is how a sequence of edits is written down and repeated. P7 by script: collapse
# the five shortest edges that may be collapsed, then smooth around the last merged
# vertex. `scripted.held()` draws once at the end instead of after every edit; every
# edit is still validated and can be undone.

# %%
def shortest_collapsible(mesh):
    """The shortest live edge that may be collapsed (None if there is none)."""
    live = np.flatnonzero(~mesh.edge_deleted)
    ends = mesh.edge_vertices()[live]                                    # (E, 2)
    lengths = np.linalg.norm(mesh.positions[ends[:, 0]] - mesh.positions[ends[:, 1]], axis=1)
    return next((int(e) for e in live[np.argsort(lengths, kind="stable")] if mesh.can_collapse(int(e))), None)


with scripted.held():
    for _ in range(5):
        scripted.select("edge", shortest_collapsible(scripted.mesh))
        scripted.apply("collapse")                       # selects the merged vertex
    scripted.apply("smooth")
print("\n".join(scripted.describe().splitlines()[:3]))
print(f"{scripted.mesh.n_faces} faces (from {mine.n_faces}); {scripted.can_undo} edits can be undone")

# %% [markdown]
# When you are done, save both meshes as the assignment asks (here into a scratch folder;
# use your own folder for the hand-in). `garbage_collect()` on a copy gives the edited
# mesh compact indices, as an OBJ file has them.

# %%
import tempfile
from pathlib import Path

scratch = tempfile.TemporaryDirectory()
folder = Path(scratch.name)
edited = editor.mesh.copy()
edited.garbage_collect()
hx.save(mine, folder / "p7.obj")
hx.save(edited, folder / "p7.custom.obj")
again = hx.load(folder / "p7.custom.obj")
again.validate()
print(f"p7.obj: {mine.n_faces} faces; p7.custom.obj: {again.n_faces} faces, "
      f"V - E + F = {again.euler_characteristic}")
scratch.cleanup()
