"""LoopStepper: every step is the real algorithm's state, coloured by what each element is."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from halfedge_edu.algorithms import loop_subdivide
from halfedge_edu.data import sample
from halfedge_edu.viz.loop_stepper import LoopStepper


@pytest.fixture
def stepper(closing):
    widget = LoopStepper(sample("octahedron"), mode="static")
    closing(widget)
    return widget


def _faces(mesh) -> set:
    return {tuple(sorted(row)) for row in mesh.to_arrays()[1].tolist()}


def test_steps_are_positions_then_one_split_per_edge_one_flip_per_face_then_reposition(stepper):
    phases = [record.phase for record in stepper.records]
    assert phases == ["positions"] + ["split"] * 12 + ["flip"] * 8 + ["reposition"]
    assert stepper.n_steps == 21


def test_step_zero_says_positions_come_from_the_old_mesh(stepper):
    text = stepper.describe()
    assert text.splitlines()[0].endswith("step 0 of 21, positions")
    assert "computed from the old mesh, before any connectivity changes" in text
    assert "after the level: 18 vertices, 48 edges, 32 faces" in text


def test_the_last_step_is_loop_subdivide(stepper):
    stepper.go("end")
    reference = loop_subdivide(sample("octahedron"))
    assert _faces(stepper.state) == _faces(reference)
    assert np.allclose(stepper.state.positions, reference.positions)


def test_a_split_step_names_the_edge_and_its_new_vertex(stepper):
    stepper.go(1)
    line = stepper.describe().splitlines()[1]
    assert line.startswith("now: split edge 0 (vertices 0 and 2) at its midpoint: new vertex 6")
    assert stepper.state.n_vertices == 7


def test_a_flip_turns_an_old_to_new_edge_into_a_new_to_new_edge(stepper):
    stepper.go("flip")
    line = stepper.describe().splitlines()[1]
    assert "joined new vertex" in line or "joined old vertex" in line
    assert line.count("old vertex") == 1
    assert "now it joins new vertex" in line and line.endswith(f"and new vertex {line.split()[-1]}")


def test_after_the_splits_the_to_flip_edges_are_exactly_the_flips_to_come(stepper):
    stepper.go(stepper.phase_start("flip") - 1)
    assert len(stepper.edge_kinds()["to_flip"]) == 8
    stepper.go("reposition")
    kinds = stepper.edge_kinds()
    assert len(kinds["to_flip"]) == 0
    assert len(kinds["between_new"]) == 3 * 8 and len(kinds["old"]) == 2 * 12


def test_go_moves_by_phase_and_back(stepper):
    assert stepper.go("phase") == 1
    assert stepper.go("flip") == 13
    assert stepper.go("phase back") == 1
    assert stepper.back() == 0 and stepper.back() == 0


def test_buttons_drive_the_same_moves(stepper):
    stepper.buttons["step"].click()
    assert stepper.step_index == 1
    stepper.buttons["end"].click()
    assert stepper.phase == "reposition"


def test_unknown_moves_and_steps_are_refused_in_words(stepper):
    with pytest.raises(ValueError, match="unknown move"):
        stepper.go("sideways")
    with pytest.raises(IndexError, match="steps run from 0 to 21"):
        stepper.go(22)


def test_the_mesh_passed_in_is_never_changed(closing):
    mesh = sample("open_patch")
    before = mesh.positions.copy()
    widget = LoopStepper(mesh, mode="static")
    closing(widget)
    widget.go("end")
    assert np.array_equal(mesh.positions, before) and mesh.n_faces == 18


def test_big_meshes_are_refused_with_the_alternative():
    with pytest.raises(ValueError, match="loop_subdivide"):
        LoopStepper(sample("icosphere", subdivisions=3), mode="static")


def test_the_picture_and_the_text_are_in_the_display_bundle(stepper):
    bundle = stepper._repr_mimebundle_()
    assert bundle["text/plain"] == stepper.describe()
    assert bundle["image/png"]


def test_the_large_preset_for_a_projector(closing):
    widget = LoopStepper(sample("tetrahedron"), mode="static", preset="large")
    closing(widget)
    widget.go("flip")
    assert widget.scene.window_size == (1024, 768)
    assert "font-size:20px" in widget._legend.value


def _purple_pixels(png: bytes) -> int:
    """Pixels in the current step's colour (reddish purple #CC79A7, shaded)."""
    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
    red, green, blue = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return int(((red > 150) & (blue > 110) & (green < red - 50) & (blue > green + 20)).sum())


def test_the_panel_says_when_a_step_happens_out_of_sight_and_only_then(stepper):
    far, near = [], []
    for step in range(1, stepper.n_steps):                     # the splits and flips
        stepper.go(step)
        said = "far side of the mesh" in stepper._panel_html()
        assert said == stepper.on_far_side()
        (far if said else near).append((step, _purple_pixels(stepper.screenshot())))
    assert far and near
    assert all(purple < 20 for _, purple in far), f"a step said to be out of sight shows its colour: {far}"
    assert all(purple > 100 for _, purple in near), f"a step in sight does not show its colour: {near}"
