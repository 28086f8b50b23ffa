"""Chapter 05's viewer: a slider over Laplacian smoothing iterations, flat or smooth shading.

    from halfedge_edu.viz import SmoothingViewer
    w = SmoothingViewer(noisy_spot)
    w                          # the slider, the shading toggle and the picture
    w.iterations.value = 10    # the same as dragging the slider
    print(w.describe())        # "10 iterations, flat shading: volume 0.1234"

The picture is drawn off screen into an image, so the viewer works the same in
JupyterLab, in VS Code and, as a still picture, on GitHub.
"""

from __future__ import annotations

import base64

import numpy as np

from .main_thread import on_main_thread
from .pictures import plotter_png

#: The surface colour of chapter 05's pictures.
SURFACE = "#E8B96A"
#: Where chapter 05 looks at Spot from: ``[eye, focus, up]``.
SPOT_CAMERA = [(2.6, 0.9, -2.2), (0.0, 0.1, 0.1), (0.0, 1.0, 0.0)]


def enclosed_volume(mesh) -> float:
    """The volume a closed mesh encloses: the sum over faces of ``a · (b × c) / 6``."""
    P = mesh.positions
    corners = mesh.face_vertices()[~mesh.face_deleted]                   # (F, 3)
    a, b, c = P[corners[:, 0]], P[corners[:, 1]], P[corners[:, 2]]
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


class SmoothingViewer:
    """A slider over smoothing iterations and a flat/smooth toggle for one mesh.

    Args:
        mesh: the mesh to smooth (never changed).
        max_iterations: the slider's end.
        window_size: the picture's size in pixels.
        camera: ``[eye, focus, up]`` (default :data:`SPOT_CAMERA`).

    ``iterations`` (an IntSlider) and ``shading`` (ToggleButtons, "flat" or "smooth") are
    the controls: setting their ``value`` from code redraws as a learner's click does.
    ``smoothed`` is the mesh shown; ``describe()`` says the iterations, the shading and
    the enclosed volume; ``close()`` frees the picture.
    """

    def __init__(self, mesh, max_iterations: int = 60, window_size=(460, 360), camera=None):
        import ipywidgets as widgets
        import pyvista as pv

        self.mesh = mesh
        self.plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
        self.surface = mesh.to_pyvista()
        self.actor = self.plotter.add_mesh(self.surface, color=SURFACE)
        self.plotter.camera_position = SPOT_CAMERA if camera is None else camera
        self.iterations = widgets.IntSlider(value=0, min=0, max=max_iterations, description="iterations")
        self.shading = widgets.ToggleButtons(options=["flat", "smooth"], value="flat")
        self.image = widgets.Image(format="png")
        self.status = widgets.Label()
        # Changes from the browser arrive on another thread; redraws run on the main one.
        self.iterations.observe(on_main_thread(self.redraw), names="value")
        self.shading.observe(on_main_thread(self.redraw), names="value")
        self.panel = widgets.VBox([widgets.HBox([self.iterations, self.shading]), self.image, self.status])
        self.redraw()

    def redraw(self, change=None) -> None:
        """Smooth the mesh by the slider's iterations and draw it in the toggle's shading."""
        from ..algorithms.normals import vertex_normals
        from ..algorithms.smoothing import smooth

        self.smoothed = smooth(self.mesh, iterations=self.iterations.value)
        self.surface.points = self.smoothed.positions
        if self.shading.value == "smooth":
            self.surface.point_data["Normals"] = vertex_normals(self.smoothed)
            self.surface.point_data.active_normals_name = "Normals"
            self.actor.prop.interpolation = "gouraud"
        else:
            self.surface.point_data.pop("Normals", None)
            self.actor.prop.interpolation = "flat"
        self.image.value = plotter_png(self.plotter)
        self.status.value = self.describe()

    def describe(self) -> str:
        return (f"{self.iterations.value} iterations, {self.shading.value} shading: "
                f"volume {enclosed_volume(self.smoothed):.4f}")

    def close(self) -> None:
        """Close the widgets and free the render window."""
        self.panel.close()
        self.plotter.close()

    def _repr_mimebundle_(self, **kwargs):
        # The live panel where widgets run; the current picture everywhere else.
        bundle = self.panel._repr_mimebundle_(**kwargs) or {}
        bundle["image/png"] = base64.b64encode(self.image.value).decode("ascii")
        bundle["text/plain"] = self.describe()
        return bundle
