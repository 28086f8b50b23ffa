"""Step through quadric error simplification: the queue, the costs, one collapse at a time.

    from halfedge_edu.viz.qem_stepper import QEMStepper
    w = QEMStepper(mesh, target_faces=100)
    w                   # step 0: every edge priced, coloured by its cost; the queue's head
    w.step()            # one collapse: the cheapest edge that may be collapsed
    w.jump(50)          # fifty collapses at once; w.go(k), w.go("end"), w.back()
    print(w.describe())

:class:`QEMSteps` runs the course's algorithm,
:func:`~halfedge_edu.algorithms.simplify_queue.simplify_sequential`, once, and keeps its
step records (:class:`~halfedge_edu.algorithms.simplify_queue.CollapseStep`: the edge,
the two vertices, the cost, the point, the cheapest entries left in the queue). The
mesh at step ``k`` is rebuilt by replaying the first ``k`` collapses on a copy (with a
stored copy every ``checkpoint_every`` steps, so jumping back is quick), and the vertex
quadrics are replayed with it (``Q_kept = Q_a + Q_b``). So every picture is the real
algorithm's state. :class:`QEMPainter` draws a step.

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
from .steps import Stepper

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


class QEMSteps:
    """The :class:`~.steps.Steps` of a QEM simplification: step ``k`` is the mesh after
    the first ``k`` collapses, with the vertex quadrics of that moment.

    ``records`` holds the :class:`CollapseStep` s; ``initial_quadrics`` and
    ``initial_candidates`` the queue before the first collapse.
    """

    def __init__(self, mesh, target_faces: int, *, max_normal_angle: float = 80.0, checkpoint_every: int = 64):
        before = mesh.copy()
        if before.has_garbage:
            before.garbage_collect()
        self.before = before
        self.target_faces = int(target_faces)
        self.max_normal_angle = float(max_normal_angle)
        start = QuadricQueue(before.copy())
        self.initial_quadrics = start.quadrics.copy()
        self.initial_candidates = start.peek(5)
        self.records: list[CollapseStep] = []
        self.after = simplify_sequential(before, self.target_faces, max_normal_angle=max_normal_angle,
                                         on_step=self.records.append)
        self.checkpoint_every = max(1, int(checkpoint_every))
        self._checkpoints: dict[int, tuple[object, np.ndarray]] = {0: (before.copy(), self.initial_quadrics.copy())}
        self._shown = (0, *self._replayed(0))
        self._costs = (0, edge_costs(self._shown[1], self._shown[2])[0])

    @property
    def n_steps(self) -> int:
        return len(self.records)

    def at(self, k: int):
        """``(mesh, quadrics)`` after the first ``k`` collapses (the last asked for is kept)."""
        if self._shown[0] != k:
            self._shown = (k, *self._replayed(k))
        return self._shown[1], self._shown[2]

    def mesh(self, k: int):
        return self.at(k)[0]

    def costs(self, k: int) -> np.ndarray:
        """(n_edge_slots,) the queue's price of every edge after ``k`` collapses (NaN: deleted)."""
        if self._costs[0] != k:
            self._costs = (k, edge_costs(*self.at(k))[0])
        return self._costs[1]

    @property
    def result(self):
        return self.after.copy()

    def moves(self, k: int) -> dict[str, int]:
        """"+10" and "+100": that many collapses on (at most to the end)."""
        return {"+10": min(k + 10, self.n_steps), "+100": min(k + 100, self.n_steps)}

    def resolve(self, target, k: int) -> int | None:
        return None

    def candidates(self, k: int) -> list[tuple[float, int]]:
        """The cheapest ``(cost, edge)`` entries in the queue after ``k`` collapses (at most five)."""
        if k == 0:
            return list(self.initial_candidates)
        return list(self.records[k - 1].next_candidates)

    def ring_edges(self, k: int, v: int) -> list[int]:
        """The edges around vertex ``v`` after ``k`` collapses."""
        return [h.edge.index for h in self.mesh(k).vertex(v).outgoing()]

    def refusal(self, k: int, edge: int) -> str | None:
        """Why the queue would skip ``edge`` after ``k`` collapses, or None if it may be collapsed."""
        mesh, quadrics = self.at(k)
        check = mesh.can_collapse(edge)
        if not check:
            return f"not allowed: {check.reason}"
        point = edge_costs(mesh, quadrics)[1][edge]
        if turns_a_face(mesh, edge, point, float(np.cos(np.radians(self.max_normal_angle)))):
            return f"refused: a face would turn over (its normal would swing by more than {self.max_normal_angle:g} degrees)"
        return None

    def _replayed(self, k: int):
        """(mesh, quadrics) after the first ``k`` collapses, from the nearest checkpoint."""
        base = max(step for step in self._checkpoints if step <= k)
        mesh, quadrics = (thing.copy() for thing in self._checkpoints[base])
        for number in range(base, k):
            record = self.records[number]
            merged = quadrics[record.kept] + quadrics[record.removed]
            kept = mesh.collapse(record.edge, record.position).index
            if kept != record.kept:
                raise RuntimeError(f"replaying collapse {record.number} kept vertex {kept}, the run kept {record.kept}")
            quadrics[kept] = merged
            if (number + 1) % self.checkpoint_every == 0 and number + 1 not in self._checkpoints:
                self._checkpoints[number + 1] = (mesh.copy(), quadrics.copy())
        return mesh, quadrics


class QEMPainter:
    """How a step of QEM simplification looks (a :class:`~.steps.Painter`): every edge
    coloured by its cost, the queue's next edges and the last collapse on top."""

    title = "Quadric error simplification: the queue"
    keys = {"PageDown": "+10", "+": "+100"}
    buttons = (("start", "no collapse yet: every edge priced", "start"),
               ("back", "one collapse back", "back"),
               ("step", "one collapse", "step"),
               ("+10", "ten collapses", "+10"),
               ("+100", "a hundred collapses", "+100"),
               ("end", "down to the target", "end"))
    moves_help = "a step number"

    def __init__(self, steps: QEMSteps, *, view_direction=None):
        self.steps = steps
        self.view_direction = view_direction

    def make_scene(self, mesh, look, **options) -> PaintedScene:
        return PaintedScene(mesh, preset=look, plotter=options["plotter"], window_size=options["window_size"],
                            view_direction=self.view_direction, vertex_labels=False)

    def value_range(self) -> tuple[float, float]:
        """log10 of the first and the last collapse's cost (a little apart if they agree)."""
        costs = np.array([s.cost for s in self.steps.records] or [1.0])
        positive = costs[costs > 0]
        floor = positive.min() if len(positive) else 1e-12
        low = np.log10(max(costs[0], floor))
        high = np.log10(max(costs.max(), floor))
        return (float(low), float(max(high, low + 1.0)))

    def paint(self, scene, k: int) -> None:
        steps = self.steps
        low, high = self.value_range()
        values = np.log10(np.maximum(steps.costs(k), 10.0 ** low))
        layers = []
        if k:
            last = steps.records[k - 1]
            layers += [Layer("re-priced after the last collapse", LAST_COLLAPSE, "edges",
                             steps.ring_edges(k, last.kept), 3.5),
                       Layer("vertex of the last collapse", LAST_COLLAPSE, "vertices", [last.kept], 14.0)]
        queued = [e for _, e in steps.candidates(k)]
        if k < steps.n_steps:
            coming = steps.records[k].edge
            layers.append(Layer("queued next", QUEUED, "edges", [e for e in queued if e != coming], 4.5))
            layers.append(Layer("collapsed next", NEXT_EDGE, "edges", [coming], 6.0))
        scene.paint(steps.mesh(k), layers=layers, edge_values=values, value_label="log10 cost",
                    value_range=(low, high))

    def legend_html(self, scene, look) -> str:
        return legend_html(scene.legend_entries(), look)

    def describe(self, k: int) -> str:
        """The state in words: the last collapse, the queue's head, what comes next."""
        steps = self.steps
        before, mesh = steps.before, steps.mesh(k)
        lines = [f"QEM simplification of {before.n_faces} faces to {steps.target_faces}: "
                 f"step {k} of {steps.n_steps}, {mesh.n_faces} faces"]
        if k == 0:
            lines.append(f"start: {before.n_faces} face quadrics summed into {before.n_vertices} vertices; "
                         f"{before.n_edges} edges priced and queued")
        else:
            last = steps.records[k - 1]
            lines.append(f"last: {last.describe()}")
            ring = steps.ring_edges(k, last.kept)
            lines.append(f"re-priced and pushed again: the {len(ring)} edges around vertex {last.kept}")
        lines.append("queue, cheapest first: " + ", ".join(f"edge {e} ({cost:.3g})" for cost, e in steps.candidates(k)))
        lines += self.upcoming(k)
        return "\n".join(lines)

    def upcoming(self, k: int) -> list[str]:
        """What the queue does next: skipped entries with their reason, then the collapse."""
        steps = self.steps
        if k == steps.n_steps:
            return [f"done: {steps.mesh(k).n_faces} faces (target {steps.target_faces})"]
        coming = steps.records[k]
        lines = []
        for _, e in steps.candidates(k):
            if e == coming.edge:
                break
            lines.append(f"skip: edge {e}, {steps.refusal(k, e) or 'refused'}")
        lines.append(f"next: edge {coming.edge} (vertex {coming.removed} into {coming.kept}, cost {coming.cost:.3g})")
        return lines

    def panel_html(self, stepper) -> str:
        steps, k = self.steps, stepper.step_index
        size = panel_css(stepper.look)["font"]
        cell = "padding:2px 8px;border-bottom:1px solid #ddd;text-align:left;white-space:nowrap"
        coming = steps.records[k].edge if k < steps.n_steps else None
        rows, seen_next = [], coming is None
        for rank, (cost, e) in enumerate(steps.candidates(k), start=1):
            if e == coming:
                fate, color, seen_next = "collapsed next", NEXT_EDGE, True
            else:
                fate, color = ("queued" if seen_next else "skipped: may not collapse"), QUEUED
            rows.append(f'<tr><td style="{cell};border-left:6px solid {color}">{rank}</td>'
                        f'<td style="{cell}">edge {e}</td><td style="{cell}">{cost:.3g}</td>'
                        f'<td style="{cell}">{fate}</td></tr>')
        header = "".join(f'<th style="{cell}">{h}</th>' for h in ("", "queue", "cost", ""))
        table = f'<table style="border-collapse:collapse;font-size:{size};font-family:monospace">{header}{"".join(rows)}</table>'
        text = "<br>".join(html.escape(line) for line in self.describe(k).splitlines()[1:])
        return (f'<div style="font-size:{size};margin:4px 0">step <b>{k}</b> of {steps.n_steps}: '
                f"<b>{steps.mesh(k).n_faces}</b> faces (target {steps.target_faces})</div>{table}"
                f'<div style="font-size:{size};max-width:36em;margin-top:6px">{text}</div>')


class QEMStepper(Stepper):
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
    ``jump(n)`` and ``go(k | "start" | "end" | "+10" | "+100")`` move; ``state`` is the
    mesh now, ``costs`` the heat-map's numbers, ``result`` the simplified mesh.

    Keys (mouse pointer over the panel below the buttons): → or space one collapse,
    ← one back, PgDn ten collapses, ``+`` a hundred, Home the start, End the end.
    """

    def __init__(self, mesh, target_faces: int, *, max_normal_angle: float = 80.0, mode: str | None = None,
                 preset="default", window_size=None, view_direction=None, checkpoint_every: int = 64):
        steps = QEMSteps(mesh, target_faces, max_normal_angle=max_normal_angle, checkpoint_every=checkpoint_every)
        super().__init__(steps, QEMPainter(steps, view_direction=view_direction), mode=mode, preset=preset,
                         window_size=window_size)

    @property
    def steps(self) -> list[CollapseStep]:
        """The collapses the run made, in order."""
        return self.source.records

    @property
    def before(self):
        return self.source.before

    @property
    def target_faces(self) -> int:
        return self.source.target_faces

    @property
    def max_normal_angle(self) -> float:
        return self.source.max_normal_angle

    @property
    def initial_quadrics(self) -> np.ndarray:
        return self.source.initial_quadrics

    @property
    def initial_candidates(self) -> list[tuple[float, int]]:
        return self.source.initial_candidates

    @property
    def quadrics(self) -> np.ndarray:
        """(n_vertex_slots, 4, 4) the vertex quadrics now (a copy)."""
        return self.source.at(self._step)[1].copy()

    @property
    def costs(self) -> np.ndarray:
        """(n_edge_slots,) the queue's price of every edge now (NaN for deleted edges)."""
        return self.source.costs(self._step)

    @property
    def candidates(self) -> list[tuple[float, int]]:
        """The cheapest ``(cost, edge)`` entries in the queue now (at most five)."""
        return self.source.candidates(self._step)

    def jump(self, collapses: int) -> int:
        """Move ``collapses`` steps at once (negative: back), stopping at either end."""
        return self.go(min(max(self._step + int(collapses), 0), self.n_steps))

    def skipped_steps(self) -> list[int]:
        """The steps at which the queue's cheapest entry is skipped, not collapsed.

        At step ``k`` (``k`` collapses done) the head of the queue is the first of
        :attr:`candidates`; where the collapse that follows is another edge, the head was
        refused. ``go(k)`` and then ``describe()`` say why.
        """
        records = self.source.records
        heads = [self.source.initial_candidates] + [step.next_candidates for step in records[:-1]]
        return [k for k, (queued, step) in enumerate(zip(heads, records))
                if queued and queued[0][1] != step.edge]

    def refusal(self, edge: int) -> str | None:
        """Why the queue would skip ``edge`` now, or None if it may be collapsed."""
        return self.source.refusal(self._step, edge)
