"""Labels can be read: no label box overlaps another, measured in the picture's pixels.

Each check projects every drawn label's point with the scene's camera, estimates its box
from its font size and text (``labels.label_boxes``) and asks ``overlapping_labels`` for
boxes that overlap or leave the picture. The scenes are those issue 11 found crowded:
chapter 07's opening pictures, the collapse stepper and the collapse atlas at every step,
the split stepper at its end, the bunny's one-ring viewer; then every figure. On dense
meshes (issue 30's "crowded labels") the labels that are neither named nor highlighted
also keep ``SPACING`` pixels from every other, and the highlighted ones are all shown.
"""

from __future__ import annotations

import numpy as np
import pytest

from halfedge_edu import figures
from halfedge_edu.core.ops import OperationLog, collapse
from halfedge_edu.data import sample
from halfedge_edu.viz import (CollapseAtlas, CollapseStepper, FlipStepper, HalfedgeScene, LoopStepper,
                              OneRingViewer, SplitStepper)
from halfedge_edu.viz import labels as labels_module
from halfedge_edu.viz import pictures, scene as scene_module
from halfedge_edu.viz.labels import PREFIX, SPACING, label_boxes, overlapping_labels, place
from halfedge_edu.viz.palette import ROLES

#: Label boxes checked by this module's tests, by test (printed with ``-s``).
CHECKED: dict[str, int] = {}


def _readable(plotter, where: str) -> int:
    """Assert the labels ``plotter`` shows can all be read; return how many boxes were checked."""
    problems = overlapping_labels(plotter)
    assert problems == [], f"{where}: {problems}"
    return len(label_boxes(plotter))


def _record(name: str, count: int) -> None:
    CHECKED[name] = count
    print(f"{name}: {count} label boxes checked")


def test_the_check_finds_two_labels_on_one_spot():
    import pyvista as pv

    plotter = pv.Plotter(off_screen=True, window_size=[300, 200])
    try:
        data = pv.PolyData(np.zeros((2, 3)))
        data.point_data["labels"] = np.array(["v1", "v2"])
        plotter.add_point_labels(data, "labels", name="vertex_labels", font_size=12, always_visible=True,
                                 show_points=False, justification_horizontal="left", justification_vertical="bottom")
        assert overlapping_labels(plotter) == [("v1", "v2")]
    finally:
        plotter.close()


def test_a_measured_box_holds_every_pixel_of_its_label(closing):
    scene = HalfedgeScene(sample("strip"), legend=False)
    closing(scene)
    scene.set_roles({"current": [0]})
    texts = dict(label_boxes(scene.plotter))
    scene.plotter.set_background("#FF00FF")     # a colour no label uses
    for actor_name, actor in scene.plotter.actors.items():
        if not actor_name.endswith("-labels"):
            actor.SetVisibility(False)
    scene.plotter.render()
    image = np.asarray(scene.plotter.screenshot(return_img=True))
    rows, columns = np.nonzero((image != (255, 0, 255)).any(axis=2))
    height = image.shape[0]
    inside = np.zeros(len(rows), dtype=bool)
    for box in texts.values():
        x0, y0, x1, y1 = box
        inside |= (columns >= x0 - 1) & (columns <= x1 + 1) & (height - 1 - rows >= y0 - 1) & (height - 1 - rows <= y1 + 1)
    assert len(texts) >= 10 and inside.all()


def test_place_moves_a_label_off_another_and_drops_one_without_room():
    anchors = np.array([[50.0, 50.0], [50.0, 50.0], [50.0, 50.0]])
    sizes = np.array([[30.0, 14.0], [30.0, 14.0], [200.0, 14.0]])
    centres = place(anchors, sizes, [0.0, 0.0, 0.0], np.zeros((0, 3)), np.zeros((0, 4)), (100, 100))
    assert np.allclose(centres[0], [50.0, 50.0])
    assert np.abs(centres[1] - centres[0]).max() >= 14.0      # moved clear of the first
    assert np.isnan(centres[2]).all()                           # wider than the picture


def _named_picture_plotter(mesh, log, camera, closing):
    """Chapter 07's opening picture: the collapse's elements labelled by their names."""
    names = {}
    for name, element in log.named.items():
        names[element] = f"{names[element]}/{name}" if element in names else name
    named = lambda kind: [i for k, i in log.named.values() if k == kind]  # noqa: E731
    scene = HalfedgeScene(mesh, window_size=(380, 290), legend=False, labels=("vertex",), follow=False)
    closing(scene)
    if camera is not None:
        scene.plotter.camera_position = camera
    scene.set_roles({"named": named("halfedge"), "named_vertex": named("vertex"), "named_face": named("face")},
                    names=names)
    return scene



def _place_one_candidate_at_a_time(anchors, sizes, keep_clear, dots, obstacles, window_size,
                                   optional) -> np.ndarray:
    """The rule of ``place`` written candidate by candidate: each label takes the first place
    around its anchor (nearest first) whose box is inside the picture and overlaps no label
    placed before (a pixel apart; ``SPACING`` pixels for an optional label), no obstacle
    (a pixel apart) and no dot. An optional label takes only the two rings of places
    nearest its anchor."""
    width, height = window_size
    placed, centres = [], np.full((len(anchors), 2), np.nan)
    for i, (anchor, (w, h), clear, spare) in enumerate(zip(anchors, sizes, keep_clear, optional)):
        if clear > 0:
            rings = (1.0, 1.8) if spare else (1.0, 1.8, 2.8)
            places = [anchor + np.array([dx * (reach * clear + w / 2), dy * (reach * clear + h / 2)])
                      for reach in rings for dx, dy in labels_module.DIRECTIONS]
        else:
            step_x, step_y = max(0.4 * w, 6.0), 0.6 * h
            rings = (1, 2) if spare else (1, 2, 3)
            places = [anchor.copy()] + [anchor + np.array([dx * ring * step_x, dy * ring * step_y])
                                        for ring in rings for dx, dy in labels_module.AROUND]
        gap = SPACING if spare else 1.0
        for centre in places:
            box = np.array([centre[0] - w / 2, centre[1] - h / 2, centre[0] + w / 2, centre[1] + h / 2])
            if box[0] < 0 or box[1] < 0 or box[2] > width or box[3] > height:
                continue
            near = [other for other in placed
                    if box[0] < other[2] + gap and other[0] < box[2] + gap
                    and box[1] < other[3] + gap and other[1] < box[3] + gap]
            near += [other for other in obstacles
                     if box[0] < other[2] + 1 and other[0] < box[2] + 1
                     and box[1] < other[3] + 1 and other[1] < box[3] + 1]
            nearest = np.clip(dots[:, :2], box[:2], box[2:])                # (d, 2)
            if near or (((nearest - dots[:, :2]) ** 2).sum(axis=1) < dots[:, 2] ** 2).any():
                continue
            centres[i] = centre
            placed.append(box)
            break
    return centres


@pytest.mark.parametrize("seed", range(20))
def test_place_takes_the_same_places_as_the_rule_written_one_candidate_at_a_time(seed):
    """``place`` decides every candidate's picture, dot and obstacle tests at once; the
    places it picks are exactly the rule's, in a crowd where most first choices are taken."""
    rng = np.random.default_rng(seed)
    k = int(rng.integers(20, 60))
    anchors = rng.uniform(0, 160, size=(k, 2)).round(1)
    sizes = np.column_stack([rng.uniform(10, 60, k), rng.uniform(8, 20, k)]).round(1)
    keep_clear = np.where(rng.random(k) < 0.5, 5.0, 0.0)
    dots = np.column_stack([rng.uniform(0, 160, size=(30, 2)), rng.uniform(2, 6, 30)])
    obstacles = np.array([[120.0, 120.0, 160.0, 160.0]])
    optional = np.sort(rng.random(k) < 0.6)              # the optional ones last, as the scene orders them
    expected = _place_one_candidate_at_a_time(anchors, sizes, keep_clear, dots, obstacles, (160, 160), optional)
    centres = place(anchors, sizes, keep_clear, dots, obstacles, (160, 160), optional)
    without_room = np.isnan(expected[:, 0])
    assert without_room.any() and not without_room.all()              # a crowd, not a wall
    assert np.array_equal(centres, expected, equal_nan=True)

def test_chapter_07_opening_pictures_have_no_label_on_another(closing):
    corner_view = [(-1.9, -2.4, -1.6), (0.5, 0.5, 0.5), (0.0, 0.0, 1.0)]
    count = 0
    for name, camera in (("cube", corner_view), ("single_collapse", None)):
        before = sample(name)
        after, log = before.copy(), OperationLog()
        collapse(after, after.halfedge(0), log=log)
        for mesh in (before, after):
            scene = _named_picture_plotter(mesh, log, camera, closing)
            count += _readable(scene.plotter, f"{name}")
            if mesh is before and name == "cube":
                assert any(text.startswith("gL/gR") for text in scene.labels_shown()["face"])
    _record("chapter 07 opening", count)
    assert count >= 40


@pytest.mark.parametrize("name", ["cube", "single_collapse"])
def test_collapse_stepper_labels_never_overlap(name, closing):
    stepper = CollapseStepper(sample(name), 0, window_size=(480, 360))
    closing(stepper)
    count = 0
    for step in range(stepper.n_steps + 1):
        stepper.go(step)
        count += _readable(stepper.scene.plotter, f"{name} step {step}")
    _record(f"collapse stepper {name}", count)
    assert count > 10 * stepper.n_steps


def test_split_and_flip_steppers_labels_never_overlap(closing):
    count = 0
    for make in (SplitStepper, FlipStepper):
        stepper = make(sample("strip"), 1, window_size=(480, 360))
        closing(stepper)
        for step in range(stepper.n_steps + 1):
            stepper.go(step)
            count += _readable(stepper.scene.plotter, f"{make.__name__} step {step}")
    _record("split and flip steppers", count)
    assert count > 100


def test_collapse_atlas_labels_never_overlap_in_any_phase(closing):
    atlas = CollapseAtlas()
    closing(atlas)
    count = sum(_readable(s.scene.plotter, f"refused {s.log.edge}") for s in atlas.refused)
    for phase in range(len(atlas.phases) + 1):
        atlas.go(phase)
        count += sum(_readable(s.scene.plotter, f"phase {phase}") for s in atlas.steppers)
    _record("collapse atlas", count)
    assert count > 100


def test_bunny_one_ring_viewer_labels_never_overlap(bunny, closing):
    viewer = OneRingViewer(bunny, 100)
    closing(viewer)
    count = 0
    for move in ("ccw", "ccw", "tip", "cw", 2000, "ccw"):
        viewer.go(move)
        count += _readable(viewer.scene.plotter, f"bunny after {move}")
    _record("bunny one-ring viewer", count)
    assert count > 30


def test_every_figure_has_readable_labels(tmp_path, monkeypatch):
    checked: list[int] = []
    encode = pictures.plotter_png

    def checked_png(plotter, path=None, **options):
        checked.append(_readable(plotter, "a figure"))
        return encode(plotter, path, **options)

    for module in (pictures, scene_module, figures):
        monkeypatch.setattr(module, "plotter_png", checked_png)
    assert figures.main(["--out", str(tmp_path)]) == 0
    _record("figures", sum(checked))
    assert sum(checked) > 100


def test_labels_module_lists_a_label_without_room(closing):
    # A tiny picture of the cube with every halfedge highlighted: not all their labels
    # fit, the rest are listed.
    scene = HalfedgeScene(sample("cube"), window_size=(160, 120), legend=False, labels=True)
    closing(scene)
    scene.set_roles({"named": range(scene.mesh.n_halfedges)})
    listing = scene.plotter.actors[labels_module.LIST_ACTOR]
    assert listing.GetVisibility() and listing.GetInput().startswith("no room for: ")
    assert overlapping_labels(scene.plotter) == []


def test_place_leaves_out_an_optional_label_that_would_crowd_one_placed_before():
    anchors = np.array([[50.0, 50.0], [50.0, 50.0], [50.0, 50.0 + 14.0 + SPACING + 1.0]])
    sizes = np.array([[30.0, 14.0], [30.0, 14.0], [30.0, 14.0]])
    centres = place(anchors, sizes, [0.0, 0.0, 0.0], np.zeros((0, 3)), np.zeros((0, 4)), (100, 100),
                    optional=[False, True, True])
    assert np.allclose(centres[0], [50.0, 50.0])
    assert np.isnan(centres[1]).all()                        # would have to stray from its anchor
    assert np.allclose(centres[2], anchors[2])               # far enough: shown on its anchor
    kept = place(anchors, sizes, [0.0, 0.0, 0.0], np.zeros((0, 3)), np.zeros((0, 4)), (100, 100))
    assert not np.isnan(kept).any()                          # not optional: moved, not left out


def _gap(a: np.ndarray, b: np.ndarray) -> float:
    """The distance in pixels between two boxes ``(x0, y0, x1, y1)`` along x or y, whichever
    is larger (negative when they overlap): what ``labels.overlaps`` compares with its gap."""
    return float(max(b[0] - a[2], a[0] - b[2], b[1] - a[3], a[1] - b[3]))


def _highlighted_texts(scene) -> set[str]:
    """The labels of the highlighted elements that face the camera (a label whose element
    faces away is left out on purpose: a halfedge's twin over a ridge)."""
    mesh, eye = scene.mesh, np.array(scene.plotter.camera.position)

    def facing(kind: str, index: int) -> bool:
        face = int(mesh.halfedge_face[index]) if kind == "halfedge" else index
        if kind == "vertex" or face < 0:
            return True
        a, b, c = mesh.positions[mesh.face_vertices()[face]]
        return float(np.cross(b - a, c - a) @ (eye - (a + b + c) / 3)) > 0

    return {f"{PREFIX[ROLES[role].kind]}{int(i)}" for role, members in scene.roles.items() for i in members
            if facing(ROLES[role].kind, int(i))}


@pytest.mark.parametrize("name, labels", [("bunny", True), ("bunny", "auto"), ("icosphere", True),
                                          ("icosphere", "auto")])
def test_on_a_dense_mesh_no_label_crowds_another_and_every_highlighted_one_is_shown(name, labels, closing):
    mesh = sample(name, subdivisions=2) if name == "icosphere" else sample(name)
    scene = HalfedgeScene(mesh, labels=labels)
    closing(scene)
    count = 0
    for h in (0, mesh.n_halfedges // 3, mesh.n_halfedges - 7):
        scene.show_halfedge(h)
        measured = label_boxes(scene.plotter)
        highlighted = _highlighted_texts(scene)
        texts = [text for text, _ in measured]
        assert highlighted <= set(texts), f"halfedge {h}: {highlighted - set(texts)} not shown"
        assert not scene.plotter.actors.get(labels_module.LIST_ACTOR) or \
            not scene.plotter.actors[labels_module.LIST_ACTOR].GetVisibility()
        crowded = [(a, b, round(_gap(box_a, box_b), 1))
                   for i, (a, box_a) in enumerate(measured) for b, box_b in measured[i + 1:]
                   if not {a, b} <= highlighted and _gap(box_a, box_b) < SPACING - 1.0]   # 1 px: rounding
        assert crowded == [], f"halfedge {h}: labels closer than {SPACING} px: {crowded}"
        count += len(measured)
        assert len(set(texts) - highlighted) >= 5, "hardly any other label is shown"
    _record(f"dense {name} labels={labels}", count)


def test_loop_stepper_vertex_numbers_never_crowd_and_each_steps_own_are_written(closing):
    """The Loop stepper's numbers (a painted scene's, not a HalfedgeScene's) on a mesh of
    42 vertices, where beside-every-dot numbers ran into each other near the outline."""
    stepper = LoopStepper(sample("icosphere", subdivisions=0), mode="static")
    closing(stepper)
    count = 0
    for step in range(stepper.n_steps + 1):
        stepper.go(step)
        record = stepper.records[step]
        mesh, eye = record.mesh, np.array(stepper.scene.plotter.camera.position)
        measured = label_boxes(stepper.scene.plotter)
        texts = {text for text, _ in measured}
        own = {str(v) for v in stepper.step_vertices()
               if ((mesh.positions[v] - mesh.positions[~mesh.vertex_deleted].mean(axis=0))
                   @ (eye - mesh.positions[v])) > 0}                  # on the near side of the sphere
        assert own <= texts, f"step {step}: the step's own vertices {own - texts} are not numbered"
        crowded = [(a, b) for i, (a, box_a) in enumerate(measured) for b, box_b in measured[i + 1:]
                   if not {a, b} <= own and _gap(box_a, box_b) < SPACING - 1.0]
        assert crowded == [], f"step {step}: numbers closer than {SPACING} px: {crowded}"
        count += len(measured)
    _record("loop stepper numbers", count)
    assert count > 10 * stepper.n_steps
