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

The library is imported only once a subcommand runs, so ``--help`` is instant.
"""

from __future__ import annotations

import argparse
import errno
import math
import os
import signal
import sys
import threading
import warnings
from contextlib import contextmanager
from pathlib import Path
from types import FrameType
from typing import Callable, Iterator, NoReturn, Sequence, TextIO

from halfedge_edu.course import add_course_parser

PROG = "halfedge-edu"

EXIT_OK = 0
EXIT_INVALID = 1  # a mesh breaks a halfedge invariant: `check`'s input, or a command's result
EXIT_ERROR = 2  # bad input or usage (argparse uses 2 for usage errors too)

# How many non-manifold elements `info` lists by index before it only counts them.
MAX_LISTED = 10

#: ``--max-faces``'s default: about 1-2 GB of memory for the halfedge arrays and the
#: algorithms' work arrays.
DEFAULT_MAX_FACES = 10_000_000

#: The largest coordinate (in absolute value) a computing command accepts: the same
#: limit every public algorithm checks (its reason is written where it is defined).
from halfedge_edu.algorithms.arguments import MAX_COORDINATE, MIN_EXTENT  # noqa: E402


class InputProblem(Exception):
    """Input the command cannot use; reported as one line on stderr with exit status 2."""


class BrokenResult(Exception):
    """An algorithm returned a mesh that fails ``validate()``: a bug, reported with exit status 1."""


class Terminated(BaseException):
    """SIGTERM arrived. A ``BaseException`` like ``KeyboardInterrupt``, so that it unwinds
    through every ``except Exception`` and ``hx.save`` removes its temporary file."""


def _raise_terminated(signum: int, frame: FrameType | None) -> NoReturn:
    raise Terminated()


@contextmanager
def _sigterm_unwinds() -> Iterator[None]:
    """In the body, SIGTERM raises ``Terminated`` (signal handlers exist only in the main thread)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


class _Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose usage errors are one line, like every other error."""

    def error(self, message: str) -> NoReturn:
        _fail(f"{message} (see '{self.prog} --help')")
        self.exit(EXIT_ERROR)


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
        return _fail(str(problem))
    except BrokenResult as problem:
        return _fail(str(problem), EXIT_INVALID)
    except KeyboardInterrupt:
        return 130
    except MemoryError:
        return _fail("out of memory: the mesh or the result is too large for this machine")
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
        missing_extra = _missing_extra(args, error)
        if missing_extra:
            return _fail(missing_extra)
        if _is_input_error(error):
            return _fail(_with_path(args.file, error))
        # Anything else is a bug in halfedge_edu, not a problem with the input.
        return _fail(
            f"internal error ({type(error).__name__}: {error}); "
            f"run again with --debug to see the traceback, and please report it"
        )


def _missing_extra(args: argparse.Namespace, error: Exception) -> str | None:
    """For an optional dependency that is not installed, the line naming the extra that
    brings it (``grade`` without the notebooks extra); None for any other error."""
    from halfedge_edu._extras import extra_for, install_hint

    if not isinstance(error, ModuleNotFoundError) or extra_for(error.name) is None:
        return None
    return f"{args.command} needs {error.name}, which is not installed: {install_hint(extra_for(error.name))}"


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every registered subcommand."""
    parser = _Parser(
        prog=PROG,
        description="Inspect, check, refine, simplify, smooth, remesh and convert triangle meshes as halfedge meshes.",
        epilog=(
            "Exit status: 0 success; 1 a mesh breaks a halfedge invariant (`check` on its "
            "input; any other command on its own result, which is a bug: nothing is "
            "written); 2 bad input or usage (one line on stderr, no output file)."
        ),
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    parser.add_argument(
        "--debug", action="store_true", help="show the full traceback of an internal error"
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    info = commands.add_parser(
        "info",
        help="print counts, Euler characteristic, genus, boundary loops and degrees",
        description=(
            "Print the element counts, Euler characteristic, genus, boundary loops, "
            "manifoldness and vertex-degree histogram of a mesh file. A file that is "
            "not manifold gets a report of its non-manifold edges and vertices instead."
        ),
    )
    info.add_argument("file", type=Path, metavar="FILE", help=INPUT_HELP)
    _add_repair(info)
    info.set_defaults(run=run_info)

    check = commands.add_parser(
        "check",
        help="load a mesh and validate every halfedge invariant",
        description=(
            "Load a mesh file, build its halfedge structure and validate it. "
            "Exit status 0 if it is a valid halfedge mesh, 1 (with the broken rule) if "
            "not, 2 if the file cannot be read or built."
        ),
    )
    check.add_argument("file", type=Path, metavar="FILE", help=INPUT_HELP)
    _add_repair(check)
    check.set_defaults(run=run_check)

    subdivide = _add_transform(
        commands, "subdivide", run_subdivide,
        help="Loop subdivision: every level splits each triangle into 4",
        description=(
            "Loop subdivision, N levels (each multiplies the faces by 4), written to OUT. "
            "Old vertices move with Warren's weights (beta = 3/16 for degree 3, 3/(8n) "
            "otherwise) unless --weights loop asks for Loop's original beta. "
            "Example: halfedge-edu subdivide in.obj out.obj 2"
        ),
    )
    subdivide.add_argument(
        "levels", nargs="?", type=_whole_number(0), metavar="N",
        help="how many levels (default 1)",
    )
    subdivide.add_argument(
        "--levels", dest="levels_option", type=_whole_number(0), metavar="N",
        help="the same as the positional N",
    )
    subdivide.add_argument(
        "--weights", choices=("warren", "loop"), default="warren",
        help="how an old vertex moves: 'warren' (default; beta = 3/16 for degree 3, 3/(8n) "
             "otherwise) or 'loop' (Loop's original beta = (5/8 - (3/8 + cos(2 pi/n)/4)^2)/n)",
    )
    _add_max_faces(subdivide)

    simplify = _add_transform(
        commands, "simplify", run_simplify,
        help="quadric-error edge collapses down to a face count",
        description=(
            "Simplify by quadric-error edge collapses to N faces (--faces) or to a "
            "fraction of the input's faces (--ratio), written to OUT."
        ),
    )
    target = simplify.add_mutually_exclusive_group(required=True)
    target.add_argument("--faces", type=_whole_number(1), metavar="N", help="how many faces to keep")
    target.add_argument(
        "--ratio", type=_ratio, metavar="R", help="the fraction of faces to keep, 0 < R <= 1"
    )

    smooth = _add_transform(
        commands, "smooth", run_smooth,
        help="Laplacian smoothing (uniform or cotangent weights)",
        description="Laplacian smoothing: move every vertex towards a weighted mean of its neighbours.",
    )
    smooth.add_argument(
        "--iterations", type=_whole_number(0), default=1, metavar="N", help="how many iterations (default 1)"
    )
    smooth.add_argument(
        "--weights", choices=("uniform", "cotangent"), default="uniform",
        help="the neighbours' weights (default uniform)",
    )
    smooth.add_argument(
        "--boundary", choices=("fixed", "along"), default="fixed",
        help="boundary vertices stay (fixed, the default) or move along their boundary loop",
    )

    remesh = _add_transform(
        commands, "remesh", run_remesh,
        help="isotropic remeshing: edges of about one length, degrees near 6",
        description=(
            "Isotropic remeshing: split long edges, collapse short ones, flip towards "
            "degree 6, smooth tangentially and project back onto the input surface."
        ),
    )
    remesh.add_argument(
        "--length", type=_positive_number, metavar="L",
        help="the edge length to aim for (default: the input's mean edge length)",
    )
    remesh.add_argument(
        "--iterations", type=_whole_number(0), default=5, metavar="N", help="how many rounds (default 5)"
    )
    remesh.add_argument(
        "--feature-angle", type=_feature_angle, default=argparse.SUPPRESS, metavar="DEG",
        help=("keep creases whose faces meet at more than DEG degrees, and the boundary "
              "(default: remesh's, 45; 'none': keep only the boundary, round the creases)"),
    )
    _add_max_faces(remesh)

    _add_transform(
        commands, "convert", run_convert, progress=False,
        help="write a mesh in another format (picked by OUT's suffix)",
        description=(
            "Read IN and write it to OUT; the format is picked by the suffix "
            "(.obj by halfedge_edu's own writer, .ply .stl .off .glb .gltf through trimesh)."
        ),
    )
    add_course_parser(commands)
    _add_grade(commands)
    return parser


INPUT_HELP = "a .obj, .ply, .stl, .off, .glb or .gltf file"


def _seconds(text: str) -> float:
    """An argparse type: a positive number of seconds."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not value > 0 or value != value or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text}")
    return value


def _add_grade(commands) -> None:
    """``grade SUBMISSION.ipynb... --out DIR``: see :func:`run_grade`."""
    grade = commands.add_parser(
        "grade",
        help="run learners' chapter notebooks in a sandbox and grade their exercises (JSON and JUnit reports)",
        description=(
            "Run each submitted chapter notebook top to bottom in its own sandbox (a private folder, "
            "limits, and with bubblewrap no network and no view of other submissions), check each "
            "exercise's function from a separate judge process with the package's public and hidden "
            "cases, and write DIR/NAME.json (Gradescope/otter results.json) and DIR/NAME.xml (JUnit). "
            "Every submission gets its report, whatever another one does. Exit status 0 when every "
            "report was written, whatever the scores; 1 when a report could not be written; 2 for bad "
            "arguments; 130/143 when interrupted (no report is written for the submission being graded)."
        ),
    )
    grade.add_argument("submissions", type=Path, nargs="+", metavar="SUBMISSION.ipynb",
                       help="the learners' notebooks (the chapter comes from the file name, else the notebook)")
    grade.add_argument("--out", type=Path, required=True, metavar="DIR",
                       help="the folder for the reports (created if missing)")
    grade.add_argument("--chapter", metavar="NN",
                       help="grade every submission as this chapter (default: the number the file name starts "
                            "with, else the notebook's own stamp)")
    grade.add_argument("--cell-timeout", type=_seconds, default=60, metavar="S",
                       help="seconds one cell may run before it is interrupted (default 60)")
    grade.add_argument("--timeout", type=_seconds, default=600, metavar="S",
                       help="seconds a whole notebook may run (default 600)")
    grade.add_argument("--isolation", choices=("auto", "bubblewrap", "process"), default="auto",
                       help="bubblewrap: own namespaces, no network, only its own files, a throwaway user when "
                            "run as root; process: private folder, environment and limits only; auto (default): "
                            "bubblewrap where it works")
    grade.add_argument("--memory", type=_whole_number(64), default=2048, metavar="MB",
                       help="memory of one submission's processes together (default 2048)")
    grade.add_argument("--processes", type=_whole_number(16), default=256, metavar="N",
                       help="processes and threads of one submission (default 256)")
    grade.add_argument("--file-size", type=_whole_number(1), default=64, metavar="MB",
                       help="the largest file one submission may write (default 64)")
    grade.add_argument("--output", type=_whole_number(1), default=8, metavar="MB",
                       help="printed cell output kept per submission; more is dropped (default 8)")
    grade.add_argument("--seed", type=_whole_number(0), default=None, metavar="N",
                       help="the hidden cases' seed (default: a new one per run, written in each report)")
    grade.set_defaults(run=run_grade)


def run_grade(args: argparse.Namespace) -> int:
    """``grade SUBMISSION.ipynb... --out DIR``: per submission DIR/NAME.json and DIR/NAME.xml and one line.

    The JSON follows Gradescope's ``results.json`` schema (otter-grader writes it too),
    the XML is JUnit (GitHub Classroom, GitLab and Jenkins show it). Every argument is
    checked before the first submission runs, so a bad one costs no grading time. Then
    every submission gets its report, written atomically, whatever another one did; the
    exit status is decided at the end: 0 when every report was written, 1 otherwise.
    SIGTERM and Ctrl-C stop at once: every process of the submission being graded is
    ended, no report claims a score for it, and the status is 143 or 130. What one grade
    does: ``halfedge_edu.exercises.grading``.
    """
    for submission in args.submissions:
        if not submission.exists():
            raise InputProblem(f"{submission}: no such file")
        if submission.is_dir():
            raise InputProblem(f"{submission}: is a folder, not a notebook")
    if args.out.exists() and not args.out.is_dir():
        raise InputProblem(f"{args.out}: exists and is not a folder")

    import importlib.util

    for module in ("nbformat", "nbclient", "ipykernel"):  # the sandboxed run needs them: say so before it starts
        if importlib.util.find_spec(module) is None:
            raise ModuleNotFoundError(f"No module named {module!r}", name=module)
    from halfedge_edu.exercises.grading import GradingError, Limits, exercises_for, grade_notebook, summary_line
    from halfedge_edu.exercises.sandbox import choose_isolation

    try:
        if args.chapter is not None:
            exercises_for(args.chapter)
        isolation = choose_isolation(args.isolation)
        args.out.mkdir(parents=True, exist_ok=True)
    except (GradingError, RuntimeError, OSError) as problem:
        raise InputProblem(str(problem)) from problem
    if isolation == "process" and args.isolation == "auto":
        _warn("bubblewrap is not available here: each submission gets a private folder, environment and limits, "
              "but can see this machine's files; grade one submission per CI job, or install bubblewrap")
    limits = Limits(memory_mb=args.memory, processes=args.processes, file_size_mb=args.file_size,
                    output_mb=args.output)
    status = EXIT_OK
    for submission, name in zip(args.submissions, report_names(args.submissions)):
        try:
            grade = grade_notebook(submission, chapter=args.chapter, cell_timeout=args.cell_timeout,
                                   total_timeout=args.timeout, isolation=isolation, limits=limits, seed=args.seed)
        except Exception as error:  # a bug of the grader: this submission's report says so, the batch goes on
            from halfedge_edu.exercises.grading import Grade

            grade = Grade(str(submission), args.chapter or "", [], 0.0,
                          f"the grader failed on this submission ({type(error).__name__}: {error}); "
                          f"please report it")
            status = EXIT_INVALID
        try:
            _write_report(args.out / f"{name}.json", grade.to_json())
            _write_report(args.out / f"{name}.xml", grade.to_junit_xml())
        except OSError as error:
            _fail(f"{args.out / name}: the report could not be written ({error.strerror or error}); "
                  f"grading goes on")
            status = EXIT_INVALID
        _print(summary_line(grade))
    return status


def report_names(submissions: Sequence[Path]) -> list[str]:
    """One report name per submission, never the same twice: the file's stem, with its folders
    joined in where two stems are alike, with odd characters replaced by ``_``."""
    import re

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
    from halfedge_edu.io.obj import atomic_output

    with atomic_output(path) as out:
        out.write(text + "\n")


def _add_repair(command: argparse.ArgumentParser) -> None:
    command.add_argument(
        "--repair", action="store_true",
        help="repair the triangles on loading: drop degenerate and duplicate faces, "
        "orient them consistently, split non-manifold edges and vertices",
    )


def _add_max_faces(command: argparse.ArgumentParser) -> None:
    command.add_argument(
        "--max-faces", type=_whole_number(1), default=DEFAULT_MAX_FACES, metavar="N",
        help=f"refuse to start if the result would have more than about N faces (default {DEFAULT_MAX_FACES:,})",
    )


def _add_transform(commands, name: str, run: Callable, *, progress: bool = True, **texts) -> argparse.ArgumentParser:
    """Add a subcommand ``name IN OUT ...`` with ``--repair`` (and ``--progress``)."""
    command = commands.add_parser(name, **texts)
    command.add_argument("file", type=Path, metavar="IN", help=INPUT_HELP)
    command.add_argument("output", type=Path, metavar="OUT", help="where to write; the suffix picks the format")
    _add_repair(command)
    if progress:
        command.add_argument(
            "--progress", action=argparse.BooleanOptionalAction, default=None,
            help="show a progress bar on stderr (default: when stderr is a terminal)",
        )
    command.set_defaults(run=run)
    return command


def _whole_number(minimum: int) -> Callable[[str], int]:
    """An argparse type: a whole number >= ``minimum``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum}, got {value}")
        return value

    return parse


def _ratio(text: str) -> float:
    """An argparse type: a number in (0, 1]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not 0 < value <= 1:
        raise argparse.ArgumentTypeError(f"must be in (0, 1], got {text}")
    return value


def _positive_number(text: str) -> float:
    """An argparse type: a finite number > 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text}")
    return value


def run_info(args: argparse.Namespace) -> int:
    """``info FILE``: describe the mesh, or its non-manifold parts if it cannot be built."""
    from halfedge_edu.core.errors import MeshInputError

    path = args.file
    try:
        mesh = _load(path, repair=args.repair)
    except MeshInputError as error:
        return _info_not_buildable(path, error)

    import numpy as np

    live_degrees = mesh.vertex_degrees()[~np.asarray(mesh.vertex_deleted)]  # (n_vertices,)
    lines = [
        f"file: {path}",
        f"vertices: {mesh.n_vertices}",
        f"edges: {mesh.n_edges}",
        f"faces: {mesh.n_faces}",
        f"halfedges: {mesh.n_halfedges}",
        f"euler characteristic: {mesh.euler_characteristic}",
        f"genus: {mesh.genus}",
        f"boundary loops: {mesh.n_boundary_loops}",
        "manifold: yes",
        "vertex degrees:",
    ]
    counts = np.bincount(live_degrees) if live_degrees.size else np.zeros(0, dtype=int)
    lines += [f"  {degree:>3}: {count}" for degree, count in enumerate(counts) if count]
    _print("\n".join(lines))
    return EXIT_OK


def _info_not_buildable(path: Path, error: Exception) -> int:
    """Report on a file the halfedge structure cannot hold: what keeps it from being one."""
    import numpy as np

    import halfedge_edu as hx

    try:
        vertices, faces = _read_raw(path)  # (n, 3) float, (m, 3) int
        report = hx.manifold_report(faces)
    except Exception:
        # Not even a face list (a bad line, an index out of range): say why not.
        raise InputProblem(_with_path(path, error)) from error
    if report:
        # A manifold, consistently oriented face list that still did not build: the
        # library's message says what else is wrong.
        raise InputProblem(_with_path(path, error))

    corners = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)  # (3m, 2) directed edges
    n_edges = len(np.unique(np.sort(corners, axis=1), axis=0))
    manifold = not (len(report.nonmanifold_edges) or len(report.nonmanifold_vertices))
    lines = [
        f"file: {path}",
        f"vertices: {len(vertices)}",
        f"edges: {n_edges}",
        f"faces: {len(faces)}",
        f"manifold: {'yes' if manifold else 'no'}",
        "halfedge mesh: no, because of",
    ]
    problems = [
        ("non-manifold edges (more than two faces)", "nonmanifold_edges", "{0}-{1}"),
        ("non-manifold vertices (more than one fan)", "nonmanifold_vertices", "{0}"),
        ("edges used twice in the same direction", "inconsistent_edges", "{0}->{1}"),
        ("degenerate faces (a repeated vertex)", "degenerate_faces", "{0}"),
        ("duplicate faces", "duplicate_faces", "{0}"),
    ]
    for title, attribute, form in problems:
        found = np.asarray(getattr(report, attribute, []))
        if len(found):
            rows = found.reshape(len(found), -1).tolist()
            lines.append(f"  {title}: {len(found)}{_listing(form.format(*row) for row in rows)}")
    lines.append(f"loading said: {_one_line(str(error))}")
    _print("\n".join(lines))
    return EXIT_OK


def run_check(args: argparse.Namespace) -> int:
    """``check FILE``: exit 0 if the file is a valid halfedge mesh, 1 if an invariant breaks."""
    from halfedge_edu.core.errors import MeshInvariantError

    path = args.file
    mesh = _load_or_fail(path, repair=args.repair)
    try:
        mesh.validate()
    except MeshInvariantError as error:
        _print(f"{path}: not a valid halfedge mesh: {_one_line(str(error))}")
        return EXIT_INVALID
    _print(f"{path}: valid halfedge mesh ({mesh.n_vertices} vertices, {mesh.n_faces} faces)")
    return EXIT_OK


def run_subdivide(args: argparse.Namespace) -> int:
    """``subdivide IN OUT N``: Loop subdivision, N levels."""
    levels = args.levels if args.levels is not None else args.levels_option
    if args.levels_option is not None and levels != args.levels_option:
        raise InputProblem(f"N is {args.levels} but --levels is {args.levels_option}; give the number of levels once")
    levels = 1 if levels is None else levels

    def algorithm(mesh):
        from halfedge_edu.algorithms.loop import loop_subdivide

        return loop_subdivide(mesh, levels, weights=args.weights, progress=_progress(args))

    def estimate(mesh) -> tuple[float, str]:
        # Beyond 500 levels 4.0**levels leaves float range: more than any limit.
        return mesh.n_faces * 4.0**levels if levels <= 500 else math.inf, f"{levels} levels of subdivision"

    return _transform(args, algorithm, estimate=estimate)


def run_simplify(args: argparse.Namespace) -> int:
    """``simplify IN OUT --faces N | --ratio R``: quadric-error edge collapses."""

    def algorithm(mesh):
        from halfedge_edu.algorithms.simplify import simplify

        target = args.faces if args.faces is not None else max(1, round(args.ratio * mesh.n_faces))
        if target >= mesh.n_faces:
            _warn(f"the target of {target} faces is not below the input's {mesh.n_faces}: nothing to simplify")
        return simplify(mesh, target, progress=_progress(args))

    return _transform(args, algorithm)


def run_smooth(args: argparse.Namespace) -> int:
    """``smooth IN OUT [--iterations N] [--weights W] [--boundary B]``: Laplacian smoothing."""

    def algorithm(mesh):
        from halfedge_edu.algorithms.smoothing import smooth

        return smooth(
            mesh, args.iterations, weights=args.weights, boundary=args.boundary, progress=_progress(args)
        )

    return _transform(args, algorithm)


def _feature_angle(text: str) -> float | None:
    """An argparse type: an angle from 0 to 180 degrees, or ``none`` (no creases kept)."""
    if text.strip().lower() == "none":
        return None
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is neither a number nor 'none'") from None
    if not 0 <= value <= 180:
        raise argparse.ArgumentTypeError(f"must be an angle from 0 to 180 degrees, got {text}")
    return value


def run_remesh(args: argparse.Namespace) -> int:
    """``remesh IN OUT [--length L] [--iterations N] [--feature-angle DEG]``: isotropic remeshing."""

    def algorithm(mesh):
        from halfedge_edu.algorithms.remesh import remesh

        # Not given: remesh's own default (the library is not imported to parse arguments).
        features = {"feature_angle": args.feature_angle} if "feature_angle" in vars(args) else {}
        return remesh(mesh, args.length, args.iterations, progress=_progress(args), **features)

    def estimate(mesh) -> tuple[float, str]:
        if args.length is None:  # the input's mean edge length: about the input's face count
            return mesh.n_faces, "remeshing"
        return _faces_at_edge_length(mesh, args.length), f"remeshing to edge length {args.length:g}"

    return _transform(args, algorithm, estimate=estimate)


def _faces_at_edge_length(mesh, length: float) -> float:
    """About how many triangles with edges of ``length`` cover the mesh's surface.

    An equilateral triangle with edge L has area sqrt(3)/4 L^2; isotropic remeshing
    makes nearly equilateral triangles, so surface area / that area is the estimate.
    """
    import numpy as np

    from halfedge_edu.algorithms.normals import face_areas

    area = face_areas(mesh).sum()
    with np.errstate(over="ignore", divide="ignore"):  # a tiny length: the estimate is inf
        return float(area / (np.sqrt(3) / 4 * np.float64(length) ** 2))


def run_convert(args: argparse.Namespace) -> int:
    """``convert IN OUT``: the same mesh in the format of OUT's suffix."""
    return _transform(args, lambda mesh: mesh, computes=False)


def _transform(
    args: argparse.Namespace,
    algorithm: Callable,
    *,
    estimate: Callable | None = None,
    computes: bool = True,
) -> int:
    """Load IN, run ``algorithm(mesh) -> mesh``, validate the result, write it to OUT.

    OUT is checked before loading (so a long run does not end in "cannot write
    there"), and written last, atomically: if anything fails, OUT is as it was.
    ``estimate(mesh) -> (faces, what)`` says how large the result will be, checked
    against ``--max-faces`` before the work starts; ``computes`` (every command but
    ``convert``) refuses coordinates too large to compute with.
    """
    from halfedge_edu.core.errors import MeshInvariantError

    output = args.output
    _check_readable(args.file)
    _check_writable(output)
    mesh = _load_or_fail(args.file, repair=args.repair)
    faces_before = mesh.n_faces
    if computes:
        _check_coordinate_size(mesh, args.file)
    if estimate is not None:
        _check_result_size(*estimate(mesh), args.max_faces)
    with _warnings_as_lines():
        result = algorithm(mesh)
    try:
        result.validate()
    except MeshInvariantError as error:
        raise BrokenResult(
            f"internal error: {args.command} made a mesh that is not a valid halfedge mesh "
            f"({_one_line(str(error))}); nothing was written; please report it"
        ) from error
    _save(result, output)
    _print(f"{args.command}: {faces_before} -> {result.n_faces} faces, wrote {output}")
    return EXIT_OK


def _check_coordinate_size(mesh, path: Path) -> None:
    """Raise ``InputProblem`` if a coordinate is beyond ``MAX_COORDINATE`` (products would
    overflow) or the mesh is smaller across than ``MIN_EXTENT`` (products would round to zero)."""
    import numpy as np

    vertices = mesh.to_arrays()[0]  # (n, 3)
    largest = float(np.abs(vertices).max()) if vertices.size else 0.0
    if largest > MAX_COORDINATE:
        raise InputProblem(
            f"{path}: coordinates up to {largest:.3g} are too large for the computation "
            f"(at most {MAX_COORDINATE:.0e}, so that the products the algorithms take stay finite); scale the mesh down"
        )
    extent = float(np.ptp(vertices, axis=0).max()) if mesh.n_faces else MIN_EXTENT
    if extent < MIN_EXTENT:
        raise InputProblem(
            f"{path}: the mesh is {extent:.3g} across, too small for the computation "
            f"(at least {MIN_EXTENT:.0e}, so that the products the algorithms take do not round to zero); scale the mesh up"
        )


def _check_result_size(estimated_faces: float, what: str, limit: int) -> None:
    """Raise ``InputProblem`` if the estimated result is above ``--max-faces``."""
    if estimated_faces > limit:
        about = f"about {estimated_faces:.3g}" if math.isfinite(estimated_faces) else "more than 1e308"
        raise InputProblem(
            f"{what} would make {about} faces, more than the limit of {limit:,}; "
            f"raise it with --max-faces N if the machine has the memory"
        )


def _progress(args: argparse.Namespace) -> bool:
    """``--progress`` / ``--no-progress``, or by default: is stderr a terminal? An explicit
    ``--progress`` without tqdm installed is an input problem naming the extra (by
    default the bar is simply left out)."""
    if args.progress:
        import importlib.util

        from halfedge_edu._extras import extra_for, install_hint

        if importlib.util.find_spec("tqdm") is None:
            raise InputProblem(f"--progress needs tqdm, which is not installed: {install_hint(extra_for('tqdm'))}")
    if args.progress is not None:
        return args.progress
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # replaced or closed stderr
        return False


def _check_writable(output: Path) -> None:
    """Raise ``InputProblem`` if ``output`` cannot be written (suffix, path, folder, permission)."""
    from halfedge_edu.io import SUFFIXES
    from halfedge_edu.io.obj import path_error, shown_path

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


def _save(mesh, output: Path) -> None:
    """``hx.save`` (temporary file beside OUT, then moved into place), errors as ``InputProblem``.

    A ``MeshInputError`` here is OUT's format refusing the mesh, so it names OUT. First
    removes temporary files that earlier runs, killed mid-write, left in OUT's folder
    (only ``.halfedge_edu-XXXXXXXX.tmp`` files untouched for 10 minutes).
    """
    import halfedge_edu as hx
    from halfedge_edu.core.errors import MeshInputError
    from halfedge_edu.io.obj import remove_stale_temporaries

    # What an earlier run killed mid-write (SIGKILL, a power cut) could not remove itself.
    remove_stale_temporaries(output.parent)
    try:
        hx.save(mesh, output)
    except (OSError, MeshInputError) as error:
        raise InputProblem(_with_path(output, error)) from error


def _load_or_fail(path: Path, *, repair: bool = False):
    """``_load``, with every ``MeshInputError`` an ``InputProblem`` (suggesting ``--repair`` if it helps)."""
    from halfedge_edu.core.errors import MeshInputError

    try:
        return _load(path, repair=repair)
    except MeshInputError as error:
        message = _with_path(path, error)
        if not repair and _repair_would_help(path):
            message += "; run again with --repair to load it repaired"
        raise InputProblem(message) from error


def _repair_would_help(path: Path) -> bool:
    """Are the file's triangles readable but not manifold (what ``repair=True`` fixes)?"""
    import halfedge_edu as hx

    try:
        _, faces = _read_raw(path)
        return not hx.manifold_report(faces)
    except Exception:  # the file cannot even be read as triangles: repair will not help
        return False


def _load(path: Path, *, repair: bool = False):
    """``hx.load(path)`` with input problems turned into ``InputProblem``.

    ``MeshInputError`` is passed through so that a caller can look closer; the library's
    warnings (e.g. dropped unreferenced vertices) are printed as one line each.
    """
    import halfedge_edu as hx
    from halfedge_edu.core.errors import MeshInputError

    _check_readable(path)
    with _warnings_as_lines():
        try:
            mesh = hx.load(path, repair=repair)
        except MeshInputError:
            raise
        except (OSError, ValueError) as error:  # UnicodeDecodeError is a ValueError
            raise InputProblem(_with_path(path, error)) from error
    return mesh


@contextmanager
def _warnings_as_lines() -> Iterator[None]:
    """Collect the library's warnings in the body; if it succeeds, print each as one line."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UserWarning)  # MeshWarning among them
        yield
    for warning in caught:
        _warn(str(warning.message))


def _warn(message: str) -> None:
    _print(f"{PROG}: warning: {_one_line(message)}", file=sys.stderr)


def _print(text: str, file: TextIO | None = None) -> None:
    """``print``, with file-name bytes that are not UTF-8 shown as ``\\xe9``.

    Python hands such bytes over as lone surrogates (``\\udce9``), which a UTF-8
    console refuses to encode: printing the name must not become the error.
    """
    print(text.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace"), file=file)


def _read_raw(path: Path):
    """The vertex and face arrays of a file, without building anything from them."""
    from halfedge_edu.io import load_arrays

    vertices, faces, _ = load_arrays(path)
    return vertices, faces


def _is_input_error(error: Exception) -> bool:
    """Is this one of halfedge_edu's own errors about the input or the mesh?"""
    try:
        from halfedge_edu.core.errors import MeshInputError, MeshInvariantError, TopologyError
    except ImportError:
        return False

    return isinstance(error, (MeshInputError, MeshInvariantError, TopologyError))


def _check_readable(path: Path) -> None:
    """Raise ``InputProblem`` unless ``path`` is a regular file this system can name."""
    from halfedge_edu.io.obj import path_error, shown_path

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


def _with_path(path: Path, error: Exception) -> str:
    """The error's message, starting with the file (unless it already does; a very long path cut short)."""
    from halfedge_edu.io.obj import shown_path

    if isinstance(error, OSError) and error.strerror:
        message = error.strerror
    else:
        message = str(error) or type(error).__name__
    shown = shown_path(path)
    if not message.startswith((str(path), path.name, shown)):
        message = f"{shown}: {message}"
    return _one_line(message)


def _listing(items) -> str:
    items = list(items)
    if not items:
        return ""
    shown = ", ".join(items[:MAX_LISTED])
    more = f", ... ({len(items) - MAX_LISTED} more)" if len(items) > MAX_LISTED else ""
    return f" ({shown}{more})"


def _one_line(text: str) -> str:
    return " ".join(text.split())


#: The longest error message printed whole: a message quoting a whole file or a list of
#: a million faces must not become megabytes on one line.
MAX_MESSAGE = 2000


def _fail(message: str, status: int = EXIT_ERROR) -> int:
    """Print ``message`` as one ``error:`` line on stderr (cut short past ``MAX_MESSAGE``); return ``status``."""
    message = _one_line(message)
    if len(message) > MAX_MESSAGE:
        message = f"{message[:MAX_MESSAGE]} ... ({len(message) - MAX_MESSAGE} more characters cut)"
    _print(f"{PROG}: error: {message}", file=sys.stderr)
    return status


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("halfedge_edu")
    except PackageNotFoundError:
        return "(not installed)"
