"""Pictures and notebook widgets for halfedge meshes (PyVista + ipywidgets).

    from halfedge_edu.viz import HalfedgeScene, HalfedgeExplorer, OneRingViewer
    from halfedge_edu.viz import FlipStepper, SplitStepper, CollapseStepper, CollapseAtlas
    from halfedge_edu.viz import LoopStepper, QEMStepper, RemeshStepper, Stepper
    from halfedge_edu.viz import SmoothingViewer, LinkViewer, link_png, named_picture
    from halfedge_edu.viz import DeCasteljauViewer, BezierSurfaceEditor
    from halfedge_edu.viz import side_by_side, grid, scene_picture, surface_png, plotter_png
    from halfedge_edu.viz import on_main_thread

- :class:`HalfedgeScene`: draw a mesh with its halfedges as arrows inside their faces,
  highlight elements by role (current, twin, next, prev, origin, tip, face, one-ring),
  labels, legend, ``preset="large"`` for projectors.
- Widgets: a view beside buttons and tables; live 3D in JupyterLab, a static image that
  follows every step elsewhere (:func:`choose_mode`, ``HALFEDGE_EDU_VIZ=static|live``).
  Each can be driven from code (``w.go("twin")``, ``w.step()``) and says its state in
  plain text (``w.describe()``).
- Steppers: every one is the :class:`Stepper` widget over an algorithm's steps (its
  :class:`~.steps.Steps`: the records the algorithm wrote down) with a painter for them.
- Still pictures: :func:`side_by_side` and :func:`grid` paste PNGs in titled rows,
  :func:`scene_picture` makes one picture of a scene, :func:`surface_png` a plain picture
  of a mesh, :func:`plotter_png` encodes what any plotter shows.

The modules, one concern each (as pyvista splits its plotting package), from the bottom up:

- ``palette``: colours, roles (:data:`ROLES`), presets and widget panel sizes (``panel_css``).
- ``screen``: unit vectors and placing points a few pixels aside on screen.
- ``neighbourhood``: rings of vertices and the halfedges between them (what "near" means).
- ``pictures``: PNG encoding, screenshots, rows and grids of titled pictures.
- ``renderer``: static or live mode, and the plotters the scenes draw into; :func:`show`,
  how a chapter shows a plotter of its own (menu collapsed, no stray wasm line).
- ``actors``: a scene's named parts in a plotter, refilled in place.
- ``arrows``: halfedge arrows, their geometry and the arrow layer that colours them by role.
- ``geometry``: what a scene knows about its mesh (normals, centre, faces as drawn).
- ``highlights``: the highlight (roles, names) and its coloured faces and dots.
- ``labels``: index labels ("v3", "h7", "f1") near the highlight, hidden when facing away.
- ``legend``: the legend box and its entries.
- ``camera``: where the camera stands: the whole mesh, some vertices, following the highlight.
- ``scene``: :class:`HalfedgeScene`, which owns the surface and decides what is redrawn when.
- ``painted_scene``: a mesh with coloured layers (Loop, QEM, remeshing, Bezier widgets).
- ``editor``: :class:`MeshEditor`, edit a mesh by hand (select, flip/split/collapse/smooth,
  upsample/downsample/remesh, drag a vertex, undo, the pointer diff of the last edit).
- ``main_thread``: :func:`on_main_thread`, which runs a widget callback (a click, a slider
  move) on the kernel's main thread, where VTK's OpenGL context lives; every button and
  observer of these widgets goes through it, and so should a chapter's own widget.
- ``keys``: :class:`~.keys.KeyArea`, the part of a widget's panel that answers keys (n, p,
  t, the arrows, space, Home, End) in a live Lab, each by clicking its button.
- ``steps``: the one stepper model: the :class:`~.steps.Steps` protocol (an algorithm's
  run as numbered steps), the :class:`~.steps.Painter` protocol, and :class:`Stepper`,
  the widget that shows any steps by asking their painter.
- ``steppers`` (flip, split, collapse, and :func:`named_picture` of an operation's log),
  ``atlas`` (:class:`CollapseAtlas`), ``loop_stepper``, ``qem_stepper``,
  ``remesh_stepper``: each algorithm's steps, painter and named stepper.
- ``widgets``, ``bezier_widgets``, ``smoothing_viewer`` (chapter 05), ``link_viewer``
  (chapter 08's link pictures and :class:`LinkViewer`): the other notebook widgets.

The rule between modules (``tests/viz/test_layout.py`` checks it): a module uses only the
public names of another, so no ``from .x import _name`` and no ``obj._attr`` on an object
that is not ``self`` (or ``cls``/``super()``). What a part needs from another is passed
to its constructor (a stepper gives the scene its arrow placement as ``corners=``) or
offered as a public method. The one exception is IPython's display protocol
(``widget._repr_mimebundle_``), which is public by convention.

Nothing here imports pyvista or ipywidgets until a scene or widget is made, and the
package itself (``import halfedge_edu``) never imports this module.
"""

from halfedge_edu._extras import require

require("notebooks", "halfedge_edu.viz")

from .atlas import CollapseAtlas
from .bezier_widgets import BezierSurfaceEditor, DeCasteljauViewer
from .editor import MeshEditor
from .link_viewer import LINK_VIEWS, LinkViewer, draw_link, link_png
from .loop_stepper import LoopStepper
from .main_thread import on_main_thread
from .palette import PRESETS, ROLES
from .pictures import grid, plotter_png, side_by_side, surface_png
from .qem_stepper import QEMStepper
from .remesh_stepper import RemeshStepper
from .renderer import choose_mode, show
from .scene import HalfedgeScene, scene_picture
from .smoothing_viewer import SmoothingViewer
from .steppers import CollapseStepper, FlipStepper, SplitStepper, created_roles, gathered_roles, named_picture
from .steps import Painter, Stepper, Steps
from .widgets import HalfedgeExplorer, OneRingViewer

__all__ = [
    "PRESETS", "ROLES", "choose_mode", "show", "HalfedgeScene", "HalfedgeExplorer", "OneRingViewer",
    "FlipStepper", "SplitStepper", "CollapseStepper", "CollapseAtlas", "LoopStepper",
    "QEMStepper", "RemeshStepper", "DeCasteljauViewer", "BezierSurfaceEditor", "side_by_side", "grid",
    "plotter_png", "surface_png", "scene_picture", "MeshEditor", "on_main_thread", "Stepper", "SmoothingViewer",
    "LinkViewer", "LINK_VIEWS", "draw_link", "link_png", "named_picture", "gathered_roles", "created_roles",
    "Steps", "Painter",
]
