"""One model for every stepper: an algorithm's run as numbered steps, and one widget to show them.

    from halfedge_edu.viz.loop_stepper import LoopPainter, LoopSteps
    from halfedge_edu.viz.steps import Stepper
    steps = LoopSteps(hx.sample("octahedron"))   # the records the algorithm wrote down
    steps.n_steps, steps.mesh(3)                  # how many steps; the mesh after step 3
    w = Stepper(steps, LoopPainter(steps))        # the widget: step(), back(), go(...), describe()

Every algorithm the course steps through already writes down what it does: a local
operation its :class:`~halfedge_edu.core.ops.log.OperationLog`, Loop subdivision a
:class:`~halfedge_edu.algorithms.loop.LoopStep` per split and flip, the QEM queue a
:class:`~halfedge_edu.algorithms.simplify_queue.CollapseStep` per collapse, remeshing a
:class:`~halfedge_edu.algorithms.remesh.RemeshStep` per phase. A :class:`Steps` holds
those records and answers two questions: how many steps there are, and what the mesh is
after the first ``k`` of them. It also names the moves its algorithm has beyond step,
back, start and end ("phase", "iteration", "+10").

The :class:`Stepper` widget knows nothing about any algorithm. It keeps the step number,
moves it, and asks a :class:`Painter` (one small class per algorithm) how to draw step
``k``, what the panel says about it, and how to describe it in words. The named
steppers (:class:`~halfedge_edu.viz.steppers.FlipStepper`,
:class:`~halfedge_edu.viz.loop_stepper.LoopStepper`, ...) are this widget with their
algorithm's steps and painter, plus a few questions of their own (``edge_kinds``,
``refusal``, ``quality``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from .widgets import SceneWidget

if TYPE_CHECKING:
    from ..core.mesh import HalfedgeMesh
    from .palette import Preset


class Steps(Protocol):
    """An algorithm's run as steps 0 .. ``n_steps``: step 0 is the input, each later step
    one record the algorithm wrote down (a change, a split, a collapse, a phase).

    Attributes:
        before: the input (a copy; never changed).
    """

    before: "HalfedgeMesh"

    @property
    def n_steps(self) -> int:
        """How many steps after step 0."""

    def mesh(self, k: int) -> "HalfedgeMesh":
        """The mesh after the first ``k`` steps. Attention: it may be shared with the
        steps' own records: read it, or take a ``copy()`` to change it."""

    @property
    def result(self) -> "HalfedgeMesh":
        """A copy of the mesh after the last step."""

    def moves(self, k: int) -> dict[str, int]:
        """Named moves of this algorithm from step ``k`` (name -> step), beyond "step",
        "back", "start" and "end": {} when it has none."""

    def resolve(self, target, k: int) -> int | None:
        """The step for a target that is not a number or a named move (a phase name,
        ``(iteration, phase)``), or None."""


class Painter(Protocol):
    """How one algorithm's steps look: the scene, the picture of a step, the panel's
    text and the words. A painter is made with the :class:`Steps` it paints.

    Attributes:
        title: the widget's heading.
        keys: key -> button label, beyond the arrows, space, Home and End (see :mod:`.keys`).
        buttons: ``(label, tooltip, move)`` of the buttons, ``move`` a target of
            :meth:`Stepper.go` ("start", "step", "phase", ...); empty for no buttons.
        moves_help: how :meth:`Stepper.go`'s error names the targets it takes.
    """

    title: str
    keys: dict[str, str]
    buttons: tuple[tuple[str, str, object], ...]
    moves_help: str

    def make_scene(self, mesh: "HalfedgeMesh", look: "Preset", **options):
        """The scene the widget draws into (``options``: plotter, window_size, labels, rings)."""

    def paint(self, scene, k: int) -> None:
        """Put step ``k`` into ``scene``."""

    def panel_html(self, stepper: "Stepper") -> str:
        """The panel's HTML for the step ``stepper`` shows (it also has ``look`` and ``mode``)."""

    def legend_html(self, scene, look: "Preset") -> str:
        """The legend of what ``scene`` shows now."""

    def describe(self, k: int) -> str:
        """Step ``k`` in plain text (deterministic, for nbval and for reading)."""


class Stepper(SceneWidget):
    """Show the steps of any algorithm, one at a time, painted by its painter.

    Args:
        steps: a :class:`Steps` (the records and the mesh at each step).
        painter: a :class:`Painter` for those steps.
        mode, preset, window_size, rings: as for every widget.

    ``go(target)`` (a step number, "step", "back", "start", "end", or a move the steps
    name), ``step()`` and ``back()`` (which stay at either end, and say so);
    ``step_index`` is the step shown, ``state`` a copy of the mesh there, ``result`` a
    copy of the mesh after the last step, ``describe()`` the step in words. ``source`` is the :class:`Steps`, ``painter`` the painter.

    Keys (the painter adds its own): → or space one step, ← one step back, Home the
    start, End the end.
    """

    KEYS = {"ArrowRight": "step", "Space": "step", "ArrowLeft": "back", "Home": "start", "End": "end"}

    def __init__(self, steps: Steps, painter: Painter, *, mode: str | None = None, preset="default",
                 window_size=None, rings: int = 0):
        self.source = steps
        self.painter = painter
        self.title = painter.title
        self.KEYS = {**self.KEYS, **painter.keys}
        self._moves_help = painter.moves_help
        self._step = 0                       # the step shown
        super().__init__(steps.before.copy(), mode=mode, preset=preset, labels=None, rings=rings,
                         window_size=window_size)

    @property
    def n_steps(self) -> int:
        """How many steps after step 0."""
        return self.source.n_steps

    @property
    def state(self):
        """A copy of the mesh at the step shown (half way through an operation it is
        usually not a valid mesh)."""
        return self.source.mesh(self._step).copy()

    @property
    def result(self):
        """A copy of the mesh after the last step."""
        return self.source.result

    def describe(self) -> str:
        """The step shown, in plain text (deterministic, for nbval and for reading)."""
        return self.painter.describe(self._step)

    @property
    def step_index(self) -> int:
        """The step shown now: 0 (the start) to ``n_steps`` (the end)."""
        return self._step

    def _named_moves(self) -> dict[str, int]:
        """Move name -> step: next, step, back, start, end, and the moves the steps name."""
        forward, backward = min(self._step + 1, self.n_steps), max(self._step - 1, 0)
        return {"next": forward, "step": forward, "back": backward, "start": 0, "end": self.n_steps,
                **self.source.moves(self._step)}

    def go(self, target) -> int:
        """Go to a step (a number or a named move; see the class). Returns the step shown."""
        resolved, move = self.source.resolve(target, self._step), None
        if resolved is not None:
            target = resolved
        elif isinstance(target, str):
            moves = self._named_moves()
            move = target.strip().lower()
            if move not in moves:
                raise ValueError(f"unknown move {target!r}: use {self._moves_help} or one of "
                                 f"{', '.join(repr(m) for m in moves)}")
            target = moves[move]
        target = int(target)
        if not 0 <= target <= self.n_steps:
            raise IndexError(f"there is no step {target}: steps run from 0 to {self.n_steps}")
        shown = self._step
        try:
            self._step = target
            self._changed()
        except Exception:
            # A failed step leaves the widget where it was: the step shown, its picture, its panel.
            self._step = shown
            self._changed()
            raise
        self._say(self._why_not_moved(move) if move is not None and target == shown else "")
        return self._step

    def _why_not_moved(self, move: str) -> str:
        """What a named move that leaves the step where it is says (at the end, at the start)."""
        if self._step == self.n_steps and move not in ("back", "start", "phase back"):
            return (f"{move}: step {self._step} of {self.n_steps} is the last one; "
                    f"← back or Home to go through it again")
        if self._step == 0:
            return f"{move}: this is the start (step 0 of {self.n_steps}); → or space steps forward"
        return f"{move}: already at step {self._step} of {self.n_steps}"

    def step(self) -> int:
        """One step forward (stays at the end, and says so)."""
        return self.go("step")

    def back(self) -> int:
        """One step back (stays at the start, and says so)."""
        return self.go("back")

    # -- what the widget asks of its steps and painter -----------------------------------

    def _make_scene(self, mesh, **options):
        return self.painter.make_scene(mesh, self.look, **options)

    def _show(self) -> None:
        self.painter.paint(self.scene, self._step)

    def _controls(self) -> list:
        if not self.painter.buttons:
            self.buttons = {}
            return []
        return self._button_row([(label, tooltip, lambda move=move: self.go(move))
                                 for label, tooltip, move in self.painter.buttons])

    def _panel_html(self) -> str:
        return self.painter.panel_html(self)

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = self.painter.legend_html(self.scene, self.look)


def phase_moves(starts: list[int], k: int, n_steps: int) -> dict[str, int]:
    """"phase" and "phase back" from step ``k``: the next / previous of the phase ``starts``."""
    return {"phase": next((s for s in starts if s > k), n_steps),
            "phase back": max([s for s in starts if s < k], default=0)}
