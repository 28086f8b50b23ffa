"""The harness every exercise check shares: the result type, running a learner's function, words.

    from halfedge_edu.exercises.harness import CheckResult, failed, passed, run
    status, answer = run(learner_function, mesh, 3)   # "ok", "error" or "timeout"
    return failed("flip", checked, "cube", "edge 3 ...", ("halfedge", 6), mesh)

A check module (``checks.py``, ``ops_checks.py``, ``loop_checks.py``,
``quadric_checks.py``, ``bezier_checks.py``, ``remesh_checks.py`` ...) runs the
learner's function with :func:`run`, compares its answer with the library, and returns
:func:`passed` or :func:`failed`; a function that still has blanks (``...``) is not run
at all (:func:`blanks_left`, the usual opening of a check). The small helpers at the
end put points and slips into words the same way in every check.

Attention: a learner's function that loops forever is stopped after
``TIME_LIMIT`` seconds, where the platform allows it (a timer signal in the main
thread on Linux and macOS); elsewhere such a function simply does not return.
"""

from __future__ import annotations

import copy
import re
import signal
import sysconfig
import threading
import traceback
from contextlib import contextmanager
from pathlib import Path
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from halfedge_edu.core.mesh import HalfedgeMesh

__all__ = [
    "CheckResult", "TIME_LIMIT", "all_good", "as_point", "blanks_left", "close", "counted", "failed", "hidden_name", "hidden_rng", "own_line",
    "passed", "point_text", "run", "trouble", "unfinished",
]

#: Seconds a learner's function may run on one small mesh before the check gives up.
TIME_LIMIT = 1.0


# --------------------------------------------------------------------------------------
# The result every check returns
# --------------------------------------------------------------------------------------

@dataclass
class CheckResult:
    """What a check found. ``bool(result)`` is True when everything agreed.

    Attributes:
        exercise: which exercise was checked ("build" or "one_ring").
        passed: True when the learner's function agreed on every mesh.
        message: the explanation (for a failure: the first difference, in words).
        checked: names of the cases the function agreed on before it stopped.
        total: how many cases the check runs (public or hidden), so that a report can say
            "3 of 5 public cases"; 0 when the check stopped before running any (blanks left).
        mesh_name: the mesh where the first difference was found (None if passed).
        element: ``(kind, index)`` of the offending element, e.g. ``("halfedge", 4)``.
        mesh: that mesh as a ``HalfedgeMesh`` (the reference), for :meth:`show`.
        names: labels by ``(kind, index)`` for :meth:`show`, the names the message uses
            (an operation's ``v0``, ``h3``, ``vA``, ...); None labels by index.
        rerun: when the learner's function raised, calls it again on a fresh copy of the
            case it failed on, so that the learner sees the whole traceback (and can
            step into it with ``%debug``); None otherwise.
    """

    exercise: str
    passed: bool
    message: str
    checked: list[str] = field(default_factory=list)
    mesh_name: str | None = None
    element: tuple | None = None
    mesh: HalfedgeMesh | None = field(default=None, repr=False)
    total: int = 0
    rerun: Callable[[], object] | None = field(default=None, repr=False, compare=False)
    names: dict | None = field(default=None, repr=False, compare=False)

    def __bool__(self) -> bool:
        return self.passed

    def __repr__(self) -> str:
        return self.message

    def _repr_pretty_(self, printer, cycle) -> None:  # IPython's display of the result
        printer.text(self.message)

    def show(self, **scene_options):
        """A picture of the offending element on its mesh (an IPython image).

        Needs pyvista. Returns None when there is nothing to show (the check passed,
        or the problem is not about one element).
        """
        if self.passed or self.mesh is None or self.element is None:
            return None
        from IPython.display import Image

        from halfedge_edu.viz.scene import HalfedgeScene

        kind, index = self.element
        scene = HalfedgeScene(self.mesh, **scene_options)
        try:
            if self.names:     # one naming scheme: the picture labels what the message names
                scene.set_roles(_roles_around(self.mesh, kind, index), names=self.names)
            elif kind == "halfedge":
                scene.show_halfedge(index)
            elif kind == "vertex":
                scene.show_one_ring(index)
            elif kind == "face":
                scene.set_roles({"face": [index]})
            return Image(data=scene.screenshot())
        finally:
            scene.close()


def _roles_around(mesh: HalfedgeMesh, kind: str, index: int) -> dict[str, list[int]]:
    """The highlight roles of one element and its neighbourhood (as ``show_halfedge`` /
    ``show_one_ring`` draw them), for a picture labelled with the operation's names."""
    if kind == "halfedge":
        roles = {"current": [index], "twin": [index ^ 1], "next": [int(mesh.halfedge_next[index])],
                 "prev": [int(mesh.halfedge_prev[index])], "origin": [int(mesh.halfedge_vertex[index])],
                 "tip": [int(mesh.halfedge_vertex[index ^ 1])]}
        if mesh.halfedge_face[index] >= 0:
            roles["face"] = [int(mesh.halfedge_face[index])]
        return roles
    if kind == "vertex":
        vertex = mesh.vertex(index)
        outgoing = [h.index for h in vertex.outgoing()]
        return {"center": [index], "outgoing": outgoing, "neighbor": [int(mesh.halfedge_vertex[h ^ 1]) for h in outgoing],
                "ring_face": [f.index for f in vertex.faces()]}
    return {"face": [index]}


def passed(exercise: str, checked: list[str], praise: str) -> CheckResult:
    """The congratulation for a learner's function that agreed with the reference on every mesh."""
    names = ", ".join(checked)
    return CheckResult(exercise, True, f"All good! Your {exercise} agrees with the reference on {len(checked)} meshes "
                       f"({names}). {praise}", list(checked))


def failed(exercise: str, checked: list[str], mesh_name: str | None, text: str,
            element: tuple | None = None, mesh: HalfedgeMesh | None = None,
            error: BaseException | None = None, names: dict | None = None) -> CheckResult:
    """The first difference, in words: on which mesh, what is wrong (``text``), what agreed before.

    ``element`` and ``mesh`` let :meth:`CheckResult.show` draw the offending element.
    ``error``, the learner's exception when their function raised (as :func:`run` gave
    it), gives the result its :attr:`~CheckResult.rerun`; ``names`` labels the picture
    with the names the message uses.
    """
    where = f"On {mesh_name!r}: " if mesh_name else ""
    if not where:
        text = text[:1].upper() + text[1:]
    before = f" (It agreed on {', '.join(checked)} first.)" if checked else ""
    if (error is not None and getattr(error, "_halfedge_edu_call", None) is not None
            and not isinstance(error, NotImplementedError) and "ellipsis" not in str(error).lower()):
        text += " result.rerun() calls it again on this case, to show the whole traceback."
    return CheckResult(exercise, False, f"Not yet. {where}{text}{before}", list(checked), mesh_name, element, mesh,
                       rerun=_rerun_of(error), names=names)


def counted(result: CheckResult, total: int) -> CheckResult:
    """``result`` with ``total`` set: how many cases its check runs. Returns the same object."""
    result.total = total
    return result


def blanks_left(exercise: str, total: int, function: Callable, name: str | None = None) -> CheckResult | None:
    """How every check opens: the result "fill in the blanks" if the learner's ``function``
    still holds a ``...`` (failed before any case, out of ``total``), else None.

    ``name``: what the message calls the function (by default ``exercise``). Compare the
    answer with None, not by truth: a failed :class:`CheckResult` is falsy.
    """
    words = unfinished(function, exercise if name is None else name)
    return None if words is None else counted(failed(exercise, [], None, words), total)


# --------------------------------------------------------------------------------------
# Hidden cases: what a grader runs and the chapter's check cell never shows
# --------------------------------------------------------------------------------------

def hidden_rng(seed: int) -> np.random.Generator:
    """The random source of one grading run's hidden cases: the same seed, the same cases."""
    return np.random.default_rng(seed)


def hidden_name(number: int, what: str) -> str:
    """The name a hidden case is reported under, e.g. ``"hidden case 2: icosphere(2), 8 random flips"``.

    It says what kind of case failed, so that a learner knows where to look, without
    giving the grader's exact mesh or numbers away.
    """
    return f"hidden case {number}: {what}"


# --------------------------------------------------------------------------------------
# Running a learner's function safely
# --------------------------------------------------------------------------------------

class _TookTooLong(BaseException):
    """Raised by the timer; a BaseException, so a learner's ``except Exception`` cannot swallow it."""


@contextmanager
def _time_limit(seconds: float):
    """Raise _TookTooLong inside the body after ``seconds``, where a timer signal is possible."""
    usable = hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    if not usable:
        yield
        return

    def stop(signum, frame):
        raise _TookTooLong

    previous = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _snapshot(value):
    """A copy of one argument as it was before the learner's function could change it."""
    if isinstance(value, (HalfedgeMesh, np.ndarray)):
        return value.copy()
    if isinstance(value, (list, dict)):
        return copy.deepcopy(value)
    return value


def run(function: Callable, *args, seconds: float | None = None):
    """Call the learner's function: ``("ok", value)``, ``("error", exception)`` or ``("timeout", None)``.

    ``seconds`` is the time limit (default ``TIME_LIMIT``; a whole-mesh exercise such as
    a downsampling loop gets more). On an error the exception remembers the call
    (function and copies of the arguments as they were before it), so that
    :func:`failed` can offer ``result.rerun()``.
    """
    global _limit_now
    saved = tuple(_snapshot(argument) for argument in args)
    limit = TIME_LIMIT if seconds is None else seconds
    previous, _limit_now = _limit_now, limit
    try:
        with _time_limit(limit):
            return "ok", function(*args)
    except _TookTooLong:
        return "timeout", None
    except Exception as error:  # the learner's bug, reported in words below
        try:
            error._halfedge_edu_call = (function, saved)
        except (AttributeError, TypeError):  # an exception type that takes no attributes
            pass
        return "error", error
    finally:
        _limit_now = previous


#: The time limit of the call :func:`run` is making now (the grader's judge passes it on
#: to the learner's kernel, which enforces it there).
_limit_now = TIME_LIMIT


def limit_now() -> float:
    """The time limit of the learner's call under way (``TIME_LIMIT`` outside one)."""
    return _limit_now


def _rerun_of(error: BaseException | None) -> Callable[[], object] | None:
    """``rerun()`` for a failed call: the learner's function again, on fresh copies of the
    same arguments, through :func:`run`; it returns the value or raises the learner's
    exception with its own traceback."""
    call = getattr(error, "_halfedge_edu_call", None) if error is not None else None
    if call is None:
        return None
    function, saved = call

    def rerun():
        status, value = run(function, *(_snapshot(argument) for argument in saved))
        if status == "timeout":
            raise TimeoutError(f"it did not finish within {TIME_LIMIT:g} s")
        if status == "error":
            value.__dict__.pop("_halfedge_edu_call", None)
            raise value
        return value

    return rerun


#: Folders whose frames are not the learner's: this package, Python's own library, installed packages.
_NOT_LEARNER_FOLDERS = tuple(str(Path(folder).resolve()) for folder in {
    str(Path(__file__).resolve().parents[1]), sysconfig.get_paths()["stdlib"], sysconfig.get_paths()["purelib"],
    sysconfig.get_paths()["platlib"]})

_TRACEBACK_FRAME = re.compile(r'File "([^"]+)", line (\d+), in ([^\n]+)\n[ \t]+([^\n]+)')


def _learner_frames(error: BaseException) -> list[tuple[str, int, str, str]]:
    """``(file, line, function, source)`` of the frames in the learner's own code, outermost first.

    From ``error.learner_traceback`` when the error came from another process (the
    grader's judge puts the formatted traceback there), else from ``error.__traceback__``.
    """
    text = getattr(error, "learner_traceback", None)
    if isinstance(text, str):
        frames = [(f, int(n), name.strip(), line.strip()) for f, n, name, line in _TRACEBACK_FRAME.findall(text)]
    else:
        frames = [(frame.filename, frame.lineno or 0, frame.name, (frame.line or "").strip())
                  for frame in traceback.extract_tb(error.__traceback__)]
    return [frame for frame in frames
            if not str(Path(frame[0]).resolve()).startswith(_NOT_LEARNER_FOLDERS) and frame[3]]


def own_line(error: BaseException) -> str:
    """Where in the learner's own code ``error`` was raised, as a sentence ("" if unknown):
    e.g. ``" It came from line 7 of your my_flip: `nxt[h1] = h_next[h4]`."``"""
    frames = _learner_frames(error)
    if not frames:
        return ""
    _, line, function, source = frames[-1]
    return f" It came from line {line} of your {function}: `{source}`."




def unfinished(function: Callable, name: str) -> str | None:
    """The "fill in the blanks" message if the function's own code still holds a ``...``."""
    code = getattr(function, "__code__", None)
    if code is not None and any(constant is Ellipsis for constant in code.co_consts):
        return (f"your {name} still has blanks (...) in it. Fill each one in (no ... left) "
                f"and run the check again.")
    return None


# --------------------------------------------------------------------------------------
# Words shared by the checks of points (chapters 09 to 12)
# --------------------------------------------------------------------------------------

def point_text(point) -> str:
    """A point or vector as ``(x, y, z)`` with four significant digits."""
    return "(" + ", ".join(f"{float(c):.4g}" for c in np.asarray(point, dtype=np.float64).ravel()) + ")"


def as_point(value, size: int = 3) -> np.ndarray | None:
    """A learner's answer as a point, ``(size,)`` float64, or None if it is not ``size`` numbers."""
    try:
        array = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return None
    return array if array.shape == (size,) else None


def close(a, b) -> bool:
    """Whether two answers agree, to the tolerance every check of points uses."""
    return bool(np.allclose(a, b, rtol=1e-7, atol=1e-9))


def all_good(exercise: str, checked: list[str], noun: str, praise: str) -> CheckResult:
    """The congratulation: what agreed, on how many cases, and what it means."""
    verb = "match" if " and " in exercise else "matches"
    return CheckResult(exercise, True, f"All good! Your {exercise} {verb} the library on {len(checked)} {noun} "
                       f"({', '.join(checked)}). {praise}", list(checked))


def trouble(status: str, answer, name: str) -> str | None:
    """Words for a learner function that timed out or raised (``run``'s status), else None."""
    if status == "timeout":
        return f"your {name} did not finish within {TIME_LIMIT:g} s: a loop probably never ends."
    if status == "error":
        if isinstance(answer, NotImplementedError) or "ellipsis" in str(answer).lower():
            return f"{name} is not finished yet ({type(answer).__name__}: {answer}). Fill it in and check again."
        return f"your {name} raised {type(answer).__name__}: {answer}.{own_line(answer)}"
    return None
