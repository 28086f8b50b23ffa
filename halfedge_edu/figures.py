"""Every still picture the README and the notebooks' text use, made by one command.

    python -m halfedge_edu.figures                  # writes figures/*.png at the repository root
    python -m halfedge_edu.figures --out somewhere  # elsewhere
    python -m halfedge_edu.figures --only cube      # just some of them (names without .png)
    python -m halfedge_edu.figures --check          # exit 1 if a file in figures/ is out of date
    python -m halfedge_edu.figures --list           # the names and what each shows

The pictures are deterministic: a fixed camera for each, no randomness, and the same
bytes on every run on the same machine (Mesa's software renderer on a headless Linux
box; another OpenGL driver may round pixels differently). Each is made by the same
scenes and widgets the notebooks use, in static mode.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path
from typing import Callable

from .viz.pictures import TitleStyle, grid_png, plotter_png
from .viz.scene import scene_picture

#: name -> (what it shows, function returning PNG bytes); filled by @figure below.
FIGURES: dict[str, tuple[str, Callable[[], bytes]]] = {}


def figure(name: str, caption: str):
    """Register a function returning PNG bytes as the figure ``name``.png."""

    def register(make: Callable[[], bytes]) -> Callable[[], bytes]:
        FIGURES[name] = (caption, make)
        return make

    return register


def _headless() -> None:
    """The settings measured for rendering with no screen (see the notebooks notes)."""
    empty = os.path.join(tempfile.gettempdir(), "halfedge_edu-vtk-wasm-empty")
    os.makedirs(empty, exist_ok=True)
    if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    os.environ.setdefault("PYVISTA_JUPYTER_BACKEND", "static")
    os.environ.setdefault("VTK_WASM_DIR_OVERRIDE", empty)


def _widget_picture(widget, *moves) -> bytes:
    try:
        for move in moves:
            widget.go(move)
        return widget.screenshot()
    finally:
        widget.close()


#: Titles above the pictures of a figure row: a little larger than the notebooks' own.
FIGURE_TITLES = TitleStyle(font_size=18, band=30, left=12, top=6, color=(20, 20, 20))


def _row(pictures: list[bytes], titles: list[str]) -> bytes:
    """PNGs side by side on white, each with its title above it."""
    return grid_png([pictures], [titles], style=FIGURE_TITLES)


def _two_triangles():
    from .core.mesh import HalfedgeMesh

    return HalfedgeMesh.from_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])


@figure("two_triangles", "two triangles sharing an edge: every halfedge, twins and boundary, with indices")
def two_triangles() -> bytes:
    return scene_picture(_two_triangles(), labels=True, legend=True)


@figure("navigation", "the open patch with halfedge 7 and its twin, next, prev, origin, tip and face")
def navigation() -> bytes:
    from .data import sample

    return scene_picture(sample("open_patch"), lambda s: s.show_halfedge(7), labels=True)


@figure("boundary", "a boundary halfedge of the open patch: no face, next and prev run along the hole")
def boundary() -> bytes:
    from .data import sample

    mesh = sample("open_patch")
    h = int(mesh.boundary_loops()[0][0])
    return scene_picture(mesh, lambda s: s.show_halfedge(h))


@figure("one_ring", "the one-ring of vertex 5 of the open patch: outgoing halfedges, neighbours, faces")
def one_ring() -> bytes:
    from .data import sample

    mesh = sample("open_patch")
    return scene_picture(mesh, lambda s: s.show_one_ring(5, current=mesh.vertex(5).halfedge.index))


@figure("cube", "the cube's halfedge 0 with its neighbours, every element labelled")
def cube() -> bytes:
    from .data import sample

    return scene_picture(sample("cube"), lambda s: s.show_halfedge(0))


@figure("cube_large", "the same in the lecture-hall preset (preset='large')")
def cube_large() -> bytes:
    from .data import sample

    return scene_picture(sample("cube"), lambda s: s.show_halfedge(0), preset="large")


@figure("bunny", "the Stanford bunny, whole")
def bunny() -> bytes:
    import pyvista as pv

    from .data import sample
    from .viz.palette import PRESETS

    look = PRESETS["default"]
    plotter = pv.Plotter(off_screen=True, window_size=list(look.window_size), lighting="none")
    try:
        plotter.add_light(pv.Light(light_type="headlight"))
        plotter.set_background(look.background)
        plotter.add_mesh(sample("bunny").to_pyvista(), color=look.surface, ambient=0.3, diffuse=0.7,
                         smooth_shading=True)
        plotter.view_xy()
        plotter.camera.zoom(1.3)
        return plotter_png(plotter)
    finally:
        plotter.close()


@figure("bunny_closeup", "on the bunny only the arrows and labels near the highlight are drawn")
def bunny_closeup() -> bytes:
    from .data import sample

    mesh = sample("bunny")
    return scene_picture(mesh, lambda s: s.show_halfedge(int(mesh.boundary_loops()[0][0]) ^ 1))


@figure("flip", "edge flip of the open patch's edge 12: gathered elements, then the result")
def flip() -> bytes:
    from .data import sample
    from .viz import FlipStepper

    first = _widget_picture(FlipStepper(sample("open_patch"), 12, mode="static"), "start")
    last = _widget_picture(FlipStepper(sample("open_patch"), 12, mode="static"), "end")
    return _row([first, last], ["before: the gathered elements", "after the flip"])


@figure("split", "edge split of the open patch's edge 12: gathered elements, then the result")
def split() -> bytes:
    from .data import sample
    from .viz import SplitStepper

    first = _widget_picture(SplitStepper(sample("open_patch"), 12, mode="static"), "start")
    last = _widget_picture(SplitStepper(sample("open_patch"), 12, mode="static"), "end")
    return _row([first, last], ["before: the gathered elements", "after the split (new elements in blue)"])


@figure("collapse_cases", "collapse with the removed vertex of degree 3 (cube) and > 3, before and after")
def collapse_cases() -> bytes:
    from .data import sample
    from .viz import CollapseStepper

    size = (440, 330)
    pictures = []
    for name in ("cube", "single_collapse"):
        for move in ("start", "end"):
            pictures.append(_widget_picture(CollapseStepper(sample(name), 0, mode="static", window_size=size), move))
    return _row(pictures, ["degree 3: before", "degree 3: after", "degree > 3: before", "degree > 3: after"])


@figure("collapse_refused", "collapses the link condition refuses: tetrahedron, figure 8, lone triangle")
def collapse_refused() -> bytes:
    from .viz import CollapseAtlas

    # The atlas's pictures of the refusals: seen at a slant, their vertices labelled.
    atlas = CollapseAtlas(mode="static")
    try:
        return _row([stepper.screenshot() for stepper in atlas.refused], atlas.refused_titles)
    finally:
        atlas.close()


def default_folder() -> Path:
    """``figures/`` at the repository root when run from a checkout, else in the current folder."""
    root = Path(__file__).resolve().parents[1]
    return root / "figures" if (root / "pyproject.toml").exists() else Path.cwd() / "figures"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m halfedge_edu.figures", description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=None, help="folder to write into (default: figures/)")
    parser.add_argument("--only", nargs="+", metavar="NAME", help="make only these figures")
    parser.add_argument("--check", action="store_true", help="compare with the files instead of writing")
    parser.add_argument("--list", action="store_true", help="list the figures and exit")
    args = parser.parse_args(argv)
    if args.list:
        for name, (caption, _) in FIGURES.items():
            print(f"{name + '.png':<24}{caption}")
        return 0
    names = args.only or list(FIGURES)
    unknown = [name for name in names if name not in FIGURES]
    if unknown:
        parser.error(f"unknown figure(s) {', '.join(unknown)}; see --list")
    _headless()
    folder = args.out or default_folder()
    folder.mkdir(parents=True, exist_ok=True)
    stale = []
    for name in names:
        data = FIGURES[name][1]()
        path = folder / f"{name}.png"
        if args.check:
            if not path.exists() or path.read_bytes() != data:
                stale.append(path.name)
            continue
        if not path.exists() or path.read_bytes() != data:
            temporary = path.with_suffix(".png.tmp")
            temporary.write_bytes(data)
            temporary.replace(path)
            print(f"wrote {path}")
        else:
            print(f"unchanged {path}")
    if stale:
        print(f"out of date: {', '.join(stale)} (run python -m halfedge_edu.figures)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
