"""``course DEST [--update]``: the student edition of the chapters, copied into DEST.

The copying itself is :func:`halfedge_edu.course.copy_course` (standard library only, so
that ``setup.py`` can load that file by path at build time); this module prints what it
did, one line per outcome.
"""

from __future__ import annotations

import argparse
import sys

from halfedge_edu.cli.errors import EXIT_ERROR, EXIT_OK, InputProblem
from halfedge_edu.course import copy_course


def run_course(args: argparse.Namespace) -> int:
    """``course DEST [--update]``: copy, then print one line per outcome. Exit status 0, or
    2 (one line per chapter on stderr) if a chapter could not be copied."""
    try:
        result = copy_course(args.destination, update=args.update)
    except OSError as problem:
        raise InputProblem(str(problem)) from problem
    where = result.destination
    print(f"course: copied {len(result.copied)} chapters (halfedge_edu {result.version}) to {where}")
    if result.updated:
        print(f"course: updated {len(result.updated)} unedited chapters to {result.version}: "
              f"{', '.join(result.updated)}")
    for name, newer in result.beside:
        print(f"course: {name} has your edits and was kept; the {result.version} version is beside it: {newer}")
    for name, broken in result.repaired:
        print(f"course: {name} was not a valid notebook; copied it again (the broken file is now {broken})")
    if result.kept:
        print(f"course: kept {len(result.kept)} already there: {', '.join(result.kept)}")
    if result.outdated:
        print(f"course: kept {len(result.outdated)} from another version of halfedge_edu: "
              f"{', '.join(result.outdated)}; 'halfedge-edu course {where} --update' brings {result.version}")
    for name, reason in result.skipped:
        print(f"halfedge-edu: error: {where / name}: not copied: {reason}", file=sys.stderr)
    print(f"next: jupyter lab {where}")
    return EXIT_ERROR if result.skipped else EXIT_OK
