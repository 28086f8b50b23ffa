"""Grade a learner's chapter notebook: points per exercise, with the reason for each lost point.

    from halfedge_edu.exercises.grading import grade_notebook
    grade = grade_notebook("06_flip_and_split.ipynb")
    grade.score, grade.max_score          # e.g. (1.0, 1.0)
    grade.to_json(); grade.to_junit_xml()

A learner's notebook is untrusted code, so the score is computed where it cannot reach.
What happens, in order:

1. **The chapter** is the one ``chapter=`` says, else the number the file name starts
   with (``06_...``), else the notebook's own ``halfedge_edu.chapter`` stamp.
2. **The notebook runs in a sandbox** (:mod:`~halfedge_edu.exercises.sandbox`): a private
   folder holding only its own copy, private ``HOME``/``TMPDIR``/``IPYTHONDIR``, a reduced
   environment, limits on memory, processes, file size and printed output, and (with
   bubblewrap) no network and no view of anything else on the machine. It runs top to
   bottom in a fresh kernel (:mod:`~halfedge_edu.exercises.runner`), with a time limit
   per cell and one for the whole run; a cell that raises does not stop the run.
3. **The judge** (:mod:`~halfedge_edu.exercises.judge`), a separate process outside the
   sandbox that imports the checks itself, runs each exercise's ``check_*`` helper on the
   learner's functions, calling them through the kernel as plain data. Nothing printed,
   patched, hooked or planted in the learner's kernel can change what the judge decides.
   Each exercise runs its public cases and hidden ones drawn from a seed per grading
   run, and while the learner's function runs, the package's own answer to that
   exercise (``Exercise.forbids``) refuses to be called from it.
4. **Points**: an exercise earns its points when its public and hidden cases pass and the
   package's answer was not used; otherwise zero, with the reason in words: the check's
   first message, or the cell's own error when the function never came to exist (a
   SyntaxError with its line), or the cell in which the kernel died.
5. Every process the notebook started is ended and its folder removed.

Report formats, chosen to plug into what courses already run:

- ``Grade.to_json()`` follows the ``results.json`` schema of Gradescope's autograder
  (``score``, ``tests`` with ``name``/``score``/``max_score``/``output``), which
  otter-grader also writes, so a Gradescope or otter workflow can read it unchanged.
- ``Grade.to_junit_xml()`` writes one ``testcase`` per exercise (``failure`` with the
  reason when points were lost): GitHub Classroom, GitLab and Jenkins show JUnit. Text
  that XML cannot hold (NUL, terminal escapes) is shown as ``\\x1b``.

What it does not promise: a learner who copies the package's source text into their
notebook has written nothing themselves, and no grader can tell; that is a matter for a
course's policy on copying, like copying from a textbook.
"""

from __future__ import annotations

import json
import os
import re
import secrets
import socket
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass, field
from pathlib import Path

from .sandbox import Limits, Sandbox

__all__ = [
    "EXERCISES", "Exercise", "ExerciseGrade", "Grade", "GradingError", "Limits", "chapter_of", "check_function",
    "exercises_for", "grade_notebook", "submission_chapter",
]


@dataclass(frozen=True)
class Exercise:
    """One graded exercise: where it is taught, how it is checked, and what the learner must write.

    Attributes:
        name: short id used in reports ("flip").
        chapter: the number of the chapter that teaches it ("06"; "08b" for the debugging lab).
        functions: the names the learner's notebook defines, passed to the check in order.
        check: the name of the ``halfedge_edu.exercises`` helper that judges them.
        points: what a passing check earns.
        forbids: the package's own answers to this exercise, which the learner's function may
            not call while it is graded: dotted paths of functions, methods or whole modules
            (every function and method the module defines), or ``"notebook:NAME"`` for a
            function the chapter itself defines; ``"!dotted.path"`` exempts one function of
            a forbidden module that the exercise hands the learner. Every exercise also
            forbids the checks' own reference code (:data:`ANSWER_KEYS`).
    """

    name: str
    chapter: str
    functions: tuple[str, ...]
    check: str
    points: float = 1.0
    forbids: tuple[str, ...] = ()


_MESH = "halfedge_edu.core.mesh.HalfedgeMesh"
_VERTEX = "halfedge_edu.core.elements.Vertex"
_OPS = "halfedge_edu.core.ops"
_ONE_RING = (f"{_OPS}.link.one_ring", f"{_OPS}.link.outgoing", f"{_VERTEX}.neighbors", f"{_VERTEX}.outgoing",
             f"{_VERTEX}.faces", f"{_VERTEX}.edges", f"{_MESH}.one_rings", "halfedge_edu.core.rings")
_FLIP = (f"{_MESH}.flip", f"{_OPS}.flip.flip")
_SPLIT = (f"{_MESH}.split", f"{_OPS}.split.split")
_COLLAPSE = (f"{_MESH}.collapse", f"{_OPS}.collapse.collapse", f"{_OPS}.collapse.apply_collapse",
             f"{_OPS}.collapse.prepare_collapse", f"{_OPS}.collapse._apply", f"{_OPS}.collapse._gather",
             f"{_OPS}.collapse._take_place")
_OBJ = ("halfedge_edu.io.obj", "halfedge_edu.io.formats")
_SOUP = "halfedge_edu.core.soup.SoupTopology"
#: Remeshing is a package, one module per phase: forbidding it names every module, since a
#: whole module in ``forbids`` covers only the functions that module itself defines.
_REMESH = tuple(f"halfedge_edu.algorithms.remesh{module}" for module in
                ("", ".lengths", ".split", ".collapse", ".flip", ".smooth", ".project", ".quality"))

#: The checks' own reference code: forbidden to every exercise (``_de_casteljau``, the
#: debugging lab's right versions, ``smooth_once_in_place`` ...).
ANSWER_KEYS: tuple[str, ...] = tuple(f"halfedge_edu.exercises.{module}" for module in (
    "bezier_checks", "chapter_checks", "checks", "classic_bugs", "io_checks", "loop_checks", "ops_checks",
    "quadric_checks", "remesh_checks"))

#: Every graded exercise (the first ones in chapter order, later additions after them).
#: The function names are the ones each chapter's exercise cell asks the learner to fill in.
EXERCISES: tuple[Exercise, ...] = (
    Exercise("fan", "01", ("fan",), "check_fan", forbids=_OBJ),
    Exercise("obj_io", "01", ("read_obj", "write_obj"), "check_obj_io", forbids=_OBJ),
    Exercise("build", "02", ("build",), "check_build",
             forbids=("halfedge_edu.core.build", f"{_MESH}.from_faces", f"{_MESH}.from_trimesh", *_OBJ)),
    Exercise("one_ring", "03", ("one_ring",), "check_one_ring", forbids=_ONE_RING),
    Exercise("cut", "04", ("cut_bowtie",), "check_cut", forbids=("halfedge_edu.core.repair",)),
    Exercise("laplacian_step", "05", ("laplacian_step",), "check_laplacian_step",
             forbids=("halfedge_edu.algorithms.smoothing",)),
    Exercise("flip", "06", ("my_flip",), "check_flip", forbids=_FLIP),
    Exercise("collapse", "07", ("my_collapse",), "check_collapse", forbids=_COLLAPSE),
    Exercise("collapse_is_safe", "08", ("collapse_is_safe",), "check_collapse_is_safe",
             forbids=(f"{_OPS}.link.link_condition", f"{_OPS}.link.link_of_edge", f"{_OPS}.link.link_of_vertex",
                      f"{_OPS}.link.link_violation", f"{_OPS}.collapse.can_collapse", f"{_OPS}.collapse._check",
                      f"{_MESH}.can_collapse", "notebook:rings_only")),
    Exercise("fixed_flip", "08b", ("fixed_flip",), "check_flip", forbids=_FLIP),
    Exercise("fixed_collapse", "08b", ("fixed_collapse",), "check_collapse", forbids=_COLLAPSE),
    Exercise("fixed_one_ring", "08b", ("fixed_one_ring",), "check_one_ring", forbids=_ONE_RING),
    Exercise("loop_rules", "09", ("edge_point", "vertex_point"), "check_loop_rules",
             forbids=("halfedge_edu.algorithms.loop",)),
    Exercise("plane_quadric", "10", ("plane_quadric",), "check_plane_quadric",
             forbids=("halfedge_edu.algorithms.simplify", "halfedge_edu.algorithms.simplify_queue",
                      "halfedge_edu.algorithms.collapse_rounds")),
    Exercise("optimal_point", "10", ("optimal_point",), "check_optimal_point",
             forbids=("halfedge_edu.algorithms.simplify", "halfedge_edu.algorithms.simplify_queue",
                      "halfedge_edu.algorithms.collapse_rounds")),
    Exercise("tangential_smoothing", "11", ("my_tangential_smoothing",), "check_tangential_smoothing",
             forbids=(*_REMESH, "halfedge_edu.algorithms.smoothing",
                      "halfedge_edu.exercises.remesh_checks.tangential_smoothing_reference")),
    Exercise("de_casteljau", "12", ("my_de_casteljau",), "check_de_casteljau",
             forbids=("halfedge_edu.algorithms.bezier",)),
    Exercise("nonmanifold", "04", ("has_nonmanifold_edges", "has_nonmanifold_vertices"), "check_nonmanifold",
             forbids=("halfedge_edu.core.manifold", f"{_SOUP}.nonmanifold_edges", f"{_SOUP}.nonmanifold_vertices",
                      f"{_SOUP}.has_nonmanifold_edges", f"{_SOUP}.has_nonmanifold_vertices", f"{_SOUP}.fans")),
    Exercise("vertex_normal", "11", ("my_vertex_normal",), "check_vertex_normal",
             forbids=("halfedge_edu.algorithms.normals",)),
    Exercise("bezier_patch", "12", ("my_patch_point",), "check_bezier_patch",
             forbids=("halfedge_edu.algorithms.bezier",)),
    Exercise("upsample", "09", ("my_upsample",), "check_upsample_connectivity",
             forbids=("halfedge_edu.algorithms.loop",)),
    Exercise("downsample", "10", ("my_downsample",), "check_downsample",
             forbids=("halfedge_edu.algorithms.simplify", "halfedge_edu.algorithms.simplify_queue",
                      "halfedge_edu.algorithms.collapse_rounds",
                      # the exercise hands the learner the quadrics; the loop is theirs
                      "!halfedge_edu.algorithms.simplify.face_quadrics")),
    Exercise("flip_improves", "11", ("my_flip_improves",), "check_flip_improves",
             forbids=_REMESH),
    Exercise("split_long_edges", "11", ("my_split_long_edges",), "check_split_long_edges",
             forbids=_REMESH),
    Exercise("split", "06", ("my_split",), "check_split", forbids=_SPLIT),
    Exercise("collapse_short_edges", "11", ("my_collapse_short_edges",), "check_collapse_short_edges",
             forbids=(*_REMESH, "halfedge_edu.algorithms.collapse_rounds",
                      "halfedge_edu.exercises.remesh_checks.collapse_short_edges_reference")),
)


class GradingError(ValueError):
    """The grader was asked for something it cannot do (e.g. a chapter with no exercises)."""


@dataclass
class ExerciseGrade:
    """Points for one exercise and why; ``public``/``hidden`` are (cases passed, cases run)."""

    name: str
    chapter: str
    score: float
    max_score: float
    output: str
    public: tuple[int, int] = (0, 0)
    hidden: tuple[int, int] = (0, 0)

    @property
    def passed(self) -> bool:
        return self.score >= self.max_score


@dataclass
class Grade:
    """The grade of one submission: one :class:`ExerciseGrade` per exercise of its chapter.

    ``problem`` is set when something stopped the run as a whole (unreadable file, dead
    kernel, total time limit); the exercises that could not be checked then carry it as
    their reason. ``chapter_from`` says what picked the chapter; ``seed`` is the hidden
    cases' seed (pass it back as ``seed=`` to reproduce a grade).
    """

    submission: str
    chapter: str
    exercises: list[ExerciseGrade]
    seconds: float
    problem: str | None = None
    cell_errors: list[str] = field(default_factory=list)
    chapter_from: str = "the file name"
    seed: int = 0
    isolation: str = ""

    @property
    def score(self) -> float:
        return sum(exercise.score for exercise in self.exercises)

    @property
    def max_score(self) -> float:
        return sum(exercise.max_score for exercise in self.exercises)

    def to_json(self) -> str:
        """The report in Gradescope's ``results.json`` schema (also otter-grader's)."""
        report = {
            "score": self.score,
            "max_score": self.max_score,
            "execution_time": round(self.seconds, 2),
            "output": printable(self.problem or f"{self.submission}: {self.score:g} of {self.max_score:g} points"),
            "tests": [
                {"name": f"{e.chapter} {e.name}", "score": e.score, "max_score": e.max_score,
                 "status": "passed" if e.passed else "failed", "output": printable(e.output),
                 "visibility": "visible"}
                for e in self.exercises
            ],
            "extra_data": {"submission": printable(self.submission), "chapter": self.chapter,
                           "chapter_from": self.chapter_from, "seed": self.seed, "isolation": self.isolation,
                           "cases": {e.name: {"public": list(e.public), "hidden": list(e.hidden)}
                                     for e in self.exercises},
                           "cell_errors": [printable(line) for line in self.cell_errors]},
        }
        return json.dumps(report, indent=2, ensure_ascii=False)

    def to_junit_xml(self) -> str:
        """The report as JUnit XML: one ``testcase`` per exercise, ``failure`` when points were lost.

        Well-formed for strict (xunit2) readers: every text is stripped of what XML 1.0
        cannot hold, and the counts are attributes of both ``testsuite`` and ``testsuites``.
        """
        failures = sum(not e.passed for e in self.exercises)
        name = printable(self.submission)
        suites = ElementTree.Element("testsuites", name="halfedge_edu grade", tests=str(len(self.exercises)),
                                     failures=str(failures), errors="0", time=f"{self.seconds:.2f}")
        suite = ElementTree.SubElement(suites, "testsuite", name=name, tests=str(len(self.exercises)),
                                       failures=str(failures), errors="0", skipped="0", time=f"{self.seconds:.2f}")
        for exercise in self.exercises:
            case = ElementTree.SubElement(suite, "testcase", classname=f"chapter{exercise.chapter}",
                                          name=exercise.name, time="0")
            properties = ElementTree.SubElement(case, "properties")
            for key, value in (("score", f"{exercise.score:g}"), ("max_score", f"{exercise.max_score:g}"),
                               ("public_cases", "{}/{}".format(*exercise.public)),
                               ("hidden_cases", "{}/{}".format(*exercise.hidden))):
                ElementTree.SubElement(properties, "property", name=key, value=value)
            if not exercise.passed:
                text = printable(exercise.output)
                failure = ElementTree.SubElement(case, "failure", message=text[:500], type="LostPoints")
                failure.text = text
        return ElementTree.tostring(suites, encoding="unicode", xml_declaration=True)


_NOT_PRINTABLE = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f\ud800-\udfff\ufffe\uffff]")


def printable(text: str) -> str:
    """``text`` with what a terminal, JSON reader or XML 1.0 cannot show written as ``\\xNN``.

    Control characters (NUL, ESC ...) and the odd bytes of a file name that is not UTF-8
    (Python keeps them as lone surrogates) become visible escapes instead of breaking a
    report or a terminal.
    """
    def escape(match: re.Match) -> str:
        code = ord(match.group())
        return f"\\x{code - 0xDC00:02x}" if 0xDC80 <= code <= 0xDCFF else f"\\x{code:02x}" if code < 0x100 \
            else f"\\u{code:04x}"

    return _NOT_PRINTABLE.sub(escape, str(text))


def exercises_for(chapter: str) -> list[Exercise]:
    """The graded exercises of ``chapter`` ("06"); GradingError if it has none."""
    found = [exercise for exercise in EXERCISES if exercise.chapter == chapter]
    if not found:
        graded = sorted({exercise.chapter for exercise in EXERCISES})
        raise GradingError(f"chapter {chapter!r} has no graded exercises; graded chapters: {', '.join(graded)}")
    return found


#: A chapter's number as its file name starts: "06", or "08b" for a chapter inserted after 08.
_CHAPTER = r"\d\d[a-z]?"
#: Seconds the grader gives a run beyond its total time limit to stop by itself (the
#: runner stops its kernel at the limit; this covers starting and stopping).
_GRACE = 15
#: The largest submission the grader reads (a chapter with its pictures is a few MB).
MAX_SUBMISSION_BYTES = 50 * 1024 * 1024


def chapter_of(notebook: dict, path: Path) -> str | None:
    """The chapter a submission belongs to: the number its file name starts with, else the
    notebook's ``halfedge_edu.chapter`` metadata (the editions stamp it)."""
    return _chapter_from_name(path) or _stamped_chapter(notebook)


def _stamped_chapter(notebook: dict) -> str | None:
    metadata = notebook.get("metadata", {}) if isinstance(notebook, dict) else {}
    stamped = metadata.get("halfedge_edu", {}).get("chapter") if isinstance(metadata, dict) else None
    return stamped if isinstance(stamped, str) and re.fullmatch(_CHAPTER, stamped) else None


def _chapter_from_name(path: Path) -> str | None:
    match = re.match(rf"({_CHAPTER})_", Path(path).name)
    return match.group(1) if match else None


def _chapter_and_source(path: Path, chapter: str | None) -> tuple[str | None, str]:
    """(chapter, what picked it): ``chapter`` if given, else the file name, else the notebook's stamp."""
    if chapter is not None:
        return chapter, "--chapter"
    named = _chapter_from_name(path)
    if named is not None:
        return named, "the file name"
    import nbformat  # outside the try: a missing notebooks extra is the grader's problem, said as such

    try:
        if path.stat().st_size <= MAX_SUBMISSION_BYTES:
            return _stamped_chapter(nbformat.read(path, as_version=4)), "the notebook's metadata"
    except Exception:  # unreadable: nothing says the chapter
        pass
    return None, "nothing"


def submission_chapter(path: str | Path, chapter: str | None = None) -> str:
    """The chapter ``path`` will be graded as (``chapter`` if given, else its file name, else its
    stamp), checked to have exercises. Raises :class:`GradingError` when it cannot be told or has
    no graded exercises."""
    path = Path(path)
    found, _ = _chapter_and_source(path, chapter)
    if found is None:
        raise GradingError(f"{printable(str(path))}: cannot tell the chapter (the file name does not start with "
                           f"NN_ and the notebook has no halfedge_edu.chapter metadata); give it with --chapter")
    exercises_for(found)
    return found


def check_function(exercise: Exercise):
    """The ``check_*`` helper that judges ``exercise``: from ``halfedge_edu.exercises``, or
    from :mod:`halfedge_edu.exercises.chapter_checks` for the checks of chapters 01, 04, 05, 08."""
    from halfedge_edu import exercises
    from halfedge_edu.exercises import chapter_checks

    found = getattr(exercises, exercise.check, None) or getattr(chapter_checks, exercise.check, None)
    if found is None:
        raise GradingError(f"exercise {exercise.name!r} names the check {exercise.check!r}, which does not exist")
    return found


# --------------------------------------------------------------------------------------
# One submission
# --------------------------------------------------------------------------------------

def grade_notebook(path: str | Path, *, chapter: str | None = None, cell_timeout: float = 60,
                   total_timeout: float = 600, kernel_name: str = "python3", isolation: str = "auto",
                   limits: Limits = Limits(), seed: int | None = None) -> Grade:
    """Run the notebook at ``path`` in a sandbox and grade its exercises from outside it.

    Args:
        path: the learner's ``.ipynb``.
        chapter: "06" and so on; by default the file name's number, else the notebook's stamp.
        cell_timeout: seconds one cell may run before it is interrupted.
        total_timeout: seconds the whole run may take; past that every process of it is
            ended and what was not checked scores zero.
        kernel_name: the Jupyter kernel to run it in (the course environment's).
        isolation: "auto" (bubblewrap where it works, else "process"), "bubblewrap" or
            "process"; see :mod:`halfedge_edu.exercises.sandbox`.
        limits: memory, processes, file size and output of the run.
        seed: the hidden cases' seed; by default a fresh one per call.

    Returns:
        A :class:`Grade`. Raises :class:`GradingError` only for the grader's own arguments
        (a ``chapter`` with no exercises); every problem of the submission, including one
        whose chapter cannot be told, is reported inside the grade.
    """
    path = Path(path)
    started = time.monotonic()
    seed = secrets.randbits(31) if seed is None else int(seed)
    if chapter is not None:
        exercises_for(chapter)
    chosen, chosen_from = _chapter_and_source(path, chapter)
    if chosen is None:
        return Grade(str(path), "", [], time.monotonic() - started,
                     "cannot tell the chapter: the file name does not start with NN_ (like 06_flip.ipynb) and the "
                     "notebook has no halfedge_edu.chapter metadata; the grader's --chapter can say it",
                     chapter_from=chosen_from, seed=seed)
    try:
        exercises = exercises_for(chosen)
    except GradingError as error:
        return Grade(str(path), chosen, [], time.monotonic() - started, f"{error} (chosen by {chosen_from})",
                     chapter_from=chosen_from, seed=seed)

    def zero(reason: str, cell_errors: list[str] | None = None, isolation_used: str = "") -> Grade:
        graded = [ExerciseGrade(e.name, e.chapter, 0.0, e.points, reason) for e in exercises]
        return Grade(str(path), chosen, graded, time.monotonic() - started, reason, cell_errors or [],
                     chosen_from, seed, isolation_used)

    try:
        if not path.is_file():
            return zero("the submission is not a file")
        if path.stat().st_size > MAX_SUBMISSION_BYTES:
            return zero(f"the submission is larger than {MAX_SUBMISSION_BYTES // 2**20} MB")
        data = path.read_bytes()
    except OSError as error:
        return zero(f"the submission cannot be read: {error.strerror or error}")

    with Sandbox(isolation, limits) as sandbox:
        return _grade_in(sandbox, data, path, chosen, chosen_from, exercises, cell_timeout, total_timeout,
                         kernel_name, seed, started, zero)


def _grade_in(sandbox: Sandbox, data: bytes, path: Path, chapter: str, chapter_from: str, exercises: list,
              cell_timeout: float, total_timeout: float, kernel_name: str, seed: int, started: float, zero) -> Grade:
    """Run the notebook (its bytes ``data``) in ``sandbox`` and the judge beside it."""
    notebook = sandbox.work / "submission.ipynb"
    notebook.write_bytes(data)
    if sandbox.uid is not None:
        os.chown(notebook, sandbox.uid, sandbox.uid)
    address = str(sandbox.exchange / "judge.sock")
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    # The judge starts at once (its imports overlap the notebook's run) and waits on
    # ``handoff`` for the kernel's connection, which the grader accepts and passes on. A
    # run that ends without connecting closes ``handoff``, and the judge stops at once.
    handoff, judge_end = socket.socketpair()
    judge = None
    try:
        listener.bind(address)
        os.chmod(address, 0o666)
        listener.listen(1)
        judge = subprocess.Popen(
            [sys.executable, "-m", "halfedge_edu.exercises.judge", "--handoff-fd", str(judge_end.fileno()),
             "--exercises", ",".join(e.name for e in exercises), "--seed", str(seed)],
            pass_fds=(judge_end.fileno(),), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL, start_new_session=True,
        )
        judge_end.close()
        functions = sorted({name for e in exercises for name in e.functions})
        forbids = {e.name: [*e.forbids, *ANSWER_KEYS] for e in exercises}
        runner_out = sandbox.root / "runner.out"
        with open(runner_out, "wb") as out:
            runner = sandbox.start(
                [sys.executable, "-m", "halfedge_edu.exercises.runner", str(notebook), "--socket", address,
                 "--functions", ",".join(functions), "--forbids", json.dumps(forbids),
                 "--cell-timeout", str(cell_timeout), "--total-timeout", str(total_timeout),
                 "--kernel", kernel_name, "--max-output", str(sandbox.limits.output_mb * 2**20)],
                stdout=out,
            )
            deadline = time.monotonic() + total_timeout + _GRACE
            _hand_over_connection(listener, handoff, runner, deadline)
            try:
                runner.wait(timeout=max(0.0, deadline - time.monotonic()))
                stopped = None
            except subprocess.TimeoutExpired:
                stopped = f"the notebook did not finish within {total_timeout:g} s and was stopped"
        sandbox.end_processes()
        try:
            # With the notebook's processes gone, the judge finishes at once (every call left fails).
            judged, _ = judge.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            judge.kill()
            judged, _ = judge.communicate()
        report = _runner_report(runner_out)
    finally:
        listener.close()
        handoff.close()
        judge_end.close()
        if judge is not None and judge.poll() is None:
            judge.kill()
            judge.wait()
    out_of_memory = sandbox.out_of_memory()
    verdict = _judge_verdict(judged, exercises)
    cell_errors = [f"cell {e['cell']}: {e['error']} (the cell that starts {e['first_line']!r})"
                   for e in report.get("cell_errors", [])]
    problem = stopped or _run_problem(report, out_of_memory, sandbox.limits)
    if verdict is None:
        reason = problem or ("the notebook's run was killed before its functions could be checked (by the "
                             "notebook's own code, or a limit on memory, processes or time)" if not report
                             else "the grading cell did not run (the kernel stopped before it)")
        return zero(reason, cell_errors, sandbox.isolation)
    graded = []
    for exercise in exercises:
        entry = verdict[exercise.name]
        output = entry["output"]
        if entry["missing"]:
            output = _why_missing(entry["missing"], exercise, report) or output
        graded.append(ExerciseGrade(exercise.name, exercise.chapter, exercise.points if entry["passed"] else 0.0,
                                    exercise.points, output, tuple(entry["public"]), tuple(entry["hidden"])))
    return Grade(str(path), chapter, graded, time.monotonic() - started, problem, cell_errors, chapter_from, seed,
                 sandbox.isolation)


def _hand_over_connection(listener: socket.socket, handoff: socket.socket, runner: subprocess.Popen,
                          deadline: float) -> None:
    """Wait for the kernel's one connection (or the run's end) and pass it to the judge."""
    listener.settimeout(0.2)
    try:
        while runner.poll() is None and time.monotonic() < deadline:
            try:
                connection, _ = listener.accept()
            except TimeoutError:
                continue
            with connection:
                socket.send_fds(handoff, [b"k"], [connection.fileno()])
            return
    finally:
        listener.close()
        handoff.close()   # no connection came: the judge reads the end of the pipe and stops


def _runner_report(path: Path) -> dict:
    """The runner's account of the run (the learner's side: used for reasons, never for points)."""
    from .runner import REPORT_PREFIX

    try:
        with open(path, "rb") as handle:
            handle.seek(max(0, path.stat().st_size - 2**20))
            text = handle.read().decode("utf-8", "replace")
    except OSError:
        return {}
    for line in reversed(text.splitlines()):
        if line.startswith(REPORT_PREFIX):
            try:
                report = json.loads(line[len(REPORT_PREFIX):])
            except json.JSONDecodeError:
                return {}
            if not isinstance(report, dict):
                return {}
            errors = report.get("cell_errors")
            report["cell_errors"] = [
                {"cell": int(e.get("cell", 0)), "first_line": str(e.get("first_line", ""))[:60],
                 "error": str(e.get("error", ""))[:500], "traceback": str(e.get("traceback", ""))[-3000:]}
                for e in (errors if isinstance(errors, list) else [])[:50] if isinstance(e, dict)]
            return report
    return {}


def _run_problem(report: dict, out_of_memory: bool, limits: Limits) -> str | None:
    """The run as a whole, in words (None when it ran to the end)."""
    if out_of_memory:
        return f"the notebook ran out of memory (the limit is {limits.memory_mb} MiB) and its kernel was stopped"
    problem = report.get("problem") if isinstance(report.get("problem"), str) else None
    if problem == "the kernel died":
        cell = report.get("dead_cell")
        where = f" while running cell {int(cell)}" if isinstance(cell, int) else ""
        return (f"the kernel died{where} (a crash, os._exit, running out of memory, or a limit on processes or "
                f"file size)")
    return problem[:500] if problem else None


def _why_missing(missing: list[str], exercise: Exercise, report: dict) -> str | None:
    """The real reason a function does not exist: the error of the cell that should define it."""
    defines = report.get("defines") if isinstance(report.get("defines"), dict) else {}
    errors = {e["cell"]: e for e in report.get("cell_errors", [])}
    for name in missing:
        cell = defines.get(name)
        if isinstance(cell, int) and cell in errors:
            error = errors[cell]
            where = _error_line(error["traceback"])
            return (f"your {name} was never defined: cell {cell} ({error['first_line']}) raised "
                    f"{error['error']}{where}. Fix that cell and run the notebook top to bottom.")
        if isinstance(cell, int):
            return (f"your {name} was defined in cell {cell}, but it did not exist at the end of the notebook "
                    f"(a later cell deleted or replaced it).")
    return None


def _error_line(traceback_text: str) -> str:
    """' (line 3: def my_flip(mesh, e)' ...)' from a cell's traceback, when it names a line."""
    lines = [line for line in traceback_text.splitlines() if line.strip()]
    numbered = [line for line in lines if re.search(r"line \d+", line)]
    if not numbered:
        return ""
    at = re.search(r"line (\d+)", numbered[-1]).group(1)
    index = lines.index(numbered[-1])
    code = lines[index + 1].strip() if index + 1 < len(lines) and not lines[index + 1].strip().startswith("^") \
        else ""
    return f" at line {at}" + (f": {code[:80]}" if code and not code.startswith(("File ", "Cell ")) else "")


def _judge_verdict(output: bytes, exercises: list) -> dict | None:
    """The judge's results, validated: one entry per exercise with the right types, or None."""
    lines = output.decode("utf-8", "replace").strip().splitlines()
    if not lines:
        return None
    try:
        result = json.loads(lines[-1])
    except json.JSONDecodeError:
        return None
    found = result.get("exercises") if isinstance(result, dict) else None
    if not isinstance(found, dict):
        return None
    verdict = {}
    for exercise in exercises:
        entry = found.get(exercise.name)
        if not isinstance(entry, dict) or not isinstance(entry.get("output"), str):
            return None
        counts = [entry.get("public"), entry.get("hidden")]
        if not all(isinstance(c, list) and len(c) == 2 and all(isinstance(n, int) and 0 <= n < 10**6 for n in c)
                   for c in counts):
            return None
        missing = entry.get("missing")
        verdict[exercise.name] = {
            "passed": entry.get("passed") is True,   # exactly True: "no", 1 or "yes" are not a pass
            "output": entry["output"][:4000], "public": counts[0], "hidden": counts[1],
            "missing": [m for m in missing if isinstance(m, str)] if isinstance(missing, list) else [],
        }
    return verdict


def summary_line(grade: Grade) -> str:
    """One line for a terminal: 'alice.ipynb  chapter 06  2/3  (collapse: Not yet. ...)'."""
    lost = [f"{e.name}: {e.output[:80]}" for e in grade.exercises if not e.passed]
    if grade.problem and not grade.exercises:
        lost = [grade.problem[:120]]
    tail = f"  ({'; '.join(lost)})" if lost else ""
    return printable(f"{Path(grade.submission).name}  chapter {grade.chapter or '?'}  "
                     f"{grade.score:g}/{grade.max_score:g}{tail}")
