"""``grade SUBMISSION.ipynb... --out DIR``: learners' chapter notebooks graded into reports.

Per submission DIR/NAME.json (Gradescope's ``results.json`` schema, which otter-grader
writes too) and DIR/NAME.xml (JUnit: GitHub Classroom, GitLab and Jenkins show it), and
one summary line. What one grade does, and the sandbox it runs in:
``halfedge_edu.exercises.grading``.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
from pathlib import Path
from typing import Sequence

from halfedge_edu.cli.errors import EXIT_INVALID, EXIT_OK, InputProblem, echo, fail, warn
from halfedge_edu.exercises.grading import (
    Grade,
    GradingError,
    Limits,
    exercises_for,
    grade_notebook,
    summary_line,
)
from halfedge_edu.exercises.sandbox import choose_isolation
from halfedge_edu.io.obj import atomic_output

#: What the sandboxed run of a notebook needs besides the library (the notebooks extra brings them).
NOTEBOOK_RUNNERS = ("nbformat", "nbclient", "ipykernel")


def run_grade(args: argparse.Namespace) -> int:
    """``grade SUBMISSION.ipynb... --out DIR``: per submission DIR/NAME.json and DIR/NAME.xml and one line.

    Every argument is checked before the first submission runs, so a bad one costs no
    grading time. Then every submission gets its report, written atomically, whatever
    another one did; the exit status is decided at the end: 0 when every report was
    written, 1 otherwise. SIGTERM and Ctrl-C stop at once: every process of the submission
    being graded is ended, no report claims a score for it, and the status is 143 or 130.
    """
    for submission in args.submissions:
        if not submission.exists():
            raise InputProblem(f"{submission}: no such file")
        if submission.is_dir():
            raise InputProblem(f"{submission}: is a folder, not a notebook")
    if args.out.exists() and not args.out.is_dir():
        raise InputProblem(f"{args.out}: exists and is not a folder")
    for module in NOTEBOOK_RUNNERS:  # say so before the first submission starts, not inside its sandbox
        if importlib.util.find_spec(module) is None:
            raise ModuleNotFoundError(f"No module named {module!r}", name=module)

    try:
        if args.chapter is not None:
            exercises_for(args.chapter)
        isolation = choose_isolation(args.isolation)
        args.out.mkdir(parents=True, exist_ok=True)
    except (GradingError, RuntimeError, OSError) as problem:
        raise InputProblem(str(problem)) from problem
    if isolation == "process" and args.isolation == "auto":
        warn("bubblewrap is not available here: each submission gets a private folder, environment and limits, "
             "but can see this machine's files; grade one submission per CI job, or install bubblewrap")
    limits = Limits(memory_mb=args.memory, processes=args.processes, file_size_mb=args.file_size,
                    output_mb=args.output)
    status = EXIT_OK
    for submission, name in zip(args.submissions, report_names(args.submissions)):
        try:
            grade = grade_notebook(submission, chapter=args.chapter, cell_timeout=args.cell_timeout,
                                   total_timeout=args.timeout, isolation=isolation, limits=limits, seed=args.seed)
        except Exception as error:  # a bug of the grader: this submission's report says so, the batch goes on
            grade = Grade(str(submission), args.chapter or "", [], 0.0,
                          f"the grader failed on this submission ({type(error).__name__}: {error}); "
                          f"please report it")
            status = EXIT_INVALID
        try:
            _write_report(args.out / f"{name}.json", grade.to_json())
            _write_report(args.out / f"{name}.xml", grade.to_junit_xml())
        except OSError as error:
            fail(f"{args.out / name}: the report could not be written ({error.strerror or error}); "
                 f"grading goes on")
            status = EXIT_INVALID
        echo(summary_line(grade))
    return status


def report_names(submissions: Sequence[Path]) -> list[str]:
    """One report name per submission, never the same twice: the file's stem, with its folders
    joined in where two stems are alike, with odd characters replaced by ``_``."""

    def clean(text: str) -> str:
        return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("._") or "submission"

    stems = [clean(path.stem) for path in submissions]
    names: list[str] = []
    for path, stem in zip(submissions, stems):
        name = stem
        if stems.count(stem) > 1:
            name = clean("__".join(path.resolve().parts[-3:-1] + (path.stem,)))
        base, number = name, 2
        while name in names:
            name, number = f"{base}-{number}", number + 1
        names.append(name)
    return names


def _write_report(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (``hx.save``'s own writer: temporary file, fsync, rename)."""
    with atomic_output(path) as out:
        out.write(text + "\n")
