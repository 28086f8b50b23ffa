"""QEMStepper: the sequential queue algorithm replayed, its costs as a heat-map."""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu.algorithms import simplify
from halfedge_edu.algorithms.simplify_queue import QuadricQueue, simplify_sequential
from halfedge_edu.data import sample
from halfedge_edu.viz.qem_stepper import QEMStepper, edge_costs


@pytest.fixture(scope="module")
def small_spot():
    return simplify(sample("spot"), 400)


@pytest.fixture
def stepper(small_spot, closing):
    widget = QEMStepper(small_spot, 300, mode="static", checkpoint_every=8)
    closing(widget)
    return widget


def _bumpy_patch():
    patch = sample("open_patch")
    x, y = patch.positions[:, 0], patch.positions[:, 1]
    patch.positions[:, 2] = np.sin(2 * x) * np.cos(3 * y)
    return patch


@pytest.mark.parametrize("mesh", [_bumpy_patch(), sample("icosphere", subdivisions=2), sample("cube")],
                         ids=["bumpy patch (boundary)", "icosphere", "cube"])
def test_edge_costs_agree_with_the_queue_price_of_every_edge(mesh):
    queue = QuadricQueue(mesh.copy())
    costs, points = edge_costs(mesh, queue.quadrics)
    for e in range(mesh.n_edges):
        cost, point = queue.price(e)
        assert costs[e] == pytest.approx(cost, rel=1e-9, abs=1e-15)
        assert np.allclose(points[e], point)


def test_the_steps_are_simplify_sequential_and_the_end_is_its_result(stepper, small_spot):
    reference = simplify_sequential(small_spot, 300)
    assert stepper.n_steps == 50
    assert np.array_equal(stepper.result.to_arrays()[1], reference.to_arrays()[1])
    stepper.go("end")
    assert stepper.state.n_faces == 300


def test_replay_matches_the_recorded_collapse_at_every_step_both_ways(stepper):
    stepper.go(30)
    assert stepper.state.n_faces == 400 - 2 * 30
    stepper.go(9)
    assert stepper.describe().splitlines()[1].startswith(f"last: collapse 9: edge {stepper.steps[8].edge} ")
    stepper.go(30)
    again = stepper.state
    assert again.n_faces == 340


def test_the_next_collapse_is_the_cheapest_allowed_queue_entry(stepper):
    for k in (0, 5, 20):
        stepper.go(k)
        coming = stepper.steps[k].edge
        edges = [e for _, e in stepper.candidates]
        for e in edges[: edges.index(coming)] if coming in edges else edges:
            assert stepper.refusal(e) is not None
        assert stepper.refusal(coming) is None


def test_describe_lists_the_queue_head_and_what_was_re_pushed(stepper):
    stepper.step()
    lines = stepper.describe().splitlines()
    assert lines[0] == "QEM simplification of 400 faces to 300: step 1 of 50, 398 faces"
    assert lines[2].startswith("re-priced and pushed again: the ")
    assert lines[3].startswith("queue, cheapest first: edge ")
    assert lines[-1].startswith("next: edge ")


def test_skipped_steps_are_the_steps_whose_description_lists_a_skip(small_spot, closing):
    # Down to 100 faces the queue refuses its head a few times (here near the end).
    widget = QEMStepper(small_spot, 100, mode="static", checkpoint_every=8)
    closing(widget)
    skipped = widget.skipped_steps()
    assert skipped
    # Each skip, the steps on either side of it, and a spread of the others.
    near_skips = {k + d for k in skipped for d in (-1, 0, 1)}
    looked_at = sorted({0, widget.n_steps - 1, *range(0, widget.n_steps, 25),
                        *(k for k in near_skips if 0 <= k < widget.n_steps)})
    for k in looked_at:
        widget.go(k)
        lines = widget.describe().splitlines()
        assert any(line.startswith("skip: edge") for line in lines) == (k in skipped), k


def test_quadrics_are_merged_as_the_run_merged_them(stepper, small_spot):
    stepper.go(10)
    last = stepper.steps[9]
    state_costs = edge_costs(stepper.state, stepper.quadrics)[0]
    assert np.isfinite(state_costs[~stepper.state.edge_deleted]).all()
    for cost, e in stepper.candidates:
        assert state_costs[e] == pytest.approx(cost, rel=1e-9, abs=1e-18)
    assert last.kept in stepper.state.face_vertices()


def test_jumps_stop_at_the_ends(stepper):
    assert stepper.jump(100) == 50
    assert stepper.jump(-7) == 43
    assert stepper.jump(-100) == 0


def test_buttons_drive_the_same_moves(stepper):
    stepper.buttons["+10"].click()
    assert stepper.step_index == 10
    stepper.buttons["back"].click()
    assert stepper.step_index == 9


def test_the_heat_map_is_drawn_with_its_colour_bar(stepper):
    assert "edge_values" in stepper.scene.plotter.actors
    assert stepper.scene.plotter.scalar_bars


def test_a_mesh_with_a_boundary_and_the_large_preset(closing):
    widget = QEMStepper(_bumpy_patch(), 10, mode="static", preset="large")
    closing(widget)
    widget.go("end")
    assert widget.state.n_faces == 10 and widget.state.n_boundary_loops == 1
    assert widget.describe().splitlines()[-1] == "done: 10 faces (target 10)"
    assert widget.scene.window_size == (1024, 768)
