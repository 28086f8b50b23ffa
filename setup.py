"""Build step that pyproject.toml cannot say: put the chapters into the wheel.

Everything else about the package is in pyproject.toml. ``build_py`` here also writes
``halfedge_edu/chapters/NN_*.ipynb``: the executed notebooks of ``notebooks/`` with
their outputs removed, by ``halfedge_edu/course.py`` (loaded by path, standard library
only, so the isolated build needs nothing more than setuptools). Why at build time and
not checked in: see course.py's docstring.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent


def _course_module():
    """halfedge_edu/course.py as a module, without importing the package (which needs numpy)."""
    spec = importlib.util.spec_from_file_location("_halfedge_edu_course", ROOT / "halfedge_edu" / "course.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


class BuildWithChapters(build_py):
    """setuptools' build_py, then the chapters without outputs into the built package."""

    def run(self) -> None:
        super().run()
        if not self.editable_mode:
            written = _course_module().write_chapters(ROOT / "notebooks", Path(self.build_lib) / "halfedge_edu" / "chapters")
            if not written:
                raise RuntimeError("no notebooks/NN_*.ipynb to put in the wheel: build from a full clone or the sdist")


setup(cmdclass={"build_py": BuildWithChapters})
