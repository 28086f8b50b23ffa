"""What the command line accepts: every subcommand, its arguments and its help.

Building the parser imports none of the subcommands' modules, and so neither the library
nor numpy: each subcommand names the function that runs it (:func:`_run_by`), whose module
is imported once that subcommand is chosen. ``halfedge-edu --help``, ``COMMAND --help`` and
a usage error load the standard library only. The argument types here refuse a bad value
(a negative count, a ratio above 1) as a usage error, before any file is read.
"""

from __future__ import annotations

import argparse
import importlib
import math
from pathlib import Path
from typing import Callable, NoReturn

from halfedge_edu.cli.errors import EXIT_ERROR, PROG, fail

#: ``--max-faces``'s default: about 1-2 GB of memory for the halfedge arrays and the
#: algorithms' work arrays.
DEFAULT_MAX_FACES = 10_000_000

INPUT_HELP = "a .obj, .ply, .stl, .off, .glb or .gltf file"


def _run_by(module: str, function: str) -> Callable[[argparse.Namespace], int]:
    """The subcommand runner ``halfedge_edu.cli.<module>.<function>(args)``, imported when called.

    Every subcommand module imports what it needs at its top (the library, numpy); this
    is the one place that defers it, so that only the chosen subcommand's module loads.
    """

    def run(args: argparse.Namespace) -> int:
        return getattr(importlib.import_module(f"halfedge_edu.cli.{module}"), function)(args)

    return run


class _Parser(argparse.ArgumentParser):
    """An ``ArgumentParser`` whose usage errors are one line, like every other error."""

    def error(self, message: str) -> NoReturn:
        fail(f"{message} (see '{self.prog} --help')")
        self.exit(EXIT_ERROR)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand (none of their modules is imported)."""
    parser = _Parser(
        prog=PROG,
        description="Inspect, check, refine, simplify, smooth, remesh and convert triangle meshes as halfedge meshes.",
        epilog=(
            "Exit status: 0 success; 1 a mesh breaks a halfedge invariant (`check` on its "
            "input; any other command on its own result, which is a bug: nothing is "
            "written); 2 bad input or usage (one line on stderr, no output file)."
        ),
    )
    parser.add_argument("--version", action=_Version, help="show program's version number and exit")
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
    info.set_defaults(run=_run_by("inspect", "run_info"))

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
    check.set_defaults(run=_run_by("inspect", "run_check"))

    subdivide = _add_transform(
        commands, "subdivide", _run_by("transform", "run_subdivide"),
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
        commands, "simplify", _run_by("transform", "run_simplify"),
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
        commands, "smooth", _run_by("transform", "run_smooth"),
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
        commands, "remesh", _run_by("transform", "run_remesh"),
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
        commands, "convert", _run_by("transform", "run_convert"), progress=False,
        help="write a mesh in another format (picked by OUT's suffix)",
        description=(
            "Read IN and write it to OUT; the format is picked by the suffix "
            "(.obj by halfedge_edu's own writer, .ply .stl .off .glb .gltf through trimesh)."
        ),
    )
    _add_course(commands)
    _add_grade(commands)
    return parser


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


def _add_course(commands) -> None:
    """``course DEST [--update]``: see ``halfedge_edu.cli.course``."""
    course = commands.add_parser(
        "course",
        help="copy the chapters (student edition, without outputs) into a folder, to open in JupyterLab",
        description=(
            "Copy the course's chapters, student edition (exercises without their answers), "
            "without their stored outputs and stamped with this version of halfedge_edu, into DEST "
            "(created if missing). A chapter already in DEST is never overwritten; one that is "
            "not a valid notebook (a copy cut short) is moved aside to NAME.broken and copied again. "
            "Then: jupyter lab DEST. Needs the notebooks extra: halfedge_edu[notebooks]."
        ),
    )
    course.add_argument("destination", type=Path, metavar="DEST", help="the folder to copy the chapters into")
    course.add_argument(
        "--update", action="store_true",
        help=("bring the chapters of this version into a course copied by an older one: a chapter "
              "nobody edited is replaced, an edited one is kept and the newer one written beside it"),
    )
    course.set_defaults(run=_run_by("course", "run_course"))


def _add_grade(commands) -> None:
    """``grade SUBMISSION.ipynb... --out DIR``: see ``halfedge_edu.cli.grade``."""
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
    grade.set_defaults(run=_run_by("grade", "run_grade"))


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


def _seconds(text: str) -> float:
    """An argparse type: a positive number of seconds."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not value > 0 or value != value or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, got {text}")
    return value


class _Version(argparse.Action):
    """``--version``: print the installed version and exit. Looked up only when asked:
    ``importlib.metadata`` takes longer to import than the rest of ``--help`` takes to run."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings=option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None) -> NoReturn:
        print(f"{parser.prog} {_version()}")
        parser.exit()


def _version() -> str:
    """The installed halfedge_edu's version, or ``(not installed)``."""
    from importlib.metadata import PackageNotFoundError, version  # here, not at the top: see _Version

    try:
        return version("halfedge_edu")
    except PackageNotFoundError:
        return "(not installed)"
