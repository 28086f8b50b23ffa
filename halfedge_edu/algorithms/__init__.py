"""Whole-mesh algorithms: each reads a mesh and returns a new one (the input is never modified)."""

from .bezier import bezier_curve, bezier_surface, bezier_surface_points, de_casteljau, grid_triangles
from .loop import LoopStep, loop_positions, loop_subdivide, loop_subdivide_by_operations
from .normals import corner_angles, face_areas, face_normals, vertex_normals
from .remesh import MeshQuality, RemeshStep, quality_report, remesh, remesh_history, remesh_step_by_step
from .simplify import SimplifyReport, SimplifyResult, simplify, simplify_with_report
from .simplify_queue import CollapseStep, simplify_sequential
from .smoothing import smooth, smooth_reference

__all__ = [
    "CollapseStep", "LoopStep", "MeshQuality", "RemeshStep", "SimplifyReport", "SimplifyResult", "bezier_curve", "bezier_surface", "bezier_surface_points", "corner_angles",
    "de_casteljau", "face_areas", "face_normals", "grid_triangles", "loop_positions",
    "loop_subdivide", "loop_subdivide_by_operations", "quality_report", "remesh", "remesh_history", "remesh_step_by_step", "simplify", "simplify_sequential",
    "simplify_with_report", "smooth", "smooth_reference",
    "vertex_normals",
]
