"""Screen geometry shared by the scenes: unit vectors, placing labels beside points, and
world points to and from the picture's pixels."""

from __future__ import annotations

import numpy as np


def unit(vectors: np.ndarray) -> np.ndarray:
    """Vectors (..., 3) scaled to length 1 (zero vectors stay zero)."""
    length = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return vectors / np.maximum(length, 1e-300)


def beside(plotter, window_size, points: np.ndarray, pixels: float) -> np.ndarray:
    """``points`` (k, 3) moved ``pixels`` up and right on screen (labels beside their dots).

    A pixel covers more of the world the farther a point is from the camera, so each
    point's offset is scaled by its depth along the viewing direction.
    """
    camera = plotter.camera
    eye = np.array(camera.position)
    forward = unit(np.array(camera.focal_point) - eye)
    up = unit(np.array(camera.up))
    right = np.cross(forward, up)
    depth = (points - eye) @ forward                                   # (k,)
    world_per_pixel = 2.0 * depth * np.tan(np.radians(camera.view_angle / 2)) / window_size[1]
    return points + (pixels * world_per_pixel)[:, None] * (right + up)


def _world_to_ndc(plotter, window_size) -> np.ndarray:
    """(4, 4) the camera's world-to-normalised-device matrix for a ``window_size`` picture
    (what vtk's ``WorldToDisplay`` applies, as one matrix for many points)."""
    aspect = window_size[0] / window_size[1]
    matrix = plotter.camera.GetCompositeProjectionTransformMatrix(aspect, -1.0, 1.0)
    return np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])


def to_screen(plotter, window_size, points: np.ndarray) -> np.ndarray:
    """(k, 3) world points -> (k, 3) display pixels ``(x, y, depth)``: x to the right and y
    up from the picture's lower left corner (vtk's display coordinates), depth in [-1, 1]."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    homogeneous = np.hstack([points, np.ones((len(points), 1))]) @ _world_to_ndc(plotter, window_size).T
    ndc = homogeneous[:, :3] / homogeneous[:, 3:4]
    size = np.array(window_size, dtype=float)
    return np.column_stack([(ndc[:, :2] + 1.0) * 0.5 * size, ndc[:, 2]])


def from_screen(plotter, window_size, screen: np.ndarray) -> np.ndarray:
    """The inverse of :func:`to_screen`: (k, 3) ``(x, y, depth)`` pixels -> (k, 3) world points."""
    screen = np.asarray(screen, dtype=float).reshape(-1, 3)
    size = np.array(window_size, dtype=float)
    ndc = np.column_stack([screen[:, :2] / (0.5 * size) - 1.0, screen[:, 2], np.ones(len(screen))])
    world = ndc @ np.linalg.inv(_world_to_ndc(plotter, window_size)).T
    return world[:, :3] / world[:, 3:4]
