# %% [markdown]
# # 12 · Bezier curves and surfaces
#
# So far every surface in this course was a mesh: flat triangles, sharp edges between
# them. Designers of cars and fonts work differently. They place a handful of *control
# points*, and a smooth curve or surface follows them, as if pulled by springs. This
# chapter builds those curves and surfaces with one tiny operation, repeated: go a
# fraction `t` of the way from one point to the next. The method is Paul de
# Casteljau's (at Citroën, 1959), and it turns the control points into a triangle
# mesh you can use with everything from the earlier chapters.
#
# **After this chapter you can**
#
# - evaluate a Bezier curve at any `t` with de Casteljau's algorithm, level by level;
# - read the construction from a picture, and say why the curve starts at `P_0`, ends
#   at `P_n` and leaves `P_0` towards `P_1`;
# - build a Bezier surface from a 4 x 4 grid of control points as "curves of curves",
#   and turn it into a halfedge mesh;
# - predict what moving one control point does to the surface;
# - write `de_casteljau` yourself and have `check_de_casteljau` check it.

# %%
import math

import matplotlib.pyplot as plt
import numpy as np

import halfedge_edu as hx
from halfedge_edu.algorithms import bezier_curve, bezier_surface, de_casteljau
from halfedge_edu.algorithms.bezier import bezier_surface_points
from halfedge_edu.viz.bezier_widgets import BezierSurfaceEditor, DeCasteljauViewer

examples = {
    "an arch (degree 3)": [[0, 0], [1, 2], [3, 2], [4, 0]],
    "an S (degree 3)": [[0, 0], [3, 2.5], [1, -0.5], [4, 2]],
    "a loop (degree 3)": [[0, 0], [5, 2], [-1, 2], [4, 0]],
    "degree 6": [[0, 0], [0.5, 2], [1.5, -1], [2, 2], [2.5, -1], [3.5, 2], [4, 0]],
}
figure, axes = plt.subplots(1, 4, figsize=(10.5, 2.6))
for ax, (name, points) in zip(axes, examples.items()):
    points = np.array(points, dtype=float)
    curve = bezier_curve(points, 200)
    ax.plot(*points.T, "o--", color="#7A7A7A", ms=5, lw=1)
    ax.plot(*curve.T, color="#0072B2", lw=2.5)
    ax.set_title(name, fontsize=10)
    ax.set_aspect("equal")
    ax.axis("off")
plt.show()

# %% [markdown]
# Four Bezier curves (blue) with their control polygons (grey). The curve starts at
# the first control point and ends at the last, but in between it only *heads towards*
# the other points: it never reaches them. Moving one control point pulls the whole
# curve a little, the nearest part most.

# %% [markdown]
# ## The idea
#
# Take the control points `P_0 .. P_n`. Replace every pair of neighbours `P_i, P_(i+1)`
# by the point a fraction `t` of the way from the first to the second. That leaves `n`
# points: the first *level*. Do it again with them, and again, until one point is
# left. That point is the curve's point at `t`. Let `t` run from 0 to 1 and the point
# traces the whole curve.

# %% [markdown]
# ## 1. One step: the point a fraction `t` of the way
#
# **Convention: the point a fraction `t` of the way from `P` to `Q` is
# `(1 - t) P + t Q`; `t = 0` gives `P`, `t = 1` gives `Q`.**
#
# This is *linear interpolation*, often called `lerp`. It is the only arithmetic
# de Casteljau needs.

# %%
def lerp(P, Q, t):
    return (1 - t) * np.asarray(P, dtype=float) + t * np.asarray(Q, dtype=float)


for t in (0.0, 0.25, 0.5, 1.0):
    print(f"t = {t}: {lerp([0, 0], [4, 2], t)}")

# %% [markdown]
# ## 2. All the levels, by hand
#
# **Convention: level 0 is the control points; level `k + 1` has one point fewer than
# level `k`, point `i` of it being `lerp(level_k[i], level_k[i + 1], t)`; the last level
# holds one point, the curve's point `C(t)`.**
#
# The arch at `t = 0.5`, level by level:

# %%
arch = np.array(examples["an arch (degree 3)"], dtype=float)
t = 0.5
level = arch
print("level 0:", level.tolist())
for k in range(1, len(arch)):
    level = np.array([lerp(level[i], level[i + 1], t) for i in range(len(level) - 1)])
    print(f"level {k}:", level.tolist())

# %% [markdown]
# Four control points, so a curve of degree 3 and three steps: 3 points, then 2, then
# 1. The arch's top at `t = 0.5` is `(2, 1.5)`: not as high as the control points at
# height 2, because the curve only heads towards them.
#
# The library's `de_casteljau(points, t)` returns every level at once (each level in
# one numpy step instead of a Python loop over its points):

# %%
for k, level in enumerate(de_casteljau(arch, 0.5)):
    print(f"level {k}: {level.tolist()}")

# %% [markdown]
# ## 3. Try it: de Casteljau's construction under a slider
#
# Move `t` and watch the construction slide along; move `levels` to draw it one level
# at a time. The thick black part of the curve is the part already traced from `t = 0`.
# Every coloured polyline is one level; the vermillion dot is the curve's point.
#
# In JupyterLab the control points are grey balls: drag one, and the curve and its
# construction follow when you let go (**reset** puts them back). Where the picture is
# a still image (GitHub, a static export) there is nothing to drag; the widget says so,
# and the cells below do the same from code.

# %%
viewer = DeCasteljauViewer(arch, t=0.35)
viewer

# %% [markdown]
# The same from code, on a viewer of its own (the one above stays as you leave it).
# First only the control points, then one level at a time:

# %%
by_code = DeCasteljauViewer(arch, t=0.35, mode="static")
by_code.set_t(0.25)
by_code.show_levels(0)
print(by_code.describe())
by_code.step()
print(by_code.describe().splitlines()[-1])
by_code.step()
print(by_code.describe().splitlines()[-1])
by_code.step()
print(by_code.describe().splitlines()[-2:])

# %% [markdown]
# Dragging from code: `move_control_point(i, (x, y))` moves `P_i`, as letting go of its
# ball does.
#
# **Your turn.** Lift `P_1` from `(1, 2)` to `(1, 3)`, one unit up. Does the curve's point
# at `t = 0.25` rise by the whole unit, or by less? Does `C(0)` move?

# %%
before = by_code.point.copy()
by_code.move_control_point(1, (1.0, 3.0))
print(by_code.describe().splitlines()[-1])
print("the point rose by", round(float(by_code.point[1] - before[1]), 4))
print("de_casteljau on the moved points agrees:",
      np.allclose(by_code.point, de_casteljau(by_code.control_points, 0.25)[-1][0]))
print("C(0) is still P_0:", de_casteljau(by_code.control_points, 0.0)[-1][0])
by_code.reset()

# %% [markdown]
# By less: 0.4219 of the unit, `27/64`. Each lerp passes on only part of `P_1`'s move:
# at level 1, the two points made from `P_1` move `1/4` and `3/4` of it; level 2 mixes
# those again, and so on down to the last level. The share that arrives, `3 t (1 - t)^2`
# at `t = 0.25`, is `P_1`'s weight in the Bernstein form of section 4. `C(0)` stays at
# `P_0`: only `P_0` has any weight there. `reset()` put the arch back.

# %% [markdown]
# ## 4. What the construction tells you
#
# Three facts can be read straight off the picture.
#
# - **The ends.** At `t = 0` every lerp returns its first point, so `C(0) = P_0`; at
#   `t = 1`, `C(1) = P_n`.
# - **The direction at the ends.** For small `t` the last level is a short segment
#   near `P_0` pointing towards `P_1`: the curve leaves `P_0` heading for `P_1` (its
#   velocity there is `n (P_1 - P_0)`), and arrives at `P_n` coming from `P_(n-1)`.
# - **The hull.** Every lerp with `0 <= t <= 1` stays between its two points, so every
#   level, and the curve, stays inside the convex hull of the control points.
#
# Let us check the first two numerically on the arch:

# %%
n = len(arch) - 1
print("C(0) =", de_casteljau(arch, 0.0)[-1][0], " C(1) =", de_casteljau(arch, 1.0)[-1][0])
h = 1e-6
velocity = (de_casteljau(arch, h)[-1][0] - de_casteljau(arch, 0.0)[-1][0]) / h
print("velocity at t = 0:", velocity.round(4), " n (P1 - P0) =", n * (arch[1] - arch[0]))

# %% [markdown]
# The same curve has a second formula, the one you may meet in books: the *Bernstein
# form* `C(t) = sum_i C(n, i) t^i (1 - t)^(n - i) P_i`. Multiplying out the lerps gives
# exactly these weights, so the two agree:

# %%
def bernstein_point(points, t):
    n = len(points) - 1
    return sum(math.comb(n, i) * t**i * (1 - t) ** (n - i) * points[i] for i in range(n + 1))


ts = np.linspace(0, 1, 11)
print("Bernstein == de Casteljau at 11 values of t:",
      all(np.allclose(bernstein_point(arch, t), de_casteljau(arch, t)[-1][0]) for t in ts))

# %% [markdown]
# De Casteljau is the one to use in practice: it only ever averages two points, so it
# is numerically stable, and its levels are the picture.
#
# One more fact connects back to chapter 09. The first point of every level (the left
# side of the triangle of levels) is a control polygon of its own: the one of the part
# of the curve from `t = 0` to `t = 0.5`. So de Casteljau *subdivides* a curve into two
# curves of the same degree, each with its own, shorter control polygon:

# %%
levels = de_casteljau(arch, 0.5)
left = np.array([level[0] for level in levels])          # first point of each level
right = np.array([level[-1] for level in levels[::-1]])  # last point of each level, backwards
s = 0.3
print("left half at s = 0.3 equals C(0.15):", np.allclose(de_casteljau(left, s)[-1][0], de_casteljau(arch, 0.5 * s)[-1][0]))
print("right half at s = 0.3 equals C(0.65):", np.allclose(de_casteljau(right, s)[-1][0], de_casteljau(arch, 0.5 + 0.5 * s)[-1][0]))

# %% [markdown]
# Subdivide again and again and the control polygons close in on the curve, just as
# Loop's meshes closed in on their limit surface.

# %% [markdown]
# ## 5. Surfaces: curves of curves
#
# **Convention: a Bezier surface has an `(m + 1) x (n + 1)` grid of control points
# `P[i][j]`; its point `S(u, v)` is found by running de Casteljau at `u` down each of
# the `n + 1` columns, which gives `n + 1` points, and then once more at `v` along those.**
#
# A 4 x 4 grid gives a *bicubic* patch, the workhorse of car bodies and of the Utah
# teapot. Here is one over the square `[0, 3] x [0, 3]`, flat at the rim with its four
# inner control points raised to height 1:

# %%
u_index, v_index = np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij")
grid = np.stack([u_index, v_index, np.zeros((4, 4))], axis=-1)    # (4, 4, 3): P[i][j] = (i, j, 0)
grid[1:3, 1:3, 2] = 1.0                                           # lift the four inner points


def surface_point(grid, u, v):
    columns = [de_casteljau(grid[:, j], u)[-1][0] for j in range(grid.shape[1])]   # one curve per column, at u
    return de_casteljau(np.array(columns), v)[-1][0]                                # then one curve through them, at v


print("S(0.5, 0.5) =", surface_point(grid, 0.5, 0.5))
print("S(0, 0) =", surface_point(grid, 0.0, 0.0), " = P[0][0] =", grid[0, 0])
print("library agrees:", np.allclose(bezier_surface_points(grid, 5)[2, 2], surface_point(grid, 0.5, 0.5)))

# %% [markdown]
# **Coming from CS184?** That assignment stores the grid as rows, `controlPoints[i]`,
# runs de Casteljau at `u` *along each row* (over `j`) and then at `v` through the row
# results (over `i`). Here `u` runs down the columns (over `i`) and `v` along the rows
# (over `j`): the two conventions are each other's transpose. This package's `S(u, v)`
# is CS184's `S(v, u)` on the same grid, or, to keep CS184's meaning of `u` and `v`,
# pass the transposed grid `grid.transpose(1, 0, 2)`:

# %%
def cs184_point(grid, u, v):
    rows = [de_casteljau(grid[i], u)[-1][0] for i in range(grid.shape[0])]    # one curve per row, at u
    return de_casteljau(np.array(rows), v)[-1][0]                              # then through the rows, at v


asymmetric = grid.copy()
asymmetric[1, 2, 2] = 3.0                                         # one raised point, so transposing shows
print("CS184 S(0.2, 0.7):                 ", cs184_point(asymmetric, 0.2, 0.7))
print("here, S(0.7, 0.2):                 ", surface_point(asymmetric, 0.7, 0.2))
print("here, transposed grid, S(0.2, 0.7):", surface_point(asymmetric.transpose(1, 0, 2), 0.2, 0.7))

# %% [markdown]
# The middle of the patch rises to `0.5625 = 9/16` of the inner points' height: just as
# with curves, the surface heads towards its inner control points without reaching
# them. At the corners it passes exactly through the corner control points.
#
# To draw it, or to use it with the rest of this course, sample it on a grid of
# `(u, v)` values and join the samples into triangles. `bezier_surface` does that and
# returns a `HalfedgeMesh`:

# %%
patch = bezier_surface(grid, resolution=16)
print(f"{patch.n_vertices} vertices, {patch.n_edges} edges, {patch.n_faces} faces, "
      f"{patch.n_boundary_loops} boundary loop, V - E + F = {patch.euler_characteristic}")

# %% [markdown]
# A 16 x 16 grid of samples: 256 vertices, 2 · 15 · 15 = 450 triangles, one boundary
# loop and `V - E + F = 1`, like every disc. From here on it is a mesh like any other:
# you could Loop-subdivide it, simplify it, or walk its halfedges.

# %% [markdown]
# ## 6. Try it: move a control point
#
# Pick a control point with the `row i` and `column j` sliders and move it with `x`,
# `y` and `z`. The surface follows; the control net (grey) shows where the control
# points are; the selected one is vermillion.

# %%
editor = BezierSurfaceEditor(grid, selected=(1, 1))
editor

# %% [markdown]
# From code, on an editor of its own (the one above stays as you leave it): lift the
# inner point `P[1][2]` to height 3, then look at what moved.

# %%
lifted = BezierSurfaceEditor(grid, selected=(1, 2))
surface = lifted.surface
rim = surface.vertex_is_boundary()
rim_before = surface.positions[rim].copy()
inside_before = surface.positions[~rim].copy()

lifted.move(1, 2, [1.0, 2.0, 3.0])
print(lifted.describe())
print("boundary of the surface moved:", not np.allclose(surface.positions[rim], rim_before))
print("inside moved:", not np.allclose(surface.positions[~rim], inside_before))

# %% [markdown]
# The inside bulges up towards the lifted point, but the boundary of the patch has not
# moved at all. Why? Along the edge `u = 0` of the patch, every column's de Casteljau
# returns its first control point, so the edge curve depends on row `i = 0` only; the
# same holds for the other three edges. An inner control point is in none of them.
# Now move a point *on* the rim:

# %%
lifted.reset()
lifted.move(0, 1, [0.0, 1.0, 1.0])
print(lifted.describe().splitlines()[2])
print("boundary of the surface moved:", not np.allclose(surface.positions[rim], rim_before))
lifted

# %% [markdown]
# This is why designers can fit patches together. Two neighbouring patches that share
# the control points of their common edge share the whole edge curve, with no gap,
# whatever their inner control points do.

# %% [markdown]
# ## Check yourself
#
# Predict, then run: the arch's point at `t = 0.5`; how many levels a curve with 6
# control points has, and how many points each; the patch's height at `(0.5, 0.5)`
# with the inner points at 1; and whether the patch passes through `P[3][3]`.

# %%
print("arch C(0.5) =", de_casteljau(arch, 0.5)[-1][0])
print("6 control points: level sizes", [len(level) for level in de_casteljau(np.zeros((6, 2)), 0.3)])
print("patch S(0.5, 0.5) =", surface_point(grid, 0.5, 0.5))
print("patch through P[3][3]:", np.allclose(bezier_surface_points(grid, 4)[-1, -1], grid[3, 3]))

# %% [markdown]
# `(2, 1.5)`; six levels of 6, 5, 4, 3, 2 and 1 points (degree 5); height `9/16 = 0.5625`
# (at `u = 0.5` the weights of a cubic's four points are `1/8, 3/8, 3/8, 1/8`, so the
# two inner points carry `3/4` of the weight in each direction, and `3/4 · 3/4 = 9/16`);
# and yes, every corner control point is on the patch.

# %% [markdown]
# ## Exercises
#
# **1. de Casteljau.** Write `my_de_casteljau(points, t)` (named so that it does not
# replace the library's `de_casteljau`) that returns the list of all levels: level 0 is
# the control points themselves (as an array), and the last level holds the single
# point on the curve. Fill in the blanks. `check_de_casteljau` tries
# a line, a quadratic, a cubic at three values of `t` (including both ends) and a
# degree-4 curve in 3D, and explains the first difference.

# %%
def my_de_casteljau(points, t):
    levels = [np.asarray(points, dtype=float)]
    while len(levels[-1]) > 1:
        previous = levels[-1]
        ### BEGIN SOLUTION
        level = (1 - t) * previous[:-1] + t * previous[1:]   # 1. lerp each neighbouring pair of previous, a fraction t of the way
        ### END SOLUTION
        levels.append(level)
    return levels

# %%
from halfedge_edu.exercises.algorithm_checks import check_de_casteljau

check_de_casteljau(my_de_casteljau)

# %% [markdown]
# ### What a mistake looks like
#
# Writing `t P_i + (1 - t) P_(i+1)` gives the same curve *backwards*: at `t = 0.25` you
# get the point of `t = 0.75`.

# %%
def backwards(points, t):
    levels = [np.asarray(points, dtype=float)]
    while len(levels[-1]) > 1:
        previous = levels[-1]
        levels.append(t * previous[:-1] + (1 - t) * previous[1:])
    return levels


check_de_casteljau(backwards)

# %% [markdown]
# **1b. A point of a patch (CS184's `BezierPatch::evaluate`).** Write
# `my_patch_point(grid, u, v)` with your own `my_de_casteljau` and nothing else: any grid
# of `(m + 1) x (n + 1)` control points, not only 4 x 4. Either convention is right, the
# chapter's (`u` down the columns) or CS184's (`u` along each row), as long as you keep
# to one; `check_bezier_patch` says which one it recognised.

# %%
from halfedge_edu.exercises.algorithm_checks import check_bezier_patch


def my_patch_point(grid, u, v):
    ### BEGIN SOLUTION
    columns = [my_de_casteljau(grid[:, j], u)[-1][0] for j in range(grid.shape[1])]
    return my_de_casteljau(np.array(columns), v)[-1][0]
    ### END SOLUTION


check_bezier_patch(my_patch_point)

# %% [markdown]
# **2. Think about it.** A curve has control points `P_0 = (0, 0)`, `P_1 = (1, 1)`,
# `P_2 = (2, 2)`, `P_3 = (3, 3)`. What does it look like, and where is `C(1/3)`?
#
# **3. Surfaces.** On the 4 x 4 patch above, you lift the corner control point `P[0][0]`
# by 1. Which of the four boundary curves of the patch change?

# %% [markdown] tags=["solution"]
# ### Answers
#
# **1.** The answer is in the exercise cell: `(1 - t) * previous[:-1] + t * previous[1:]`;
# `previous[:-1]` holds the first point of every pair and `previous[1:]` the second, so
# one line does the whole level. (A loop over `i` with `lerp(previous[i], previous[i + 1], t)`
# is just as right.)

# %% [markdown] tags=["solution"]
# **2.** A straight segment from `(0, 0)` to `(3, 3)`: every lerp of points on a line stays
# on the line. Because the control points are evenly spaced, the curve also runs at
# constant speed, so `C(1/3) = (1, 1)`. (Space them unevenly and the curve is the same
# segment, but traced at a varying speed.)
#
# **3.** Two: the edge curves `u = 0` (row 0) and `v = 0` (column 0) both contain `P[0][0]`,
# and both start there. The other two edges, row 3 and column 3, do not contain it and
# stay put.

# %% [markdown]
# ## Summary
#
# - `lerp(P, Q, t) = (1 - t) P + t Q`. De Casteljau applies it to neighbouring pairs,
#   level after level, until one point is left: the curve's point `C(t)`.
# - The curve starts at `P_0`, ends at `P_n`, leaves `P_0` towards `P_1`, and stays in the
#   convex hull of its control points. The Bernstein form gives the same points.
# - The levels at `t = 0.5` split a curve into two halves with their own control polygons.
# - A Bezier surface is a curve of curves: de Casteljau down the columns at `u`, then
#   along the results at `v`. A 4 x 4 grid makes a bicubic patch; `bezier_surface` samples it
#   into a halfedge mesh.
# - Each boundary curve depends only on the control points of its own row or column,
#   which is why patches that share an edge's control points join without a gap.
#
# Next, chapter 13 puts the operations of the whole course together on one mesh.
