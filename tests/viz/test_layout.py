"""The viz modules use only each other's public names (the rule in viz/__init__)."""

from __future__ import annotations

import ast
from pathlib import Path

import halfedge_edu.viz

VIZ = Path(halfedge_edu.viz.__file__).parent
#: IPython's display protocol: public by convention although it starts with "_".
DISPLAY_PROTOCOL = ("_repr_mimebundle_", "_repr_png_", "_repr_html_")


def _private_uses(source: str) -> list[str]:
    """``from .x import _name`` and ``obj._attr`` where obj is not self, cls or super()."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            found += [f"line {node.lineno}: import {alias.name}" for alias in node.names
                      if alias.name.startswith("_") and not alias.name.startswith("__")]
        elif isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
            owner = node.value
            own = isinstance(owner, ast.Name) and owner.id in ("self", "cls")
            own |= isinstance(owner, ast.Call) and isinstance(owner.func, ast.Name) and owner.func.id == "super"
            if not own and node.attr not in DISPLAY_PROTOCOL:
                found.append(f"line {node.lineno}: {ast.unparse(node)}")
    return found


def test_the_rule_catches_what_it_forbids():
    source = "from .scene import _ranges\nscene._ring_mark(v)\nself._ok()\nsuper()._ok()\nw._repr_mimebundle_()\n"
    assert _private_uses(source) == ["line 1: import _ranges", "line 2: scene._ring_mark"]


def test_no_viz_module_uses_another_modules_private_names():
    offences = {path.name: _private_uses(path.read_text()) for path in sorted(VIZ.glob("*.py"))}
    assert {name: found for name, found in offences.items() if found} == {}
