"""Step through one level of Loop subdivision the course's way: positions, split, flip, move.

    from halfedge_edu.viz.loop_stepper import LoopStepper
    w = LoopStepper(hx.sample("octahedron"))
    w                      # step 0: every new position computed from the old mesh
    w.step()               # split the first edge
    w.go("flip")           # to the first flip; also "split", "reposition", "start", "end", 7
    print(w.describe())

The stepper runs :func:`~halfedge_edu.algorithms.loop.loop_subdivide_by_operations` once
and keeps a copy of the mesh after every step, so going back costs nothing and every
picture is the real algorithm's state. The colours say what each element is:

- old vertices and new vertices (the edge points) in two colours;
- edges lying on an old edge (an old edge, or one half of a split one) in dark grey;
- new edges from an old vertex to a new one in vermillion: these are the ones the flip
  phase turns around;
- new edges between two new vertices in green: the sides of the centre triangles;
- the element of the current step in purple, drawn thicker.

At step 0 the new positions are shown too (small dots, and a line from each old vertex
to where it will go); at the last step, a line from where each vertex was to where it
went. The mesh passed in is never changed; ``w.result`` is the subdivided mesh.

Attention: one step and one stored copy per edge and per face: meant for small meshes
(at most ``MAX_EDGES`` edges).
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import numpy as np

from ..algorithms.loop import LoopStep, loop_positions, loop_subdivide_by_operations
from ..algorithms.normals import face_normals
from .painted_scene import Layer, PaintedScene, legend_html
from .palette import BLACK, BLUE, BLUISH_GREEN, ORANGE, REDDISH_PURPLE, VERMILLION, panel_css
from .widgets import StepperWidget

#: The largest mesh (in edges) the stepper accepts: it keeps one copy per step.
MAX_EDGES = 600

OLD_VERTEX, NEW_VERTEX = BLUE, ORANGE
ON_OLD_EDGE, TO_FLIP, BETWEEN_NEW, CURRENT = "#5A5A5A", VERMILLION, BLUISH_GREEN, REDDISH_PURPLE
PHASES = ("positions", "split", "flip", "reposition")


@dataclass(eq=False)
class _Record:
    """One stored step: its phase, its number within the phase, the element and the mesh after it."""

    phase: str
    number: int
    element: int | None
    mesh: object
    ends_before: tuple[int, int] | None = None   # a flipped edge's ends before the flip


class LoopStepper(StepperWidget):
    """Loop subdivision, one split or flip at a time, with old and new elements coloured.

    Args:
        mesh: a small triangle mesh (copied, never changed).
        weights: ``"warren"`` (the course's) or ``"loop"``, as for ``loop_subdivide``.
        mode: ``"live"``, ``"static"`` or None (automatic).
        preset: ``"default"`` or ``"large"`` (a projector).
        window_size: picture size in pixels.
        view_direction: (3,) from the mesh toward the camera (oblique by default).
        vertex_labels: write vertex numbers ("auto": on small meshes).

    Drive it with ``step()``, ``back()`` and ``go(...)``; ``describe()`` says the state in
    words. ``records`` (phase, number, element, mesh) is every step; ``state`` the mesh
    shown now; ``result`` the subdivided mesh, the same as ``loop_subdivide`` gives.

    Keys (mouse pointer over the panel below the buttons): → or space the next split or
    flip, ← one back, PgDn the next phase, Home the start, End the end.
    """

    title = "Loop subdivision: step by step"
    KEYS = {**StepperWidget.KEYS, "PageDown": "phase"}

    def __init__(self, mesh, *, weights: str = "warren", mode: str | None = None, preset="default",
                 window_size=None, view_direction=None, vertex_labels="auto"):
        if mesh.n_edges > MAX_EDGES:
            raise ValueError(f"LoopStepper keeps a copy of the mesh per step and is meant for small meshes "
                             f"(at most {MAX_EDGES} edges); this one has {mesh.n_edges}. "
                             f"Use loop_subdivide for big meshes.")
        before = mesh.copy()
        if before.has_garbage:
            before.garbage_collect()
        self.before = before
        self.weights = weights
        self.n_old_vertices = before.n_vertex_slots
        self.old_edges = before.edge_vertices().copy()                 # (E, 2) ends of the old edges
        self.vertex_points, self.edge_points = loop_positions(before, weights)
        self.records: list[_Record] = [_Record("positions", 0, None, before.copy())]

        def remember(step: LoopStep) -> None:
            element = None if step.element is None else int(step.element.index)
            ends = None
            if step.phase == "flip":
                previous = self.records[-1].mesh
                ends = tuple(int(v) for v in previous.edge_vertices()[element])
            self.records.append(_Record(step.phase, step.number, element, step.mesh.copy(), ends))

        self.after = loop_subdivide_by_operations(before, weights=weights, on_step=remember)
        self._step = 0
        self._view_direction = view_direction
        self._vertex_labels = vertex_labels
        super().__init__(before.copy(), mode=mode, preset=preset, labels=None, rings=0, window_size=window_size)

    # -- public --------------------------------------------------------------------------

    @property
    def n_steps(self) -> int:
        """Steps after step 0: one per split, one per flip, one for the repositioning."""
        return len(self.records) - 1

    @property
    def phase(self) -> str:
        """The current step's phase: "positions", "split", "flip" or "reposition"."""
        return self.records[self._step].phase

    @property
    def state(self):
        """A copy of the mesh as it is at the current step."""
        return self.records[self._step].mesh.copy()

    @property
    def result(self):
        """A copy of the subdivided mesh."""
        return self.after.copy()

    def phase_start(self, phase: str) -> int:
        """The step number of the first step of ``phase``."""
        for k, record in enumerate(self.records):
            if record.phase == phase:
                return k
        raise ValueError(f"unknown phase {phase!r}: use one of {', '.join(PHASES)}")

    _moves_help = f"a step number, a phase ({', '.join(PHASES)})"

    def _named_moves(self) -> dict[str, int]:
        """Also "phase" (the next phase's start) and "phase back"."""
        return {**super()._named_moves(), **self._phase_moves([self.phase_start(p) for p in PHASES])}

    def _resolve(self, target) -> int | None:
        """A phase name ("split", "flip", "reposition") goes to its first step."""
        if isinstance(target, str) and target.strip().lower() in PHASES:
            return self.phase_start(target.strip().lower())
        return None

    def edge_kinds(self, mesh=None) -> dict[str, np.ndarray]:
        """The live edges of ``mesh`` (the current state by default) sorted by kind:
        "old" (an old edge or half of one), "to_flip" (old to new vertex, across a
        triangle) and "between_new" (two new vertices)."""
        mesh = self.records[self._step].mesh if mesh is None else mesh
        live = np.flatnonzero(~mesh.edge_deleted)
        a, b = mesh.edge_vertices()[live].T
        n_old = self.n_old_vertices
        a_old, b_old = a < n_old, b < n_old
        new_end = np.where(a_old, b, a)
        old_end = np.where(a_old, a, b)
        one_old = a_old != b_old
        parent = self.old_edges[np.clip(new_end - n_old, 0, len(self.old_edges) - 1)]    # (k, 2)
        half = one_old & ((parent[:, 0] == old_end) | (parent[:, 1] == old_end))
        return {
            "old": live[(a_old & b_old) | half],
            "to_flip": live[one_old & ~half],
            "between_new": live[~a_old & ~b_old],
        }

    def on_far_side(self, step: int | None = None) -> bool:
        """Whether the element of ``step`` (the current one by default) is out of sight:
        every face around the vertex a split inserted, or beside the edge a flip turned,
        faces away from the camera (exact on a convex mesh such as the octahedron)."""
        record = self.records[self._step if step is None else int(step)]
        mesh = record.mesh
        if record.phase == "split":
            faces = [f.index for f in mesh.vertex(record.element).faces()]
        elif record.phase == "flip":
            faces = [f.index for f in mesh.edge(record.element).faces()]
        else:
            return False
        corners = mesh.positions[mesh.face_vertices()[faces]]               # (k, 3, 3)
        eye = np.asarray(self.scene.plotter.camera.position, dtype=float)
        toward_eye = np.einsum("ij,ij->i", face_normals(mesh)[faces], eye - corners.mean(axis=1))
        return bool((toward_eye <= 0).all())

    def describe(self) -> str:
        """The current step in words (deterministic, for nbval and for reading)."""
        before = self.before
        record = self.records[self._step]
        goal = (f"{before.n_vertices + before.n_edges} vertices, {2 * before.n_edges + 3 * before.n_faces} edges, "
                f"{4 * before.n_faces} faces")
        lines = [f"Loop subdivision ({self.weights} weights) of {self._counts(before)}: "
                 f"step {self._step} of {self.n_steps}, {self._phase_text(record)}",
                 f"now: {self._now_text(record)}",
                 f"mesh: {self._counts(record.mesh)} (after the level: {goal})"]
        return "\n".join(lines)

    # -- text ----------------------------------------------------------------------------

    @staticmethod
    def _counts(mesh) -> str:
        return f"{mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces"

    def _phase_total(self, phase: str) -> int:
        return sum(1 for r in self.records if r.phase == phase)

    def _phase_text(self, record: _Record) -> str:
        if record.phase in ("split", "flip"):
            return f"{record.phase} {record.number + 1} of {self._phase_total(record.phase)}"
        return record.phase

    def _vertex_word(self, v: int) -> str:
        return f"{'old' if v < self.n_old_vertices else 'new'} vertex {v}"

    def _now_text(self, record: _Record) -> str:
        n_old = self.n_old_vertices
        if record.phase == "positions":
            return (f"every new position is computed from the old mesh, before any connectivity changes: "
                    f"{n_old} vertex points (where the old vertices go) and {len(self.old_edges)} edge points "
                    f"(where the new vertices go)")
        if record.phase == "split":
            m = record.element
            a, b = (int(v) for v in self.old_edges[m - n_old])
            mesh = record.mesh
            across = []
            for h in mesh.vertex(m).outgoing():
                tip = h.tip.index
                if tip not in (a, b):
                    fate = "old vertex: to flip" if tip < n_old else "two new vertices: stays"
                    across.append(f"{h.edge.index} ({m} - {tip}, {fate})")
            text = f"split edge {m - n_old} (vertices {a} and {b}) at its midpoint: new vertex {m}"
            return text + ("; new edges across: " + ", ".join(across) if across else "; no new edge across")
        if record.phase == "flip":
            e = record.element
            a, b = record.ends_before
            c, d = (int(v) for v in record.mesh.edge_vertices()[e])
            return (f"flip edge {e}: it joined {self._vertex_word(a)} and {self._vertex_word(b)}; "
                    f"now it joins {self._vertex_word(c)} and {self._vertex_word(d)}")
        moved = self._displacements()
        return (f"move every vertex to its computed position: the old vertices moved by up to "
                f"{moved[:n_old].max():.4g}, the edge points by up to {moved[n_old:].max():.4g} from the midpoints")

    def _displacements(self) -> np.ndarray:
        """How far each vertex moved in the repositioning (the last step)."""
        previous, last = self.records[-2].mesh, self.records[-1].mesh
        return np.linalg.norm(last.positions - previous.positions, axis=1)

    # -- the picture ---------------------------------------------------------------------

    def _make_scene(self, mesh, **options) -> PaintedScene:
        return PaintedScene(mesh, preset=self.look, plotter=options["plotter"], window_size=options["window_size"],
                            view_direction=self._view_direction, vertex_labels=self._vertex_labels)

    def _layers(self) -> list[Layer]:
        record = self.records[self._step]
        mesh = record.mesh
        kinds = self.edge_kinds(mesh)
        n_old = self.n_old_vertices
        live = np.flatnonzero(~mesh.vertex_deleted)
        layers = [
            Layer("old edge (or half of one)", ON_OLD_EDGE, "edges", kinds["old"], 2.0),
            Layer("new edge, old to new vertex: to flip", TO_FLIP, "edges", kinds["to_flip"], 3.0),
            Layer("new edge between new vertices", BETWEEN_NEW, "edges", kinds["between_new"], 3.0),
        ]
        if record.phase == "positions":
            layers += [
                Layer("where each old vertex goes", BLACK, "segments",
                      np.stack([mesh.positions[:n_old], self.vertex_points], axis=1), 1.5),
                Layer("edge point (computed, not yet inserted)", NEW_VERTEX, "points", self.edge_points, 7.0),
            ]
        if record.phase == "reposition":
            previous = self.records[self._step - 1].mesh
            layers.append(Layer("how far each vertex moved", BLACK, "segments",
                                np.stack([previous.positions, mesh.positions], axis=1), 1.5))
        if record.phase == "flip":
            layers.append(Layer("flipped now", CURRENT, "edges", [record.element], 6.0))
        layers += [
            Layer("old vertex", OLD_VERTEX, "vertices", live[live < n_old]),
            Layer("new vertex (edge point)", NEW_VERTEX, "vertices", live[live >= n_old]),
        ]
        if record.phase == "split":
            layers.append(Layer("inserted now", CURRENT, "vertices", [record.element], 18.0))
        return layers

    def step_vertices(self, step: int | None = None) -> list[int]:
        """The vertices step ``step`` (the one shown, by default) is about, whose numbers
        are always written: the one a split inserts, the ends of the edge a flip turns."""
        record = self.records[self._step if step is None else step]
        if record.phase == "split":
            return [int(record.element)]
        if record.phase == "flip":
            return [int(v) for v in record.mesh.edge_vertices()[record.element]]
        return []

    def _show(self) -> None:
        # At step 0 the surface is see-through: on a convex shape the new points lie inside.
        opacity = 0.45 if self.phase == "positions" else 1.0
        self.scene.paint(self.records[self._step].mesh, layers=self._layers(), surface_opacity=opacity,
                         keep_labels=self.step_vertices())

    # -- panel ---------------------------------------------------------------------------

    def _controls(self) -> list:
        return self._button_row([
            ("start", "step 0: the new positions, computed first", lambda: self.go("start")),
            ("back", "one step back", self.back),
            ("step", "the next split or flip", self.step),
            ("phase", "to the start of the next phase", lambda: self.go("phase")),
            ("end", "the subdivided mesh", lambda: self.go("end")),
        ])

    def _panel_html(self) -> str:
        size = panel_css(self.look)["font"]
        record = self.records[self._step]
        before, mesh = self.before, record.mesh
        rows = [("vertices", before.n_vertices, mesh.n_vertices, f"V + E = {before.n_vertices + before.n_edges}"),
                ("edges", before.n_edges, mesh.n_edges, f"2E + 3F = {2 * before.n_edges + 3 * before.n_faces}"),
                ("faces", before.n_faces, mesh.n_faces, f"4F = {4 * before.n_faces}")]
        cell = "padding:2px 8px;border-bottom:1px solid #ddd;text-align:left;white-space:nowrap"
        table = "".join(f'<tr><td style="{cell}">{name}</td><td style="{cell}">{old}</td>'
                        f'<td style="{cell}"><b>{now}</b></td><td style="{cell}">{goal}</td></tr>'
                        for name, old, now, goal in rows)
        header = "".join(f'<th style="{cell}">{h}</th>' for h in ("", "before", "now", "after the level"))
        return (f'<div style="font-size:{size};margin:4px 0">step <b>{self._step}</b> of {self.n_steps}: '
                f"<i>{html.escape(self._phase_text(record))}</i></div>"
                f'<div style="font-size:{size};max-width:34em;margin-bottom:6px">'
                f"{html.escape(self._now_text(record))}</div>"
                f"{self._far_side_html(size, record.phase)}"
                f'<table style="border-collapse:collapse;font-size:{size}">{header}{table}</table>')

    def _far_side_html(self, size: str, phase: str) -> str:
        """A line saying the step happened out of sight (empty when it is in sight)."""
        if not self.on_far_side():
            return ""
        turn = "drag the view round to see it" if self.mode == "live" else "out of sight in this picture"
        return (f'<div style="font-size:{size};margin-bottom:6px;color:{CURRENT}"><b>this {phase} is on the '
                f"far side of the mesh</b>: {turn}</div>")

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = legend_html(self.scene.legend_entries(), self.look)
