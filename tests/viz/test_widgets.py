"""HalfedgeExplorer and OneRingViewer, driven by clicks and by code, in static mode."""

from __future__ import annotations

import base64
import io

import pytest
from PIL import Image

from halfedge_edu.data import sample
from halfedge_edu.viz import HalfedgeExplorer, OneRingViewer


@pytest.fixture
def explorer(closing):
    widget = HalfedgeExplorer(sample("open_patch"), 5, mode="static")
    closing(widget)
    return widget


def test_buttons_walk_the_pointers(explorer):
    h = explorer.halfedge
    explorer.buttons["next"].click()
    assert explorer.halfedge == h.next
    explorer.buttons["twin"].click()
    assert explorer.halfedge == h.next.twin
    explorer.buttons["prev"].click()
    assert explorer.halfedge == h.next.twin.prev


def test_go_reads_a_chain_left_to_right(explorer):
    h = explorer.halfedge
    assert explorer.go("next.twin.next") == h.next.twin.next
    assert explorer.trail == [h.index, h.next.index, h.next.twin.index, h.next.twin.next.index]


def test_step_is_next_and_back_undoes(explorer):
    h = explorer.halfedge
    explorer.step()
    assert explorer.halfedge == h.next
    explorer.back()
    assert explorer.halfedge == h
    explorer.back()                                       # nothing left to undo
    assert explorer.trail == [h.index]


def test_back_at_the_start_of_the_walk_says_why_it_does_not_move(explorer):
    explorer.buttons["back"].click()
    assert "is where the walk started" in explorer._status.value
    explorer.buttons["next"].click()
    assert "walk started" not in explorer._status.value


def test_three_nexts_come_back_around_a_triangle(explorer):
    h = explorer.halfedge
    for _ in range(3):
        explorer.step()
    assert explorer.halfedge == h


def test_describe_names_the_pointers_and_the_trail(explorer):
    explorer.go("twin")
    assert explorer.describe() == (
        "current: halfedge 4 (5 -> 0, face 0); next 0; prev 2; twin 5; edge 2\n"
        "trail: h5 -twin-> h4"
    )


def test_pick_by_index_box(explorer):
    explorer._index_box.value = 12
    explorer.buttons["go to"].click()
    assert explorer.halfedge.index == 12


def test_bad_pick_shows_the_reason_and_stays(explorer):
    explorer._index_box.value = 9999
    explorer.buttons["go to"].click()
    assert explorer.halfedge.index == 5
    assert "there is no halfedge 9999" in explorer._status.value


def test_unknown_move_from_code_raises(explorer):
    with pytest.raises(ValueError, match="unknown move 'sideways'"):
        explorer.go("sideways")


def test_each_step_puts_a_new_picture_in_the_static_view_once_it_is_shown(explorer):
    explorer._repr_mimebundle_()                       # what displaying it in a notebook does
    before = explorer.view.widget.value
    explorer.go("twin")
    assert explorer.view.widget.value != before
    assert Image.open(io.BytesIO(explorer.view.widget.value)).format == "PNG"


def test_a_static_widget_never_shown_renders_only_when_a_picture_is_asked_for(monkeypatch):
    quiet = HalfedgeExplorer(sample("open_patch"), halfedge=7, mode="static")
    renders = []
    original = quiet.scene.screenshot
    monkeypatch.setattr(quiet.scene, "screenshot", lambda *a, **k: renders.append(1) or original(*a, **k))
    for move in ("next", "twin", "prev"):
        quiet.go(move)
    assert renders == []                               # driven for its text: no render window needed
    picture = quiet.screenshot()                       # asked for: rendered now, of the current state
    assert len(renders) == 1 and Image.open(io.BytesIO(picture)).format == "PNG"
    assert quiet.screenshot() == picture and len(renders) == 1   # not stale: not rendered again
    quiet.close()


def test_pointer_table_shows_the_current_halfedge(explorer):
    explorer.go("next")
    assert ">6<" in explorer._info.value and "h.twin" in explorer._info.value


def test_notebook_output_carries_describe_and_a_png(explorer):
    bundle = explorer._repr_mimebundle_()
    assert bundle["text/plain"] == explorer.describe()
    assert base64.b64decode(bundle["image/png"]).startswith(b"\x89PNG")
    assert "application/vnd.jupyter.widget-view+json" in bundle


def test_large_preset_has_bigger_buttons(closing):
    widget = HalfedgeExplorer(sample("cube"), 0, mode="static", preset="large")
    closing(widget)
    assert widget.buttons["next"].style.font_size == "20px"


def test_explorer_on_the_bunny(bunny, closing):
    widget = HalfedgeExplorer(bunny, 1000, mode="static")
    closing(widget)
    widget.go("next.twin")
    assert widget.halfedge.index == bunny.halfedge(1000).next.twin.index


@pytest.mark.parametrize("make", [lambda mesh: HalfedgeExplorer(mesh, 0, mode="static"),
                                  lambda mesh: OneRingViewer(mesh, 0, mode="static")])
def test_a_widget_keeps_its_own_copy_when_a_later_cell_edits_the_mesh(closing, make):
    mesh = sample("open_patch")
    widget = make(mesh)
    closing(widget)
    text = widget.describe()
    mesh.collapse(mesh.vertex(0).halfedge.edge)            # vertex 0 or its neighbour goes
    assert widget.describe() == text
    assert widget.mesh.n_vertices == mesh.n_vertices + 1
    widget.go("cw" if isinstance(widget, OneRingViewer) else "next")


@pytest.fixture
def ring(closing):
    widget = OneRingViewer(sample("open_patch"), 5, mode="static")
    closing(widget)
    return widget


def test_ccw_steps_visit_the_outgoing_halfedges_in_order(ring):
    order = [h.index for h in ring.vertex.outgoing()]
    seen = [ring.current.index]
    for _ in range(len(order) - 1):
        seen.append(ring.step().index)
    assert seen == order
    assert ring.step().index == order[0]


def test_cw_undoes_ccw(ring):
    start = ring.current
    ring.buttons["ccw"].click()
    ring.buttons["cw"].click()
    assert ring.current == start


def test_to_tip_recentres_on_the_neighbour(ring):
    tip = ring.current.tip
    ring.buttons["to tip"].click()
    assert ring.vertex == tip


def test_one_ring_describe(ring):
    ring.step()
    assert ring.describe() == (
        "vertex 5 (interior, degree 6)\n"
        "outgoing (CCW): 3, 17, 37, 26, 6, 4\n"
        "neighbours (CCW): 1, 6, 10, 9, 4, 0\n"
        "faces (CCW): 3, 8, 9, 6, 1, 0\n"
        "current: halfedge 17 (2 of 6) -> vertex 6"
    )


def test_boundary_vertex_ring_includes_the_boundary_halfedge(closing):
    widget = OneRingViewer(sample("open_patch"), 1, mode="static")
    closing(widget)
    assert widget.vertex.is_boundary
    assert widget.current.is_boundary                     # a boundary vertex starts on the boundary
    assert "(boundary, degree 4)" in widget.describe()


@pytest.mark.parametrize("typed", ["1e3", "12.5", "", "h7"])
def test_an_index_box_that_is_not_a_whole_number_is_refused_in_words_and_nothing_moves(explorer, typed):
    h = explorer.halfedge
    explorer._index_box.widget.value = typed
    explorer.buttons["go to"].click()
    assert explorer.halfedge == h
    assert "is not an index: type a whole number" in explorer._status.value
