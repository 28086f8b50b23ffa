"""Where a live 3D view is drawn: in the kernel (``server``) or in the browser (``client``).

A hub sets this once for every student with the environment variable
``HALFEDGE_EDU_LIVE_BACKEND`` (deploy/jupyterhub/jupyterhub_config.py passes it on):

- ``server`` (the default): the kernel renders every frame with VTK and sends pictures
  (pyvista's ``trame`` backend). Costs kernel memory for the render window and server
  CPU for every step and every frame of a rotation.
- ``client``: the kernel sends the scene's geometry once and vtk.js draws it in the
  browser (pyvista's ``client`` backend); rotating costs the server nothing.

:func:`trame_mode` turns the setting into the ``mode`` that trame-pyvista's view takes
(``plotter.show(jupyter_backend="trame", jupyter_kwargs={"mode": trame_mode()})``). The
mode goes in ``jupyter_kwargs`` on purpose: ``jupyter_backend="client"`` alone still gives
the server-rendered view unless ``trame_pyvista`` was imported before (its entry points
register every backend name without a mode; measured with trame-pyvista 0.2.3).
"""

from __future__ import annotations

import os

ENV_VARIABLE = "HALFEDGE_EDU_LIVE_BACKEND"
# The setting's values and trame-pyvista's view mode for each: "trame" is the view the
# widgets have always used (server rendering, with a switch in its menu), "client" is vtk.js.
TRAME_MODES = {"server": "trame", "client": "client"}


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
