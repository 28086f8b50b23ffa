"""Optional progress bars: tqdm when it is installed and asked for, nothing otherwise."""

from __future__ import annotations

from typing import Iterable


def progress_range(n: int, enabled: bool, description: str) -> Iterable[int]:
    """``range(n)``, wrapped in a ``tqdm.auto`` bar when ``enabled`` and tqdm is installed.

    ``tqdm.auto`` draws a widget in Jupyter and a text bar in a terminal. Without
    tqdm the loop simply runs without a bar (no warning: a bar is a convenience).
    """
    if enabled:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            return range(n)
        return tqdm(range(n), desc=description, total=n)
    return range(n)
