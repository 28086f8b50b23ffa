"""Reading and writing mesh files.

``load`` / ``save`` pick the format from the suffix: ``.obj`` through the package's own
reader and writer (``read_obj`` / ``write_obj``, taught in chapter 01), ``.stl`` through
its own small reader (``io/stl.py``), ``.ply`` and ``.off`` through trimesh after their
header's counts are checked against the file (``io/headers.py``), ``.glb``, ``.gltf`` and
``.dae`` through trimesh (imported on use). A file whose contents do not match what it
declares is refused with ``MeshInputError``, never loaded as another mesh.
"""

from .formats import SUFFIXES, load, load_arrays, save
from .obj import ObjData, read_obj, write_obj

__all__ = ["SUFFIXES", "ObjData", "load", "load_arrays", "read_obj", "save", "write_obj"]
