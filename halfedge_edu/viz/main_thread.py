"""Run widget callbacks on the kernel's main thread, where VTK's OpenGL context lives.

    from halfedge_edu.viz import on_main_thread
    button.on_click(on_main_thread(clicked))
    slider.observe(on_main_thread(redraw), names="value")

Why: ipykernel 7 with JupyterLab 4 delivers widget messages (a click, a slider move, a
dropdown change) on a kernel *subshell* thread, not on the thread that runs the cells.
An OpenGL context belongs to the thread that made it current; a VTK render from the
subshell thread into a plotter the main thread made breaks that context: "Error setting
'vertexMC' in shader VAO" in the kernel's log, a picture of vertical stripes, and in the
end a segmentation fault that kills the kernel. Code run in a cell (nbval, the tests,
``w.go("twin")``) is on the main thread, so only a learner's clicks ever hit it.

The cure: a callback that may draw goes through :func:`on_main_thread`. Called on the
main thread it runs at once, as before. Called on any other thread it is handed to the
kernel's event loop with ``io_loop.add_callback`` (tornado's one thread-safe way into
the loop); the loop runs such callbacks one at a time, in the order they arrived, on
the main thread. Outside a kernel there is no subshell and no loop to hand over to, so
the callback runs at once wherever it was called.

Every widget of :mod:`halfedge_edu.viz` wires its buttons and observers through this
module (:func:`~halfedge_edu.viz.widgets.panel_button` does it for every button), and a
chapter that builds its own widget around a plotter does the same with
:func:`on_main_thread`.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable


def kernel_loop():
    """The running IPython kernel's event loop (a tornado ``IOLoop``), or None outside a kernel."""
    try:
        from ipykernel.kernelbase import Kernel
    except ImportError:
        return None
    if not Kernel.initialized():
        return None
    return getattr(Kernel.instance(), "io_loop", None)


def call_on_main_thread(function: Callable[..., object], *args, loop=None, **kwargs) -> None:
    """Run ``function(*args, **kwargs)`` on the main thread: now if this is the main
    thread, else queued on ``loop`` (by default the kernel's, :func:`kernel_loop`).

    Queued calls run in the order they were made. A queued call's return value is
    dropped (the caller has moved on), so callbacks report through their widget
    (a status line), not by returning or printing.
    """
    if threading.current_thread() is threading.main_thread():
        function(*args, **kwargs)
        return
    loop = kernel_loop() if loop is None else loop
    if loop is None:
        function(*args, **kwargs)
        return
    loop.add_callback(functools.partial(function, *args, **kwargs))


def on_main_thread(function: Callable[..., object], *, loop=None) -> Callable[..., None]:
    """``function`` wrapped so that every call runs on the main thread (see
    :func:`call_on_main_thread`); for ``Button.on_click`` and ``observe`` handlers."""

    @functools.wraps(function)
    def on_main(*args, **kwargs) -> None:
        call_on_main_thread(function, *args, loop=loop, **kwargs)

    return on_main
