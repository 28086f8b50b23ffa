"""Screen geometry shared by the scenes: unit vectors and placing labels beside points."""

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
