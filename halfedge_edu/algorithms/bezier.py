"""Bezier curves and surfaces, evaluated by de Casteljau's algorithm.

A Bezier curve of degree ``n`` has ``n + 1`` control points ``P_0 .. P_n``. To find its
point at a parameter ``t`` in ``[0, 1]``, de Casteljau repeats one simple step: replace
every pair of neighbouring points by the point a fraction ``t`` of the way between
them,

    P_i  <-  (1 - t) P_i + t P_(i+1)

Each step leaves one point fewer (a new *level*); after ``n`` steps one point is left,
and that is the curve's point. The same value is ``sum_i B_(i,n)(t) P_i`` with the
Bernstein polynomials ``B_(i,n)(t) = C(n, i) t^i (1 - t)^(n - i)``, but de Casteljau
needs only interpolation, so it is numerically stable and easy to draw: the levels are
the construction lines a slider over ``t`` shows.

A tensor-product Bezier surface has an ``(m + 1) x (n + 1)`` grid of control points.
Evaluate it at ``(u, v)`` as curves of curves: each of the ``n + 1`` columns is a curve
in ``u``, which gives ``n + 1`` points; those are the control points of one curve in
``v``. Everything here is vectorized over all parameter values at once, with one numpy
step per de Casteljau level.
"""

from __future__ import annotations

import numpy as np

from ..core import HalfedgeMesh
from ..core.build import real_array
from ..core.errors import MeshInputError
from .arguments import real_number, whole_number


def _control_array(control_points, min_ndim: int, name: str) -> np.ndarray:
    points = np.array(control_points, dtype=np.float64)
    if points.ndim != min_ndim or any(size == 0 for size in points.shape):
        raise ValueError(f"{name} must be a non-empty array with {min_ndim} axes, got shape {points.shape}")
    if not np.isfinite(points).all():
        raise ValueError(f"{name} must be finite numbers")
    return points


def de_casteljau(control_points, t: float) -> list[np.ndarray]:
    """Every level of de Casteljau's algorithm at one parameter ``t``, for teaching.

    Args:
        control_points: (n + 1, d) the control polygon (any dimension d).
        t: the parameter; ``0 <= t <= 1`` stays on the curve segment (other values
            extrapolate along the same polynomial).

    Returns:
        ``n + 1`` arrays: ``levels[0]`` is (a copy of) the control points (n + 1, d),
        ``levels[k]`` has ``n + 1 - k`` points, and ``levels[-1]`` (1, d) holds the
        curve's point at ``t``.
    """
    points = _control_array(real_array(control_points, "control_points"), 2, "control_points")
    t = real_number(t, "t")
    levels = [points]
    while len(levels[-1]) > 1:
        previous = levels[-1]
        levels.append((1.0 - t) * previous[:-1] + t * previous[1:])   # one point fewer
    return levels


def _evaluate(control: np.ndarray, t: np.ndarray) -> np.ndarray:
    """De Casteljau along axis 0 of ``control`` (k + 1, ...) at every ``t`` (S,): (S, ...)."""
    weight = t.reshape((-1,) + (1,) * control.ndim)                       # (S, 1, 1...)
    points = np.broadcast_to(control, (len(t),) + control.shape)          # (S, k + 1, ...)
    while points.shape[1] > 1:
        points = (1.0 - weight) * points[:, :-1] + weight * points[:, 1:]  # (S, level size, ...)
    return points[:, 0]


def bezier_curve(control_points, samples: int = 64) -> np.ndarray:
    """Points of the Bezier curve at ``samples`` evenly spaced ``t`` from 0 to 1.

    Args:
        control_points: (n + 1, d) control points.
        samples: how many points (>= 2); the first is ``P_0`` and the last ``P_n``.

    Returns:
        (samples, d) float64 points along the curve.
    """
    points = _control_array(real_array(control_points, "control_points"), 2, "control_points")
    samples = whole_number(samples, "samples", minimum=2)
    return _evaluate(points, np.linspace(0.0, 1.0, samples))


def bezier_surface_points(control_grid, resolution=(16, 16)) -> np.ndarray:
    """(n_u, n_v, 3) points of a Bezier surface on an even grid of ``(u, v)`` in ``[0, 1]^2``.

    Row ``i`` is ``u = i / (n_u - 1)`` and column ``j`` is ``v = j / (n_v - 1)``; ``u``
    runs along the first axis of ``control_grid``, ``v`` along the second.
    """
    grid = _control_array(real_array(control_grid, "control_grid"), 3, "control_grid")
    if grid.shape[2] != 3:
        raise ValueError(f"control_grid must have shape (m + 1, n + 1, 3), got {grid.shape}")
    n_u, n_v = _resolution(resolution)
    along_u = _evaluate(grid, np.linspace(0.0, 1.0, n_u))                 # (n_u, n + 1, 3)
    along_v = _evaluate(along_u.transpose(1, 0, 2), np.linspace(0.0, 1.0, n_v))   # (n_v, n_u, 3)
    return along_v.transpose(1, 0, 2)                                      # (n_u, n_v, 3)


def _resolution(resolution) -> tuple[int, int]:
    sizes = (resolution, resolution) if np.isscalar(resolution) else tuple(resolution)
    if len(sizes) != 2:
        raise MeshInputError(f"resolution must be one whole number or two (samples along u and v), got {resolution!r}",
                             element=("argument", "resolution"))
    return whole_number(sizes[0], "resolution", minimum=2), whole_number(sizes[1], "resolution", minimum=2)


def grid_triangles(n_u: int, n_v: int) -> np.ndarray:
    """(2 (n_u - 1)(n_v - 1), 3) triangles of an ``n_u x n_v`` grid of vertices.

    Vertex ``(i, j)`` is number ``i * n_v + j``. Each grid square ``a = (i, j)``,
    ``b = (i + 1, j)``, ``c = (i + 1, j + 1)``, ``d = (i, j + 1)`` becomes ``[a, b, c]``
    and ``[a, c, d]``, so the normals point along ``d/du x d/dv``.
    """
    n_u, n_v = whole_number(n_u, "n_u", minimum=2), whole_number(n_v, "n_v", minimum=2)
    i, j = np.meshgrid(np.arange(n_u - 1), np.arange(n_v - 1), indexing="ij")
    a = (i * n_v + j).ravel()                                              # (Q,) square corners
    b, c, d = a + n_v, a + n_v + 1, a + 1
    return np.stack([np.stack([a, b, c], 1), np.stack([a, c, d], 1)], axis=1).reshape(-1, 3)


def bezier_surface(control_grid, resolution=(16, 16)) -> HalfedgeMesh:
    """A triangle mesh of the Bezier surface with control points ``control_grid``.

    Args:
        control_grid: (m + 1, n + 1, 3) control points (a 4 x 4 grid is bicubic).
        resolution: samples along ``u`` and ``v`` (an int means the same for both),
            each >= 2.

    Returns:
        A :class:`HalfedgeMesh` with ``n_u * n_v`` vertices (vertex ``i * n_v + j`` at
        ``u = i / (n_u - 1)``, ``v = j / (n_v - 1)``) and ``2 (n_u - 1)(n_v - 1)``
        triangles facing along ``d/du x d/dv``. Its four corners are the grid's corner
        control points.
    """
    points = bezier_surface_points(control_grid, resolution)              # (n_u, n_v, 3)
    n_u, n_v = points.shape[:2]
    return HalfedgeMesh.from_faces(points.reshape(-1, 3), grid_triangles(n_u, n_v))
