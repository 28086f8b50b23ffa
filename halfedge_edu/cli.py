"""The command line: ``halfedge-edu info FILE`` and ``halfedge-edu check FILE``.

Also run as ``python -m halfedge_edu``. Each subcommand reads one mesh file and prints
plain text. A problem with the input (a missing or unreadable file, a file that cannot
become a halfedge mesh) ends with one line on stderr, ``halfedge-edu: error: ...``, and
exit status 2, never a traceback. The library is imported only once a subcommand runs,
so ``--help`` is instant.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path
from typing import Sequence

PROG = "halfedge-edu"

EXIT_OK = 0
EXIT_INVALID = 1  # `check`: the file loads, but the mesh breaks a halfedge invariant
EXIT_ERROR = 2  # bad input or usage (argparse uses 2 for usage errors too)

# How many non-manifold elements `info` lists by index before it only counts them.
MAX_LISTED = 10


class InputProblem(Exception):
    """Input the command cannot use; reported as one line on stderr with exit status 2."""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: ``sys.argv[1:]``); return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except InputProblem as problem:
        return _fail(str(problem))
    except KeyboardInterrupt:
        return 130
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
        if _is_input_error(error):
            return _fail(_with_path(args.file, error))
        # Anything else is a bug in halfedge_edu, not a problem with the input.
        return _fail(
            f"internal error ({type(error).__name__}: {error}); "
            f"run again with --debug to see the traceback, and please report it"
        )


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every registered subcommand."""
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Inspect triangle meshes as halfedge meshes.",
        epilog=(
            "Exit status: 0 success; 1 `check` found a broken invariant; "
            "2 the input could not be read or built into a halfedge mesh, or bad usage."
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
    info.add_argument("file", type=Path, metavar="FILE", help=".obj (or .ply .stl .off .glb)")
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
    check.add_argument("file", type=Path, metavar="FILE", help=".obj (or .ply .stl .off .glb)")
    check.set_defaults(run=run_check)
    return parser


def run_info(args: argparse.Namespace) -> int:
    """``info FILE``: describe the mesh, or its non-manifold parts if it cannot be built."""
    from halfedge_edu.core.errors import MeshInputError

    path = args.file
    try:
        mesh = _load(path)
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
    print("\n".join(lines))
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
    print("\n".join(lines))
    return EXIT_OK


def run_check(args: argparse.Namespace) -> int:
    """``check FILE``: exit 0 if the file is a valid halfedge mesh, 1 if an invariant breaks."""
    from halfedge_edu.core.errors import MeshInvariantError

    path = args.file
    mesh = _load(path)
    try:
        mesh.validate()
    except MeshInvariantError as error:
        print(f"{path}: not a valid halfedge mesh: {_one_line(str(error))}")
        return EXIT_INVALID
    print(f"{path}: valid halfedge mesh ({mesh.n_vertices} vertices, {mesh.n_faces} faces)")
    return EXIT_OK


def _load(path: Path):
    """``hx.load(path)`` with input problems turned into ``InputProblem``.

    ``MeshInputError`` is passed through so that a caller can look closer; the library's
    warnings (e.g. dropped unreferenced vertices) are printed as one line each.
    """
    import halfedge_edu as hx
    from halfedge_edu.core.errors import MeshInputError

    _check_readable(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UserWarning)  # MeshWarning among them
        try:
            mesh = hx.load(path)
        except MeshInputError:
            raise
        except (OSError, ValueError) as error:  # UnicodeDecodeError is a ValueError
            raise InputProblem(_with_path(path, error)) from error
    for warning in caught:
        print(f"{PROG}: warning: {_one_line(str(warning.message))}", file=sys.stderr)
    return mesh


def _read_raw(path: Path):
    """The vertex and face arrays of a file, without building anything from them."""
    import numpy as np

    if path.suffix.lower() == ".obj":
        from halfedge_edu.io.obj import read_obj

        data = read_obj(path)
        return data.vertices, data.faces
    import trimesh

    raw = trimesh.load(path, process=False, force="mesh")
    return np.asarray(raw.vertices), np.asarray(raw.faces, dtype=np.int64)


def _is_input_error(error: Exception) -> bool:
    """Is this one of halfedge_edu's own errors about the input or the mesh?"""
    try:
        from halfedge_edu.core.errors import MeshInputError, MeshInvariantError, TopologyError
    except ImportError:
        return False

    return isinstance(error, (MeshInputError, MeshInvariantError, TopologyError))


def _check_readable(path: Path) -> None:
    if not path.exists():
        raise InputProblem(f"{path}: no such file")
    if path.is_dir():
        raise InputProblem(f"{path}: is a folder, not a mesh file")


def _with_path(path: Path, error: Exception) -> str:
    """The error's message, starting with the file (unless it already does)."""
    if isinstance(error, OSError) and error.strerror:
        message = error.strerror
    else:
        message = str(error) or type(error).__name__
    if not message.startswith((str(path), path.name)):
        message = f"{path}: {message}"
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


def _fail(message: str) -> int:
    print(f"{PROG}: error: {_one_line(message)}", file=sys.stderr)
    return EXIT_ERROR


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("halfedge_edu")
    except PackageNotFoundError:
        return "(not installed)"
