"""Where a widget's picture goes: a live 3D view, or a static image redrawn each step.

One widget code path, two renderers:

- ``"live"``: the scene's plotter is shown through PyVista's trame backend inside
  JupyterLab; a step updates the actors and pushes a frame (the server view renders
  and sends one picture; a client view gets the new scene through ``plotter.render()``).
- ``"static"``: the plotter renders off screen and each step puts a fresh PNG into an
  ``ipywidgets.Image``. This is what course CI, ``nbconvert``, GitHub's preview and a
  static HTML export can show.

:func:`choose_mode` picks one: the ``mode`` argument if given, else the environment
variable ``HALFEDGE_EDU_VIZ`` (``static``, ``live`` or ``auto``), else automatically:
live only inside a Jupyter kernel with trame available and PyVista's notebook backend
not forced to something static (``PYVISTA_JUPYTER_BACKEND=static``, as the headless test
and figure builds set it).
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import os
import sys

from halfedge_edu import live_backend

MODES = ("live", "static")
ENV_VARIABLE = "HALFEDGE_EDU_VIZ"
_LIVE_BACKENDS = {"trame", "server", "client"}


def choose_mode(mode: str | None = None) -> str:
    """``"live"`` or ``"static"``, from ``mode``, then ``$HALFEDGE_EDU_VIZ``, then the setting.

    Raises:
        ValueError: ``mode`` (or the variable) is not ``live``, ``static`` or ``auto``.
    """
    source = "mode"
    if mode is None:
        mode, source = os.environ.get(ENV_VARIABLE, "auto"), ENV_VARIABLE
    chosen = str(mode).strip().lower() or "auto"
    if chosen == "auto":
        return "live" if live_available() else "static"
    if chosen not in MODES:
        raise ValueError(f"{source}={mode!r}: use 'live', 'static' or 'auto'")
    return chosen


def live_available() -> bool:
    """True inside a Jupyter kernel that can show PyVista's trame view."""
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    shell = get_ipython()
    if shell is None or type(shell).__name__ != "ZMQInteractiveShell":
        return False
    if importlib.util.find_spec("trame_pyvista") is None and importlib.util.find_spec("trame") is None:
        return False
    backend = os.environ.get("PYVISTA_JUPYTER_BACKEND")
    if backend is None:
        import pyvista

        backend = pyvista.global_theme.jupyter_backend
    # pyvista leaves the backend unset (None) to mean "trame if it is installed".
    return backend is None or str(backend).lower() in _LIVE_BACKENDS


def make_plotter(mode: str, window_size: tuple[int, int]):
    """A ``pyvista.Plotter`` for ``mode``: off screen for static, notebook-ready for live."""
    import pyvista as pv

    if mode == "static":
        return pv.Plotter(off_screen=True, window_size=list(window_size))
    return pv.Plotter(notebook=True, window_size=list(window_size))


class View:
    """The picture part of a widget, for a scene, in one of the two modes.

    ``view.widget`` is what goes into the widget's layout; ``view.update()`` shows the
    scene's current state (a new PNG, or a pushed frame).

    A static picture is rendered only once someone can see it: after ``shown()`` (the
    widget was displayed) every update renders a new PNG; before, an update only marks
    the picture stale and ``picture()`` renders it on demand. A widget a chapter drives
    from code for its text alone then never opens a render window (about 27 MiB of
    kernel memory each, measured on chapter 03's two such widgets).
    """

    def __init__(self, scene, mode: str):
        import ipywidgets as widgets

        self.scene = scene
        self.mode = mode
        self._shown = False
        self._stale = True
        #: trame-pyvista's view mode of a live view ("server" or "client"), None when static.
        self.trame_mode: str | None = None
        width, height = scene.window_size
        if mode == "static":
            self.widget = widgets.Image(format="png", width=width, height=height,
                                        layout=widgets.Layout(width=f"{width}px", height=f"{height}px",
                                                              flex="0 0 auto"))
        else:
            # A collapsed menu is one small button in the corner; the full toolbar would
            # cover the top ~60 px of the view, where the highlighted halfedge may be.
            trame_mode = self.trame_mode = live_backend.trame_mode()
            with without_wasm_notice():
                self.widget = scene.plotter.show(
                    jupyter_backend="trame", return_viewer=True,
                    jupyter_kwargs={"collapse_menu": True, "mode": trame_mode})
            if trame_mode == "client":
                # The browser fetches the scene's arrays after it loads the view, which
                # may be long after the last step: keep them (see live_backend).
                live_backend.keep_scene_arrays(self.widget.viewer)
            else:
                # Send each step's picture as soon as it is encoded, not 0.5 s later.
                live_backend.answer_clicks_promptly(self.widget.viewer.server)
        self.update()

    def shown(self) -> None:
        """The view is on screen (its widget was displayed): keep its picture current."""
        self._shown = True
        if self.mode == "static" and self._stale:
            self._render_picture()

    def picture(self) -> bytes:
        """The static view's current PNG, rendered now if it is stale."""
        if self._stale:
            self._render_picture()
        return bytes(self.widget.value)

    def _render_picture(self) -> None:
        self.widget.value = self.scene.screenshot()
        self._stale = False

    def update(self) -> None:
        """Show the scene's current state."""
        if self.mode == "static":
            self._stale = True
            if self._shown:
                self._render_picture()
        elif self.trame_mode == "client":
            # trame-pyvista's views follow the plotter's renders (a render callback sends
            # the new scene to vtk.js), so one render is the whole update. Calling the
            # viewer's update() as well did all of it twice (measured with trame-pyvista
            # 0.2.3: four scene serialisations a step instead of two).
            self.scene.render()
        else:
            # The server view renders the window itself when it makes the picture it
            # sends (trame-vtk's still render); plotter.render() would render it once
            # more before that, for nothing (about 20 ms a step on the bunny).
            self.widget.viewer.update()


def prepare_plotter(look, window_size: tuple[int, int], plotter=None):
    """``plotter`` (by default a new off-screen one of ``window_size``) set up as every
    scene is: the preset's background and one light at the eye, so faces seen head-on
    show their true colour."""
    import pyvista as pv

    if plotter is None:
        plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.set_background(look.background)
    plotter.remove_all_lights()
    plotter.add_light(pv.Light(light_type="headlight"))
    return plotter


def show(plotter):
    """Show a chapter's own ``plotter`` in its cell, as the widgets show theirs.

    In a live Lab: PyVista's menu collapsed to one button in the corner (the full toolbar
    covers the top of the plot, where titles are), and without the line trame-vtklocal
    prints when it starts. Elsewhere (PNG output, nbval) just ``plotter.show()``.
    """
    if not live_available():
        return plotter.show()
    with without_wasm_notice():
        if tuple(getattr(plotter, "shape", (1, 1))) != (1, 1):
            # Several views in one plotter: the collapsed menu's view settings throw in the
            # browser (vtk.js: "getOpacity is not a function"), so those keep PyVista's menu.
            return plotter.show(jupyter_kwargs={"mode": live_backend.trame_mode()})
        return plotter.show(jupyter_kwargs={"collapse_menu": True, "mode": live_backend.trame_mode()})


def widget_bundle(widget, text: str, plotters, screenshot, include=None, exclude=None) -> dict:
    """The MIME bundle of a widget whose pictures ``plotters`` draw: what Jupyter displays.

    ``widget`` (an ipywidget) is shown where widgets run, ``text`` in a plain console,
    and ``screenshot()`` (PNG bytes) wherever there is no widget manager (nbviewer, the
    website, a notebook opened without its kernel). A client-side live view
    (``HALFEDGE_EDU_LIVE_BACKEND=client``) renders in the browser only: its kernel
    plotter has no picture to give, so then the PNG is left out (asking raised, and a hub
    student saw a traceback under chapter 07's atlas).
    """
    import base64

    bundle = widget._repr_mimebundle_(include=include, exclude=exclude) or {}
    bundle["text/plain"] = text
    if not any(getattr(plotter, "suppress_rendering", False) for plotter in plotters):
        bundle["image/png"] = base64.b64encode(screenshot()).decode("ascii")
    return bundle


@contextlib.contextmanager
def without_wasm_notice():
    """Leave out the line "Using wasm_dir: <folder>" that trame-vtklocal prints each time a
    live view starts with ``VTK_WASM_DIR_OVERRIDE`` set (as ``make lab`` sets it, so that
    nothing is downloaded): above a chapter's first widget it reads like an error.
    Everything else printed meanwhile goes through."""
    stream = _WithoutWasmNotice(sys.stdout)
    with contextlib.redirect_stdout(stream):
        yield


class _WithoutWasmNotice(io.TextIOBase):
    """``stream`` without the lines that start "Using wasm_dir: " (``print`` writes the
    text and its newline in two calls)."""

    NOTICE = "Using wasm_dir: "

    def __init__(self, stream):
        self._stream = stream
        self._dropping = False

    def write(self, text: str) -> int:
        if text.startswith(self.NOTICE):
            self._dropping = not text.endswith("\n")
            return len(text)
        if self._dropping and text.startswith("\n"):
            self._dropping = False
            text = text[1:]
        return self._stream.write(text) if text else 0

    def flush(self) -> None:
        self._stream.flush()
