"""The course from the wheel: ``halfedge-edu course DEST`` (also ``python -m halfedge_edu course DEST``).

Copies the **student edition** of the chapters (``00_setup_and_tour.ipynb`` ...
``13_putting_it_together.ipynb``: each exercise's answer replaced by a stub, the answer
cells left out; see tools/build_notebooks.py) into DEST with their stored outputs
removed and the package version stamped in, so that installing the package with its
notebooks extra (README, "Without make"), then ``halfedge-edu course my-course`` and
``jupyter lab my-course`` is enough to start. The meshes the chapters load are package
data (``hx.sample("spot")``, ``hx.sample("bunny")``), already installed with the
library; the chapters need no other file.

How the wheel gets the chapters: at build time, not in the repository. ``setup.py``
extends setuptools' ``build_py`` to run :func:`write_chapters` from this file (loaded by
path, so the build needs neither numpy nor an installed halfedge_edu) on the executed
student edition ``notebooks/student/NN_*.ipynb`` and put the results in
``halfedge_edu/chapters/`` inside the wheel. The alternative, checked-in copies under
``halfedge_edu/chapters/`` kept in step by a test, would duplicate 15 notebooks in git
and need one more regeneration step every time the chapters are rebuilt; building them
cannot drift. ``MANIFEST.in`` puts ``notebooks/student/*.ipynb`` (and only the student
edition) into the sdist so that a wheel built from the sdist has them too. In a source
checkout (``pip install -e .``) there is no ``chapters/`` folder: the command then reads
the repository's ``notebooks/student/`` and strips the outputs as it copies. The
solution edition (``notebooks/NN_*.ipynb``) stays in the repository, for instructors;
it is in neither the wheel nor the sdist.

Outputs are removed because they are most of a notebook's size (pictures), because a
student should see each output appear when running the cell, and because a fresh copy
then never shows results of another version of the library.

The version stamp (errata reach a class): each copied chapter says under its title
which version of halfedge_edu it came from, and its metadata ``halfedge_edu.course``
records that version and a digest of its cells as copied (:func:`cells_digest`).

What happens to each chapter, in DEST (one outcome per chapter, :class:`CourseCopy`):

- missing: written (``copied``);
- a valid notebook (the student's work): never overwritten (``kept``). With
  ``--update`` (:func:`copy_course` ``update=True``), a chapter stamped with another
  version is replaced if its cells are still exactly as copied (``updated``: only outputs
  of running it are lost); if the student edited it, or it has no stamp, the newer
  chapter is written beside it as ``NN_topic-VERSION.ipynb`` and it is left as it is
  (``beside``);
- not a valid notebook (truncated by a kill, a full disk or a file-size limit): the
  broken file is moved aside to ``NN_topic.ipynb.broken`` and the chapter written again
  (``repaired``);
- a symbolic link (dangling, a loop, or pointing anywhere), or not a regular file: never
  followed or touched (``skipped``, with the reason). So is a chapter that cannot be read
  or written (permissions, a full disk): the others are still copied.

Every chapter is written to a temporary file in DEST, flushed to disk (fsync) and then
renamed over its name, so a chapter in DEST is either whole or absent, never half written.

This module imports only the standard library and nothing of the package, so that
``setup.py`` can load it by path during a build (tests/test_architecture.py holds it to
that). The ``course`` subcommand that prints what it did is ``halfedge_edu/cli/course.py``.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import json
import os
import re
import stat
import tempfile
from dataclasses import dataclass
from pathlib import Path

# Chapter notebooks are named NN_topic.ipynb (NNb_topic.ipynb for one inserted after NN);
# other notebooks (scratch files) are not shipped.
CHAPTER_GLOB = "[0-9][0-9]*_*.ipynb"
PACKAGE_CHAPTERS = Path(__file__).resolve().parent / "chapters"
#: The student edition in a source checkout; what setup.py puts in the wheel.
REPOSITORY_NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks" / "student"
#: The suffix a chapter that is not a valid notebook is moved aside with before it is repaired.
BROKEN_SUFFIX = ".broken"


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


def package_version() -> str:
    """The installed halfedge_edu's version (its metadata; in a bare checkout, ``__init__.py``'s)."""
    try:
        return importlib.metadata.version("halfedge_edu")
    except importlib.metadata.PackageNotFoundError:
        init = (Path(__file__).resolve().parent / "__init__.py").read_text(encoding="utf-8")
        return re.search(r'^__version__ = "([^"]+)"', init, flags=re.M).group(1)


def _source_text(cell: dict) -> str:
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else str(source)


def cells_digest(notebook: dict) -> str:
    """SHA-256 of the notebook's cell types and sources: changes when a student edits a
    cell, not when they run one (outputs, counts and metadata are left out)."""
    digest = hashlib.sha256()
    for cell in notebook.get("cells", []):
        digest.update(json.dumps([cell.get("cell_type"), _source_text(cell)], ensure_ascii=False).encode("utf-8"))
    return digest.hexdigest()


def version_line(version: str) -> str:
    """The line under each chapter's title that says which version it is."""
    return (f"*This copy of the chapter is from halfedge_edu {version}. "
            f"`halfedge-edu course DEST --update` brings a newer one; CHANGELOG.md says what changed.*")


def stamp_version(notebook: dict, version: str) -> dict:
    """Return ``notebook`` with ``version`` under its title (first markdown cell) and in its
    metadata, ``halfedge_edu.course``: ``{"version": ..., "cells_sha256": ...}`` (the digest
    of the cells as stamped, :func:`cells_digest`)."""
    cells = [dict(cell) for cell in notebook["cells"]]
    for cell in cells:
        if cell["cell_type"] == "markdown":
            title, _, rest = _source_text(cell).partition("\n")
            cell["source"] = f"{title}\n\n{version_line(version)}\n{rest}"
            break
    stamped = {**notebook, "cells": cells}
    ours = dict(notebook.get("metadata", {}).get("halfedge_edu", {}))
    ours["course"] = {"version": version, "cells_sha256": cells_digest(stamped)}
    return {**stamped, "metadata": {**notebook.get("metadata", {}), "halfedge_edu": ours}}


def _notebook_text(notebook: dict) -> str:
    return json.dumps(notebook, indent=1, ensure_ascii=False) + "\n"


def write_chapters(source: Path, destination: Path) -> list[Path]:
    """Write every ``NN_*.ipynb`` of ``source`` into ``destination`` without outputs; return the written paths.

    Used by ``setup.py`` at build time (no version stamp: that is added when a chapter is
    copied into a course). Existing files in ``destination`` are replaced.
    """
    destination.mkdir(parents=True, exist_ok=True)
    written = []
    for notebook_path in sorted(source.glob(CHAPTER_GLOB)):
        notebook = strip_outputs(json.loads(notebook_path.read_text(encoding="utf-8")))
        target = destination / notebook_path.name
        target.write_text(_notebook_text(notebook), encoding="utf-8")
        written.append(target)
    return written


def write_atomically(target: Path, text: str) -> None:
    """Write ``text`` to ``target`` through a temporary file in its folder, flushed to disk
    and renamed into place: ``target`` is afterwards the whole text, or as it was before.

    The rename replaces a symbolic link at ``target`` itself and never writes through it;
    the temporary file is removed if anything fails.
    """
    descriptor, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(temporary, 0o644 & ~_umask())
        os.replace(temporary, target)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise
    _fsync_folder(target.parent)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _fsync_folder(folder: Path) -> None:
    """Flush ``folder``'s entries (the rename) to disk, where the system allows it."""
    try:
        descriptor = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(descriptor)
    except OSError:
        pass
    finally:
        os.close(descriptor)


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
    """What :func:`copy_course` did, chapter by chapter (file names; see the module docstring).

    ``beside`` pairs a chapter the student edited with the newer chapter's name written
    beside it; ``repaired`` pairs a chapter with the name its broken file was moved to;
    ``outdated`` lists kept chapters stamped with another version (``--update`` would
    bring them); ``skipped`` pairs a chapter with the reason it was left alone.
    """

    destination: Path
    version: str
    copied: tuple[str, ...] = ()
    kept: tuple[str, ...] = ()
    outdated: tuple[str, ...] = ()
    updated: tuple[str, ...] = ()
    beside: tuple[tuple[str, str], ...] = ()
    repaired: tuple[tuple[str, str], ...] = ()
    skipped: tuple[tuple[str, str], ...] = ()


def _read_existing(target: Path) -> dict | None:
    """The notebook at ``target`` (a regular file, not followed if a link), or None if it
    is not a valid notebook. Raises OSError if it cannot be read."""
    descriptor = os.open(target, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    with os.fdopen(descriptor, "rb") as handle:
        data = handle.read()
    try:
        notebook = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        return None
    if (not isinstance(notebook, dict) or notebook.get("nbformat") != 4
            or not isinstance(notebook.get("cells"), list)
            or not all(isinstance(cell, dict) and "cell_type" in cell for cell in notebook["cells"])):
        return None
    return notebook


def _free_name(folder: Path, name: str) -> Path:
    """``folder / name``, or with ``.1``, ``.2`` ... before the suffix while that exists (even as a link)."""
    candidate = folder / name
    stem, dot, suffix = name.partition(".")
    number = 1
    while os.path.lexists(candidate):
        candidate = folder / f"{stem}.{number}{dot}{suffix}"
        number += 1
    return candidate


def copy_course(destination: Path, *, update: bool = False) -> CourseCopy:
    """Copy every chapter of the student edition, without outputs and stamped with the
    package version, into ``destination`` (created if missing); see the module docstring
    for what happens to a chapter already there, and ``update``.

    Raises ``NotADirectoryError`` if ``destination`` exists and is not a folder, and
    ``FileNotFoundError`` if the installation has no chapters (:func:`chapter_source`);
    ``OSError`` if ``destination`` cannot be created. A chapter that cannot be read or
    written is listed in ``skipped``; the others are still copied.
    """
    source = chapter_source()
    if destination.exists() and not destination.is_dir():
        raise NotADirectoryError(f"{destination} exists and is not a folder")
    destination.mkdir(parents=True, exist_ok=True)
    version = package_version()
    outcome: dict[str, list] = {key: [] for key in
                                ("copied", "kept", "outdated", "updated", "beside", "repaired", "skipped")}
    for notebook_path in sorted(source.glob(CHAPTER_GLOB)):
        name = notebook_path.name
        try:
            kind, detail = _place_chapter(notebook_path, destination / name, version, update)
        except OSError as problem:
            kind, detail = "skipped", problem.strerror or str(problem)
        outcome[kind].append(name if detail is None else (name, detail))
    return CourseCopy(destination, version, **{key: tuple(value) for key, value in outcome.items()})


def _place_chapter(notebook_path: Path, target: Path, version: str, update: bool) -> tuple[str, str | None]:
    """Put one chapter at ``target``; return (outcome, detail). OSError: it could not."""
    try:
        status = os.lstat(target)
    except FileNotFoundError:
        status = None
    if status is not None and stat.S_ISLNK(status.st_mode):
        return "skipped", "a symbolic link in the course folder; not followed (remove it to get the chapter)"
    if status is not None and not stat.S_ISREG(status.st_mode):
        return "skipped", "there is something there that is not a file; left alone"

    chapter = stamp_version(strip_outputs(json.loads(notebook_path.read_text(encoding="utf-8"))), version)
    if status is None:
        write_atomically(target, _notebook_text(chapter))
        return "copied", None

    existing = _read_existing(target)
    if existing is None:
        broken = _free_name(target.parent, target.name + BROKEN_SUFFIX)
        os.rename(target, broken)
        write_atomically(target, _notebook_text(chapter))
        return "repaired", broken.name

    stamp = existing.get("metadata", {}).get("halfedge_edu", {}).get("course", {})
    if not isinstance(stamp, dict):
        stamp = {}
    if stamp.get("version") == version:
        return "kept", None
    if not update:
        return ("outdated" if stamp else "kept"), None
    if stamp.get("cells_sha256") == cells_digest(existing):
        write_atomically(target, _notebook_text(chapter))
        return "updated", None
    newer = target.with_name(f"{target.stem}-{version}{target.suffix}")
    if os.path.lexists(newer):
        if os.path.islink(newer):
            return "skipped", f"{newer.name} is a symbolic link; not followed"
        return "beside", newer.name
    write_atomically(newer, _notebook_text(chapter))
    return "beside", newer.name
