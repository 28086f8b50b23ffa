"""The checks of chapters 09, 10 and 12 under one name: Loop's rules, quadrics, Bezier curves.

    from halfedge_edu.exercises.algorithm_checks import check_loop_rules
    check_loop_rules(edge_point, vertex_point)     # chapter 09
    check_plane_quadric(plane_quadric)             # chapter 10
    check_optimal_point(optimal_point)             # chapter 10
    check_de_casteljau(de_casteljau)               # chapter 12

Each check lives in the module of its chapter, which says its contracts and slips:
:mod:`~halfedge_edu.exercises.loop_checks` (09: ``check_loop_rules``,
``check_upsample_connectivity``), :mod:`~halfedge_edu.exercises.quadric_checks`
(10: ``check_plane_quadric``, ``check_optimal_point``, ``check_downsample``) and
:mod:`~halfedge_edu.exercises.bezier_checks` (12: ``check_de_casteljau``,
``check_bezier_patch``). This module gathers them under the name the chapters import
them from.
"""

from __future__ import annotations

from .bezier_checks import check_bezier_patch, check_de_casteljau, patch_point
from .loop_checks import (check_loop_rules, check_upsample_connectivity, loop_cases, loop_original_beta,
                          warren_beta)
from .quadric_checks import check_downsample, check_optimal_point, check_plane_quadric

__all__ = ["check_bezier_patch", "check_downsample", "check_upsample_connectivity", "check_loop_rules", "check_plane_quadric", "check_optimal_point", "check_de_casteljau",
           "patch_point",
           "loop_cases", "loop_original_beta", "warren_beta"]
