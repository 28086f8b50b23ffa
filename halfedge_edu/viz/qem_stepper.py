"""Step through quadric error simplification: the queue, the costs, one collapse at a time.

    from halfedge_edu.viz.qem_stepper import QEMStepper
    w = QEMStepper(mesh, target_faces=100)
    w                   # step 0: every edge priced, coloured by its cost; the queue's head
    w.step()            # one collapse: the cheapest edge that may be collapsed
    w.jump(50)          # fifty collapses at once; w.go(k), w.go("end"), w.back()
    print(w.describe())

The stepper runs the course's algorithm,
:func:`~halfedge_edu.algorithms.simplify_queue.simplify_sequential`, once, and keeps its
step records (:class:`~halfedge_edu.algorithms.simplify_queue.CollapseStep`: the edge,
the two vertices, the cost, the point, the cheapest entries left in the queue). The
mesh at step ``k`` is rebuilt by replaying the first ``k`` collapses on a copy (with a
stored copy every ``checkpoint_every`` steps, so jumping back is quick), and the vertex
quadrics are replayed with it (``Q_kept = Q_a + Q_b``). So every picture is the real
algorithm's state.

The picture colours every edge by the cost of collapsing it now (``log10`` of
``[x, 1] Q [x, 1]^T`` at the edge's best point ``x``). The colour bar runs from the
first collapse's cost to the last one's, so an edge in the brightest colour will not be
collapsed before the target is reached. On top: the edge the queue pops next
(vermillion), the next few queued ones (purple), and the vertex of the last collapse
with the edges around it that were re-priced and pushed again (black).
"""

from __future__ import annotations

import html

import numpy as np

from ..algorithms.simplify import optimal_points, quadric_cost
from ..algorithms.simplify_queue import CollapseStep, QuadricQueue, simplify_sequential, turns_a_face
from .painted_scene import Layer, PaintedScene, legend_html
from .palette import BLACK, REDDISH_PURPLE, VERMILLION, panel_css
from .widgets import StepperWidget

NEXT_EDGE, QUEUED, LAST_COLLAPSE = VERMILLION, REDDISH_PURPLE, BLACK


def edge_costs(mesh, quadrics: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The queue's price of every edge, for all edges at once.

    The same rule as :meth:`QuadricQueue.price`: the best point of ``Q_a + Q_b`` (the
    3x3 solve, pulled towards the midpoint where the planes leave it undecided: see
    :func:`~halfedge_edu.algorithms.simplify.optimal_points`), except that an interior
    edge with exactly one end on the boundary collapses onto that end.

    Returns:
        ``(costs (n_edge_slots,), points (n_edge_slots, 3))``; NaN for deleted edges.
    """
    live = np.flatnonzero(~mesh.edge_deleted)                               # (k,)
    a, b = mesh.edge_vertices()[live].T
    quadric = quadrics[a] + quadrics[b]                                     # (k, 4, 4)
    pa, pb = mesh.positions[a], mesh.positions[b]
    points, cost = optimal_points(quadric, pa, pb)
    face = mesh.halfedge_face
    interior = (face[2 * live] >= 0) & (face[2 * live + 1] >= 0)
    on_boundary = mesh.vertex_is_boundary()
    onto_a = interior & on_boundary[a] & ~on_boundary[b]
    onto_b = interior & on_boundary[b] & ~on_boundary[a]
    points[onto_a], points[onto_b] = pa[onto_a], pb[onto_b]
    fixed = onto_a | onto_b
    if fixed.any():
        cost[fixed] = np.maximum(quadric_cost(quadric[fixed], points[fixed]), 0.0)
    all_costs = np.full(mesh.n_edge_slots, np.nan)
    all_points = np.full((mesh.n_edge_slots, 3), np.nan)
    all_costs[live], all_points[live] = cost, points
    return all_costs, all_points


class QEMStepper(StepperWidget):
    """Quadric error simplification, collapse by collapse, then in jumps.

    Args:
        mesh: the mesh to simplify (copied, never changed).
        target_faces: where to stop, in faces (as for ``simplify_sequential``).
        max_normal_angle: the largest swing of a face normal a collapse may cause.
        mode: ``"live"``, ``"static"`` or None (automatic).
        preset: ``"default"`` or ``"large"`` (a projector).
        window_size: picture size in pixels.
        view_direction: (3,) from the mesh toward the camera.
        checkpoint_every: keep a copy of the mesh every this many steps.

    ``steps`` holds the :class:`CollapseStep` records; ``step()``, ``back()``,
    ``jump(n)`` and ``go(k | "start" | "end")`` move; ``state`` is the mesh now,
    ``costs`` the heat-map's numbers, ``result`` the simplified mesh.

    Keys (mouse pointer over the panel below the buttons): → or space one collapse,
    ← one back, PgDn ten collapses, ``+`` a hundred, Home the start, End the end.
    """

    title = "Quadric error simplification: the queue"
    KEYS = {**StepperWidget.KEYS, "PageDown": "+10", "+": "+100"}

    def __init__(self, mesh, target_faces: int, *, max_normal_angle: float = 80.0, mode: str | None = None,
                 preset="default", window_size=None, view_direction=None, checkpoint_every: int = 64):
        before = mesh.copy()
        if before.has_garbage:
            before.garbage_collect()
        self.before = before
        self.target_faces = int(target_faces)
        self.max_normal_angle = float(max_normal_angle)
        start = QuadricQueue(before.copy())
        self.initial_quadrics = start.quadrics.copy()
        self.initial_candidates = start.peek(5)
        self.steps: list[CollapseStep] = []
        self.after = simplify_sequential(before, self.target_faces, max_normal_angle=max_normal_angle,
                                         on_step=self.steps.append)
        self.checkpoint_every = max(1, int(checkpoint_every))
        self._checkpoints: dict[int, tuple[object, np.ndarray]] = {0: (before.copy(), self.initial_quadrics.copy())}
        self._step = 0
        self._view_direction = view_direction
        self._state, self._quadrics = self._replayed(0)
        self.costs = edge_costs(self._state, self._quadrics)[0]
        super().__init__(before.copy(), mode=mode, preset=preset, labels=None, rings=0, window_size=window_size)

    # -- public --------------------------------------------------------------------------

    @property
    def n_steps(self) -> int:
        """How many collapses the run made."""
        return len(self.steps)

    @property
    def state(self):
        """A copy of the mesh after the first ``step_index`` collapses (not compacted)."""
        return self._state.copy()

    @property
    def quadrics(self) -> np.ndarray:
        """(n_vertex_slots, 4, 4) the vertex quadrics now (a copy)."""
        return self._quadrics.copy()

    @property
    def result(self):
        """A copy of the simplified mesh (compacted, as ``simplify_sequential`` returns it)."""
        return self.after.copy()

    @property
    def candidates(self) -> list[tuple[float, int]]:
        """The cheapest ``(cost, edge)`` entries in the queue now (at most five)."""
        if self._step == 0:
            return list(self.initial_candidates)
        return list(self.steps[self._step - 1].next_candidates)

    def _show_step(self, step: int) -> None:
        """Replay the first ``step`` collapses and re-price the edges."""
        self._state, self._quadrics = self._replayed(step)
        self.costs = edge_costs(self._state, self._quadrics)[0]

    def jump(self, collapses: int) -> int:
        """Move ``collapses`` steps at once (negative: back), stopping at either end."""
        return self.go(min(max(self._step + int(collapses), 0), self.n_steps))

    def skipped_steps(self) -> list[int]:
        """The steps at which the queue's cheapest entry is skipped, not collapsed.

        At step ``k`` (``k`` collapses done) the head of the queue is the first of
        :attr:`candidates`; where the collapse that follows is another edge, the head was
        refused. ``go(k)`` and then ``describe()`` say why.
        """
        heads = [self.initial_candidates] + [step.next_candidates for step in self.steps[:-1]]
        return [k for k, (queued, step) in enumerate(zip(heads, self.steps))
                if queued and queued[0][1] != step.edge]

    def refusal(self, edge: int) -> str | None:
        """Why the queue would skip ``edge`` now, or None if it may be collapsed."""
        mesh = self._state
        check = mesh.can_collapse(edge)
        if not check:
            return f"not allowed: {check.reason}"
        point = edge_costs(mesh, self._quadrics)[1][edge]
        if turns_a_face(mesh, edge, point, float(np.cos(np.radians(self.max_normal_angle)))):
            return f"refused: a face would turn over (its normal would swing by more than {self.max_normal_angle:g} degrees)"
        return None

    def describe(self) -> str:
        """The state in words: the last collapse, the queue's head, what comes next."""
        mesh, k = self._state, self._step
        lines = [f"QEM simplification of {self.before.n_faces} faces to {self.target_faces}: "
                 f"step {k} of {self.n_steps}, {mesh.n_faces} faces"]
        if k == 0:
            lines.append(f"start: {self.before.n_faces} face quadrics summed into {self.before.n_vertices} vertices; "
                         f"{self.before.n_edges} edges priced and queued")
        else:
            last = self.steps[k - 1]
            lines.append(f"last: {last.describe()}")
            ring = self._ring_edges(last.kept)
            lines.append(f"re-priced and pushed again: the {len(ring)} edges around vertex {last.kept}")
        lines.append("queue, cheapest first: " + ", ".join(f"edge {e} ({cost:.3g})" for cost, e in self.candidates))
        lines += self._upcoming()
        return "\n".join(lines)

    # -- replay --------------------------------------------------------------------------

    def _replayed(self, k: int):
        """(mesh, quadrics) after the first ``k`` collapses, from the nearest checkpoint."""
        base = max(step for step in self._checkpoints if step <= k)
        mesh, quadrics = (thing.copy() for thing in self._checkpoints[base])
        for number in range(base, k):
            record = self.steps[number]
            merged = quadrics[record.kept] + quadrics[record.removed]
            kept = mesh.collapse(record.edge, record.position).index
            if kept != record.kept:
                raise RuntimeError(f"replaying collapse {record.number} kept vertex {kept}, the run kept {record.kept}")
            quadrics[kept] = merged
            if (number + 1) % self.checkpoint_every == 0 and number + 1 not in self._checkpoints:
                self._checkpoints[number + 1] = (mesh.copy(), quadrics.copy())
        return mesh, quadrics

    def _ring_edges(self, v: int) -> list[int]:
        return [h.edge.index for h in self._state.vertex(v).outgoing()]

    def _upcoming(self) -> list[str]:
        """What the queue does next: skipped entries with their reason, then the collapse."""
        if self._step == self.n_steps:
            return [f"done: {self._state.n_faces} faces (target {self.target_faces})"]
        coming = self.steps[self._step]
        lines = []
        for _, e in self.candidates:
            if e == coming.edge:
                break
            lines.append(f"skip: edge {e}, {self.refusal(e) or 'refused'}")
        lines.append(f"next: edge {coming.edge} (vertex {coming.removed} into {coming.kept}, cost {coming.cost:.3g})")
        return lines

    # -- the picture ---------------------------------------------------------------------

    def _make_scene(self, mesh, **options) -> PaintedScene:
        return PaintedScene(mesh, preset=self.look, plotter=options["plotter"], window_size=options["window_size"],
                            view_direction=self._view_direction, vertex_labels=False)

    def _value_range(self) -> tuple[float, float]:
        """log10 of the first and the last collapse's cost (a little apart if they agree)."""
        costs = np.array([s.cost for s in self.steps] or [1.0])
        positive = costs[costs > 0]
        floor = positive.min() if len(positive) else 1e-12
        low = np.log10(max(costs[0], floor))
        high = np.log10(max(costs.max(), floor))
        return (float(low), float(max(high, low + 1.0)))

    def _show(self) -> None:
        low, high = self._value_range()
        values = np.log10(np.maximum(self.costs, 10.0 ** low))
        layers = []
        if self._step:
            last = self.steps[self._step - 1]
            layers += [Layer("re-priced after the last collapse", LAST_COLLAPSE, "edges",
                             self._ring_edges(last.kept), 3.5),
                       Layer("vertex of the last collapse", LAST_COLLAPSE, "vertices", [last.kept], 14.0)]
        queued = [e for _, e in self.candidates]
        if self._step < self.n_steps:
            coming = self.steps[self._step].edge
            layers.append(Layer("queued next", QUEUED, "edges", [e for e in queued if e != coming], 4.5))
            layers.append(Layer("collapsed next", NEXT_EDGE, "edges", [coming], 6.0))
        self.scene.paint(self._state, layers=layers, edge_values=values, value_label="log10 cost",
                         value_range=(low, high))

    # -- panel ---------------------------------------------------------------------------

    def _controls(self) -> list:
        return self._button_row([
            ("start", "no collapse yet: every edge priced", lambda: self.go("start")),
            ("back", "one collapse back", self.back),
            ("step", "one collapse", self.step),
            ("+10", "ten collapses", lambda: self.jump(10)),
            ("+100", "a hundred collapses", lambda: self.jump(100)),
            ("end", "down to the target", lambda: self.go("end")),
        ])

    def _panel_html(self) -> str:
        size = panel_css(self.look)["font"]
        cell = "padding:2px 8px;border-bottom:1px solid #ddd;text-align:left;white-space:nowrap"
        coming = self.steps[self._step].edge if self._step < self.n_steps else None
        rows, seen_next = [], coming is None
        for rank, (cost, e) in enumerate(self.candidates, start=1):
            if e == coming:
                fate, color, seen_next = "collapsed next", NEXT_EDGE, True
            else:
                fate, color = ("queued" if seen_next else "skipped: may not collapse"), QUEUED
            rows.append(f'<tr><td style="{cell};border-left:6px solid {color}">{rank}</td>'
                        f'<td style="{cell}">edge {e}</td><td style="{cell}">{cost:.3g}</td>'
                        f'<td style="{cell}">{fate}</td></tr>')
        header = "".join(f'<th style="{cell}">{h}</th>' for h in ("", "queue", "cost", ""))
        table = f'<table style="border-collapse:collapse;font-size:{size};font-family:monospace">{header}{"".join(rows)}</table>'
        text = "<br>".join(html.escape(line) for line in self.describe().splitlines()[1:])
        return (f'<div style="font-size:{size};margin:4px 0">step <b>{self._step}</b> of {self.n_steps}: '
                f"<b>{self._state.n_faces}</b> faces (target {self.target_faces})</div>{table}"
                f'<div style="font-size:{size};max-width:36em;margin-top:6px">{text}</div>')

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = legend_html(self.scene.legend_entries(), self.look)
