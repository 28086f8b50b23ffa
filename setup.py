"""Build steps that pyproject.toml cannot say: the chapters into the wheel, and a README
whose links work on the package index.

Everything else about the package is in pyproject.toml.

The README links pictures and files relative to the repository, which is right on the
repository's own page and in a clone, but the package index shows the README without
the repository beside it. :func:`readme_for_index` rewrites each relative link to an
absolute one under ``REPOSITORY`` (``/raw/main/`` for pictures, ``/blob/main/`` for
other files); the README itself stays relative. ``REPOSITORY`` is
``$HALFEDGE_EDU_REPOSITORY``, which whoever builds a wheel to publish sets to the
repository's public address (``https://github.com/ORG/halfedge_edu``); it also becomes
the package's "Repository" URL. Without it (a wheel for a class, built from a clone) the
README is left as it is and the package names no URL: no made-up address is published.
tests/test_environments.py checks that every relative link names a file in the repository.

``build_py`` here also writes
``halfedge_edu/chapters/NN_*.ipynb``: the executed student edition of the chapters,
``notebooks/student/``, with their outputs removed, by ``halfedge_edu/course.py`` (loaded by path, standard library
only, so the isolated build needs nothing more than setuptools). Why at build time and
not checked in: see course.py's docstring.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
#: The repository's public address, set by whoever builds a wheel for the package index.
REPOSITORY = os.environ.get("HALFEDGE_EDU_REPOSITORY", "").strip().rstrip("/")

# A Markdown link or picture: [text](target) or ![alt](target), target without spaces.
MARKDOWN_LINK = re.compile(r"(!?)\[([^\]]*)\]\(([^)\s]+)\)")


def is_relative(target: str) -> bool:
    """A link into the repository: not a URL, not mailto:, not an anchor on the same page."""
    return not re.match(r"^([a-z][a-z0-9+.-]*:|#|/)", target, flags=re.I)


def readme_for_index(text: str, repository: str = REPOSITORY) -> str:
    """``text`` (Markdown) with every relative link made absolute under ``repository``
    (unchanged when there is no repository address)."""
    if not repository:
        return text

    def absolute(match: re.Match) -> str:
        bang, label, target = match.groups()
        if not is_relative(target):
            return match.group(0)
        kind = "raw" if bang else "blob"
        return f"{bang}[{label}]({repository}/{kind}/main/{target})"

    return MARKDOWN_LINK.sub(absolute, text)


def _course_module():
    """halfedge_edu/course.py as a module, without importing the package (which needs numpy)."""
    spec = importlib.util.spec_from_file_location("_halfedge_edu_course", ROOT / "halfedge_edu" / "course.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


class BuildWithChapters(build_py):
    """setuptools' build_py, then the chapters' student edition without outputs into the built package."""

    def run(self) -> None:
        super().run()
        if not self.editable_mode:
            student = ROOT / "notebooks" / "student"
            written = _course_module().write_chapters(student, Path(self.build_lib) / "halfedge_edu" / "chapters")
            if not written:
                raise RuntimeError("no notebooks/student/NN_*.ipynb to put in the wheel: build from a full clone "
                                   "or the sdist")


if __name__ == "__main__":  # setuptools runs this file as __main__; tests import it for readme_for_index
    setup(
        cmdclass={"build_py": BuildWithChapters},
        long_description=readme_for_index((ROOT / "README.md").read_text(encoding="utf-8")),
        long_description_content_type="text/markdown",
        project_urls={"Repository": REPOSITORY} if REPOSITORY else {},
    )
