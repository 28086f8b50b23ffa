"""halfedge_edu: a small, fast numpy halfedge-mesh library for learning geometry processing.

    import halfedge_edu as hx
    mesh = hx.sample("cube")
    h = mesh.halfedge(0)
    h.next.twin.vertex        # reads like the course notes

Importing the package loads nothing yet: each public name (``hx.HalfedgeMesh``,
``hx.sample``, ``from halfedge_edu import smooth``) imports its module the first time it
is asked for (PEP 562), numpy with it, so that ``halfedge-edu --help`` and
``import halfedge_edu.course`` stay quick. trimesh, scipy and pyvista are imported when a
function that needs them is called.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

#: Where each public name lives: the module, relative to this package, it is imported from.
_HOMES: dict[str, str] = {
    **dict.fromkeys(
        ("Edge", "Face", "GarbageCollectMaps", "Halfedge", "HalfedgeMesh", "MeshInputError", "MeshInvariantError",
         "MeshWarning", "StaleHandleError", "TopologyError", "Vertex", "build_reference"),
        ".core",
    ),
    **dict.fromkeys(
        ("bezier_curve", "bezier_surface", "de_casteljau", "face_normals", "loop_subdivide", "quality_report",
         "remesh", "simplify", "simplify_sequential", "smooth", "vertex_normals"),
        ".algorithms",
    ),
    "ManifoldReport": ".core.manifold",
    "manifold_report": ".core.manifold",
    "RepairReport": ".core.repair",
    "repair_faces": ".core.repair",
    "SoupTopology": ".core.soup",
    "RawMesh": ".data",
    "sample": ".data",
    "samples": ".data",
    "load": ".io",
    "read_obj": ".io",
    "save": ".io",
    "write_obj": ".io",
}

#: The subpackages ``import halfedge_edu`` loaded before its names became lazy; ``hx.core``,
#: ``hx.io``, ``hx.algorithms`` and ``hx.data`` still work without importing them first.
_SUBPACKAGES = ("core", "io", "algorithms", "data")

__all__ = [
    "Edge", "Face", "GarbageCollectMaps", "Halfedge", "HalfedgeMesh", "ManifoldReport",
    "MeshInputError", "MeshInvariantError", "MeshWarning", "RawMesh", "RepairReport",
    "StaleHandleError", "TopologyError", "Vertex", "bezier_curve", "bezier_surface", "build_reference",
    "de_casteljau", "face_normals", "load", "loop_subdivide", "manifold_report", "quality_report", "read_obj", "remesh",
    "repair_faces", "sample", "samples", "save", "simplify", "simplify_sequential", "smooth", "SoupTopology",
    "vertex_normals", "write_obj",
]


def __getattr__(name: str) -> Any:
    """A public name, imported from its module on first use and kept here after that."""
    if name in _HOMES:
        value = getattr(importlib.import_module(_HOMES[name], __name__), name)
    elif name in _SUBPACKAGES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | set(_SUBPACKAGES))


if TYPE_CHECKING:  # what type checkers and editors read; never run
    from .algorithms import (
        bezier_curve,
        bezier_surface,
        de_casteljau,
        face_normals,
        loop_subdivide,
        quality_report,
        remesh,
        simplify,
        simplify_sequential,
        smooth,
        vertex_normals,
    )
    from .core import (
        Edge,
        Face,
        GarbageCollectMaps,
        Halfedge,
        HalfedgeMesh,
        MeshInputError,
        MeshInvariantError,
        MeshWarning,
        StaleHandleError,
        TopologyError,
        Vertex,
        build_reference,
    )
    from .core.manifold import ManifoldReport, manifold_report
    from .core.repair import RepairReport, repair_faces
    from .core.soup import SoupTopology
    from .data import RawMesh, sample, samples
    from .io import load, read_obj, save, write_obj
