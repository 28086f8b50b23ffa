"""How the command line ends and speaks: exit statuses, the errors a subcommand raises, and
the one-line messages on stderr.

A subcommand raises :class:`InputProblem` for input it cannot use (exit status 2) and
:class:`BrokenResult` for a result that fails ``validate()`` (a bug, exit status 1);
``halfedge_edu.cli.main`` turns each into one line, ``halfedge-edu: error: ...``, through
:func:`fail`. Everything here is the standard library, so that ``--help`` loads nothing more.
"""

from __future__ import annotations

import sys
from typing import Iterable, TextIO

from halfedge_edu._extras import extra_for, install_hint

PROG = "halfedge-edu"

EXIT_OK = 0
EXIT_INVALID = 1  # a mesh breaks a halfedge invariant: `check`'s input, or a command's result
EXIT_ERROR = 2  # bad input or usage (argparse uses 2 for usage errors too)

# How many elements a list in a message names before it only counts the rest.
MAX_LISTED = 10

#: The longest error message printed whole: a message quoting a whole file or a list of
#: a million faces must not become megabytes on one line.
MAX_MESSAGE = 2000


class InputProblem(Exception):
    """Input the command cannot use; reported as one line on stderr with exit status 2."""


class BrokenResult(Exception):
    """An algorithm returned a mesh that fails ``validate()``: a bug, reported with exit status 1."""


def one_line(text: str) -> str:
    """``text`` with every run of whitespace, newlines included, made one space."""
    return " ".join(text.split())


def listing(items: Iterable[str]) -> str:
    """`` (a, b, c)`` naming the first ``MAX_LISTED`` items and counting the rest; ``""`` for none."""
    items = list(items)
    if not items:
        return ""
    shown = ", ".join(items[:MAX_LISTED])
    more = f", ... ({len(items) - MAX_LISTED} more)" if len(items) > MAX_LISTED else ""
    return f" ({shown}{more})"


def echo(text: str, file: TextIO | None = None) -> None:
    """``print``, with file-name bytes that are not UTF-8 shown as ``\\xe9``.

    Python hands such bytes over as lone surrogates (``\\udce9``), which a UTF-8
    console refuses to encode: printing the name must not become the error.
    """
    print(text.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace"), file=file)


def warn(message: str) -> None:
    """Print ``message`` as one ``warning:`` line on stderr."""
    echo(f"{PROG}: warning: {one_line(message)}", file=sys.stderr)


def fail(message: str, status: int = EXIT_ERROR) -> int:
    """Print ``message`` as one ``error:`` line on stderr (cut short past ``MAX_MESSAGE``); return ``status``."""
    message = one_line(message)
    if len(message) > MAX_MESSAGE:
        message = f"{message[:MAX_MESSAGE]} ... ({len(message) - MAX_MESSAGE} more characters cut)"
    echo(f"{PROG}: error: {message}", file=sys.stderr)
    return status


def missing_extra(command: str, error: Exception) -> str | None:
    """For an optional dependency that is not installed, the line naming the extra that
    brings it (``grade`` without the notebooks extra); None for any other error."""
    if not isinstance(error, ModuleNotFoundError) or extra_for(error.name) is None:
        return None
    return f"{command} needs {error.name}, which is not installed: {install_hint(extra_for(error.name))}"
