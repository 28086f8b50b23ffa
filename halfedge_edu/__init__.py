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
    StaleHandleError,
    TopologyError,
    Vertex,
    build_reference,
)

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
from .core.manifold import ManifoldReport, manifold_report
from .core.repair import RepairReport, repair_faces
from .core.soup import SoupTopology
from .data import RawMesh, sample, samples
from .io import load, read_obj, save, write_obj

__version__ = "0.1.0"

__all__ = [
    "Edge", "Face", "GarbageCollectMaps", "Halfedge", "HalfedgeMesh", "ManifoldReport",
    "MeshInputError", "MeshInvariantError", "MeshWarning", "RawMesh", "RepairReport",
    "StaleHandleError", "TopologyError", "Vertex", "bezier_curve", "bezier_surface", "build_reference",
    "de_casteljau", "face_normals", "load", "loop_subdivide", "manifold_report", "quality_report", "read_obj", "remesh",
    "repair_faces", "sample", "samples", "save", "simplify", "simplify_sequential", "smooth", "SoupTopology",
    "vertex_normals", "write_obj",
]
