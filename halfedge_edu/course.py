"""The course from the wheel: ``halfedge-edu course DEST`` (also ``python -m halfedge_edu course DEST``).

Copies the **student edition** of the chapters (``00_setup_and_tour.ipynb`` ...
``13_putting_it_together.ipynb``: each exercise's answer replaced by a stub, the answer
cells left out; see tools/build_notebooks.py) into DEST with their stored outputs
removed, so that ``pip install
"halfedge_edu[notebooks]"`` followed by ``halfedge-edu course my-course`` and
``jupyter lab my-course`` is enough to start. The meshes the chapters load are package
data (``hx.sample("spot")``, ``hx.sample("bunny")``), already installed with the
library; the chapters need no other file.

How the wheel gets the chapters: at build time, not in the repository. ``setup.py``
extends setuptools' ``build_py`` to run :func:`write_chapters` from this file (loaded by
path, so the build needs neither numpy nor an installed halfedge_edu) on the executed
student edition ``notebooks/student/NN_*.ipynb`` and put the results in
``halfedge_edu/chapters/`` inside the wheel. The alternative, checked-in copies under ``halfedge_edu/chapters/`` kept in step
by a test, would duplicate 14 notebooks in git and need one more regeneration step every
time the chapters are rebuilt; building them cannot drift. ``MANIFEST.in`` puts
``notebooks/student/*.ipynb`` into the sdist so that a wheel built from the sdist has
them too. In a source checkout (``pip install -e .``) there is no ``chapters/`` folder:
the command then reads the repository's ``notebooks/student/`` and strips the outputs as
it copies. The solution edition (``notebooks/NN_*.ipynb``) stays in the repository, for
instructors; it is not in the wheel.

Outputs are removed because they are most of a notebook's size (pictures), because a
student should see each output appear when running the cell, and because a fresh copy
then never shows results of another version of the library.

A file that already exists in DEST is kept, never overwritten: running the command again
after a library update adds new chapters without touching a student's work.

This module imports only the standard library, so ``halfedge-edu --help`` stays instant
and ``setup.py`` can load it during a build.
"""

from __future__ import annotations

import argparse
import json
from dataclasses import dataclass
from pathlib import Path

# Chapter notebooks are named NN_topic.ipynb (NNb_topic.ipynb for one inserted after NN);
# other notebooks (scratch files) are not shipped.
CHAPTER_GLOB = "[0-9][0-9]*_*.ipynb"
PACKAGE_CHAPTERS = Path(__file__).resolve().parent / "chapters"
#: The student edition in a source checkout; what setup.py puts in the wheel.
REPOSITORY_NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks" / "student"


def strip_outputs(notebook: dict) -> dict:
    """Return ``notebook`` (parsed .ipynb JSON) with every code cell's outputs and counts removed.

    Cell sources and the notebook's kernel and language metadata are kept as they are;
    the per-cell ``execution`` timings that nbclient records and the saved widget state
    (``metadata.widgets``, most of a stripped chapter's size) go with the outputs.
    """
    cells = []
    for cell in notebook["cells"]:
        cell = dict(cell)
        if cell["cell_type"] == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
            cell["metadata"] = {key: value for key, value in cell.get("metadata", {}).items() if key != "execution"}
        cells.append(cell)
    metadata = {key: value for key, value in notebook.get("metadata", {}).items() if key != "widgets"}
    return {**notebook, "metadata": metadata, "cells": cells}


def write_chapters(source: Path, destination: Path) -> list[Path]:
    """Write every ``NN_*.ipynb`` of ``source`` into ``destination`` without outputs; return the written paths.

    Used by ``setup.py`` at build time. Existing files in ``destination`` are replaced.
    """
    destination.mkdir(parents=True, exist_ok=True)
    written = []
    for notebook_path in sorted(source.glob(CHAPTER_GLOB)):
        written.append(_copy_stripped(notebook_path, destination / notebook_path.name))
    return written


def _copy_stripped(notebook_path: Path, target: Path) -> Path:
    """Write the notebook at ``notebook_path`` to ``target`` without outputs; return ``target``."""
    notebook = strip_outputs(json.loads(notebook_path.read_text(encoding="utf-8")))
    target.write_text(json.dumps(notebook, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return target


def chapter_source() -> Path:
    """Where this installation keeps the chapters: the wheel's ``chapters/``, else the checkout's ``notebooks/``."""
    if PACKAGE_CHAPTERS.is_dir() and any(PACKAGE_CHAPTERS.glob(CHAPTER_GLOB)):
        return PACKAGE_CHAPTERS
    if REPOSITORY_NOTEBOOKS.is_dir() and any(REPOSITORY_NOTEBOOKS.glob(CHAPTER_GLOB)):
        return REPOSITORY_NOTEBOOKS
    raise FileNotFoundError(
        f"this installation of halfedge_edu has no chapters (looked in {PACKAGE_CHAPTERS} and "
        f"{REPOSITORY_NOTEBOOKS}); reinstall it from a wheel or a full clone"
    )


@dataclass(frozen=True)
class CourseCopy:
    """What :func:`copy_course` did: the chapters it wrote and the ones it left as they were."""

    destination: Path
    copied: tuple[str, ...]
    kept: tuple[str, ...]


def copy_course(destination: Path) -> CourseCopy:
    """Copy every chapter of the student edition, without outputs, into ``destination`` (created if missing).

    Raises ``NotADirectoryError`` if ``destination`` exists and is not a folder, and
    ``FileNotFoundError`` if the installation has no chapters (:func:`chapter_source`).
    Chapters already in ``destination`` are kept unchanged and listed in ``kept``.
    """
    source = chapter_source()
    if destination.exists() and not destination.is_dir():
        raise NotADirectoryError(f"{destination} exists and is not a folder")
    destination.mkdir(parents=True, exist_ok=True)
    copied, kept = [], []
    for notebook_path in sorted(source.glob(CHAPTER_GLOB)):
        target = destination / notebook_path.name
        if target.exists():
            kept.append(notebook_path.name)
            continue
        _copy_stripped(notebook_path, target)
        copied.append(notebook_path.name)
    return CourseCopy(destination, tuple(copied), tuple(kept))


def add_course_parser(commands: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Register ``course DEST`` on the command line's subcommands (called by ``cli.build_parser``)."""
    course = commands.add_parser(
        "course",
        help="copy the chapters (student edition, without outputs) into a folder, to open in JupyterLab",
        description=(
            "Copy the course's chapters, student edition (exercises without their answers), "
            "without their stored outputs, into DEST (created if missing). Chapters already in DEST are kept, never overwritten. Then: "
            "jupyter lab DEST. Needs the notebooks extra: pip install \"halfedge_edu[notebooks]\"."
        ),
    )
    course.add_argument("destination", type=Path, metavar="DEST", help="the folder to copy the chapters into")
    course.set_defaults(run=run_course)
    return course


def run_course(args: argparse.Namespace) -> int:
    """The ``course`` subcommand: copy, then print one line per outcome; exit status 0."""
    from halfedge_edu.cli import EXIT_OK, InputProblem

    try:
        result = copy_course(args.destination)
    except OSError as problem:
        raise InputProblem(str(problem)) from problem
    print(f"course: copied {len(result.copied)} chapters to {result.destination}")
    if result.kept:
        print(f"course: kept {len(result.kept)} already there: {', '.join(result.kept)}")
    print(f"next: jupyter lab {result.destination}")
    return EXIT_OK
