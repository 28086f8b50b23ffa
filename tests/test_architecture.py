"""The package's imports run one way: no module imports a layer above its own.

Each module of ``halfedge_edu`` is read with :mod:`ast` (nothing is imported), and every
import in it is collected: module-level ones, the lazy ones inside functions and
methods, relative (``from ..core import x``) and absolute (``import halfedge_edu.io``).
Each import is an arrow from the importing module's layer to the imported module's
layer; an arrow that is not in :data:`ALLOWED` runs up and fails the test, with the
file, the line and the arrow in the message.

Within a layer, no module may import itself back, however far round: the imports that
run (all of them but those under ``if TYPE_CHECKING:``, which only type checkers read)
form no circle. And what importing costs: the package's public names load their modules
on first use, so ``import halfedge_edu`` loads none of them.
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
#: nothing of the package, so any layer may ask them. ``course`` (``course.py``, copying
#: the chapters) imports nothing of the package either, because ``setup.py`` loads it by
#: path at build time; the command line's ``course`` subcommand is ``cli/course.py``.
_BASE = frozenset({"_extras", "live_backend"})
ALLOWED: dict[str, frozenset[str]] = {
    "_extras": frozenset(),
    "live_backend": frozenset(),
    "course": frozenset(),
    "core": _BASE,
    "io": _BASE | {"core"},
    "algorithms": _BASE | {"core"},
    "data": _BASE | {"core", "io"},
    "viz": _BASE | {"core", "algorithms", "data"},
    "exercises": _BASE | {"core", "io", "algorithms", "data", "viz"},
    "figures": _BASE | {"core", "io", "algorithms", "data", "viz"},
    "cli": _BASE | {"core", "io", "algorithms", "data", "viz", "package", "exercises", "figures", "course"},
    "__main__": _BASE | {"core", "io", "algorithms", "data", "viz", "package", "exercises", "figures", "cli", "course"},
    "package": _BASE | {"core", "io", "algorithms", "data", "viz", "exercises", "figures", "cli"},
}


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
    return "package" if len(parts) == 1 else parts[1]


def _is_module(name: str) -> bool:
    """Whether a dotted name of the package is a module or a package on disk."""
    relative = Path(*name.split(".")[1:]) if "." in name else Path()
    base = PACKAGE_DIR / relative
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def _is_type_checking(test: ast.expr) -> bool:
    """``TYPE_CHECKING`` or ``typing.TYPE_CHECKING``: the test of a block only type checkers read."""
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _import_statements(tree: ast.AST, *, for_type_checkers: bool) -> list[ast.Import | ast.ImportFrom]:
    """Every import statement in ``tree``; without those under ``if TYPE_CHECKING:`` unless
    ``for_type_checkers`` (their ``else:`` runs, so it is kept)."""
    found, todo = [], [tree]
    while todo:
        node = todo.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        elif isinstance(node, ast.If) and not for_type_checkers and _is_type_checking(node.test):
            todo.extend(node.orelse)
        else:
            todo.extend(ast.iter_child_nodes(node))
    return found


def imports_of(path: Path, *, for_type_checkers: bool = True) -> list[Arrow]:
    """Every import of a package module into the package, wherever it stands in the file
    (at the top or inside a function); ``for_type_checkers=False`` leaves out the imports
    under ``if TYPE_CHECKING:``, which never run."""
    here = module_name(path)
    package = here if is_package(path) else here.rpartition(".")[0]
    arrows = []
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    for node in _import_statements(tree, for_type_checkers=for_type_checkers):
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


def import_graph() -> dict[str, list[Arrow]]:
    """Each module of the package -> the imports of the package that run when it is imported
    or its functions are called (``if TYPE_CHECKING:`` blocks left out)."""
    return {
        module_name(path): [arrow for arrow in imports_of(path, for_type_checkers=False)
                            if arrow.target != module_name(path)]
        for path in sorted(PACKAGE_DIR.rglob("*.py"))
    }


def circles(graph: dict[str, list[Arrow]]) -> list[list[str]]:
    """The import circles in ``graph``: each group of modules that reach one another through
    their imports (a strongly connected component of more than one module), sorted.

    Tarjan's algorithm, with an explicit stack so that a long chain cannot exhaust Python's.
    """
    targets = {module: sorted({arrow.target for arrow in arrows}) for module, arrows in graph.items()}
    order: dict[str, int] = {}  # module -> when the search first reached it
    lowest: dict[str, int] = {}  # module -> the earliest module on the stack it reaches
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in sorted(targets):
        if root in order:
            continue
        walk = [(root, iter(targets[root]))]
        order[root] = lowest[root] = len(order)
        stack.append(root)
        on_stack.add(root)
        while walk:
            module, pending = walk[-1]
            step = next(pending, None)
            if step is None:
                walk.pop()
                if walk:
                    parent = walk[-1][0]
                    lowest[parent] = min(lowest[parent], lowest[module])
                if lowest[module] == order[module]:
                    group = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        group.append(member)
                        if member == module:
                            break
                    if len(group) > 1:
                        found.append(sorted(group))
            elif step not in order:
                order[step] = lowest[step] = len(order)
                stack.append(step)
                on_stack.add(step)
                walk.append((step, iter(targets.get(step, ()))))
            elif step in on_stack:
                lowest[module] = min(lowest[module], order[step])
    return sorted(found)


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


def test_no_module_imports_itself_back():
    graph = import_graph()
    found = circles(graph)
    described = []
    for group in found:
        members = set(group)
        arrows = [f"  {arrow.source.relative_to(PACKAGE_DIR.parent)}:{arrow.line}: {module} -> {arrow.target}"
                  for module in group for arrow in graph[module] if arrow.target in members]
        described.append(" <-> ".join(group) + "\n" + "\n".join(arrows))
    assert not found, "import circles:\n" + "\n".join(described)


def test_the_circle_finder_finds_a_circle_and_nothing_else():
    def arrows(*targets: str) -> list[Arrow]:
        return [Arrow(Path("x.py"), 1, target) for target in targets]

    graph = {"a": arrows("b"), "b": arrows("c"), "c": arrows("a", "d"), "d": arrows(), "e": arrows("d")}
    assert circles(graph) == [["a", "b", "c"]]
    assert circles({"a": arrows("b"), "b": arrows()}) == []


def test_the_reader_leaves_out_what_only_type_checkers_read():
    """``core/elements.py`` names the mesh for its annotations only: no import that runs."""
    probe = PACKAGE_DIR / "core" / "elements.py"
    assert "halfedge_edu.core.mesh" in {arrow.target for arrow in imports_of(probe)}
    assert "halfedge_edu.core.mesh" not in {arrow.target for arrow in imports_of(probe, for_type_checkers=False)}


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
        for node in _import_statements(ast.parse(init.read_text(encoding="utf-8")), for_type_checkers=True)
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


#: The longest a module of the package may be (issue 28): past it, a file holds more
#: than one concern, and a course can no longer cite it as one reading.
MAX_MODULE_LINES = 800


def test_no_module_is_longer_than_a_reading():
    long = {str(path.relative_to(PACKAGE_DIR)): n for path in PACKAGE_DIR.rglob("*.py")
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_MODULE_LINES}
    assert not long, f"modules over {MAX_MODULE_LINES} lines (split them by concern): {long}"
