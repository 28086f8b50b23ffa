"""Checks for the learners' exercises: write one piece yourself, then ask a ``check_...``.

    from halfedge_edu.exercises import check_build, check_one_ring, check_flip, check_collapse
    check_build(my_build)          # chapter 02: build the halfedges from a face list
    check_one_ring(my_one_ring)    # chapter 03: walk around a vertex counter-clockwise
    check_flip(my_flip)            # chapter 06: flip an edge in place
    check_collapse(my_collapse)    # chapter 07: collapse an edge in place
    check_loop_rules(edge_point, vertex_point)   # chapter 09: Loop's weights
    check_plane_quadric(f), check_optimal_point(f)   # chapter 10: quadrics
    check_tangential_smoothing(f)  # chapter 11: move only in the tangent plane
    check_de_casteljau(f)          # chapter 12: de Casteljau's levels

Each check runs the learner's function on several small meshes, compares it with the
package's reference, and returns a :class:`CheckResult`: its text says what agreed or,
at the first difference, what is wrong, in words; ``result.show()`` draws the element.

This package is for notebooks; ``import halfedge_edu`` does not load it.
"""

from .checks import check_build, check_one_ring
from .harness import CheckResult
from .algorithm_checks import check_bezier_patch, check_downsample, check_upsample_connectivity, check_de_casteljau, check_loop_rules, check_optimal_point, check_plane_quadric
from .ops_checks import check_collapse, check_flip, check_split
from .remesh_checks import check_collapse_short_edges, check_flip_improves, check_split_long_edges, check_tangential_smoothing, check_vertex_normal
from .chapter_checks import check_collapse_is_safe, check_cut, check_fan, check_laplacian_step, check_nonmanifold
from .io_checks import check_obj_io, check_obj_reader, check_obj_writer

__all__ = [
    "CheckResult", "check_build", "check_collapse", "check_de_casteljau", "check_flip",
    "check_loop_rules", "check_one_ring", "check_optimal_point", "check_plane_quadric",
    "check_tangential_smoothing", "check_collapse_is_safe", "check_cut", "check_fan", "check_laplacian_step", "check_nonmanifold",
    "check_obj_io", "check_obj_reader", "check_obj_writer", "check_split", "check_vertex_normal", "check_bezier_patch", "check_upsample_connectivity", "check_downsample", "check_flip_improves", "check_split_long_edges", "check_collapse_short_edges",
]
