"""Index labels of a scene: "v3" beside a vertex, "f1" in a face, "h7" beside an arrow.

Which elements get one depends on the mesh's size: on a tiny mesh all of them; on a
larger one the vertices near the highlight and the highlighted elements only. Named
elements (a stepper's "vA", "h_AB") always get their name, as ``vA (3)``. A label whose
element faces away from the camera is left out, so labels never show through the surface.

No label covers another. Each label is measured on screen (its anchor projected with
the camera, its box estimated from its font size and length, :func:`text_size`) and put
at the first place near its anchor where the box overlaps no label placed before it,
no vertex dot and no legend (:func:`place`): named labels first, then highlighted ones,
then the rest, vertices before faces before halfedges, and highlighted ones of a kind in
the order of their roles (the current halfedge before its twin, next and prev). A named
or highlighted label with no room anywhere near is listed in the picture's lower left
corner ("no room for: h5, f2") instead.

Labels do not crowd either. Any other label is optional: it is shown only near its
element (the two nearest rings of places) and :data:`SPACING` pixels clear of every label
placed before it, else left out without a word. On a dense mesh that thins the labels
around the highlight to those a reader can match to their elements, instead of a wall of
badges pushed away from what they name; the named and highlighted ones are never left
out for the others' sake, as they are placed first.
:func:`label_boxes` measures the boxes of what a plotter draws, and :func:`overlapping_labels`
says which overlap (for tests).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import arrows
from .actors import Actors
from .geometry import SceneGeometry, facing
from .highlights import Highlight
from .neighbourhood import Rings
from .palette import ROLES, Preset
from .screen import from_screen, to_screen

KINDS = ("vertex", "halfedge", "face")
#: Each role's place in ``ROLES`` (the legend's order, most important first).
ROLE_ORDER = {name: order for order, name in enumerate(ROLES)}
PREFIX = {"vertex": "v", "halfedge": "h", "face": "f"}
#: Of labels of one rank, which kinds get the first choice of place.
PLACING_ORDER = ("vertex", "face", "halfedge")
#: With ``labels="auto"``: meshes with at most this many faces get every label.
TINY_FACES = 12
#: With ``labels="auto"``: meshes with at most this many vertices get every vertex label.
TINY_VERTICES = 40
#: With explicit label kinds: meshes with at most this many faces get every label of
#: those kinds; larger ones only near the highlight.
LABEL_ALL_FACES = 40
#: Pixels around a label's text that its box includes (the badge the text sits on).
PADDING = {"vertex": 3.0, "face": 3.0, "halfedge": 3.0}
#: Where a label's point lies from its box's lower left corner, in pixels: its badge is
#: drawn left- and bottom-justified from that point (measured: 2 left, 1 below).
BADGE_POINT = np.array([3.0, 2.0])
#: Average character width as a share of the font size (vtk's Arial, measured: 0.45-0.55).
CHARACTER_WIDTH = 0.56
#: The distance between the baselines of two lines of text, as a share of the font size.
LINE_SPACING = 1.25
#: The text of the list of labels without room, and its distance from the picture's corner.
LIST_ACTOR = "labels_without_room"
LIST_MARGIN = 4.0
#: Where a label may go around its anchor, in steps: (right, up) multiples.
DIRECTIONS = ((1, 1), (-1, 1), (1, -1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1))
#: Where a label that may sit on its anchor (a face's) goes next, in steps: above and
#: below first, then beside, then the corners.
AROUND = ((0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (-1, 1), (1, -1), (-1, -1))
#: Pixels an optional label (neither named nor highlighted) keeps from every label placed
#: before it; others keep one pixel.
SPACING = 6.0
#: Of :func:`candidate_offsets`, the places near the anchor, the only ones an optional
#: label may take: a vertex label's 16 just off its dot and a little farther (reach 1 and
#: 1.8), a face or halfedge label's place on its anchor and the 16 one and two steps
#: around it. (One ring only left out most of the diagonal halfedges' labels of a small
#: grid, where the face label takes the middle; three let labels stray from their elements.)
NEAR_BESIDE_DOT = 2 * len(DIRECTIONS)
NEAR_ON_ANCHOR = 1 + 2 * len(AROUND)
#: The rank of a label that is neither named nor highlighted (see :class:`Wanted`).
OPTIONAL = 2


class Wanted(NamedTuple):
    """A label to place: its kind, text, (3,) world anchor, rank (0 named, 1 highlighted,
    2 other, :data:`OPTIONAL`: lower ranks are placed first), element index, and role
    (of a highlighted label, its first role's place in ``ROLES``: of the highlighted
    halfedges, the current one is placed first)."""

    kind: str
    text: str
    anchor: np.ndarray
    rank: int
    index: int
    role: int = 0


def text_size(text: str, font_size: float, padding: float) -> tuple[float, float]:
    """(width, height) in pixels of the box around ``text`` (one or more lines) at
    ``font_size`` (vtk's pixels), with ``padding`` pixels on each side."""
    lines = text.split("\n")
    width = CHARACTER_WIDTH * font_size * max(len(line) for line in lines)
    height = font_size * (1 + LINE_SPACING * (len(lines) - 1))
    return width + 2 * padding, height + 2 * padding


def place(anchors: np.ndarray, sizes: np.ndarray, keep_clear, dots: np.ndarray, obstacles: np.ndarray,
          window_size, optional=None) -> np.ndarray:
    """Centres (k, 2) in pixels for k label boxes, in order, each where it overlaps none
    placed before, no dot and no obstacle, and lies inside the picture; NaN where none is free.

    Args:
        anchors: (k, 2) where each label belongs on screen.
        sizes: (k, 2) each box's width and height.
        keep_clear: (k,) a radius around the anchor the box keeps out of (a vertex label
            beside its dot), 0 for a label that may sit on its anchor (a face's centre).
        dots: (d, 3) vertex dots ``(x, y, radius)`` no box may cover.
        obstacles: (o, 4) boxes ``(x0, y0, x1, y1)`` no label may overlap (a legend).
        optional: (k,) bool, None for none: a label that takes only a place near its
            anchor (:data:`NEAR_BESIDE_DOT`, :data:`NEAR_ON_ANCHOR`) and keeps
            :data:`SPACING` pixels from every label placed before it, so that it never
            crowds them; NaN where it cannot.

    Each label takes the first of its :func:`candidate_offsets` that is free. Whether a
    place is inside the picture, off the obstacles and off the dots does not depend on the
    other labels, so that is decided for every place of every label at once; only the test
    against the labels placed before is left to the loop, one numpy pass per label.
    """
    width, height = window_size
    anchors = np.asarray(anchors, dtype=float).reshape(-1, 2)
    sizes = np.asarray(sizes, dtype=float).reshape(-1, 2)
    centres = np.full((len(anchors), 2), np.nan)
    if len(anchors) == 0:
        return centres
    keep_clear = np.asarray(keep_clear, dtype=float)                                   # (k,)
    optional = np.zeros(len(anchors), dtype=bool) if optional is None else np.asarray(optional, dtype=bool)
    offsets, usable = candidate_offsets(sizes, keep_clear)                             # (k, c, 2), (k, c)
    near = np.where(keep_clear > 0, NEAR_BESIDE_DOT, NEAR_ON_ANCHOR)                   # (k,)
    usable = usable & ~(optional[:, None] & (np.arange(usable.shape[1]) >= near[:, None]))
    gap = np.where(optional, SPACING, 1.0)                                             # (k,)
    candidates = anchors[:, None, :] + offsets                                         # (k, c, 2)
    half = sizes[:, None, :] / 2                                                       # (k, 1, 2)
    boxes = np.concatenate([candidates - half, candidates + half], axis=2)            # (k, c, 4)
    free = usable & (boxes[..., 0] >= 0) & (boxes[..., 1] >= 0) & (boxes[..., 2] <= width) & (boxes[..., 3] <= height)
    # A pixel apart, so that a box measured again after a round trip through world
    # coordinates (a little rounding) still clears its neighbours.
    free &= ~overlaps(boxes, obstacles, 1.0).any(axis=2)
    free &= ~covers_dot(boxes, dots).any(axis=2)
    placed = np.zeros((len(anchors), 4))                   # the first n_placed rows are in use
    n_placed = 0
    for i in range(len(anchors)):
        fits = free[i] & ~overlaps(boxes[i], placed[:n_placed], gap[i]).any(axis=1)  # (c,)
        if fits.any():
            first = int(np.argmax(fits))
            centres[i] = candidates[i, first]
            placed[n_placed] = boxes[i, first]
            n_placed += 1
    return centres


def overlaps(boxes: np.ndarray, others: np.ndarray, gap: float = 0.0) -> np.ndarray:
    """(..., o) bool: each of ``boxes`` (..., 4) ``(x0, y0, x1, y1)`` overlaps each of
    ``others`` (o, 4), or comes closer to it than ``gap`` pixels."""
    boxes = boxes[..., None, :]                                          # (..., 1, 4)
    return ((boxes[..., 0] < others[:, 2] + gap) & (others[:, 0] < boxes[..., 2] + gap)
            & (boxes[..., 1] < others[:, 3] + gap) & (others[:, 1] < boxes[..., 3] + gap))


def covers_dot(boxes: np.ndarray, dots: np.ndarray) -> np.ndarray:
    """(..., d) bool: each of ``boxes`` (..., 4) covers part of each disc of ``dots`` (d, 3)
    ``(x, y, radius)``."""
    boxes = boxes[..., None, :]                                          # (..., 1, 4)
    nearest_x = np.clip(dots[:, 0], boxes[..., 0], boxes[..., 2])
    nearest_y = np.clip(dots[:, 1], boxes[..., 1], boxes[..., 3])
    return (nearest_x - dots[:, 0]) ** 2 + (nearest_y - dots[:, 1]) ** 2 < dots[:, 2] ** 2


def candidate_offsets(sizes: np.ndarray, keep_clear: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where each of k boxes of ``sizes`` (k, 2) may go around its anchor, nearest first.

    A box with a ``keep_clear`` radius (a vertex label) goes beside its dot: its nearest
    corner or side just off the dot, then farther (``reach`` 1, 1.8, 2.8 times the
    radius), in each of the 8 :data:`DIRECTIONS`. A box without (a face's label) goes on
    its anchor first, then 1, 2 and 3 steps away in 8 directions.

    Returns:
        ``(offsets, usable)``: (k, 25, 2) offsets from the anchor in pixels, and (k, 25)
        bool, False for the 25th place of a vertex label (which has only 24).
    """
    w, h = sizes[:, 0:1], sizes[:, 1:2]                                  # (k, 1) each
    clear = keep_clear[:, None]                                          # (k, 1)
    # A vertex label has 24 places; a 25th, never usable, lets both kinds fill one array.
    beside = np.array([(reach, dx, dy) for reach in (1.0, 1.8, 2.8) for dx, dy in DIRECTIONS] + [(0.0, 0, 0)])
    reach, dx, dy = beside.T                                             # (25,) each
    beside_dot = np.stack([dx * (reach * clear + w / 2), dy * (reach * clear + h / 2)], axis=2)   # (k, 25, 2)
    around = np.array([(0, 0, 0)] + [(ring, dx, dy) for ring in (1, 2, 3) for dx, dy in AROUND])
    ring, dx, dy = around.T                                              # (25,) each
    step_x, step_y = np.maximum(0.4 * w, 6.0), 0.6 * h                   # (k, 1) each
    on_anchor = np.stack([(dx * ring) * step_x, (dy * ring) * step_y], axis=2)                   # (k, 25, 2)
    has_dot = clear > 0                                                  # (k, 1)
    offsets = np.where(has_dot[..., None], beside_dot, on_anchor)
    usable = ~has_dot | (np.arange(25) < 24)
    return offsets, usable


def legend_boxes(plotter, window_size) -> np.ndarray:
    """(k, 4) the screen boxes of the legends shown in ``plotter`` (labels keep off them)."""
    boxes = []
    size = np.array(window_size, dtype=float)
    props = plotter.renderer.GetViewProps()
    for i in range(props.GetNumberOfItems()):
        prop = props.GetItemAsObject(i)
        if prop.IsA("vtkLegendBoxActor") and prop.GetVisibility():
            corner = np.array(prop.GetPositionCoordinate().GetValue()[:2]) * size
            extent = np.array(prop.GetPosition2Coordinate().GetValue()[:2]) * size
            boxes.append([*corner, *(corner + extent)])
    return np.array(boxes, dtype=float).reshape(-1, 4)


def label_boxes(plotter, window_size=None) -> list[tuple[str, np.ndarray]]:
    """What ``plotter`` shows of index labels, measured: ``(text, (x0, y0, x1, y1))`` per
    label in screen pixels (each label's point projected with the camera, its box from
    :func:`text_size`), and the list of labels without room. For checking that no two overlap.
    """
    window_size = tuple(window_size or plotter.window_size)
    measured = []
    for name, actor in plotter.actors.items():
        kind = name.split("_labels")[0]
        if not (name.endswith("-labels") and kind in KINDS and actor.GetVisibility()):
            continue
        hierarchy = actor.GetMapper().GetInputAlgorithm()
        data = hierarchy.GetInputDataObject(0, 0)
        points = np.array([data.GetPoint(i) for i in range(data.GetNumberOfPoints())]).reshape(-1, 3)
        texts = data.GetPointData().GetAbstractArray("labels")
        font = hierarchy.GetTextProperty().GetFontSize()
        for i, point in enumerate(to_screen(plotter, window_size, points)[:, :2]):
            size = np.array(text_size(texts.GetValue(i), font, PADDING[kind]))
            corner = point - BADGE_POINT
            measured.append((texts.GetValue(i), np.concatenate([corner, corner + size])))
    listing = plotter.actors.get(LIST_ACTOR)
    if listing is not None and listing.GetVisibility():
        text = listing.GetInput()
        w, h = text_size(text, listing.GetTextProperty().GetFontSize(), 0.0)
        measured.append((text, np.array([LIST_MARGIN, LIST_MARGIN, LIST_MARGIN + w, LIST_MARGIN + h])))
    return measured


def list_text(listed: list[str], font_size: float, window_size) -> str:
    """The lines that list the labels without room, wrapped to the picture's width and
    at most a third of its height (ending "and N more" when they do not all fit)."""
    per_line = max(12, int((window_size[0] - 2 * LIST_MARGIN) / (CHARACTER_WIDTH * font_size)))
    most_lines = max(1, int(window_size[1] / 3 / (LINE_SPACING * font_size)))
    lines: list[list[str]] = [["no room for:"]]
    for n, text in enumerate(listed):
        word = text if n == len(listed) - 1 else f"{text},"
        if len(" ".join(lines[-1] + [word])) > per_line:
            lines.append([])
        lines[-1].append(word)
    if len(lines) > most_lines:
        lines = lines[:most_lines]
        shown = sum(len(line) for line in lines) - 1
        while len(lines[-1]) > 1 and len(" ".join(lines[-1] + [f"and {len(listed) - shown} more"])) > per_line:
            lines[-1].pop()
            shown -= 1
        lines[-1].append(f"and {len(listed) - shown} more")
    return "\n".join(" ".join(line) for line in lines)


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
        window_size: the picture size, for measuring labels on screen.
        kinds: what :func:`label_kinds` returned for the scene's ``labels`` option.
    """

    def __init__(self, actors: Actors, preset: Preset, window_size: tuple[int, int], kinds):
        self.actors = actors
        self.preset = preset
        self.window_size = window_size
        self.kinds = kinds
        self.texts: dict[str, list[str]] = {kind: [] for kind in KINDS}
        self.listed: list[str] = []

    def choice(self, mesh, windowed: bool) -> dict[str, str]:
        """For each kind, which elements get a label: "all", "near" or "highlighted"."""
        if self.kinds == "auto":
            if mesh.n_faces <= TINY_FACES:
                return {kind: "all" for kind in KINDS}
            return {"vertex": "all" if mesh.n_vertices <= TINY_VERTICES and not windowed else "near",
                    "halfedge": "highlighted", "face": "highlighted"}
        reach = "all" if mesh.n_faces <= LABEL_ALL_FACES and not windowed else "near"
        return {kind: reach for kind in self.kinds}

    def draw(self, mesh, geometry: SceneGeometry, highlight: Highlight, focus: np.ndarray, rings: Rings, *,
             windowed: bool, arrow_halfedges: np.ndarray, corners) -> None:
        """Place the labels for the highlight around ``focus`` (k,) vertices; ``rings``
        are the mesh's (what "near" the focus means).

        ``arrow_halfedges`` are the halfedges drawn now, ``corners`` the arrows' placement
        (``(mesh, halfedges) -> (A, B, third)``): halfedge labels sit beside their arrows.
        """
        choice = self.choice(mesh, windowed)
        near = rings.mark(focus, 1) if len(focus) and "near" in choice.values() else None
        eye = np.array(self.actors.plotter.camera.position)
        positions = mesh.positions
        wanted: list[Wanted] = []

        def chosen(kind: str) -> np.ndarray:
            return self._labelled(mesh, geometry, highlight, kind, choice.get(kind), near, arrow_halfedges)

        def add(kind: str, indices: np.ndarray, anchors: np.ndarray) -> None:
            role_of: dict[int, int] = {}
            for name, members in reversed(highlight.members(kind)):      # the first role wins
                role_of.update((int(i), ROLE_ORDER[name]) for i in members)
            for index, anchor in zip(indices, anchors):
                index = int(index)
                rank = 0 if (kind, index) in highlight.names else 1 if index in role_of else OPTIONAL
                role = role_of.get(index, 0) if rank == 1 else 0
                wanted.append(Wanted(kind, self._text(highlight, kind, index), anchor, rank, index, role))

        vertices = chosen("vertex")
        if len(vertices):
            vertices = vertices[geometry.vertex_in_sight(mesh, eye, vertices)]
            add("vertex", vertices, positions[vertices])
        faces = chosen("face")
        if len(faces):
            centroids = positions[geometry.corners_of(mesh, faces)].mean(axis=1)
            keep = facing(eye, centroids, geometry.face_normals[faces])
            faces, centroids = faces[keep], centroids[keep]
            add("face", faces, centroids + arrows.LIFT * geometry.scale * geometry.face_normals[faces])
        halfedges = chosen("halfedge")
        if len(halfedges):
            A, B, third = corners(mesh, halfedges)
            middle = 0.5 * (A + B)
            points = middle + 0.6 * ((A + B + third) / 3.0 - middle)
            keep = facing(eye, points, np.cross(B - A, third - A))
            add("halfedge", halfedges[keep], points[keep])
        self._show(wanted, self._dots(mesh, geometry, highlight, focus, rings, eye, windowed))

    def _dots(self, mesh, geometry: SceneGeometry, highlight: Highlight, focus: np.ndarray, rings: Rings,
              eye: np.ndarray, windowed: bool) -> np.ndarray:
        """(k, 3) the vertex dots in sight as screen discs ``(x, y, radius)`` in pixels:
        labels keep off them. On a large mesh only the dots near ``focus`` count."""
        live = np.flatnonzero(~mesh.vertex_deleted)
        if windowed:
            live = np.flatnonzero(rings.mark(focus, 2) & ~mesh.vertex_deleted) if len(focus) else live[:0]
        live = live[geometry.vertex_in_sight(mesh, eye, live)]
        radius = np.full(len(live), 0.5 * self.preset.vertex_size)
        highlighted = np.concatenate([m for _, m in highlight.members("vertex")] + [np.zeros(0, np.int64)])
        radius[np.isin(live, highlighted)] = 0.5 * self.preset.highlight_vertex_size
        screen = to_screen(self.actors.plotter, self.window_size, mesh.positions[live])
        return np.column_stack([screen[:, :2], radius])

    def _show(self, wanted: list[Wanted], dots: np.ndarray) -> None:
        import pyvista as pv

        look = self.preset
        plotter = self.actors.plotter
        # Every label sits on a badge drawn from its lower left corner (vtk draws the badge
        # of a centred label in the wrong place): a dark one for vertices, a pale one that
        # keeps face and halfedge labels readable over arrows and edges.
        corner = dict(justification_horizontal="left", justification_vertical="bottom")
        styles = {
            "vertex": dict(text_color="#FFFFFF", shape_color=look.vertex, shape="rounded_rect",
                           font_size=look.label_size, bold=True, **corner),
            "face": dict(text_color=look.text, shape_color="#FFFFFF", shape="rounded_rect", shape_opacity=0.7,
                         font_size=look.label_size, bold=False, italic=True, **corner),
            "halfedge": dict(text_color="#333333", shape_color="#FFFFFF", shape="rounded_rect", shape_opacity=0.7,
                             font_size=max(8, look.label_size - 1), bold=False, **corner),
        }
        wanted = sorted(wanted, key=lambda w: (w.rank, PLACING_ORDER.index(w.kind), w.role, w.index))
        anchors = to_screen(plotter, self.window_size, np.array([w.anchor for w in wanted]).reshape(-1, 3))
        sizes = np.array([text_size(w.text, styles[w.kind]["font_size"], PADDING[w.kind])
                          for w in wanted]).reshape(-1, 2)
        # A vertex label keeps off the biggest dot its vertex may have.
        keep_clear = [0.5 * look.highlight_vertex_size + 1 if w.kind == "vertex" else 0.0 for w in wanted]
        optional = [w.rank == OPTIONAL for w in wanted]
        legends = legend_boxes(plotter, self.window_size)
        listed: list[str] = []
        for _ in range(4):
            # Labels without room are listed along the bottom; that strip is kept clear,
            # which may leave other labels without room: repeat until the list settles.
            obstacles = np.vstack([legends, self._list_box(listed)])
            centres = place(anchors[:, :2], sizes, keep_clear, dots, obstacles, self.window_size, optional)
            now = [w.text for w, centre in zip(wanted, centres) if np.isnan(centre[0]) and w.rank < OPTIONAL]
            if now == listed:
                break
            listed = now
        self.listed = listed
        # What a reader can see: the labels drawn and those listed (not the optional left out).
        seen = [w for w, centre in zip(wanted, centres) if not np.isnan(centre[0]) or w.text in listed]
        self.texts = {kind: [w.text for w in seen if w.kind == kind] for kind in KINDS}
        self._show_list(listed)
        for kind in KINDS:
            name = f"{kind}_labels"
            mine = [i for i, w in enumerate(wanted) if w.kind == kind and not np.isnan(centres[i, 0])]
            if not mine:
                if name in self.actors:
                    self.actors.hide(name)
                continue
            points = centres[mine] - sizes[mine] / 2 + BADGE_POINT   # the badge is drawn from its point
            screen = np.column_stack([points, anchors[mine, 2]])      # at the anchor's depth
            data = pv.PolyData(from_screen(plotter, self.window_size, screen))
            data.point_data["labels"] = np.array([wanted[i].text for i in mine])
            if name in self.actors:
                # The label actor reads this dataset: refill it instead of a new actor.
                self.actors.refill(name, data)
            else:
                self.actors.add_labels(name, data, **styles[kind])

    def _list_box(self, listed: list[str]) -> np.ndarray:
        """(0 or 1, 4) the screen box of the list of labels without room."""
        if not listed:
            return np.zeros((0, 4))
        width, height = text_size(self._list_text(listed), self.preset.label_size, 0.0)
        return np.array([[0.0, 0.0, LIST_MARGIN + width + 2, LIST_MARGIN + height + 2]])

    def _list_text(self, listed: list[str]) -> str:
        return list_text(listed, self.preset.label_size, self.window_size)

    def _show_list(self, listed: list[str]) -> None:
        """Write the labels without room in the picture's lower left corner (or hide that)."""
        plotter = self.actors.plotter
        if not listed:
            if LIST_ACTOR in plotter.actors:
                plotter.actors[LIST_ACTOR].SetVisibility(False)
            return
        actor = plotter.add_text(self._list_text(listed), position=(LIST_MARGIN, LIST_MARGIN),
                                 color=self.preset.text, name=LIST_ACTOR, render=False)
        actor.GetTextProperty().SetFontSize(self.preset.label_size)   # pixels, as the labels
        actor.SetVisibility(True)

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
        """``v3``, or a named element's ``vA (3)`` (a name that is the plain label stays plain)."""
        plain = f"{PREFIX[kind]}{int(index)}"
        name = highlight.names.get((kind, int(index)))
        return plain if name is None or name == plain else f"{name} ({int(index)})"


def overlapping_labels(plotter, window_size=None) -> list[tuple[str, str]]:
    """The problems of the labels ``plotter`` shows, measured with :func:`label_boxes`:
    ``(text, other text)`` for two boxes that overlap, ``(text, "outside the picture")``
    for a box not wholly inside it. Empty when every label can be read."""
    width, height = tuple(window_size or plotter.window_size)
    measured = label_boxes(plotter, (width, height))
    problems = [(text, "outside the picture") for text, box in measured
                if box[0] < 0 or box[1] < 0 or box[2] > width or box[3] > height]
    for i, (text, box) in enumerate(measured):
        others = np.array([b for _, b in measured[i + 1:]]).reshape(-1, 4)
        problems += [(text, measured[i + 1 + j][0]) for j in np.flatnonzero(overlaps(box, others))]
    return problems
