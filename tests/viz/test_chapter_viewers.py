"""The chapters' viewers and picture helpers, moved into viz: chapter 05's SmoothingViewer,
chapters 06-07's named_picture, chapter 08's draw_link and LinkViewer."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from halfedge_edu.core.ops import OperationLog, collapse, flip
from halfedge_edu.data import sample
from halfedge_edu.viz import HalfedgeExplorer, LinkViewer, SmoothingViewer, created_roles, draw_link, gathered_roles, link_png
from halfedge_edu.viz import named_picture
from halfedge_edu.viz.palette import ROLES, rgb
from halfedge_edu.viz.smoothing_viewer import enclosed_volume


def _pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def _has_colour(picture: np.ndarray, color: str, at_least: int = 20) -> bool:
    return int((np.abs(picture.astype(np.int16) - rgb(color)).max(axis=2) <= 3).sum()) >= at_least


# -- chapter 08 ---------------------------------------------------------------------------

def _painted_roles(mesh, e) -> set[str]:
    """The palette roles whose colours :func:`draw_link` gave its actors."""
    import pyvista as pv

    plotter = pv.Plotter(off_screen=True, window_size=[320, 300])
    try:
        draw_link(plotter, mesh, e)
        colours = {tuple(int(round(255 * c)) for c in actor.prop.color.float_rgb)
                   for actor in plotter.actors.values() if hasattr(actor, "prop")}
    finally:
        plotter.close()
    return {name for name, role in ROLES.items() if tuple(int(c) for c in rgb(role.color)) in colours
            and name.startswith("link_")}


def test_draw_link_paints_each_set_in_its_palette_role_colour():
    assert _painted_roles(sample("cube"), 1) == {"link_a", "link_b", "link_shared", "link_extra", "link_edge"}


def test_an_allowed_collapse_paints_nothing_in_the_extra_colour():
    assert _painted_roles(sample("single_collapse"), 0) == {"link_a", "link_b", "link_shared", "link_edge"}


def test_link_png_draws_the_edge_in_its_role_colour():
    picture = _pixels(link_png(sample("single_collapse"), 0, (0, 0, 1)))
    assert _has_colour(picture, ROLES["link_edge"].color, at_least=10)


def test_the_link_viewer_follows_its_controls_and_says_the_sets(closing):
    viewer = LinkViewer("cube", 1, mode="static")
    closing(viewer)
    assert viewer.describe().splitlines()[-1] == "collapse refused (link-condition)"
    viewer.edge_choice.value = 3
    assert viewer.describe().startswith("cube, edge 3 ") and viewer.describe().endswith("collapse allowed")
    viewer.mesh_choice.value = "open_patch"
    viewer.edge_choice.value = 11
    text = viewer.describe()
    assert text.startswith("open_patch, edge 11") and "∂" in text
    assert viewer.edge_choice.max == sample("open_patch").n_edges - 1
    assert "∂" in viewer.text.value


def test_the_link_viewer_uses_the_renderers_mode_choice(closing, monkeypatch):
    import ipywidgets as widgets

    monkeypatch.setenv("HALFEDGE_EDU_VIZ", "static")
    viewer = LinkViewer("tetrahedron", 0)
    closing(viewer)
    assert viewer.mode == "static"
    assert isinstance(viewer.view.widget, widgets.Image)
    before = viewer.screenshot()
    viewer.edge_choice.value = 2
    assert viewer.screenshot() != before              # the static picture follows the slider
    bundle = viewer._repr_mimebundle_()
    assert bundle["text/plain"] == viewer.describe() and "image/png" in bundle


# -- chapter 05 ---------------------------------------------------------------------------

def test_the_smoothing_viewer_redraws_for_its_slider_and_its_shading(closing):
    viewer = SmoothingViewer(sample("spot"), max_iterations=10, window_size=(200, 160))
    closing(viewer)
    first = viewer.image.value
    assert viewer.describe() == f"0 iterations, flat shading: volume {enclosed_volume(sample('spot')):.4f}"
    viewer.iterations.value = 10
    assert viewer.describe().startswith("10 iterations, flat shading")
    assert enclosed_volume(viewer.smoothed) < enclosed_volume(sample("spot"))   # smoothing shrinks
    assert viewer.image.value != first
    viewer.shading.value = "smooth"
    assert viewer.describe().startswith("10 iterations, smooth shading")
    assert viewer.actor.prop.interpolation.name.lower() in ("gouraud", "phong")


def test_enclosed_volume_of_the_unit_cube_sample_is_its_volume():
    cube = sample("cube")
    extent = np.ptp(cube.positions, axis=0)
    assert enclosed_volume(cube) == pytest.approx(float(np.prod(extent)))


# -- chapters 06 and 07 -------------------------------------------------------------------

def test_named_picture_colours_the_gathered_elements_in_their_roles():
    mesh, log = sample("strip"), OperationLog()
    flipped = mesh.copy()
    flip(flipped, 1, log=log)
    roles = gathered_roles(log)
    assert sorted(roles["named"]) == sorted(i for k, i in log.named.values() if k == "halfedge")
    picture = _pixels(named_picture(mesh, log, size=(400, 300)))
    assert _has_colour(picture, ROLES["named"].color)
    plain = _pixels(named_picture(mesh, log, {}, size=(400, 300)))
    assert not _has_colour(plain, ROLES["named"].color)


def test_created_roles_are_what_the_split_log_created():
    from halfedge_edu.core.ops import split

    mesh, log = sample("strip"), OperationLog()
    split(mesh, 1, log=log)
    roles = created_roles(log)
    assert roles["created_vertex"] == [mesh.n_vertex_slots - 1]
    assert len(roles["created"]) == 6 and len(roles["created_face"]) == 2


def test_named_picture_joins_the_names_of_an_element_named_twice(monkeypatch):
    cube = sample("cube")
    after, log = cube.copy(), OperationLog()
    collapse(after, after.halfedge(0), log=log)
    twice = [element for element in set(log.named.values()) if len(log.names_of(*element)) > 1]
    assert twice, "the cube's collapse names some element twice (gL/gR)"
    captured = {}

    def spy(scene):
        captured.update(scene.names)

    import halfedge_edu.viz.scene as scene_module

    original = scene_module.scene_picture
    monkeypatch.setattr(scene_module, "scene_picture",
                        lambda mesh, show, **options: original(mesh, lambda s: (show(s), spy(s)), **options))
    named_picture(cube, log, size=(200, 150))
    assert captured[twice[0]] == "/".join(log.names_of(*twice[0]))


@pytest.mark.parametrize("make", [lambda: LinkViewer("cube", 1, mode="static"),
                                  lambda: HalfedgeExplorer(sample("tetrahedron"), mode="static")],
                         ids=["link viewer", "explorer"])
def test_a_client_side_view_displays_without_asking_the_kernel_for_a_picture(make, monkeypatch):
    """A client-side live view (vtk.js draws) has no kernel picture: the bundle leaves the
    PNG out instead of asking for one; any other view gives it, for viewers without widgets."""
    viewer = make()
    try:
        bundle = viewer._repr_mimebundle_()
        assert bundle["image/png"] and bundle["text/plain"] == viewer.describe()

        def no_picture(*_args, **_kwargs):
            raise AttributeError("This plotter has not yet been set up and rendered with ``show()``.")

        monkeypatch.setattr(viewer.scene.plotter, "suppress_rendering", True, raising=False)
        monkeypatch.setattr(viewer, "screenshot", no_picture)
        bundle = viewer._repr_mimebundle_()
        assert "image/png" not in bundle and bundle["text/plain"] == viewer.describe()
    finally:
        viewer.close()
