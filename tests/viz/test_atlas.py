"""The collapse atlas can be read: labelled refusals, a legend, no stale "changes now"."""

from __future__ import annotations

import io

import pytest
from PIL import Image

from halfedge_edu.viz import CollapseAtlas


@pytest.fixture(scope="module")
def atlas():
    widget = CollapseAtlas(mode="static")
    yield widget
    widget.close()


def test_refused_pictures_label_the_vertices_their_reasons_name(atlas):
    for stepper in atlas.refused:
        shown = stepper.scene.labels_shown()["vertex"]
        edge = next(index for kind, index in stepper.check.elements if kind == "edge")
        ends = [f"v{v}" for v in stepper.before.edge_vertices()[edge]]
        named = [f"v{index}" for kind, index in stepper.check.elements if kind == "vertex"]
        assert set(ends + named) <= set(shown), (stepper.check.rule, shown)


def test_a_phase_that_changes_nothing_shows_no_change(atlas):
    cube = atlas.steppers[0]
    quiet = [p for p in range(1, len(atlas.phases) + 1)
             if atlas._end_of_phase(cube, p) == atlas._end_of_phase(cube, p - 1)]
    assert quiet, "the cube's collapse has a phase without changes (no halfedge moves to vA)"
    atlas.go(quiet[0])
    assert not set(cube.scene.roles) & {"changed", "changed_vertex", "changed_face", "old_target", "new_target"}


def test_the_legend_names_every_colour_shown(atlas):
    atlas.go(1)
    texts = [text for text, _, _ in atlas.legend_entries()]
    assert "changes now" in texts and "refused edge" in texts
    assert "changes now" in atlas.widget.children[3].children[-1].value


def test_the_still_picture_has_titles_and_a_legend(atlas):
    plain = Image.open(io.BytesIO(atlas.steppers[0].screenshot()))
    picture = Image.open(io.BytesIO(atlas.screenshot()))
    assert picture.width > 2 * plain.width + 150       # the legend beside the cases
    assert picture.height > plain.height + 225 + 2 * 20  # the refusals below, with title bands


def test_a_move_that_cannot_move_says_why(atlas):
    atlas.go(0)
    atlas.buttons["back"].click()
    assert "is the start" in atlas._status.value
    atlas.go("end")
    atlas.buttons["phase"].click()
    assert "is the last one" in atlas._status.value and atlas.go(0) == 0
    assert "is the last one" not in atlas._status.value


def test_a_client_side_atlas_displays_without_a_kernel_picture(atlas, monkeypatch):
    """With HALFEDGE_EDU_LIVE_BACKEND=client every stepper's plotter has rendering
    suppressed (vtk.js draws in the browser) and cannot give a screenshot: displaying
    the atlas must not ask for one (it raised under chapter 07's atlas on a hub)."""
    def no_picture(*_args, **_kwargs):
        raise AttributeError("This plotter has not yet been set up and rendered with ``show()``.")

    for stepper in atlas.steppers + atlas.refused:
        monkeypatch.setattr(stepper.scene.plotter, "suppress_rendering", True, raising=False)
        monkeypatch.setattr(stepper, "screenshot", no_picture)
    bundle = atlas._repr_mimebundle_()
    assert "image/png" not in bundle and bundle["text/plain"] == atlas.describe()
