"""Composing still pictures for notebooks: several views in one row, each with a title."""

from __future__ import annotations

import io


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
    from IPython.display import Image
    from PIL import Image as PILImage
    from PIL import ImageDraw, ImageFont

    title_height = font_size + 11
    pictures = [PILImage.open(io.BytesIO(png)).convert("RGB") for png in pngs]
    row = PILImage.new(
        "RGB", (sum(p.width for p in pictures), max(p.height for p in pictures) + title_height), "white"
    )
    font = ImageFont.load_default(size=font_size)
    x = 0
    for picture, title in zip(pictures, titles):
        row.paste(picture, (x, title_height))
        ImageDraw.Draw(row).text((x + 10, 4), title, fill="black", font=font)
        x += picture.width
    return Image(png_bytes(row))


def png_bytes(image, path=None) -> bytes:
    """A PIL image encoded as PNG bytes; also written to ``path`` if one is given."""
    buffer = io.BytesIO()
    image.save(buffer, format="png")
    data = buffer.getvalue()
    if path is not None:
        with open(path, "wb") as file:
            file.write(data)
    return data
