"""The halfedge mesh itself: storage, handles, construction, checks. Imports nothing else from the package."""

from .build import build_reference
from .elements import Edge, Face, Halfedge, Vertex
from .errors import MeshInputError, MeshInvariantError, MeshWarning, StaleHandleError, TopologyError
from .mesh import GarbageCollectMaps, HalfedgeMesh

__all__ = [
    "Edge", "Face", "GarbageCollectMaps", "Halfedge", "HalfedgeMesh", "MeshInputError",
    "MeshInvariantError", "MeshWarning", "StaleHandleError", "TopologyError", "Vertex", "build_reference",
]
