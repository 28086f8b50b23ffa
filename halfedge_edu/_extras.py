"""Say which extra to install when an optional dependency is missing.

``import halfedge_edu`` needs numpy only; the pictures and widgets need the notebooks
extra. Without it, a bare ``ModuleNotFoundError: No module named 'pyvista'`` does not
tell a student what to do, so :func:`require` raises :class:`MissingExtraError`, a
``ModuleNotFoundError`` (code catching that still works) whose message names the
``pip install`` command.
"""

from __future__ import annotations

import importlib.util

PACKAGE = "halfedge_edu"

# The modules each extra provides that the package imports, by extra.
EXTRA_MODULES: dict[str, tuple[str, ...]] = {
    "notebooks": ("pyvista", "ipywidgets", "ipyevents"),
}


class MissingExtraError(ModuleNotFoundError):
    """An optional dependency is not installed; the message names the extra that brings it."""


def missing_modules(extra: str) -> list[str]:
    """The modules of ``extra`` that this Python cannot import, without importing any of them."""
    return [name for name in EXTRA_MODULES[extra] if importlib.util.find_spec(name) is None]


def require(extra: str, feature: str) -> None:
    """Raise :class:`MissingExtraError` if a module of ``extra`` is missing; ``feature`` is what needed it."""
    missing = missing_modules(extra)
    if missing:
        raise MissingExtraError(
            f"{feature} needs {' and '.join(missing)}, which {'is' if len(missing) == 1 else 'are'} "
            f'not installed: pip install "{PACKAGE}[{extra}]"',
            name=missing[0],
        )
