"""Where a scene's camera stands: the whole mesh, a few vertices, or following a highlight.

The camera always looks along a direction toward a focal point, with the world's y
axis up unless that is the viewing direction. A small mesh is shown whole and turned
round when the highlight is on its far side; on a large mesh the camera follows the
highlight. With a legend on the right, the picture is shifted left to leave it room.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .geometry import SceneGeometry
from .screen import unit

#: Default view direction (from the object toward the camera) for meshes that are not flat.
VIEW_DIRECTION = np.array([0.75, 0.85, 1.3])


class Camera:
    """The camera of one scene's ``plotter``.

    Args:
        plotter: the ``pyvista.Plotter`` whose camera is set.
        window_size: the picture's (width, height) in pixels.
        legend_width: the fraction of the width a legend takes on the right (0 for none).
    """

    def __init__(self, plotter, window_size: tuple[int, int], legend_width: float):
        self.plotter = plotter
        self.window_size = window_size
        self.legend_width = legend_width
        #: The last view direction (toward the camera), or None before the first aim.
        self.direction: np.ndarray | None = None

    def view_direction(self, geometry: SceneGeometry) -> np.ndarray:
        """Toward the camera: along the normal of a flat mesh, else an oblique default."""
        normals = geometry.face_normals[geometry.live_faces]
        mean = normals.mean(axis=0) if len(normals) else np.zeros(3)
        if np.linalg.norm(mean) > 0.9:
            return unit(mean)
        return unit(VIEW_DIRECTION)

    def set(self, focal: np.ndarray, direction: np.ndarray, radius: float,
            points: np.ndarray | None = None) -> None:
        """Look at ``focal`` from ``direction``, far enough to see a ball of ``radius``,
        or, when ``points`` are given, exactly those points (re-centred, small margin)."""
        direction = unit(direction)
        up = np.array([0.0, 1.0, 0.0])
        if abs(direction @ up) > 0.95:
            up = np.array([0.0, 0.0, -1.0]) if direction[1] > 0 else np.array([0.0, 0.0, 1.0])
        up = unit(up - (up @ direction) * direction)
        right = np.cross(up, direction)
        width, height = self.window_size
        free = 1.0 - self.legend_width
        tan_vertical = np.tan(np.radians(15.0))
        tan_horizontal = tan_vertical * free * width / height
        if points is None:
            distance = radius / np.sin(np.arctan(min(tan_vertical, tan_horizontal))) * 1.02
        else:
            offset = points - focal
            x, y = offset @ right, offset @ up
            focal = focal + right * 0.5 * (x.max() + x.min()) + up * 0.5 * (y.max() + y.min())
            offset = points - focal
            x, y, z = offset @ right, offset @ up, offset @ direction
            distance = float(np.max(np.maximum(np.abs(x) / tan_horizontal, np.abs(y) / tan_vertical) * 1.15 + z))
        camera = self.plotter.camera
        camera.focal_point = tuple(focal)
        # VTK's own setter: pyvista's ``camera.position = ...`` also resets the clipping
        # range over every visible part (about 2 ms with the bunny's surface), which the
        # last line does anyway once the camera is in place.
        camera.SetPosition(tuple(focal + distance * direction))
        camera.up = tuple(up)
        camera.view_angle = 30.0
        camera.SetWindowCenter(1.0 - free, 0.0)
        self.plotter.camera_set = True  # else pyvista resets the camera at the first render
        self.direction = direction
        self.plotter.renderer.ResetCameraClippingRange()

    def fit(self, geometry: SceneGeometry, points: np.ndarray, direction: np.ndarray | None = None) -> None:
        """Show all of ``points`` (the vertices and arrows of a whole mesh) from ``direction``."""
        direction = self.view_direction(geometry) if direction is None else direction
        self.set(geometry.center, direction, geometry.radius, points=points)

    def direction_toward(self, geometry: SceneGeometry, vertices: np.ndarray) -> np.ndarray:
        """Toward the camera for a view of ``vertices``: along their normal (the default
        direction on a flat mesh, or where their normals cancel)."""
        normal = unit(geometry.vertex_normals[vertices].sum(axis=0))
        if geometry.flat or not np.linalg.norm(normal) > 0:
            return self.view_direction(geometry)
        return normal

    def look_at(self, mesh, geometry: SceneGeometry, vertices: np.ndarray, around: np.ndarray) -> None:
        """Face ``vertices`` and fit them with the vertices ``around`` (pulled halfway in:
        enough to show the context)."""
        centre = mesh.positions[vertices].mean(axis=0)
        points = np.concatenate([mesh.positions[vertices], centre + 0.6 * (mesh.positions[around] - centre)])
        self.set(centre, self.direction_toward(geometry, vertices), geometry.radius, points=points)

    def follow(self, mesh, geometry: SceneGeometry, focus: np.ndarray, faces: np.ndarray | None, *,
               mode, windowed: bool, rings: int, whole_mesh_points: Callable[[], np.ndarray]) -> None:
        """Keep the highlight in sight after it moved.

        Args:
            focus: (k,) the highlighted vertices (with the ends of highlighted halfedges).
            faces: the highlighted faces, whose normal says where the highlight faces, or
                None when no face is highlighted (then the vertices' normals say it).
            mode: ``"auto"`` (follow on a large mesh; on a small one turn round only when the
                highlight is seen edge-on or from behind), True or False.
            windowed: the scene draws only the arrows near the highlight.
            rings: how many rings around the highlight a followed view shows.
            whole_mesh_points: gives what a whole-mesh view must fit; called only when the
                camera turns to the whole mesh (it gathers every vertex and arrow).
        """
        if len(focus) == 0:
            return
        if faces is not None:
            faces = faces[(faces >= 0) & (faces < mesh.n_face_slots)]
            normal = unit(geometry.face_normals[faces].sum(axis=0))
        else:
            normal = unit(geometry.vertex_normals[focus].sum(axis=0))
        if not np.linalg.norm(normal) > 0:
            return
        if mode == "auto":
            mode = windowed
            to_camera = self.direction
            centre = mesh.positions[focus].mean(axis=0) - geometry.center
            off_axis = np.linalg.norm(centre - (centre @ to_camera) * to_camera) / geometry.radius
            seen = normal @ to_camera
            if not mode and (seen < 0.3 or (seen < 0.8 and off_axis > 0.6)):
                # The highlight is seen edge-on or from behind: swing round to face it,
                # still looking at the whole mesh, a little from the side.
                self.fit(geometry, whole_mesh_points(), unit(1.5 * normal + unit(VIEW_DIRECTION)))
                return
        if mode:
            positions = mesh.positions[focus]
            centre = positions.mean(axis=0)
            radius = max(float(np.linalg.norm(positions - centre, axis=1).max()), 0.5 * geometry.scale)
            self.set(centre, normal, radius + 0.4 * rings * geometry.scale)
