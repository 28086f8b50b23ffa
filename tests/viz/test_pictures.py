"""side_by_side: several PNGs in one titled row."""

from __future__ import annotations

import io

from PIL import Image as PILImage

from halfedge_edu.viz import side_by_side


def _png(width: int, height: int, colour: str) -> bytes:
    buffer = io.BytesIO()
    PILImage.new("RGB", (width, height), colour).save(buffer, format="png")
    return buffer.getvalue()


def test_pictures_are_placed_in_a_row_under_their_titles():
    row = side_by_side([_png(40, 30, "red"), _png(50, 20, "blue")], ["a", "b"], font_size=15)
    picture = PILImage.open(io.BytesIO(row.data)).convert("RGB")
    assert picture.size == (90, 30 + 26)
    assert picture.getpixel((20, 26 + 15)) == (255, 0, 0)      # first picture, below the title band
    assert picture.getpixel((65, 26 + 10)) == (0, 0, 255)      # second picture starts at x = 40
    assert picture.getpixel((65, 26 + 25)) == (255, 255, 255)  # below the shorter one: background
    title_band = [picture.getpixel((x, y)) for x in range(10, 30) for y in range(2, 22)]
    assert any(pixel != (255, 255, 255) for pixel in title_band)  # the title was drawn
