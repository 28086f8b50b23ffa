"""Reading and writing mesh files.

``load`` / ``save`` pick the format from the suffix: ``.obj`` through the package's own
reader and writer (``read_obj`` / ``write_obj``, taught in chapter 01), ``.ply``,
``.stl``, ``.off``, ``.glb`` and ``.gltf`` through trimesh (imported on use).
"""

from .formats import SUFFIXES, load, load_arrays, save
from .obj import ObjData, read_obj, write_obj

__all__ = ["SUFFIXES", "ObjData", "load", "load_arrays", "read_obj", "save", "write_obj"]
