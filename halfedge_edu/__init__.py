"""halfedge_edu: a small, fast numpy halfedge-mesh library for learning geometry processing.

    import halfedge_edu as hx
    mesh = hx.sample("cube")
    h = mesh.halfedge(0)
    h.next.twin.vertex        # reads like the course notes

Importing the package loads numpy only; trimesh, scipy and pyvista are imported when
a function that needs them is called.
"""

from .core import (
    Edge,
    Face,
    GarbageCollectMaps,
    Halfedge,
    HalfedgeMesh,
    MeshInputError,
    MeshInvariantError,
    MeshWarning,
    TopologyError,
    Vertex,
    build_reference,
)

__version__ = "0.1.0"

__all__ = [
    "Edge", "Face", "GarbageCollectMaps", "Halfedge", "HalfedgeMesh", "MeshInputError",
    "MeshInvariantError", "MeshWarning", "TopologyError", "Vertex", "build_reference",
]
