"""Whole-mesh algorithms: each reads a mesh and returns a new one (the input is never modified)."""

from .loop import loop_positions, loop_subdivide
from .normals import corner_angles, face_areas, face_normals, vertex_normals
from .smoothing import smooth, smooth_reference

__all__ = [
    "corner_angles", "face_areas", "face_normals", "loop_positions", "loop_subdivide", "smooth", "smooth_reference", "vertex_normals",
]
