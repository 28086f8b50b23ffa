"""The package's imports run one way: no module imports a layer above its own.

Each module of ``halfedge_edu`` is read with :mod:`ast` (nothing is imported), and every
import in it is collected: module-level ones, the lazy ones inside functions and
methods, relative (``from ..core import x``) and absolute (``import halfedge_edu.io``).
Each import is an arrow from the importing module's layer to the imported module's
layer; an arrow that is not in :data:`ALLOWED` runs up and fails the test, with the
file, the line and the arrow in the message.

And what importing costs: the package's public names load their modules on first use,
so ``import halfedge_edu`` loads none of them.
"""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

import pytest

import halfedge_edu

PACKAGE_DIR = Path(halfedge_edu.__file__).resolve().parent

#: The layer -> layers it may import (besides itself). Why this shape: the mesh (``core``,
#: with its local operations in ``core/ops``) is the foundation and knows nothing above
#: it; reading and writing files (``io``) and the whole-mesh algorithms
#: (``algorithms``) work on the mesh only; the bundled samples (``data``) are files
#: read into meshes; pictures and widgets (``viz``) draw what the layers below make;
#: and only the applications on top (``exercises``, ``figures``, the ``cli``, the
#: ``__main__`` entry point and the top-level ``__init__`` that gathers the public
#: names) may use the pictures and each other. ``package`` is ``halfedge_edu/__init__``.
#: ``_extras`` (which optional packages an extra brings, and the error naming it) and
#: ``live_backend`` (which live view a hub chose, from one environment variable) import
#: nothing of the package, so any layer may ask them.
_BASE = frozenset({"_extras", "live_backend"})
ALLOWED: dict[str, frozenset[str]] = {
    "_extras": frozenset(),
    "live_backend": frozenset(),
    "core": _BASE,
    "io": _BASE | {"core"},
    "algorithms": _BASE | {"core"},
    "data": _BASE | {"core", "io"},
    "viz": _BASE | {"core", "algorithms", "data"},
    "exercises": _BASE | {"core", "io", "algorithms", "data", "viz"},
    "figures": _BASE | {"core", "io", "algorithms", "data", "viz"},
    "cli": _BASE | {"core", "io", "algorithms", "data", "viz", "package", "exercises", "figures"},
    "__main__": _BASE | {"core", "io", "algorithms", "data", "viz", "package", "exercises", "figures", "cli"},
    "package": _BASE | {"core", "io", "algorithms", "data", "viz", "exercises", "figures", "cli"},
}

#: Modules that belong to another layer than their name says: ``course.py`` is the
#: ``course`` subcommand of the command line, kept in a file of its own.
SAME_LAYER_AS: dict[str, str] = {"course": "cli"}


class Arrow(NamedTuple):
    """One import: ``source`` (a file of the package) imports ``target`` (a module name) at ``line``."""

    source: Path
    line: int
    target: str


def module_name(path: Path) -> str:
    """``halfedge_edu.core.ops.flip`` for ``halfedge_edu/core/ops/flip.py`` (packages without ``__init__``)."""
    parts = list(path.relative_to(PACKAGE_DIR.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def is_package(path: Path) -> bool:
    return path.name == "__init__.py"


def layer_of(module: str) -> str:
    """The layer of a module name of the package: its first component below ``halfedge_edu``."""
    parts = module.split(".")
    return "package" if len(parts) == 1 else SAME_LAYER_AS.get(parts[1], parts[1])


def _is_module(name: str) -> bool:
    """Whether a dotted name of the package is a module or a package on disk."""
    relative = Path(*name.split(".")[1:]) if "." in name else Path()
    base = PACKAGE_DIR / relative
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def imports_of(path: Path) -> list[Arrow]:
    """Every import of a package module into the package, wherever it stands in the file."""
    here = module_name(path)
    package = here if is_package(path) else here.rpartition(".")[0]
    arrows = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            arrows += [Arrow(path, node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = package.split(".")
                base = ".".join(anchor[: len(anchor) - (node.level - 1)])
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module or ""
            for alias in node.names:
                # ``from . import ops`` names a module; ``from .core import HalfedgeMesh`` a name in one.
                candidate = f"{base}.{alias.name}"
                arrows.append(Arrow(path, node.lineno, candidate if _is_module(candidate) else base))
    inside = (arrow for arrow in arrows if arrow.target.split(".")[0] == "halfedge_edu")
    return sorted(set(inside), key=lambda arrow: (arrow.line, arrow.target))


def upward_arrows() -> list[str]:
    """One sentence per import that runs up: ``file:line: layer -> layer (imports module)``."""
    found = []
    for path in sorted(PACKAGE_DIR.rglob("*.py")):
        source_layer = layer_of(module_name(path))
        for arrow in imports_of(path):
            target_layer = layer_of(arrow.target)
            if target_layer != source_layer and target_layer not in ALLOWED[source_layer]:
                where = path.relative_to(PACKAGE_DIR.parent)
                found.append(f"{where}:{arrow.line}: {source_layer} -> {target_layer} (imports {arrow.target})")
    return found


def test_every_layer_is_in_the_table():
    layers = {layer_of(module_name(path)) for path in PACKAGE_DIR.rglob("*.py")}
    assert layers <= set(ALLOWED), f"layers missing from ALLOWED: {sorted(layers - set(ALLOWED))}"


def test_imports_run_one_way():
    upward = upward_arrows()
    assert not upward, "imports that run up the layers:\n" + "\n".join(upward)


def test_the_reader_sees_lazy_and_relative_imports():
    """The reader itself: a lazy relative import inside a function is an arrow too."""
    probe = PACKAGE_DIR / "core" / "mesh.py"
    targets = {arrow.target for arrow in imports_of(probe)}
    assert "halfedge_edu.core.ops" in targets  # ``from . import ops`` at module level
    assert "halfedge_edu.core.validate" in targets  # ``from .validate import validate`` inside a method
    assert layer_of("halfedge_edu.viz.scene") == "viz"
    assert layer_of("halfedge_edu") == "package"


# ------------------------------------------------------------ what ``import halfedge_edu`` loads

def loaded_after(code: str) -> set[str]:
    """The modules of numpy and of the package that a fresh interpreter has loaded after ``code``."""
    script = f"import sys\n{code}\nprint(' '.join(sorted(sys.modules)))"
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            cwd=PACKAGE_DIR.parent, timeout=120)
    assert result.returncode == 0, result.stderr
    return {name for name in result.stdout.split() if name.split(".")[0] in ("numpy", "halfedge_edu")}


def test_importing_the_package_loads_none_of_its_modules():
    assert loaded_after("import halfedge_edu") == {"halfedge_edu"}


def test_a_public_name_loads_its_module_on_first_use():
    loaded = loaded_after("from halfedge_edu import sample")
    assert {"numpy", "halfedge_edu.data", "halfedge_edu.core"} <= loaded
    assert "halfedge_edu.algorithms" not in loaded


@pytest.mark.parametrize("name", halfedge_edu.__all__)
def test_every_public_name_is_the_object_of_its_module(name):
    home = importlib.import_module(halfedge_edu._HOMES[name], "halfedge_edu")
    assert getattr(halfedge_edu, name) is getattr(home, name)


def test_the_subpackages_the_package_used_to_load_are_still_attributes():
    for name in halfedge_edu._SUBPACKAGES:
        assert getattr(halfedge_edu, name) is importlib.import_module(f"halfedge_edu.{name}")


def test_the_public_names_the_lazy_table_and_the_type_checkers_imports_agree():
    """Three lists name the public names: ``__all__``, ``_HOMES`` (where each is loaded from)
    and the ``if TYPE_CHECKING:`` imports editors read. They must say the same."""
    init = PACKAGE_DIR / "__init__.py"
    for_type_checkers = {
        alias.name: "." * node.level + (node.module or "")
        for node in ast.walk(ast.parse(init.read_text(encoding="utf-8")))
        if isinstance(node, ast.ImportFrom) and node.level
        for alias in node.names
    }
    assert sorted(halfedge_edu.__all__) == sorted(halfedge_edu._HOMES)
    assert for_type_checkers == halfedge_edu._HOMES


def test_dir_lists_every_public_name_without_loading_it():
    code = "import halfedge_edu as hx\nassert set(hx.__all__) <= set(dir(hx)), sorted(set(hx.__all__) - set(dir(hx)))"
    assert loaded_after(code) == {"halfedge_edu"}


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="'halfedge_edu' has no attribute 'HalfEdgeMesh'"):
        halfedge_edu.HalfEdgeMesh
