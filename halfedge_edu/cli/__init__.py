"""The command line: ``halfedge-edu COMMAND ...`` (also ``python -m halfedge_edu``).

``info`` and ``check`` read one mesh file and print plain text. ``subdivide``,
``simplify``, ``smooth``, ``remesh`` and ``convert`` read IN, run one algorithm and
write OUT (the format picked by OUT's suffix), then print a one-line summary.
``course DEST`` copies the student edition of the chapters; ``grade`` grades learners'
chapter notebooks, each in its own sandbox, into JSON and JUnit reports (exit 0 when every
report was written, whatever the scores).

Promises, each tested in tests/test_cli.py:

- A problem with the input (a missing or unreadable file, a file that cannot become a
  halfedge mesh, a bad option value, an output folder that is missing or not writable)
  ends with one line on stderr, ``halfedge-edu: error: ...``, and exit status 2, never a
  traceback. Usage errors too.
- A file that does not say truthfully what it holds (an STL, PLY or OFF whose counts do
  not match its records, a truncated file, records after the declared ones) is bad
  input like any other: exit status 2, never another mesh (``hx.load``).
- OUT is written to a temporary file beside it, flushed to the disk and moved into place
  (``hx.save``), so a failure at any point leaves no partial file, and an existing OUT
  is left untouched. A run killed with SIGKILL cannot remove its temporary file: every
  writing run first removes ``.halfedge_edu-XXXXXXXX.tmp`` files untouched for 10
  minutes from OUT's folder (no other files).
- Error lines stay short: lists name their first few elements and count the rest, a
  path over 120 characters is shown cut in the middle, and a line is at most about 2000
  characters. A path too long for the system is bad input (exit status 2).
- Each result is validated before it is written. A broken result is a bug in
  halfedge_edu, not in the input: one line saying so, exit status 1 (the status ``check``
  gives a broken mesh), and nothing written.
- Only regular files are read (a FIFO would block, a link to ``/dev/zero`` never end).
- Work that would outgrow the machine is refused before it starts: ``subdivide`` and
  ``remesh`` estimate the faces they would make and refuse above ``--max-faces``
  (default 10 million), naming the estimate and the limit. Coordinates so large
  (beyond 1e40) that the algorithms' products of them overflow are refused by every
  command that computes with them.
- SIGTERM, like Ctrl-C, removes a half-written OUT's temporary file; exit status 143
  (130 for Ctrl-C).
- File names that are not UTF-8 are printed with the odd bytes as ``\\xe9``.

One module per concern: ``parser`` (what the command line accepts), ``errors`` (exit
statuses and the one-line messages), ``files`` (mesh files in and out), and one module per
kind of subcommand: ``inspect`` (``info``, ``check``), ``transform`` (the mesh-in,
mesh-out commands), ``course``, ``grade``. Each subcommand's module imports the library
at its top and is imported only once that subcommand is chosen; ``import halfedge_edu.cli``
and ``--help`` load neither numpy nor the algorithms (tests/test_cli.py checks it).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
from contextlib import contextmanager
from types import FrameType
from typing import Iterator, NoReturn, Sequence

from halfedge_edu.cli.errors import (
    EXIT_ERROR,
    EXIT_INVALID,
    EXIT_OK,
    PROG,
    BrokenResult,
    InputProblem,
    fail,
    missing_extra,
)
from halfedge_edu.cli.parser import build_parser

__all__ = ["main", "build_parser", "InputProblem", "BrokenResult", "EXIT_OK", "EXIT_INVALID", "EXIT_ERROR", "PROG"]


class Terminated(BaseException):
    """SIGTERM arrived. A ``BaseException`` like ``KeyboardInterrupt``, so that it unwinds
    through every ``except Exception`` and ``hx.save`` removes its temporary file."""


def _raise_terminated(signum: int, frame: FrameType | None) -> NoReturn:
    raise Terminated()


@contextmanager
def _sigterm_unwinds() -> Iterator[None]:
    """In the body, SIGTERM raises ``Terminated`` and SIGINT (Ctrl-C) ``KeyboardInterrupt``
    (signal handlers exist only in the main thread).

    SIGINT too, because Python installs its Ctrl-C handler only when SIGINT was not
    ignored at start: a grader started by a parent that ignores it (a CI runner, a test
    worker, ``nohup``) kept on grading after ``kill -INT`` and wrote no 130. (Before the
    package loaded its names lazily, something its eager import loaded had put the handler
    back by chance.)
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    previous_int = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        signal.signal(signal.SIGINT, previous_int)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: ``sys.argv[1:]``); return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    with _sigterm_unwinds():
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    """Run the chosen subcommand; every way it can end becomes an exit status."""
    try:
        return args.run(args)
    except Terminated:
        return 128 + signal.SIGTERM
    except InputProblem as problem:
        return fail(str(problem))
    except BrokenResult as problem:
        return fail(str(problem), EXIT_INVALID)
    except KeyboardInterrupt:
        return 130
    except MemoryError:
        return fail("out of memory: the mesh or the result is too large for this machine")
    except BrokenPipeError:
        # `halfedge-edu info x.obj | head -1`: the reader left; nothing went wrong here.
        # Point stdout at devnull so that flushing it at exit does not fail again.
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError):
            pass
        return EXIT_OK
    except Exception as error:
        if args.debug:
            raise
        extra = missing_extra(args.command, error)
        if extra:
            return fail(extra)
        # The library's errors about the input became InputProblem in the subcommand
        # (files.names_the_file): anything else is a bug in halfedge_edu, not in the input.
        return fail(
            f"internal error ({type(error).__name__}: {error}); "
            f"run again with --debug to see the traceback, and please report it"
        )
