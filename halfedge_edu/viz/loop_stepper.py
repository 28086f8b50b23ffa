"""Step through one level of Loop subdivision the course's way: positions, split, flip, move.

    from halfedge_edu.viz.loop_stepper import LoopStepper
    w = LoopStepper(hx.sample("octahedron"))
    w                      # step 0: every new position computed from the old mesh
    w.step()               # split the first edge
    w.go("flip")           # to the first flip; also "split", "reposition", "start", "end", 7
    print(w.describe())

:class:`LoopSteps` runs :func:`~halfedge_edu.algorithms.loop.loop_subdivide_by_operations`
once and keeps each :class:`~halfedge_edu.algorithms.loop.LoopStep` with a copy of the mesh
after it, so going back costs nothing and every picture is the real algorithm's state.
:class:`LoopPainter` colours what each element is:

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
from .steps import Stepper, phase_moves

#: The largest mesh (in edges) the stepper accepts: it keeps one copy per step.
MAX_EDGES = 600

OLD_VERTEX, NEW_VERTEX = BLUE, ORANGE
ON_OLD_EDGE, TO_FLIP, BETWEEN_NEW, CURRENT = "#5A5A5A", VERMILLION, BLUISH_GREEN, REDDISH_PURPLE
PHASES = ("positions", "split", "flip", "reposition")


@dataclass(eq=False)
class LoopRecord:
    """One stored step: its phase, its number within the phase, the element and the mesh after it."""

    phase: str
    number: int
    element: int | None
    mesh: object
    ends_before: tuple[int, int] | None = None   # a flipped edge's ends before the flip


def _counts(mesh) -> str:
    return f"{mesh.n_vertices} vertices, {mesh.n_edges} edges, {mesh.n_faces} faces"


class LoopSteps:
    """The :class:`~.steps.Steps` of one level of Loop subdivision: step 0 the new
    positions, then one step per split, one per flip, one for the repositioning.

    ``records`` holds a :class:`LoopRecord` (phase, number, element, mesh) per step;
    ``vertex_points`` and ``edge_points`` the positions computed first; ``old_edges``
    (E, 2) the ends of the old edges.
    """

    def __init__(self, mesh, weights: str = "warren"):
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
        self.records: list[LoopRecord] = [LoopRecord("positions", 0, None, before.copy())]

        def remember(step: LoopStep) -> None:
            element = None if step.element is None else int(step.element.index)
            ends = None
            if step.phase == "flip":
                previous = self.records[-1].mesh
                ends = tuple(int(v) for v in previous.edge_vertices()[element])
            self.records.append(LoopRecord(step.phase, step.number, element, step.mesh.copy(), ends))

        self.after = loop_subdivide_by_operations(before, weights=weights, on_step=remember)

    @property
    def n_steps(self) -> int:
        return len(self.records) - 1

    def mesh(self, k: int):
        return self.records[k].mesh

    @property
    def result(self):
        return self.after.copy()

    def phase_start(self, phase: str) -> int:
        """The step number of the first step of ``phase``."""
        for k, record in enumerate(self.records):
            if record.phase == phase:
                return k
        raise ValueError(f"unknown phase {phase!r}: use one of {', '.join(PHASES)}")

    def moves(self, k: int) -> dict[str, int]:
        return phase_moves([self.phase_start(p) for p in PHASES], k, self.n_steps)

    def resolve(self, target, k: int) -> int | None:
        """A phase name ("split", "flip", "reposition") goes to its first step."""
        if isinstance(target, str) and target.strip().lower() in PHASES:
            return self.phase_start(target.strip().lower())
        return None

    def edge_kinds(self, mesh) -> dict[str, np.ndarray]:
        """The live edges of ``mesh`` by kind: "old", "to_flip", "between_new" (see :class:`LoopStepper`)."""
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

    def step_vertices(self, k: int) -> list[int]:
        """The vertices step ``k`` is about: the one a split inserts, the ends of the edge a flip turns."""
        record = self.records[k]
        if record.phase == "split":
            return [int(record.element)]
        if record.phase == "flip":
            return [int(v) for v in record.mesh.edge_vertices()[record.element]]
        return []

    def displacements(self) -> np.ndarray:
        """How far each vertex moved in the repositioning (the last step)."""
        previous, last = self.records[-2].mesh, self.records[-1].mesh
        return np.linalg.norm(last.positions - previous.positions, axis=1)


class LoopPainter:
    """How a step of Loop subdivision looks (a :class:`~.steps.Painter`)."""

    title = "Loop subdivision: step by step"
    keys = {"PageDown": "phase"}
    buttons = (("start", "step 0: the new positions, computed first", "start"),
               ("back", "one step back", "back"),
               ("step", "the next split or flip", "step"),
               ("phase", "to the start of the next phase", "phase"),
               ("end", "the subdivided mesh", "end"))
    moves_help = f"a step number, a phase ({', '.join(PHASES)})"

    def __init__(self, steps: LoopSteps, *, view_direction=None, vertex_labels="auto"):
        self.steps = steps
        self.view_direction = view_direction
        self.vertex_labels = vertex_labels

    def make_scene(self, mesh, look, **options) -> PaintedScene:
        return PaintedScene(mesh, preset=look, plotter=options["plotter"], window_size=options["window_size"],
                            view_direction=self.view_direction, vertex_labels=self.vertex_labels)

    def layers(self, k: int) -> list[Layer]:
        steps = self.steps
        record = steps.records[k]
        mesh = record.mesh
        kinds = steps.edge_kinds(mesh)
        n_old = steps.n_old_vertices
        live = np.flatnonzero(~mesh.vertex_deleted)
        layers = [
            Layer("old edge (or half of one)", ON_OLD_EDGE, "edges", kinds["old"], 2.0),
            Layer("new edge, old to new vertex: to flip", TO_FLIP, "edges", kinds["to_flip"], 3.0),
            Layer("new edge between new vertices", BETWEEN_NEW, "edges", kinds["between_new"], 3.0),
        ]
        if record.phase == "positions":
            layers += [
                Layer("where each old vertex goes", BLACK, "segments",
                      np.stack([mesh.positions[:n_old], steps.vertex_points], axis=1), 1.5),
                Layer("edge point (computed, not yet inserted)", NEW_VERTEX, "points", steps.edge_points, 7.0),
            ]
        if record.phase == "reposition":
            previous = steps.records[k - 1].mesh
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

    def paint(self, scene, k: int) -> None:
        # At step 0 the surface is see-through: on a convex shape the new points lie inside.
        record = self.steps.records[k]
        opacity = 0.45 if record.phase == "positions" else 1.0
        scene.paint(record.mesh, layers=self.layers(k), surface_opacity=opacity,
                    keep_labels=self.steps.step_vertices(k))

    def legend_html(self, scene, look) -> str:
        return legend_html(scene.legend_entries(), look)

    def on_far_side(self, scene, k: int) -> bool:
        """Whether the element of step ``k`` faces away from ``scene``'s camera (see
        :meth:`LoopStepper.on_far_side`)."""
        record = self.steps.records[k]
        mesh = record.mesh
        if record.phase == "split":
            faces = [f.index for f in mesh.vertex(record.element).faces()]
        elif record.phase == "flip":
            faces = [f.index for f in mesh.edge(record.element).faces()]
        else:
            return False
        corners = mesh.positions[mesh.face_vertices()[faces]]               # (k, 3, 3)
        eye = np.asarray(scene.plotter.camera.position, dtype=float)
        toward_eye = np.einsum("ij,ij->i", face_normals(mesh)[faces], eye - corners.mean(axis=1))
        return bool((toward_eye <= 0).all())

    # -- text ----------------------------------------------------------------------------

    def phase_text(self, record: LoopRecord) -> str:
        if record.phase in ("split", "flip"):
            total = sum(1 for r in self.steps.records if r.phase == record.phase)
            return f"{record.phase} {record.number + 1} of {total}"
        return record.phase

    def _vertex_word(self, v: int) -> str:
        return f"{'old' if v < self.steps.n_old_vertices else 'new'} vertex {v}"

    def now_text(self, record: LoopRecord) -> str:
        steps = self.steps
        n_old = steps.n_old_vertices
        if record.phase == "positions":
            return (f"every new position is computed from the old mesh, before any connectivity changes: "
                    f"{n_old} vertex points (where the old vertices go) and {len(steps.old_edges)} edge points "
                    f"(where the new vertices go)")
        if record.phase == "split":
            m = record.element
            a, b = (int(v) for v in steps.old_edges[m - n_old])
            across = []
            for h in record.mesh.vertex(m).outgoing():
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
        moved = steps.displacements()
        return (f"move every vertex to its computed position: the old vertices moved by up to "
                f"{moved[:n_old].max():.4g}, the edge points by up to {moved[n_old:].max():.4g} from the midpoints")

    def describe(self, k: int) -> str:
        before = self.steps.before
        record = self.steps.records[k]
        goal = (f"{before.n_vertices + before.n_edges} vertices, {2 * before.n_edges + 3 * before.n_faces} edges, "
                f"{4 * before.n_faces} faces")
        return "\n".join([f"Loop subdivision ({self.steps.weights} weights) of {_counts(before)}: "
                          f"step {k} of {self.steps.n_steps}, {self.phase_text(record)}",
                          f"now: {self.now_text(record)}",
                          f"mesh: {_counts(record.mesh)} (after the level: {goal})"])

    def panel_html(self, stepper) -> str:
        size = panel_css(stepper.look)["font"]
        k = stepper.step_index
        record = self.steps.records[k]
        before, mesh = self.steps.before, record.mesh
        rows = [("vertices", before.n_vertices, mesh.n_vertices, f"V + E = {before.n_vertices + before.n_edges}"),
                ("edges", before.n_edges, mesh.n_edges, f"2E + 3F = {2 * before.n_edges + 3 * before.n_faces}"),
                ("faces", before.n_faces, mesh.n_faces, f"4F = {4 * before.n_faces}")]
        cell = "padding:2px 8px;border-bottom:1px solid #ddd;text-align:left;white-space:nowrap"
        table = "".join(f'<tr><td style="{cell}">{name}</td><td style="{cell}">{old}</td>'
                        f'<td style="{cell}"><b>{now}</b></td><td style="{cell}">{goal}</td></tr>'
                        for name, old, now, goal in rows)
        header = "".join(f'<th style="{cell}">{h}</th>' for h in ("", "before", "now", "after the level"))
        far_side = ""
        if self.on_far_side(stepper.scene, k):
            turn = "drag the view round to see it" if stepper.mode == "live" else "out of sight in this picture"
            far_side = (f'<div style="font-size:{size};margin-bottom:6px;color:{CURRENT}"><b>this {record.phase} is '
                        f"on the far side of the mesh</b>: {turn}</div>")
        return (f'<div style="font-size:{size};margin:4px 0">step <b>{k}</b> of {self.steps.n_steps}: '
                f"<i>{html.escape(self.phase_text(record))}</i></div>"
                f'<div style="font-size:{size};max-width:34em;margin-bottom:6px">'
                f"{html.escape(self.now_text(record))}</div>"
                f"{far_side}"
                f'<table style="border-collapse:collapse;font-size:{size}">{header}{table}</table>')


class LoopStepper(Stepper):
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

    def __init__(self, mesh, *, weights: str = "warren", mode: str | None = None, preset="default",
                 window_size=None, view_direction=None, vertex_labels="auto"):
        steps = LoopSteps(mesh, weights)
        super().__init__(steps, LoopPainter(steps, view_direction=view_direction, vertex_labels=vertex_labels),
                         mode=mode, preset=preset, window_size=window_size)

    @property
    def before(self):
        """The input (compacted)."""
        return self.source.before

    @property
    def after(self):
        """The subdivided mesh (the steps' own: take a copy to change it, or use ``result``)."""
        return self.source.after

    @property
    def records(self) -> list[LoopRecord]:
        """Every step: phase, number within the phase, element, mesh after it."""
        return self.source.records

    @property
    def weights(self) -> str:
        return self.source.weights

    @property
    def n_old_vertices(self) -> int:
        return self.source.n_old_vertices

    @property
    def old_edges(self) -> np.ndarray:
        return self.source.old_edges

    @property
    def vertex_points(self) -> np.ndarray:
        return self.source.vertex_points

    @property
    def edge_points(self) -> np.ndarray:
        return self.source.edge_points

    @property
    def phase(self) -> str:
        """The current step's phase: "positions", "split", "flip" or "reposition"."""
        return self.source.records[self._step].phase

    def phase_start(self, phase: str) -> int:
        """The step number of the first step of ``phase``."""
        return self.source.phase_start(phase)

    def edge_kinds(self, mesh=None) -> dict[str, np.ndarray]:
        """The live edges of ``mesh`` (the current state by default) sorted by kind:
        "old" (an old edge or half of one), "to_flip" (old to new vertex, across a
        triangle) and "between_new" (two new vertices)."""
        return self.source.edge_kinds(self.source.mesh(self._step) if mesh is None else mesh)

    def step_vertices(self, step: int | None = None) -> list[int]:
        """The vertices step ``step`` (the one shown, by default) is about, whose numbers
        are always written: the one a split inserts, the ends of the edge a flip turns."""
        return self.source.step_vertices(self._step if step is None else int(step))

    def on_far_side(self, step: int | None = None) -> bool:
        """Whether the element of ``step`` (the current one by default) is out of sight:
        every face around the vertex a split inserted, or beside the edge a flip turned,
        faces away from the camera (exact on a convex mesh such as the octahedron)."""
        return self.painter.on_far_side(self.scene, self._step if step is None else int(step))
