"""Checks for the learners' exercises: write one piece yourself, then ask a ``check_...``.

    from halfedge_edu.exercises import check_build, check_one_ring, check_flip, check_collapse
    check_build(my_build)          # chapter 02: build the halfedges from a face list
    check_one_ring(my_one_ring)    # chapter 03: walk around a vertex counter-clockwise
    check_flip(my_flip)            # chapter 06: flip an edge in place
    check_collapse(my_collapse)    # chapter 07: collapse an edge in place

Each check runs the learner's function on several small meshes, compares it with the
package's reference, and returns a :class:`CheckResult`: its text says what agreed or,
at the first difference, what is wrong, in words; ``result.show()`` draws the element.

This package is for notebooks; ``import halfedge_edu`` does not load it.
"""

from .checks import CheckResult, check_build, check_one_ring
from .ops_checks import check_collapse, check_flip

__all__ = ["CheckResult", "check_build", "check_collapse", "check_flip", "check_one_ring"]
