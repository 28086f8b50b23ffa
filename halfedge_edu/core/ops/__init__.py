"""Local operations: edge flip, edge split, edge collapse, each with its ``can_*`` check.

One readable file per operation (``flip.py``, ``split.py``, ``collapse.py``); each
opens with a picture of the elements it names. Every operation is *check, then act*:
it either succeeds, leaving a valid mesh, or raises ``TopologyError`` with the reason
and leaves the mesh exactly as it was. Pass ``log=OperationLog()`` to watch one step by
step (``log.py``). A collapse can also be prepared and then applied
(``prepare_collapse``, ``apply_collapse``), and made without the link condition
(``collapse(..., check_link=False)``) to see what goes wrong. ``link.py`` holds the
one-ring and link helpers of chapter 08.
"""

from .check import OpCheck
from .collapse import CollapseRecord, apply_collapse, can_collapse, collapse, prepare_collapse
from .flip import can_flip, flip
from .link import Link, LinkCondition, link_condition, link_of_edge, link_of_vertex, link_violation
from .log import OperationLog, PointerChange
from .split import can_split, split

__all__ = [
    "CollapseRecord", "Link", "LinkCondition", "OpCheck", "OperationLog", "PointerChange",
    "apply_collapse", "prepare_collapse", "can_collapse", "can_flip", "can_split", "collapse", "flip", "split",
    "link_condition", "link_of_edge", "link_of_vertex", "link_violation",
]
