"""The mesh-in, mesh-out subcommands: ``subdivide``, ``simplify``, ``smooth``, ``remesh``, ``convert``.

Each reads IN, runs one algorithm and writes OUT (the format picked by OUT's suffix), then
prints a one-line summary. :func:`transform` is the order every one of them keeps: OUT
checked before loading (so that a long run does not end in "cannot write there"); the
input's coordinates checked against the limits the algorithms compute within; the size of
the result estimated and refused above ``--max-faces`` before the work starts; the result
validated (a broken one is a bug: exit status 1, nothing written); OUT written last,
atomically.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
from pathlib import Path
from typing import Callable

import numpy as np

from halfedge_edu._extras import extra_for, install_hint

# loop_subdivide and smooth are looked up in their modules at each call (loop.loop_subdivide), so that
# replacing one there, as tests do to make an algorithm fail half way, reaches the command line too.
from halfedge_edu.algorithms import loop, smoothing
from halfedge_edu.algorithms.arguments import MAX_COORDINATE, MIN_EXTENT
from halfedge_edu.algorithms.normals import face_areas
from halfedge_edu.algorithms.remesh import remesh
from halfedge_edu.algorithms.simplify import simplify
from halfedge_edu.cli.errors import EXIT_OK, BrokenResult, InputProblem, echo, one_line, warn
from halfedge_edu.cli.files import check_readable, check_writable, load_or_fail, names_the_file, save, warnings_as_lines
from halfedge_edu.core.errors import MeshInvariantError


@names_the_file
def run_subdivide(args: argparse.Namespace) -> int:
    """``subdivide IN OUT N``: Loop subdivision, N levels."""
    levels = args.levels if args.levels is not None else args.levels_option
    if args.levels_option is not None and levels != args.levels_option:
        raise InputProblem(f"N is {args.levels} but --levels is {args.levels_option}; give the number of levels once")
    levels = 1 if levels is None else levels

    def algorithm(mesh):
        return loop.loop_subdivide(mesh, levels, weights=args.weights, progress=progress(args))

    def estimate(mesh) -> tuple[float, str]:
        # Beyond 500 levels 4.0**levels leaves float range: more than any limit.
        return mesh.n_faces * 4.0**levels if levels <= 500 else math.inf, f"{levels} levels of subdivision"

    return transform(args, algorithm, estimate=estimate)


@names_the_file
def run_simplify(args: argparse.Namespace) -> int:
    """``simplify IN OUT --faces N | --ratio R``: quadric-error edge collapses."""

    def algorithm(mesh):
        target = args.faces if args.faces is not None else max(1, round(args.ratio * mesh.n_faces))
        if target >= mesh.n_faces:
            warn(f"the target of {target} faces is not below the input's {mesh.n_faces}: nothing to simplify")
        return simplify(mesh, target, progress=progress(args))

    return transform(args, algorithm)


@names_the_file
def run_smooth(args: argparse.Namespace) -> int:
    """``smooth IN OUT [--iterations N] [--weights W] [--boundary B]``: Laplacian smoothing."""

    def algorithm(mesh):
        return smoothing.smooth(
            mesh, args.iterations, weights=args.weights, boundary=args.boundary, progress=progress(args)
        )

    return transform(args, algorithm)


@names_the_file
def run_remesh(args: argparse.Namespace) -> int:
    """``remesh IN OUT [--length L] [--iterations N] [--feature-angle DEG]``: isotropic remeshing."""

    def algorithm(mesh):
        # Not given: remesh's own default (the parser does not import the library to know it).
        features = {"feature_angle": args.feature_angle} if "feature_angle" in vars(args) else {}
        return remesh(mesh, args.length, args.iterations, progress=progress(args), **features)

    def estimate(mesh) -> tuple[float, str]:
        if args.length is None:  # the input's mean edge length: about the input's face count
            return mesh.n_faces, "remeshing"
        return faces_at_edge_length(mesh, args.length), f"remeshing to edge length {args.length:g}"

    return transform(args, algorithm, estimate=estimate)


@names_the_file
def run_convert(args: argparse.Namespace) -> int:
    """``convert IN OUT``: the same mesh in the format of OUT's suffix."""
    return transform(args, lambda mesh: mesh, computes=False)


def faces_at_edge_length(mesh, length: float) -> float:
    """About how many triangles with edges of ``length`` cover the mesh's surface.

    An equilateral triangle with edge L has area sqrt(3)/4 L^2; isotropic remeshing
    makes nearly equilateral triangles, so surface area / that area is the estimate.
    """
    area = face_areas(mesh).sum()
    with np.errstate(over="ignore", divide="ignore"):  # a tiny length: the estimate is inf
        return float(area / (np.sqrt(3) / 4 * np.float64(length) ** 2))


def transform(
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
    output = args.output
    check_readable(args.file)
    check_writable(output)
    mesh = load_or_fail(args.file, repair=args.repair)
    faces_before = mesh.n_faces
    if computes:
        check_coordinate_size(mesh, args.file)
    if estimate is not None:
        check_result_size(*estimate(mesh), args.max_faces)
    with warnings_as_lines():
        result = algorithm(mesh)
    try:
        result.validate()
    except MeshInvariantError as error:
        raise BrokenResult(
            f"internal error: {args.command} made a mesh that is not a valid halfedge mesh "
            f"({one_line(str(error))}); nothing was written; please report it"
        ) from error
    save(result, output)
    echo(f"{args.command}: {faces_before} -> {result.n_faces} faces, wrote {output}")
    return EXIT_OK


def check_coordinate_size(mesh, path: Path) -> None:
    """Raise ``InputProblem`` if a coordinate is beyond ``MAX_COORDINATE`` (products would
    overflow) or the mesh is smaller across than ``MIN_EXTENT`` (products would round to zero)."""
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


def check_result_size(estimated_faces: float, what: str, limit: int) -> None:
    """Raise ``InputProblem`` if the estimated result is above ``--max-faces``."""
    if estimated_faces > limit:
        about = f"about {estimated_faces:.3g}" if math.isfinite(estimated_faces) else "more than 1e308"
        raise InputProblem(
            f"{what} would make {about} faces, more than the limit of {limit:,}; "
            f"raise it with --max-faces N if the machine has the memory"
        )


def progress(args: argparse.Namespace) -> bool:
    """``--progress`` / ``--no-progress``, or by default: is stderr a terminal? An explicit
    ``--progress`` without tqdm installed is an input problem naming the extra (by
    default the bar is simply left out)."""
    if args.progress and importlib.util.find_spec("tqdm") is None:
        raise InputProblem(f"--progress needs tqdm, which is not installed: {install_hint(extra_for('tqdm'))}")
    if args.progress is not None:
        return args.progress
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):  # replaced or closed stderr
        return False
