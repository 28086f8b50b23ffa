"""Index labels of a scene: "v3" beside a vertex, "f1" in a face, "h7" beside an arrow.

Which elements get one depends on the mesh's size: on a tiny mesh all of them; on a
larger one the vertices near the highlight and the highlighted elements only. Named
elements (a stepper's "vA", "h_AB") always get their name, as ``vA (3)``. A label whose
element faces away from the camera is left out, so labels never show through the surface.
"""

from __future__ import annotations

import numpy as np

from . import arrows
from .actors import Actors
from .geometry import SceneGeometry, facing
from .highlights import Highlight
from .neighbourhood import ring_mark
from .palette import Preset
from .screen import beside

KINDS = ("vertex", "halfedge", "face")
PREFIX = {"vertex": "v", "halfedge": "h", "face": "f"}
#: With ``labels="auto"``: meshes with at most this many faces get every label.
TINY_FACES = 12
#: With ``labels="auto"``: meshes with at most this many vertices get every vertex label.
TINY_VERTICES = 40
#: With explicit label kinds: meshes with at most this many faces get every label of
#: those kinds; larger ones only near the highlight.
LABEL_ALL_FACES = 40


def label_kinds(labels) -> "tuple[str, ...] | str":
    """The scene option ``labels`` read: ``"auto"`` or a tuple of kinds.

    Raises:
        ValueError: a kind that is not "vertex", "halfedge" or "face".
    """
    if labels is None or labels is False:
        return ()
    if labels is True:
        return KINDS
    if labels == "auto":
        return "auto"
    kinds = tuple(labels)
    for kind in kinds:
        if kind not in KINDS:
            raise ValueError(f"labels: unknown kind {kind!r}; use 'vertex', 'halfedge' or 'face'")
    return kinds


class Labels:
    """The label parts ("vertex_labels", ...) of one scene.

    Args:
        actors: the scene's parts, where the label actors are added on first use.
        preset: sizes and colours.
        window_size: the picture size, for placing vertex labels a few pixels aside.
        kinds: what :func:`label_kinds` returned for the scene's ``labels`` option.
    """

    def __init__(self, actors: Actors, preset: Preset, window_size: tuple[int, int], kinds):
        self.actors = actors
        self.preset = preset
        self.window_size = window_size
        self.kinds = kinds
        self.texts: dict[str, list[str]] = {kind: [] for kind in KINDS}

    def choice(self, mesh, windowed: bool) -> dict[str, str]:
        """For each kind, which elements get a label: "all", "near" or "highlighted"."""
        if self.kinds == "auto":
            if mesh.n_faces <= TINY_FACES:
                return {kind: "all" for kind in KINDS}
            return {"vertex": "all" if mesh.n_vertices <= TINY_VERTICES and not windowed else "near",
                    "halfedge": "highlighted", "face": "highlighted"}
        reach = "all" if mesh.n_faces <= LABEL_ALL_FACES and not windowed else "near"
        return {kind: reach for kind in self.kinds}

    def draw(self, mesh, geometry: SceneGeometry, highlight: Highlight, focus: np.ndarray, *,
             windowed: bool, arrow_halfedges: np.ndarray, corners) -> None:
        """Place the labels for the highlight around ``focus`` (k,) vertices.

        ``arrow_halfedges`` are the halfedges drawn now, ``corners`` the arrows' placement
        (``(mesh, halfedges) -> (A, B, third)``): halfedge labels sit beside their arrows.
        """
        look = self.preset
        choice = self.choice(mesh, windowed)
        near = ring_mark(mesh, focus, 1) if len(focus) and "near" in choice.values() else None
        eye = np.array(self.actors.plotter.camera.position)
        positions = mesh.positions
        texts: dict[str, tuple[np.ndarray, list[str]]] = {}

        def chosen(kind: str) -> np.ndarray:
            return self._labelled(mesh, geometry, highlight, kind, choice.get(kind), near, arrow_halfedges)

        vertices = chosen("vertex")
        if len(vertices):
            vertices = vertices[geometry.vertex_in_sight(mesh, eye, vertices)]
            points = beside(self.actors.plotter, self.window_size, positions[vertices], 0.45 * look.highlight_vertex_size)
            texts["vertex"] = (points, [self._text(highlight, "vertex", v) for v in vertices])
        faces = chosen("face")
        if len(faces):
            centroids = positions[geometry.corners_of(mesh, faces)].mean(axis=1)
            keep = facing(eye, centroids, geometry.face_normals[faces])
            faces, centroids = faces[keep], centroids[keep]
            centroids = centroids + arrows.LIFT * geometry.scale * geometry.face_normals[faces]
            texts["face"] = (centroids, [self._text(highlight, "face", f) for f in faces])
        halfedges = chosen("halfedge")
        if len(halfedges):
            A, B, third = corners(mesh, halfedges)
            middle = 0.5 * (A + B)
            points = middle + 0.6 * ((A + B + third) / 3.0 - middle)
            keep = facing(eye, points, np.cross(B - A, third - A))
            texts["halfedge"] = (points[keep], [self._text(highlight, "halfedge", h) for h in halfedges[keep]])
        self._show(texts)

    def _show(self, texts: dict[str, tuple[np.ndarray, list[str]]]) -> None:
        import pyvista as pv

        look = self.preset
        styles = {
            "vertex": dict(text_color="#FFFFFF", shape_color=look.vertex, shape="rounded_rect",
                           font_size=look.label_size, bold=True,
                           justification_horizontal="left", justification_vertical="bottom"),
            "face": dict(text_color=look.text, shape=None, font_size=look.label_size, bold=False, italic=True,
                         justification_horizontal="center", justification_vertical="center"),
            "halfedge": dict(text_color="#333333", shape=None, font_size=max(8, look.label_size - 1), bold=False,
                             justification_horizontal="center", justification_vertical="center"),
        }
        self.texts = {kind: list(texts.get(kind, ((), []))[1]) for kind in KINDS}
        for kind in KINDS:
            name = f"{kind}_labels"
            points, words = texts.get(kind, (np.zeros((0, 3)), []))
            if len(words) == 0:
                if name in self.actors:
                    self.actors.hide(name)
                continue
            data = pv.PolyData(np.asarray(points, dtype=float))
            data.point_data["labels"] = np.array(words)
            if name in self.actors:
                # The label actor reads this dataset: refill it instead of a new actor.
                self.actors.refill(name, data)
            else:
                self.actors.add_labels(name, data, **styles[kind])

    def _labelled(self, mesh, geometry: SceneGeometry, highlight: Highlight, kind: str, choice: str | None,
                  near: np.ndarray | None, arrow_halfedges: np.ndarray) -> np.ndarray:
        """The indices of ``kind`` that get a label (named ones always do)."""
        chosen = [highlight.named(kind)]
        if choice == "highlighted" or (choice == "near" and near is None):
            chosen += [members for _, members in highlight.members(kind)]
        elif choice is not None:
            if kind == "vertex":
                candidates = np.flatnonzero(~mesh.vertex_deleted)
            elif kind == "face":
                candidates = geometry.live_faces
            else:
                candidates = arrow_halfedges
            if choice == "near":
                if kind == "vertex":
                    candidates = candidates[near[candidates]]
                elif kind == "face":
                    candidates = candidates[near[geometry.corners_of(mesh, candidates)].all(axis=1)]
                else:
                    candidates = candidates[near[mesh.halfedge_vertex[candidates]] & near[mesh.halfedge_vertex[candidates ^ 1]]]
            chosen.append(candidates)
        found = np.unique(np.concatenate(chosen).astype(np.int64))
        if kind == "halfedge":
            found = found[(found >= 0) & (found < mesh.n_halfedge_slots)]
            return found[~mesh.edge_deleted[found >> 1]]
        slots = mesh.n_vertex_slots if kind == "vertex" else mesh.n_face_slots
        deleted = mesh.vertex_deleted if kind == "vertex" else mesh.face_deleted
        found = found[(found >= 0) & (found < slots)]
        return found[~deleted[found]]

    @staticmethod
    def _text(highlight: Highlight, kind: str, index: int) -> str:
        plain = f"{PREFIX[kind]}{int(index)}"
        name = highlight.names.get((kind, int(index)))
        return plain if name is None else f"{name} ({int(index)})"
