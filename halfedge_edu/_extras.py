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


# Modules an extra brings without naming them itself (its requirements do), by extra:
# what the command line needs from the notebooks extra (grade runs notebooks with
# nbclient and nbformat, which come with jupyterlab; --progress draws with tqdm).
BROUGHT_MODULES: dict[str, tuple[str, ...]] = {
    "notebooks": ("tqdm", "nbclient", "nbformat", "ipykernel"),
}


def extra_for(module: str | None) -> str | None:
    """The extra that installs ``module`` (a top-level module name, or a submodule of one), or None."""
    top = (module or "").split(".")[0]
    for table in (EXTRA_MODULES, BROUGHT_MODULES):
        for extra, modules in table.items():
            if top in modules:
                return extra
    return None


def install_hint(extra: str) -> str:
    """The command that installs ``extra``."""
    return f'pip install "{PACKAGE}[{extra}]"'


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
            f"not installed: {install_hint(extra)}",
            name=missing[0],
        )
