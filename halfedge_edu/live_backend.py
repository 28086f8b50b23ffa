"""Where a live 3D view is drawn: in the kernel (``server``) or in the browser (``client``).

A hub sets this once for every student with the environment variable
``HALFEDGE_EDU_LIVE_BACKEND`` (deploy/jupyterhub/jupyterhub_config.py passes it on):

- ``server`` (the default): the kernel renders every frame with VTK and sends pictures
  (trame-pyvista's ``server`` view, nothing else: no hidden vtk.js view beside it). Costs kernel memory for the render window and server
  CPU for every step and every frame of a rotation.
- ``client``: the kernel sends the scene's geometry once and vtk.js draws it in the
  browser (pyvista's ``client`` backend); rotating costs the server nothing.

Two repairs of trame-vtk's private machinery live here too, each behind
:func:`missing_private_api`: :func:`keep_scene_arrays` (a client view keeps its mesh)
and :func:`answer_clicks_promptly` (a server view sends a step's picture when it is
encoded, not half a second later).

:func:`trame_mode` turns the setting into the ``mode`` that trame-pyvista's view takes
(``plotter.show(jupyter_backend="trame", jupyter_kwargs={"mode": trame_mode()})``). The
mode goes in ``jupyter_kwargs`` on purpose: ``jupyter_backend="client"`` alone still gives
the server-rendered view unless ``trame_pyvista`` was imported before (its entry points
register every backend name without a mode; measured with trame-pyvista 0.2.3).
"""

from __future__ import annotations

import os
import weakref

ENV_VARIABLE = "HALFEDGE_EDU_LIVE_BACKEND"
# The setting's values and trame-pyvista's view mode for each. "server" is the server-
# rendered view alone. Not trame-pyvista's default "trame" (the server's pictures with a
# vtk.js view beside them, hidden until its menu switches to it): that hidden view was
# sent the whole scene at every step too, twice the work, and while a student clicked a
# stepper quickly its scene sync threw in the browser ("getOpacity is not a function",
# vtk.js, seen twice in chapter 10's browser test). "client" is the vtk.js view alone.
TRAME_MODES = {"server": "server", "client": "client"}


def trame_mode(setting: str | None = None) -> str:
    """trame-pyvista's view ``mode`` for ``setting``, else for ``$HALFEDGE_EDU_LIVE_BACKEND``
    (``"server"`` when unset or empty).

    Raises:
        ValueError: the setting is neither ``server`` nor ``client`` (named in the message).
    """
    source = "setting"
    if setting is None:
        setting, source = os.environ.get(ENV_VARIABLE, ""), ENV_VARIABLE
    chosen = str(setting).strip().lower() or "server"
    if chosen not in TRAME_MODES:
        raise ValueError(f"{source}={setting!r}: use 'server' or 'client'")
    return TRAME_MODES[chosen]


# --------------------------------------------------------------------------- client views
#
# Why a client-side view can lose its mesh (measured with trame-vtk 2.11.17, VTK 9.7):
# the scene a browser loads names each data array by a hash, and the browser fetches the
# arrays afterwards (RPC ``viewport.geometry.array.get``). trame-vtk keeps those arrays in
# a cache shared by every view of the kernel and, whenever any view sends a new scene,
# drops the entries older than 20 s that nothing else references. A mesh's cells are
# converted to a fresh array for every scene (``vtkCellArray.ExportLegacyFormat``), which
# only that cache references: 20 s after a view was last updated, the next update of any
# other view (a step of another widget) deletes its cells. A browser that then loads the
# view (the cell is shown, scrolled back into sight, the page is reloaded) asks for them,
# gets "Exception raised" (JSON-RPC error -32001) and draws no mesh.
#
# The fix: an array stays in the cache while the current scene of an open client-side
# view still names it; the rest is released as trame-vtk would.

# The trame-pyvista viewers of open client-side views (held weakly).
_CLIENT_VIEWERS: weakref.WeakSet = weakref.WeakSet()

#: trame-vtk's private names this module relies on, as (module, attribute path). The same
#: in trame-vtk 2.8 to 2.11 (pyproject.toml bounds it below 2.12); a release that moves
#: one makes :func:`missing_private_api` name it, and tests/test_live_backend.py fail.
TRAME_VTK_PRIVATE_API = (
    ("trame_vtk.modules.vtk.serializers", "extract_array_hash"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebLocalRendering"),
    ("trame_vtk.modules.vtk.serializers.synchronization_context", "SynchronizationContext.check_for_arrays_to_release"),
    ("trame_vtk.modules.vtk.serializers.synchronization_context", "SynchronizationContext.__init__ sets data_array_cache"),
    ("trame_vtk.widgets.vtk.common", "VtkLocalView.__init__ sets __scene_id"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebPublishImageDelivery.push_render"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebPublishImageDelivery.render_stale_image"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebPublishImageDelivery.__init__ sets delta_stale_time_before_render"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebPublishImageDelivery.__init__ sets stale_handler_count"),
    ("trame_vtk.modules.vtk.protocols", "vtkWebPublishImageDelivery.__init__ sets last_stale_time"),
)


def missing_private_api() -> list[str]:
    """The entries of :data:`TRAME_VTK_PRIVATE_API` that the installed trame-vtk lacks,
    as ``module:attribute`` (empty when everything :func:`keep_scene_arrays` uses is there)."""
    import importlib
    import inspect

    missing = []
    for module_name, path in TRAME_VTK_PRIVATE_API:
        try:
            target = importlib.import_module(module_name)
        except ImportError:
            missing.append(f"{module_name}:{path}")
            continue
        attributes, _, assigned = path.partition(" sets ")
        try:
            for attribute in attributes.split("."):
                target = getattr(target, attribute)
        except AttributeError:
            missing.append(f"{module_name}:{path}")
            continue
        if assigned and f"self.{assigned} =" not in inspect.getsource(target):
            missing.append(f"{module_name}:{path}")
    return missing


def keep_scene_arrays(viewer) -> None:
    """Keep the data arrays that ``viewer``'s views name in the kernel until they change.

    ``viewer`` is the trame-pyvista viewer of a client-side live view
    (``plotter.show(..., return_viewer=True).viewer``). Its arrays are kept while its
    plotter is open; the viewer is held weakly. With a trame-vtk whose private API moved
    (:func:`missing_private_api`) it warns once and does nothing: the view still works,
    with trame-vtk's own release rule.
    """
    if not _private_api_present():
        return
    _CLIENT_VIEWERS.add(viewer)
    _guard_array_cache(viewer.server)


# What missing_private_api() found, once per kernel (None: not checked yet).
_API_CHECKED: list[str] | None = None


def _private_api_present() -> bool:
    """Whether the installed trame-vtk has every private name this module patches
    (checked once per kernel; when one moved, one warning says which, and what a
    student loses: the patches are skipped, the views still work)."""
    global _API_CHECKED
    if _API_CHECKED is None:
        _API_CHECKED = missing_private_api()
        if _API_CHECKED:
            import warnings

            warnings.warn(f"halfedge_edu.live_backend: this trame-vtk lacks {', '.join(_API_CHECKED)}; "
                          "client-side views may lose their mesh after 20 s and server-side views "
                          "answer a click half a second late (install trame-vtk<2.12)",
                          RuntimeWarning, stacklevel=3)
    return not _API_CHECKED


# The hashes each view's scene names, by the scene's state key: (that scene, its hashes).
# A scene is replaced, never changed in place, so its hashes are listed once.
_SCENE_HASHES: dict[str, tuple[dict, frozenset[str]]] = {}


def shown_array_hashes(server) -> set[str]:
    """The hashes of the data arrays named by the current scene of every open client-side
    viewer on ``server``: what a browser may still ask for."""
    from trame_vtk.modules.vtk.serializers import extract_array_hash

    hashes: set[str] = set()
    for viewer in list(_CLIENT_VIEWERS):
        if viewer.server is not server or viewer.plotter.render_window is None:
            continue
        for view in viewer.views:
            key = _scene_state_key(view)
            if key is None or not server.state.has(key):
                continue
            scene = server.state[key]
            listed = _SCENE_HASHES.get(key)
            if listed is None or listed[0] is not scene:
                listed = _SCENE_HASHES[key] = (scene, frozenset(entry["hash"] for entry in extract_array_hash(scene)))
            hashes |= listed[1]
    return hashes


def _scene_state_key(view) -> str | None:
    """The trame state entry that holds a local view's scene (``scene_<ref>``)."""
    return getattr(view, "_VtkLocalView__scene_id", None)


def _array_cache_context(server):
    """trame-vtk's geometry-delivery context on ``server`` (its array cache), or None
    before the server is ready."""
    from trame_vtk.modules.vtk.protocols import vtkWebLocalRendering

    protocol = server.protocol
    if protocol is None:
        return None
    for link in protocol.getLinkProtocols():
        if isinstance(link, vtkWebLocalRendering):
            return link.context
    return None


def _guard_array_cache(server) -> None:
    """Make ``server``'s array cache spare the arrays of shown scenes (once per server);
    before the server is ready, do it when it is."""
    context = _array_cache_context(server)
    if context is None:
        server.controller.on_server_ready.add(lambda **_: _guard_array_cache(server))
        return
    if getattr(context, "halfedge_edu_guarded", False):
        return
    release = context.check_for_arrays_to_release

    def release_unshown_arrays(time_window: float = 20) -> None:
        kept = {digest: context.data_array_cache.pop(digest)
                for digest in shown_array_hashes(server) if digest in context.data_array_cache}
        try:
            release(time_window)
        finally:
            context.data_array_cache.update(kept)

    context.check_for_arrays_to_release = release_unshown_arrays
    context.halfedge_edu_guarded = True


# --------------------------------------------------------------------------- server views
#
# Why a server-side view answered a click half a second late (measured with trame-vtk
# 2.11.17, benchmarks/bench_clicks.py): after a step, trame-vtk renders the view and hands
# the frame to a JPEG encoder thread, then sends what the encoder has *finished*, which
# right after a render is still the previous picture ("stale"). It looks again only
# after ``delta_stale_time_before_render`` = 0.5 s, so every click showed its picture
# 0.5 s after the step was done. A shorter delay alone is not enough: trame's retry
# (``render_stale_image``) gives up at its second look unless twice the delay has passed
# since the last stale frame, which a short delay never allows, and the new picture
# would then never be sent.
#
# The fix: look again every STALE_PICTURE_POLL seconds until the encoder has the new
# picture, at most STALE_PICTURE_LOOKS times (a view that always reports "stale", such
# as a linked one, stops there: about a second of extra looks, not forever).

#: Seconds between two looks for a picture the encoder has not finished.
STALE_PICTURE_POLL = 0.01
#: How many looks at most for one picture.
STALE_PICTURE_LOOKS = 100


def answer_clicks_promptly(server) -> None:
    """Make ``server``'s server-side views send a new picture as soon as it is encoded
    (about 10 ms after the render) instead of 0.5 s later (once per trame server; before
    the server is ready, when it is). With a trame-vtk whose private API moved
    (:func:`missing_private_api`) it warns once and does nothing."""
    if not _private_api_present():
        return
    delivery = _image_delivery(server)
    if delivery is None:
        server.controller.on_server_ready.add(lambda **_: answer_clicks_promptly(server))
        return
    poll_for_encoded_pictures(delivery)


def poll_for_encoded_pictures(delivery) -> None:
    """Replace trame-vtk's stale-picture retry on one ``vtkWebPublishImageDelivery``
    (idempotent)."""
    if getattr(delivery, "halfedge_edu_polling", False):
        return
    import types

    delivery.delta_stale_time_before_render = STALE_PICTURE_POLL
    delivery.render_stale_image = types.MethodType(_look_again_for_the_picture, delivery)
    delivery.halfedge_edu_polling = True


def _look_again_for_the_picture(delivery, view_id: str, stale_count: int = 0) -> None:
    """trame-vtk's ``render_stale_image`` without its give-up-at-the-second-look rule:
    ``push_render`` sends the picture if it is encoded now, else it schedules this again
    (``STALE_PICTURE_POLL`` later), up to ``STALE_PICTURE_LOOKS`` looks."""
    if delivery.stale_handler_count.get(view_id, 0) <= 0:
        return
    delivery.stale_handler_count[view_id] -= 1
    if delivery.last_stale_time.get(view_id, 0) != 0 and stale_count < STALE_PICTURE_LOOKS:
        delivery.push_render(view_id, False, stale_count + 1)


def _image_delivery(server):
    """trame-vtk's picture publisher on ``server``, or None before the server is ready."""
    from trame_vtk.modules.vtk.protocols import vtkWebPublishImageDelivery

    protocol = server.protocol
    if protocol is None:
        return None
    for link in protocol.getLinkProtocols():
        if isinstance(link, vtkWebPublishImageDelivery):
            return link
    return None
