"""Still pictures: a plotter's screenshot as PNG, and several PNGs in rows with titles.

    png = plotter_png(plotter)                       # what the plotter shows, as PNG bytes
    side_by_side([png_a, png_b], ["before", "after"])   # one row, shown by a notebook cell
    grid([[a, b], [c, d]], [["1", "2"], ["3", "4"]])    # rows of pictures, each titled

Every picture the package makes (figures, stepper screenshots, the chapters' rows of
pictures) is encoded and pasted here, so they all look alike and encode the same way.
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class TitleStyle:
    """How titles above pictures look.

    Attributes:
        font_size: in pixels.
        band: the height of the strip above each row that holds its titles.
        left, top: where a title starts, in pixels from its picture's band corner.
        color: the text colour (a name or an RGB tuple).
    """

    font_size: int = 15
    band: int = 26
    left: int = 10
    top: int = 4
    color: "str | tuple[int, int, int]" = "black"


#: The notebooks' titles.
NOTEBOOK_TITLES = TitleStyle()


def png_bytes(image, path=None) -> bytes:
    """A PIL image encoded as PNG bytes; also written to ``path`` if one is given."""
    buffer = io.BytesIO()
    image.save(buffer, format="png")
    data = buffer.getvalue()
    if path is not None:
        with open(path, "wb") as file:
            file.write(data)
    return data


def plotter_png(plotter, path=None, *, window_size: tuple[int, int] | None = None) -> bytes:
    """Render ``plotter`` and return what it shows as PNG bytes (also written to ``path``).

    ``window_size`` resizes the render window first (pyvista's own screenshot option).
    """
    from PIL import Image

    plotter.render()
    pixels = plotter.screenshot(None, return_img=True, window_size=None if window_size is None else list(window_size))
    return png_bytes(Image.fromarray(np.asarray(pixels)), path)


def grid_png(rows: list[list[bytes]], titles: list[list[str]] | None = None, *,
             style: TitleStyle = NOTEBOOK_TITLES, path=None) -> bytes:
    """Paste rows of PNG pictures into one PNG, each picture with its title above it.

    Args:
        rows: the pictures, row by row, as PNG bytes. A row is as tall as its tallest
            picture; the sheet is as wide as its widest row; the rest is white.
        titles: one title per picture, in the same rows; None for no titles (and no band).
        style: the titles' size, place and colour.
        path: also write the PNG here.
    """
    from PIL import Image, ImageDraw, ImageFont

    pictures = [[Image.open(io.BytesIO(png)).convert("RGB") for png in row] for row in rows if row]
    band = style.band if titles else 0
    heights = [max(p.height for p in row) + band for row in pictures]
    sheet = Image.new("RGB", (max(sum(p.width for p in row) for row in pictures), sum(heights)), "white")
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default(size=style.font_size) if titles else None
    y = 0
    for r, (row, height) in enumerate(zip(pictures, heights)):
        x = 0
        for c, picture in enumerate(row):
            sheet.paste(picture, (x, y + band))
            if titles:
                draw.text((x + style.left, y + style.top), titles[r][c], fill=style.color, font=font)
            x += picture.width
        y += height
    return png_bytes(sheet, path)


def grid(rows: list[list[bytes]], titles: list[list[str]], *, font_size: int = 15):
    """Rows of PNG pictures with titles, as an ``IPython.display.Image`` a notebook cell shows
    (its ``.data`` holds the PNG bytes). See :func:`grid_png`."""
    from IPython.display import Image

    style = TitleStyle(font_size=font_size, band=font_size + 11)
    return Image(grid_png(rows, titles, style=style))


def side_by_side(pngs: list[bytes], titles: list[str], *, font_size: int = 15):
    """Paste PNG pictures into one row, each with its title above it.

    Args:
        pngs: the pictures as PNG bytes (e.g. from ``scene.screenshot()``).
        titles: one title per picture.
        font_size: title size in pixels.

    Returns:
        An ``IPython.display.Image`` (its ``.data`` holds the PNG bytes), so a
        notebook cell that ends with it shows the row.
    """
    return grid([pngs], [titles], font_size=font_size)


def surface_png(mesh, *, size: tuple[int, int] = (380, 320), view=(1.0, 1.0, 1.0), view_up=(0.0, 1.0, 0.0),
                zoom: float = 1.0, boundary_color: str | None = None) -> bytes:
    """A plain picture of ``mesh``: the surface with its edges, on white, as PNG bytes.

    For showing what an algorithm made (chapters 10 to 13), without arrows or labels.

    Args:
        size: the picture's (width, height) in pixels.
        view: (3,) the direction from the mesh toward the camera.
        view_up: (3,) the direction that points up in the picture.
        zoom: pyvista's camera zoom after fitting the mesh.
        boundary_color: draw the boundary edges thick in this colour (None: not at all).
    """
    import pyvista as pv

    V, F = mesh.to_arrays()
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    try:
        plotter.set_background("white")
        plotter.add_mesh(pv.PolyData.from_regular_faces(V, F), color="#E9E6DF", show_edges=True,
                         edge_color="#555555", line_width=0.8)
        if boundary_color is not None:
            rim = np.flatnonzero((mesh.halfedge_face < 0) & ~mesh.halfedge_deleted)     # boundary halfedges
            ends = np.stack([mesh.halfedge_vertex[rim], mesh.halfedge_vertex[rim ^ 1]], axis=1)
            lines = np.hstack([np.full((len(rim), 1), 2), ends]).ravel()
            plotter.add_mesh(pv.PolyData(mesh.positions.copy(), lines=lines), color=boundary_color, line_width=4)
        plotter.view_vector(view, viewup=view_up)
        plotter.camera.zoom(zoom)
        return plotter_png(plotter)
    finally:
        plotter.close()


def legend_png(entries: list[tuple[str, str, str]], *, style: TitleStyle = NOTEBOOK_TITLES,
               width: int = 230) -> bytes:
    """A legend as a PNG, one row per ``(text, "#RRGGBB", kind)`` entry (what
    ``scene.legend_entries()`` gives): an arrow, dot or square in the colour, then the
    text, at the titles' font size. For still pictures whose scenes have no legend."""
    from PIL import Image, ImageDraw, ImageFont

    row = int(style.font_size * 1.6)
    sheet = Image.new("RGB", (width, row * len(entries) + style.top * 2), "white")
    draw = ImageDraw.Draw(sheet)
    font = ImageFont.load_default(size=style.font_size)
    for i, (text, color, kind) in enumerate(entries):
        top = style.top + i * row
        middle = top + row // 2
        x0, x1 = style.left, style.left + 2 * style.font_size
        if kind == "halfedge":
            draw.line([(x0, middle), (x1 - 6, middle)], fill=color, width=3)
            draw.polygon([(x1, middle), (x1 - 8, middle - 5), (x1 - 8, middle + 5)], fill=color)
        elif kind == "vertex":
            radius = style.font_size // 2
            centre = (x0 + x1) // 2
            draw.ellipse([centre - radius, middle - radius, centre + radius, middle + radius], fill=color)
        else:
            draw.rectangle([x0, middle - style.font_size // 2, x1, middle + style.font_size // 2], fill=color)
        draw.text((x1 + 8, middle), text, fill=style.color, font=font, anchor="lm")
    return png_bytes(sheet)
