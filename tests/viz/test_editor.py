"""MeshEditor driven by its buttons, keys and from code, in static mode."""

from __future__ import annotations

import numpy as np
import pytest

import halfedge_edu as hx
from halfedge_edu.data import sample
from halfedge_edu.viz.editor import KEYS, MeshEditor

ARRAYS = ("positions", "vertex_halfedge", "vertex_deleted", "halfedge_next", "halfedge_prev",
          "halfedge_vertex", "halfedge_face", "edge_deleted", "face_halfedge", "face_deleted")
SMALL = (160, 120)       # pixels: the tests read the mesh and the text, the picture only changes


def same_arrays(a, b) -> bool:
    return all(np.array_equal(getattr(a, name), getattr(b, name)) for name in ARRAYS)


@pytest.fixture
def cube():
    return sample("cube")


@pytest.fixture
def editor(cube, closing):
    widget = MeshEditor(cube, select=("edge", 4), mode="static", window_size=SMALL)
    closing(widget)
    return widget


def test_the_mesh_passed_in_is_copied_not_edited(cube, editor):
    editor.apply("flip")
    assert not same_arrays(editor.mesh, cube)
    assert same_arrays(cube, sample("cube"))


def test_flip_button_flips_the_selected_edge_and_lists_its_pointer_diff(cube, editor):
    a, b = (v.index for v in cube.edge(4).vertices)
    editor.buttons["flip"].click()
    ends = {v.index for v in editor.mesh.edge(4).vertices}
    assert ends.isdisjoint({a, b})
    assert editor.selection == ("edge", 4)
    assert editor.last_log.operation == "flip" and editor.last_log.changes
    described = editor.describe()
    assert "last edit: flip of edge 4" in described
    assert editor.last_log.changes[0].describe() in described
    assert "valid" in described.splitlines()[0]


def test_split_button_selects_the_new_vertex(editor):
    vertices = editor.mesh.n_vertices
    editor.buttons["split"].click()
    assert editor.mesh.n_vertices == vertices + 1
    kind, v = editor.selection
    assert kind == "vertex" and editor.last_log.created[0] == ("vertex", v)


def test_collapse_of_a_halfedge_removes_its_origin_and_selects_its_tip(editor):
    h = editor.mesh.halfedge(9)
    origin, tip = h.vertex.index, h.tip.index
    editor.select("halfedge", 9)
    assert editor.apply("collapse")
    assert editor.mesh.vertex_deleted[origin]
    assert editor.selection == ("vertex", tip)


def test_smooth_button_moves_only_the_selection_and_its_neighbours():
    patch = sample("open_patch")
    interior = next(v.index for v in patch.vertices if not v.is_boundary)
    widget = MeshEditor(patch, select=("vertex", interior), mode="static", window_size=SMALL)
    try:
        widget.move_vertex(interior, patch.positions[interior] + (0.0, 0.0, 1.0))
        before = widget.mesh.positions.copy()
        widget.buttons["smooth"].click()
        moved = set(np.flatnonzero(np.any(widget.mesh.positions != before, axis=1)))
        near = {interior} | {u.index for u in widget.mesh.vertex(interior).neighbors()}
        assert interior in moved and moved <= near
        assert moved == {change.index for change in widget.last_log.changes}
    finally:
        widget.close()


def test_keys_are_cmus_with_l_for_smoothing_and_z_for_undo(editor):
    assert KEYS == {"f": "flip", "s": "split", "c": "collapse", "l": "smooth", "u": "upsample",
                    "d": "downsample", "r": "remesh", "i": "info", "z": "undo"}
    editor.key("f")
    assert editor.last_log.operation == "flip"
    editor.key("z")
    assert editor.can_undo == 0
    with pytest.raises(ValueError, match="unknown key 'q'"):
        editor.key("q")


def test_each_key_typed_in_the_keys_box_is_one_edit_however_the_text_arrives(editor):
    # What the browser sends for "lll" typed fast: the text after one key, then after
    # two more; the kernel never writes the box, so nothing comes back to race them.
    for text in ("l", "lll"):
        editor._keys.value = text
    assert editor.can_undo == 3 and editor._last_text.startswith("smooth")
    editor._keys.value = "ll"                  # Backspace: no edit
    editor._keys.value = "llq"                 # not a key: no edit
    assert editor.can_undo == 3
    editor._keys.value = "llqZ"                # Shift or Caps Lock: the same key
    assert editor.can_undo == 2
    editor._keys.value = "f"                   # all selected and replaced by f
    assert editor.last_log.operation == "flip" and editor._keys.value == "f"


def test_upsample_downsample_and_remesh_replace_the_whole_mesh_and_undo_restores_it(cube, editor):
    assert editor.apply("upsample")
    assert editor.mesh.n_faces == 4 * cube.n_faces and editor.valid
    assert editor.selection == ("edge", 4)
    assert editor.apply("downsample")
    assert editor.mesh.n_faces <= cube.n_faces and editor.valid
    assert editor.apply("remesh") and editor.valid
    assert "remesh:" in editor.describe()
    for _ in range(3):
        editor.key("z")
    assert same_arrays(editor.mesh, cube)


def test_info_says_the_selected_elements_pointers_and_changes_nothing(cube, editor):
    assert editor.key("i") is None
    text = editor.info()
    h = cube.halfedge(8)
    assert text.startswith("edge 4: halfedges 8 and 9")
    assert f"vertices {h.vertex.index} - {h.tip.index}" in text
    assert text in editor._status.value and editor.can_undo == 0
    editor.select("halfedge", 8)
    assert f"next {h.next.index}" in editor.info() and "twin 9" in editor.info()


def test_a_whole_mesh_edit_that_raises_is_refused_and_changes_nothing(cube, editor, monkeypatch):
    import halfedge_edu.viz.editor as editor_module

    def refuse(mesh):
        raise hx.MeshInputError("this mesh cannot be subdivided")

    monkeypatch.setattr(editor_module, "loop_subdivide", refuse)
    check = editor.apply("upsample")
    assert not check and check.reason == "this mesh cannot be subdivided"
    assert editor.can_undo == 0 and same_arrays(editor.mesh, cube)
    assert "upsample refused: this mesh cannot be subdivided" in editor._status.value



def test_undo_button_goes_back_through_every_edit_to_identical_arrays(cube, editor):
    editor.apply("flip")
    editor.apply("split")
    editor.apply("smooth")
    editor.select("edge", 3)
    editor.apply("collapse")
    editor.move_vertex(0, (0.1, 0.2, 2.0))
    assert editor.can_undo == 5
    for _ in range(5):
        editor.buttons["undo"].click()
    assert same_arrays(editor.mesh, cube)
    assert editor.selection == ("edge", 4)
    assert not editor.undo()


def test_refused_flip_shows_the_reason_and_changes_nothing(cube, editor):
    editor.select("edge", 0)
    check = editor.apply("flip")
    assert not check and check.reason == cube.can_flip(0).reason
    assert same_arrays(editor.mesh, cube)
    assert editor.can_undo == 0
    assert f"refused: flip of edge 0 (vertices 0 - 4): {check.reason}" in editor.describe()
    assert "refused" in editor.scene.roles


def test_an_edge_operation_on_a_vertex_or_face_is_refused(cube, editor):
    for kind in ("vertex", "face"):
        editor.select(kind, 1)
        check = editor.apply("split")
        assert not check and check.rule == "selection" and f"{kind} 1 is selected" in check.reason
    assert same_arrays(editor.mesh, cube)


def test_move_vertex_sliders_move_the_selected_vertex(editor):
    editor.select("vertex", 2)
    editor._sliders[2].value = 1.5
    assert editor.mesh.positions[2, 2] == pytest.approx(1.5)
    assert editor.last_log.changes[0].field == "position"
    editor.select("edge", 1)
    assert all(slider.disabled for slider in editor._sliders)


def test_selecting_syncs_the_index_controls_and_rejects_bad_input(editor):
    editor._kind_box.value = "face"
    editor._index_box.value = 3
    editor.buttons["select"].click()
    assert editor.selection == ("face", 3)
    editor.select("vertex", 5)
    assert (editor._kind_box.value, editor._index_box.value) == ("vertex", 5)
    with pytest.raises(ValueError, match="unknown kind"):
        editor.select("corner", 1)
    with pytest.raises(IndexError):
        editor.select("edge", 999)
    with pytest.raises(ValueError, match="vertex 5"):
        editor.move_vertex(5, (0.0, np.nan, 0.0))
    with pytest.raises(ValueError, match="unknown operation"):
        editor.apply("bevel")


def test_a_button_with_bad_input_says_why_in_the_status_line(editor):
    editor._index_box.value = 999
    editor.buttons["select"].click()
    assert "999" in editor._status.value and editor.selection == ("edge", 4)


def test_pick_at_selects_the_nearest_element_of_the_chosen_kind(cube, editor):
    a, b = cube.positions[0], cube.positions[4]
    near_edge_0 = 0.5 * (a + b) + 0.01
    assert editor.pick_at(near_edge_0, "edge") == ("edge", 0)
    assert editor.pick_at(a + 0.01, "vertex") == ("vertex", 0)
    face = cube.face(5)
    centre = cube.positions[[v.index for v in face.vertices()]].mean(axis=0)
    assert editor.pick_at(centre, "face") == ("face", 5)
    kind, h = editor.pick_at(centre, "halfedge")
    assert cube.halfedge(h).face.index == 5


def test_the_static_picture_follows_every_edit(editor):
    before = editor.screenshot()
    editor.apply("split")
    after_split = editor.screenshot()
    editor.undo()
    assert before != after_split and editor.screenshot() != after_split


def test_two_hundred_random_edits_keep_the_mesh_valid_and_undo_to_the_start(closing):
    start = hx.loop_subdivide(sample("open_patch"))
    widget = MeshEditor(start, mode="static", window_size=SMALL, undo_limit=200)
    closing(widget)
    rng = np.random.default_rng(12)
    done = {"flip": 0, "split": 0, "collapse": 0, "smooth": 0, "move": 0}
    with widget.held():                       # draw once at the end; every edit is still validated
        for _ in range(200):
            random_edit(widget, rng, done)
        assert all(count > 0 for count in done.values()), done
        while widget.undo():
            pass
    assert same_arrays(widget.mesh, start)
    assert same_arrays(widget.scene.mesh, start)


def random_edit(widget, rng, done: dict) -> None:
    """One random edit of a random edge or vertex; validate after it."""
    mesh = widget.mesh
    action = rng.choice(["flip", "split", "collapse", "smooth", "move"], p=[0.3, 0.2, 0.3, 0.1, 0.1])
    if action == "move":
        v = int(rng.choice(np.flatnonzero(~mesh.vertex_deleted)))
        check = widget.move_vertex(v, mesh.positions[v] + rng.normal(scale=0.05, size=3))
    else:
        widget.select("edge", int(rng.choice(np.flatnonzero(~mesh.edge_deleted))))
        before = mesh.copy()
        check = widget.apply(str(action))
        if not check:
            assert same_arrays(widget.mesh, before)
    done[str(action)] += bool(check)
    widget.mesh.validate()
    assert widget.valid


def test_the_hint_says_an_edge_and_a_vertex(editor):
    editor._kind_box.value = "edge"
    assert "type an edge index" in editor._hint.value
    editor._kind_box.value = "vertex"
    assert "type a vertex index" in editor._hint.value


def test_upsample_past_the_editors_size_is_refused_in_words(editor, monkeypatch):
    import halfedge_edu.viz.editor as editor_module

    monkeypatch.setattr(editor_module, "MAX_UPSAMPLED_FACES", 4 * editor.mesh.n_faces - 1)
    check = editor.apply("upsample")
    assert not check and f"would make {4 * editor.mesh.n_faces} faces" in check.reason
    assert editor.can_undo == 0


def test_a_refusal_is_shown_in_vermillion_not_in_the_red_of_an_error(editor):
    editor.select("vertex", 0)
    editor.apply("collapse")                   # needs an edge: refused, not an error
    assert "#D55E00" in editor._status.value and "#D55E00" in editor._info.value
    assert "#B00020" not in editor._status.value + editor._info.value
    editor._index_box.value = 999
    editor.buttons["select"].click()           # no such vertex: an error
    assert "#B00020" in editor._status.value
