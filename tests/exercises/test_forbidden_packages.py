"""A package in an exercise's ``forbids`` guards the functions of every module in it.

After ``algorithms/remesh.py`` became a package (one file per phase), forbidding
``halfedge_edu.algorithms.remesh`` guarded only what its ``__init__`` defines: the phases
(``tangential_smoothing`` in ``remesh/smooth.py`` ...) were callable from a learner's
wrapper. :func:`serve.functions_forbidden` now expands a package to all its modules.
"""

from __future__ import annotations

import importlib
import pkgutil
import types

import pytest

from halfedge_edu.exercises import serve

PACKAGES = ["halfedge_edu.algorithms.remesh", "halfedge_edu.core.ops", "halfedge_edu.algorithms"]


def _own_functions(module_name: str) -> set[str]:
    module = importlib.import_module(module_name)
    return {f"{module_name}.{name}" for name, value in vars(module).items()
            if isinstance(value, types.FunctionType) and value.__module__ == module_name}


@pytest.mark.parametrize("package", PACKAGES)
def test_a_forbidden_package_guards_every_function_of_its_modules(package):
    forbidden = serve.functions_forbidden([package], {})
    modules = [info.name for info in pkgutil.walk_packages(importlib.import_module(package).__path__,
                                                           prefix=f"{package}.")]
    assert modules, package
    for module_name in modules:
        missing = _own_functions(module_name) - set(forbidden)
        assert not missing, (package, sorted(missing)[:5])


def test_the_remesh_phases_are_among_them():
    forbidden = serve.functions_forbidden(["halfedge_edu.algorithms.remesh"], {})
    for phase in ("smooth.tangential_smoothing", "split.split_long_edges", "collapse.collapse_short_edges",
                  "flip.flip_to_regular_degrees", "project.project_to_surface"):
        assert f"halfedge_edu.algorithms.remesh.{phase}" in forbidden, phase


def test_an_exempted_function_of_a_package_module_stays_allowed():
    key = "halfedge_edu.algorithms.remesh.smooth.tangential_smoothing"
    forbidden = serve.functions_forbidden(["halfedge_edu.algorithms.remesh", serve.ALLOWED + key], {})
    assert key not in forbidden and "halfedge_edu.algorithms.remesh.split.split_long_edges" in forbidden
