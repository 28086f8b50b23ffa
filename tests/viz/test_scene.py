"""HalfedgeScene: highlights by role, windowing on large meshes, labels, text, pictures."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from halfedge_edu.data import sample
from halfedge_edu.viz import HalfedgeScene
from halfedge_edu.viz.palette import PRESETS, ROLES, rgb


def _arrow_color(scene, h):
    """The colour the scene gives halfedge h's arrow."""
    slot = int(np.flatnonzero(scene.drawn_halfedges == h)[0])
    return tuple(scene.arrow_colors[slot])


@pytest.fixture
def cube_scene(closing):
    scene = HalfedgeScene(sample("cube"))
    closing(scene)
    return scene


def test_small_mesh_draws_every_halfedge(cube_scene):
    assert sorted(cube_scene.drawn_halfedges) == list(range(cube_scene.mesh.n_halfedges))


def test_show_halfedge_colours_each_neighbour_by_its_role(cube_scene):
    mesh = cube_scene.mesh
    h = mesh.halfedge(0)
    cube_scene.show_halfedge(0)
    for role, element in [("current", h), ("twin", h.twin), ("next", h.next), ("prev", h.prev)]:
        assert _arrow_color(cube_scene, element.index) == tuple(rgb(ROLES[role].color)), role
    plain = [x for x in range(mesh.n_halfedges) if x not in (h.index, h.twin.index, h.next.index, h.prev.index)]
    assert _arrow_color(cube_scene, plain[0]) == tuple(rgb(cube_scene.preset.plain_arrow))


def test_show_halfedge_names_origin_tip_and_face(cube_scene):
    cube_scene.show_halfedge(0)
    h = cube_scene.mesh.halfedge(0)
    assert list(cube_scene.roles["origin"]) == [h.vertex.index]
    assert list(cube_scene.roles["tip"]) == [h.tip.index]
    assert list(cube_scene.roles["face"]) == [h.face.index]


def test_boundary_halfedge_has_no_face_role(closing):
    scene = HalfedgeScene(sample("open_patch"))
    closing(scene)
    boundary = int(np.flatnonzero(scene.mesh.halfedge_face < 0)[0])
    scene.show_halfedge(boundary)
    assert "face" not in scene.roles
    assert ("boundary halfedge", scene.preset.boundary_arrow, "halfedge") in scene.legend_entries()


def test_one_ring_roles_list_the_ring_in_ccw_order(cube_scene):
    cube_scene.show_one_ring(0)
    v = cube_scene.mesh.vertex(0)
    assert list(cube_scene.roles["outgoing"]) == [h.index for h in v.outgoing()]
    assert list(cube_scene.roles["neighbor"]) == [n.index for n in v.neighbors()]


def test_unknown_role_is_refused(cube_scene):
    with pytest.raises(ValueError, match="unknown role 'sibling'"):
        cube_scene.set_roles({"sibling": [1]})


def test_legend_follows_the_roles_shown(cube_scene):
    cube_scene.show_halfedge(0)
    texts = [text for text, _, _ in cube_scene.legend_entries()]
    assert texts[:2] == ["halfedge", ROLES["current"].legend]
    assert ROLES["neighbor"].legend not in texts


def test_describe_is_plain_deterministic_text(cube_scene):
    cube_scene.show_halfedge(0)
    assert cube_scene.describe() == (
        "mesh: 8 vertices, 18 edges, 12 faces, 0 boundary loops\n"
        "h (current): halfedge 0\nh.twin: halfedge 1\nh.next: halfedge 2\nh.prev: halfedge 4\n"
        "h.vertex (origin): vertex 0\nh.tip: vertex 4\nh.face: face 0"
    )


def test_screenshot_is_a_png_of_the_preset_size_and_the_same_every_time(closing):
    pictures = []
    for _ in range(2):
        scene = HalfedgeScene(sample("cube"))
        closing(scene)
        scene.show_halfedge(3)
        pictures.append(scene.screenshot())
    assert pictures[0] == pictures[1]
    assert Image.open(io.BytesIO(pictures[0])).size == PRESETS["default"].window_size


def test_large_preset_makes_a_bigger_picture_with_thicker_arrows(closing):
    scene = HalfedgeScene(sample("cube"), preset="large")
    closing(scene)
    assert Image.open(io.BytesIO(scene.screenshot())).size == PRESETS["large"].window_size
    assert PRESETS["large"].arrow_width > PRESETS["default"].arrow_width
    assert PRESETS["large"].label_size > PRESETS["default"].label_size


def test_labels_on_a_tiny_mesh_name_every_element_in_sight(cube_scene):
    cube_scene.show_halfedge(0)
    shown = cube_scene.labels_shown()
    assert "h0" in shown["halfedge"] and "f0" in shown["face"] and {"v0", "v4"} <= set(shown["vertex"])
    assert len(shown["face"]) < cube_scene.mesh.n_faces          # the far side is not labelled


def test_labels_can_be_turned_off(closing):
    scene = HalfedgeScene(sample("cube"), labels=None)
    closing(scene)
    scene.show_halfedge(0)
    assert scene.labels_shown() == {"vertex": [], "halfedge": [], "face": []}


def test_large_mesh_labels_only_the_highlight_and_nearby_vertices(bunny, closing):
    scene = HalfedgeScene(bunny)
    closing(scene)
    scene.show_halfedge(1000)
    shown = scene.labels_shown()
    assert shown["halfedge"] and set(shown["halfedge"]) <= {"h1000", "h1001", f"h{bunny.halfedge_next[1000]}",
                                                             f"h{bunny.halfedge_prev[1000]}"}
    assert 3 <= len(shown["vertex"]) < 40


def test_large_mesh_draws_arrows_only_near_the_highlight(bunny, closing):
    scene = HalfedgeScene(bunny)
    closing(scene)
    assert scene.windowed
    scene.show_halfedge(1000)
    drawn = scene.drawn_halfedges
    assert 50 < len(drawn) < 2000
    assert {1000, 1001, int(bunny.halfedge_next[1000]), int(bunny.halfedge_prev[1000])} <= set(drawn.tolist())
    assert _arrow_color(scene, 1000) == tuple(rgb(ROLES["current"].color))


def test_large_mesh_window_moves_with_the_highlight(bunny, closing):
    scene = HalfedgeScene(bunny)
    closing(scene)
    scene.show_halfedge(1000)
    first = set(scene.drawn_halfedges.tolist())
    scene.show_halfedge(200000)
    assert 200000 in scene.drawn_halfedges
    assert first != set(scene.drawn_halfedges.tolist())


def test_refresh_draws_the_mesh_as_it_is_now(closing):
    mesh = sample("open_patch")
    scene = HalfedgeScene(mesh)
    closing(scene)
    mesh.delete_edge(0)                                   # flagged: no arrow any more
    scene.refresh()
    assert 0 not in scene.drawn_halfedges and 1 not in scene.drawn_halfedges
