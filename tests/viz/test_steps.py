"""The one stepper model: any Steps shown by the one Stepper widget through a painter."""

from __future__ import annotations

import re

import pytest

from halfedge_edu.data import sample
from halfedge_edu.viz import FlipStepper, LoopStepper, QEMStepper, RemeshStepper, Stepper
from halfedge_edu.viz.loop_stepper import LoopPainter, LoopSteps
from halfedge_edu.viz.painted_scene import Layer, PaintedScene
from halfedge_edu.viz.palette import ROLES
from halfedge_edu.viz.steps import phase_moves


class MovingVertex:
    """Steps of a toy algorithm: step k lifts vertex 0 of a triangle to height k."""

    def __init__(self, n_steps: int = 4):
        self.before = sample("lone_triangle")
        self._n = n_steps

    @property
    def n_steps(self) -> int:
        return self._n

    def mesh(self, k: int):
        mesh = self.before.copy()
        mesh.positions[0, 2] = float(k)
        return mesh

    @property
    def result(self):
        return self.mesh(self._n)

    def moves(self, k: int) -> dict[str, int]:
        return {"half": self._n // 2}

    def resolve(self, target, k: int):
        return self._n if target == "top" else None


class DotPainter:
    """Paints vertex 0 in the "changed_vertex" role's colour; counts its paints."""

    title = "A toy"
    keys = {"h": "half"}
    buttons = (("start", "", "start"), ("back", "", "back"), ("step", "", "step"), ("half", "", "half"))
    moves_help = "a step number"

    def __init__(self, steps):
        self.steps = steps
        self.painted: list[int] = []

    def make_scene(self, mesh, look, **options):
        return PaintedScene(mesh, preset=look, plotter=options["plotter"], window_size=options["window_size"],
                            vertex_labels=False)

    def paint(self, scene, k: int) -> None:
        self.painted.append(k)
        scene.paint(self.steps.mesh(k), layers=[Layer("lifted", ROLES["changed_vertex"].color, "vertices", [0])])

    def panel_html(self, stepper) -> str:
        return f"<p>step {stepper.step_index}</p>"

    def legend_html(self, scene, look) -> str:
        return "|".join(text for text, _, _ in scene.legend_entries())

    def describe(self, k: int) -> str:
        return f"vertex 0 at height {k}"


@pytest.fixture
def toy(closing):
    steps = MovingVertex()
    widget = Stepper(steps, DotPainter(steps), mode="static")
    closing(widget)
    return widget


def test_the_stepper_asks_the_painter_for_every_step_it_shows(toy):
    toy.step()
    toy.step()
    toy.back()
    assert toy.step_index == 1
    assert toy.painter.painted[-3:] == [1, 2, 1]
    assert toy.describe() == "vertex 0 at height 1"
    assert toy.state.positions[0, 2] == 1.0
    assert "step 1" in toy._info.value and toy._legend.value == "lifted"


def test_step_back_and_reset_stay_inside_the_steps_and_say_so(toy):
    assert toy.back() == 0
    assert "this is the start" in toy._status.value
    assert toy.go("end") == 4 and toy.step() == 4
    assert "step 4 of 4 is the last one" in toy._status.value
    assert toy.go("start") == 0 and re.sub("<[^>]*>", "", toy._status.value) == ""
    assert toy.state.positions[0, 2] == 0.0
    assert toy.result.positions[0, 2] == 4.0


def test_the_steps_name_their_own_moves_and_targets(toy):
    assert toy.go("half") == 2
    assert toy.go("top") == 4
    assert toy.press("h") == "half" and toy.step_index == 2
    assert set(toy.buttons) == {"start", "back", "step", "half"}
    toy.buttons["step"].click()
    assert toy.step_index == 3
    with pytest.raises(ValueError, match="'half'"):
        toy.go("sideways")
    with pytest.raises(IndexError, match="steps run from 0 to 4"):
        toy.go(5)


def test_a_failing_paint_leaves_the_widget_on_the_step_it_showed(toy):
    toy.go(1)
    painter = toy.painter
    original = painter.paint

    def broken(scene, k):
        if k == 3:
            raise RuntimeError("no picture")
        original(scene, k)

    painter.paint = broken
    with pytest.raises(RuntimeError):
        toy.go(3)
    assert toy.step_index == 1 and toy.describe() == "vertex 0 at height 1"


def test_phase_moves_go_to_the_next_and_the_previous_phase_start():
    assert phase_moves([1, 5, 9], 5, 12) == {"phase": 9, "phase back": 1}
    assert phase_moves([1, 5, 9], 9, 12) == {"phase": 12, "phase back": 5}
    assert phase_moves([], 0, 3) == {"phase": 3, "phase back": 0}


def test_every_named_stepper_is_the_one_stepper_over_its_algorithms_records(closing):
    cube = sample("cube")
    widgets = [FlipStepper(cube, 1, mode="static"), LoopStepper(sample("octahedron"), mode="static"),
               QEMStepper(sample("icosphere", subdivisions=1), 40, mode="static"),
               RemeshStepper(sample("open_patch"), target_length=0.3, iterations=1, mode="static")]
    for widget in widgets:
        closing(widget)
        assert isinstance(widget, Stepper)
        assert widget.n_steps == widget.source.n_steps > 0
        widget.go("end")
        end = widget.source.mesh(widget.n_steps)
        assert widget.state.n_faces == end.n_faces == widget.result.n_faces


def test_loop_steps_and_painter_make_a_stepper_without_the_named_class(closing):
    steps = LoopSteps(sample("octahedron"))
    widget = Stepper(steps, LoopPainter(steps), mode="static")
    closing(widget)
    widget.go("flip")
    assert steps.records[widget.step_index].phase == "flip"
    assert widget.describe().startswith(f"Loop subdivision (warren weights) of 6 vertices, 12 edges, 8 faces: "
                                        f"step {widget.step_index} of {steps.n_steps}, flip 1 of")
