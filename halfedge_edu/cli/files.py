"""Mesh files in and out for the subcommands that read them (``inspect``, ``transform``).

Reading: only regular files (a FIFO would block, a link to ``/dev/zero`` never end),
``hx.load`` with the library's warnings printed as one line each, and every problem an
:class:`~halfedge_edu.cli.errors.InputProblem` naming the file. Writing: OUT checked
before any work starts, then ``hx.save`` (a temporary file beside OUT, flushed and moved
into place), after removing what runs killed mid-write left behind.
:func:`names_the_file` makes the library's own errors about the input bad input too.
"""

from __future__ import annotations

import argparse
import errno
import functools
import os
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator

import halfedge_edu as hx
from halfedge_edu.cli.errors import InputProblem, one_line, warn
from halfedge_edu.core.errors import MeshInputError, MeshInvariantError, TopologyError
from halfedge_edu.io import SUFFIXES, load_arrays
from halfedge_edu.io.obj import path_error, remove_stale_temporaries, shown_path

def names_the_file(run: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """Decorate a subcommand that reads ``args.file``: the library's own errors about the
    input or the mesh (``MeshInputError``, ``MeshInvariantError``, ``TopologyError``) end it
    as bad input, one line naming the file, unless ``--debug`` asks for the traceback."""

    @functools.wraps(run)
    def run_naming_the_file(args: argparse.Namespace) -> int:
        try:
            return run(args)
        except (MeshInputError, MeshInvariantError, TopologyError) as error:
            if args.debug:
                raise
            raise InputProblem(with_path(args.file, error)) from error

    return run_naming_the_file


def check_readable(path: Path) -> None:
    """Raise ``InputProblem`` unless ``path`` is a regular file this system can name."""
    try:
        exists, is_folder, is_file = path.exists(), path.is_dir(), path.is_file()
    except OSError as error:  # a path too long for the system, say
        raise InputProblem(str(path_error(path, error, "read"))) from error
    if not exists:
        raise InputProblem(f"{shown_path(path)}: no such file")
    if is_folder:
        raise InputProblem(f"{shown_path(path)}: is a folder, not a mesh file")
    if not is_file:  # follows symbolic links: a link to /dev/zero is a device
        raise InputProblem(f"{shown_path(path)}: is not a regular file (a FIFO, device or socket); "
                           f"only mesh files can be read")


def check_writable(output: Path) -> None:
    """Raise ``InputProblem`` if ``output`` cannot be written (suffix, path, folder, permission)."""
    suffix = output.suffix.lower()
    if suffix not in SUFFIXES:
        raise InputProblem(f"{shown_path(output)}: unknown file type {suffix[:20] or '(no suffix)'!r}; "
                           f"use one of {', '.join(SUFFIXES)}")
    folder = output.parent
    try:
        os.stat(output)  # refuses a name too long for the system, even for a file not there yet
    except OSError as error:
        if error.errno == errno.ENAMETOOLONG:
            raise InputProblem(str(path_error(output, error, "write"))) from error
        # any other refusal (no such file yet, a folder that is a file) is named below
    is_folder, folder_exists = output.is_dir(), folder.exists()
    if is_folder:
        raise InputProblem(f"{shown_path(output)}: is a folder, not a file name")
    if not folder_exists:
        raise InputProblem(f"{shown_path(folder)}: no such folder")
    if not folder.is_dir():
        raise InputProblem(f"{shown_path(folder)}: is not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputProblem(f"{shown_path(folder)}: cannot write in this folder (permission denied)")


def load(path: Path, *, repair: bool = False) -> hx.HalfedgeMesh:
    """``hx.load(path)`` with input problems turned into ``InputProblem``.

    ``MeshInputError`` is passed through so that a caller can look closer; the library's
    warnings (e.g. dropped unreferenced vertices) are printed as one line each.
    """
    check_readable(path)
    with warnings_as_lines():
        try:
            mesh = hx.load(path, repair=repair)
        except MeshInputError:
            raise
        except (OSError, ValueError) as error:  # UnicodeDecodeError is a ValueError
            raise InputProblem(with_path(path, error)) from error
    return mesh


def load_or_fail(path: Path, *, repair: bool = False) -> hx.HalfedgeMesh:
    """:func:`load`, with every ``MeshInputError`` an ``InputProblem`` (suggesting ``--repair`` if it helps)."""
    try:
        return load(path, repair=repair)
    except MeshInputError as error:
        message = with_path(path, error)
        if not repair and repair_would_help(path):
            message += "; run again with --repair to load it repaired"
        raise InputProblem(message) from error


def read_raw(path: Path):
    """The vertex and face arrays of a file, without building anything from them."""
    vertices, faces, _ = load_arrays(path)
    return vertices, faces


def repair_would_help(path: Path) -> bool:
    """Are the file's triangles readable but not manifold (what ``repair=True`` fixes)?"""
    try:
        _, faces = read_raw(path)
        return not hx.manifold_report(faces)
    except Exception:  # the file cannot even be read as triangles: repair will not help
        return False


def save(mesh: hx.HalfedgeMesh, output: Path) -> None:
    """``hx.save`` (temporary file beside OUT, then moved into place), errors as ``InputProblem``.

    A ``MeshInputError`` here is OUT's format refusing the mesh, so it names OUT. First
    removes temporary files that earlier runs, killed mid-write, left in OUT's folder
    (only ``.halfedge_edu-XXXXXXXX.tmp`` files untouched for 10 minutes).
    """
    # What an earlier run killed mid-write (SIGKILL, a power cut) could not remove itself.
    remove_stale_temporaries(output.parent)
    try:
        hx.save(mesh, output)
    except (OSError, MeshInputError) as error:
        raise InputProblem(with_path(output, error)) from error


@contextmanager
def warnings_as_lines() -> Iterator[None]:
    """Collect the library's warnings in the body; if it succeeds, print each as one line."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UserWarning)  # MeshWarning among them
        yield
    for warning in caught:
        warn(str(warning.message))


def with_path(path: Path, error: Exception) -> str:
    """The error's message, starting with the file (unless it already does; a very long path cut short)."""
    if isinstance(error, OSError) and error.strerror:
        message = error.strerror
    else:
        message = str(error) or type(error).__name__
    shown = shown_path(path)
    if not message.startswith((str(path), path.name, shown)):
        message = f"{shown}: {message}"
    return one_line(message)
