"""Checks for chapter 12's exercises: de Casteljau's levels, and a point of a Bezier patch.

    from halfedge_edu.exercises.bezier_checks import check_de_casteljau, check_bezier_patch
    check_de_casteljau(de_casteljau)
    check_bezier_patch(patch_point)

Each check calls the learner's function on a few curves or grids, compares every
answer with :func:`~halfedge_edu.algorithms.bezier.de_casteljau`, and at the first
difference says in words what is wrong and, where the answer matches a common slip
(``t`` and ``1 - t`` swapped, level 0 left out, the four corners only), which slip it
is. The contracts:

* ``de_casteljau(points, t) -> list``: every level, from the control points (level 0)
  to the single point on the curve (level n).
* ``patch_point(grid, u, v) -> (3,)``: the patch's point, in the chapter's convention
  (``u`` down the columns) or CS184's (``u`` along the rows), the same one throughout.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from halfedge_edu.algorithms.bezier import de_casteljau as _de_casteljau

from . import harness
from .harness import CheckResult, hidden_name

__all__ = ["check_bezier_patch", "check_de_casteljau", "patch_point"]


# --------------------------------------------------------------------------------------
# Chapter 12: de Casteljau
# --------------------------------------------------------------------------------------

def _casteljau_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, float]]:
    """``(name, control points, t)`` for ``check_de_casteljau``; with a ``seed``, the
    hidden cases: random control points of degree 1 to 6 in 2D and 3D, random t (and t = 1)."""
    if seed is not None:
        rng = harness.hidden_rng(seed)
        cases = []
        for number, (degree, dimension, t) in enumerate([
                (int(rng.integers(2, 4)), 2, float(rng.uniform(0.05, 0.45))),
                (int(rng.integers(3, 7)), 3, float(rng.uniform(0.55, 0.95))),
                (int(rng.integers(1, 5)), 2, 1.0),
                (int(rng.integers(2, 6)), 3, float(rng.uniform(0.0, 1.0)))], start=1):
            points = rng.uniform(-2.0, 2.0, (degree + 1, dimension))
            cases.append((hidden_name(number, f"random degree {degree} curve in {dimension}D at a t of its own"), points, t))
        return cases
    quadratic = np.array([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])
    cubic = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])
    space = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 2.0], [0.0, 2.0, 1.0], [1.0, 3.0, 0.0]])
    return [
        ("a line (degree 1) at t = 0.25", np.array([[0.0, 0.0], [4.0, 2.0]]), 0.25),
        ("a quadratic at t = 0.5", quadratic, 0.5),
        ("a cubic at t = 0.3", cubic, 0.3),
        ("a cubic at t = 0", cubic, 0.0),
        ("a cubic at t = 1", cubic, 1.0),
        ("a degree 4 curve in 3D at t = 0.7", space, 0.7),
    ]


def check_de_casteljau(de_casteljau: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``de_casteljau(points, t)`` (every level) with the library's.

    Args:
        de_casteljau: ``(points (n + 1, d), t) -> list`` of ``n + 1`` levels, level k
            holding ``n + 1 - k`` points.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    cases = _casteljau_cases(seed)
    if (blanks := harness.blanks_left("de_casteljau", len(cases), de_casteljau)) is not None:
        return blanks
    return harness.counted(_check_de_casteljau(de_casteljau, cases), len(cases))


def _check_de_casteljau(de_casteljau: Callable, cases: list[tuple[str, np.ndarray, float]]) -> CheckResult:
    """:func:`check_de_casteljau` on the given cases."""
    checked: list[str] = []
    for case, points, t in cases:
        given = points.copy()
        status, answer = harness.run(de_casteljau, given, t)
        trouble = harness.trouble(status, answer, "de_casteljau")
        if trouble:
            return harness.failed("de_casteljau", checked, case, trouble, error=answer)
        if not np.array_equal(given, points):
            return harness.failed("de_casteljau", checked, case, "your de_casteljau changed the control points it was "
                           "given. Build each level as a new array (or list) instead of overwriting the input.")
        wanted = _de_casteljau(points, t)
        n = len(points) - 1
        try:
            levels = [np.asarray(level, dtype=np.float64).reshape(-1, points.shape[1]) for level in answer]
        except (TypeError, ValueError):
            levels = None
        if levels is None or (len(levels) and np.ndim(answer[0]) == 0):
            return harness.failed("de_casteljau", checked, case, f"de_casteljau should return a list of levels (arrays of "
                           f"points), but yours returned {answer!r:.80}.")
        if len(levels) == n and n > 0 and all(len(levels[k]) == n - k for k in range(n)):
            return harness.failed("de_casteljau", checked, case, f"a degree {n} curve has {n + 1} levels, but yours has {n}: "
                           f"level 0, the control points themselves, is missing. Start the list with them.")
        if len(levels) != n + 1:
            return harness.failed("de_casteljau", checked, case, f"a degree {n} curve ({n + 1} control points) has "
                           f"{n + 1} levels, from {n + 1} points down to 1, but yours has {len(levels)}.")
        for k, (mine, right) in enumerate(zip(levels, wanted)):
            if len(mine) != len(right):
                return harness.failed("de_casteljau", checked, case, f"level {k} should have {len(right)} points (one fewer "
                               f"than level {k - 1}), but yours has {len(mine)}." if k else
                               f"level 0 should be the {len(right)} control points, but yours has {len(mine)} points.")
            if not harness.close(mine, right):
                i = int(np.flatnonzero(~np.isclose(mine, right).all(axis=1))[0])
                text = (f"at t = {t:g}, point {i} of level {k} should be (1 - t) * level[{k - 1}][{i}] + t * "
                        f"level[{k - 1}][{i + 1}] = {harness.point_text(right[i])}, but yours is {harness.point_text(mine[i])}."
                        if k else f"level 0 should be the control points themselves; point {i} differs.")
                swapped = _de_casteljau(points, 1.0 - t)
                if k and harness.close(mine, swapped[k]):
                    text += (" You swapped t and 1 - t: with (1 - t) P_i + t P_(i+1), t = 0 gives P_0 and the "
                             "curve runs from P_0 to P_n as t goes from 0 to 1.")
                elif k and harness.close(mine[i], 0.5 * (wanted[k - 1][i] + wanted[k - 1][i + 1])):
                    text += " Yours is the midpoint: that is the construction at t = 0.5 only; use t."
                return harness.failed("de_casteljau", checked, case, text)
        checked.append(case)
    return harness.all_good("de_casteljau", checked, "curves", "The last level is the curve's point; the levels are the construction lines.")


# --------------------------------------------------------------------------------------
# Chapter 12, second exercise: a point of a Bezier patch (CS184's BezierPatch::evaluate)
# --------------------------------------------------------------------------------------

def patch_point(grid: np.ndarray, u: float, v: float) -> np.ndarray:
    """(3,) the chapter's ``S(u, v)``: ``u`` runs down the columns (first index), ``v`` along the rows."""
    columns = np.array([_de_casteljau(grid[:, j], u)[-1][0] for j in range(grid.shape[1])])
    return _de_casteljau(columns, v)[-1][0]


def _patch_cases(seed: int | None = None) -> list[tuple[str, np.ndarray, list[tuple[float, float]]]]:
    """``(name, grid (m + 1, n + 1, 3), [(u, v), ...])`` for ``check_bezier_patch``: lopsided
    grids (so that swapping u and v shows), corners and inner parameters, a grid that is
    not 4 x 4. With a ``seed``, the hidden cases: random grids and parameters."""
    rng = np.random.default_rng(12) if seed is None else harness.hidden_rng(seed)
    if seed is None:
        flat = np.stack([*np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij"), np.zeros((4, 4))], axis=-1)
        raised = flat.copy()
        raised[1, 2, 2] = 3.0
        raised[2, 1, 2] = -1.0
        wide = np.concatenate([rng.uniform(-1, 1, (3, 5, 2)), rng.uniform(0, 2, (3, 5, 1))], axis=-1)
        return [
            ("a 4 x 4 grid with two points moved, at its corners", raised, [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]),
            ("the same grid inside", raised, [(0.2, 0.7), (0.5, 0.5), (0.9, 0.3)]),
            ("a 3 x 5 grid (degree 2 by 4)", wide, [(0.3, 0.6), (0.75, 0.1)]),
        ]
    cases = []
    for number, shape in enumerate([(4, 4), (3, 5), (5, 3)], start=1):
        grid = rng.uniform(-2.0, 2.0, (*shape, 3))
        parameters = [tuple(float(x) for x in rng.uniform(0.05, 0.95, 2)) for _ in range(3)]
        cases.append((hidden_name(number, f"a random {shape[0]} x {shape[1]} grid at three (u, v) of its own"), grid,
                      parameters))
    return cases


def check_bezier_patch(patch_point_function: Callable, *, seed: int | None = None) -> CheckResult:
    """Compare the learner's ``patch_point(grid, u, v) -> (3,)`` with the Bezier surface.

    Two conventions are right, the same one at every point: the chapter's (``u`` down
    the columns, the grid's first index) and CS184's (``u`` along each row, the second
    index, so its ``S(u, v)`` is the chapter's ``S(v, u)``); the congratulation says
    which one it recognised.

    Args:
        patch_point_function: ``(grid (m + 1, n + 1, 3), u, v) -> (3,)``.
        seed: None for the public cases (the chapter's); an int for only the hidden
            cases made from it.
    """
    name = "patch_point"
    cases = _patch_cases(seed)
    if (blanks := harness.blanks_left(name, len(cases), patch_point_function)) is not None:
        return blanks
    return harness.counted(_check_bezier_patch(patch_point_function, cases), len(cases))


def _check_bezier_patch(patch_point_function: Callable, cases: list) -> CheckResult:
    """:func:`check_bezier_patch` on the given cases."""
    name = "patch_point"
    checked: list[str] = []
    convention: tuple[str, str] | None = None        # which one, and where it was first told apart
    for case, grid, parameters in cases:
        for u, v in parameters:
            given = grid.copy()
            status, answer = harness.run(patch_point_function, given, u, v)
            trouble = harness.trouble(status, answer, name)
            where = f"at (u, v) = ({u:g}, {v:g})"
            if trouble:
                return harness.failed(name, checked, case, f"{where}, {trouble}", error=answer)
            if not np.array_equal(given, grid):
                return harness.failed(name, checked, case, "your patch_point changed the control grid; build each "
                                      "row of points as a new array instead.")
            yours = harness.as_point(answer)
            if yours is None:
                return harness.failed(name, checked, case, f"patch_point should return one point (3 numbers), but "
                                      f"{where} yours returned {answer!r:.80}.")
            chapter, cs184 = patch_point(grid, u, v), patch_point(grid, v, u)
            matching = [label for label, point in (("the chapter's", chapter), ("CS184's", cs184))
                        if harness.close(yours, point)]
            if len(matching) == 1:
                if convention and convention[0] != matching[0]:
                    return harness.failed(name, checked, case, (
                        f"{where} your point follows {matching[0]} convention, but {convention[1]} it followed "
                        f"{convention[0]}: u must run along the same index of the grid every time."))
                convention = convention or (matching[0], f"{where} of {case!r}")
            if matching:
                continue
            text = (f"{where} the surface point is {harness.point_text(chapter)} (u down the columns, as the "
                    f"chapter) or {harness.point_text(cs184)} (u along the rows, as CS184); yours is "
                    f"{harness.point_text(yours)}.")
            corners = grid[[0, 0, -1, -1], [0, -1, 0, -1]]
            bilinear = ((1 - u) * (1 - v) * corners[0] + (1 - u) * v * corners[1] + u * (1 - v) * corners[2]
                        + u * v * corners[3])
            if harness.close(yours, patch_point(grid, 1 - u, 1 - v)) or harness.close(yours, patch_point(grid, 1 - v, 1 - u)):
                text += " You swapped t and 1 - t in de Casteljau's step: (1 - t) P_i + t P_(i+1)."
            elif harness.close(yours, bilinear):
                text += (" That mixes the four corners only (bilinear); every control point counts: run de Casteljau "
                         "over each column at u, then once more over those points at v.")
            elif any(harness.close(yours, _de_casteljau(grid[:, j], u)[-1][0]) for j in range(grid.shape[1])):
                text += (" That is a point of one column's curve at u: run the second pass too, through the points of "
                         "all the columns, at v.")
            return harness.failed(name, checked, case, text)
        checked.append(case)
    words = "Your patch_point evaluates the surface: de Casteljau down each column, then once across."
    if convention and convention[0] == "CS184's":
        words = ("Your patch_point follows CS184's convention (u along each row of the grid, its second index), "
                 "correct there; the chapter and hx.bezier_surface_points run u down the columns, so your S(u, v) "
                 "is the chapter's S(v, u) (or pass grid.transpose(1, 0, 2)).")
    return harness.all_good(name, checked, "grids", words)
