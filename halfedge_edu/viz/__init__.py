"""Pictures and notebook widgets for halfedge meshes (PyVista + ipywidgets).

    from halfedge_edu.viz import HalfedgeScene, HalfedgeExplorer, OneRingViewer
    from halfedge_edu.viz import FlipStepper, SplitStepper, CollapseStepper, CollapseAtlas
    from halfedge_edu.viz import LoopStepper, QEMStepper, RemeshStepper
    from halfedge_edu.viz import DeCasteljauViewer, BezierSurfaceEditor

- :class:`HalfedgeScene`: draw a mesh with its halfedges as arrows inside their faces,
  highlight elements by role (current, twin, next, prev, origin, tip, face, one-ring),
  labels, legend, ``preset="large"`` for projectors.
- Widgets: a view beside buttons and tables; live 3D in JupyterLab, a static image that
  follows every step elsewhere (:func:`choose_mode`, ``HALFEDGE_EDU_VIZ=static|live``).
  Each can be driven from code (``w.go("twin")``, ``w.step()``) and says its state in
  plain text (``w.describe()``).

Nothing here imports pyvista or ipywidgets until a scene or widget is made, and the
package itself (``import halfedge_edu``) never imports this module.
"""

from halfedge_edu._extras import require

require("notebooks", "halfedge_edu.viz")

from .bezier_widgets import BezierSurfaceEditor, DeCasteljauViewer
from .loop_stepper import LoopStepper
from .palette import PRESETS, ROLES
from .pictures import side_by_side
from .qem_stepper import QEMStepper
from .remesh_stepper import RemeshStepper
from .renderer import choose_mode
from .scene import HalfedgeScene
from .steppers import CollapseAtlas, CollapseStepper, FlipStepper, SplitStepper
from .widgets import HalfedgeExplorer, OneRingViewer

__all__ = [
    "PRESETS", "ROLES", "choose_mode", "HalfedgeScene", "HalfedgeExplorer", "OneRingViewer",
    "FlipStepper", "SplitStepper", "CollapseStepper", "CollapseAtlas", "LoopStepper",
    "QEMStepper", "RemeshStepper", "DeCasteljauViewer", "BezierSurfaceEditor", "side_by_side",
]
