"""Grade a learner's chapter notebook: points per exercise, with the reason for each lost point.

    from halfedge_edu.exercises.grading import grade_notebook
    grade = grade_notebook("06_flip_and_split.ipynb")
    grade.score, grade.max_score          # e.g. (1.0, 1.0)
    grade.to_json(); grade.to_junit_xml()

What happens, in order:

1. The submission is copied into a fresh temporary folder and run top to bottom in a
   fresh kernel (``nbclient``), with a time limit per cell and one for the whole run.
   A cell that raises does not stop the run (a later cell may still define an
   exercise's function); a cell that runs too long is interrupted.
2. One more cell, written by the grader, is appended: for each exercise of the chapter
   it looks the learner's function up by name and runs the package's own ``check_*``
   helper on it (the same reference tests the chapter's "check yourself" cells use).
   The learner's cells cannot see that cell or its per-run key, so printing a fake
   result does not count.
3. Each exercise earns its points when its check passes; otherwise zero, with the
   check's first message ("your my_flip raised NotImplementedError ...", "On 'cube':
   halfedge 4 ...") as the reason. A notebook that cannot be read, whose kernel dies or
   that runs past the total limit gets zero for what could not run, with the reason;
   the grader itself never crashes on a submission.

Report formats, chosen to plug into what courses already run:

- ``Grade.to_json()`` follows the ``results.json`` schema of Gradescope's autograder
  (``score``, ``tests`` with ``name``/``score``/``max_score``/``output``), which
  otter-grader also writes, so a Gradescope or otter workflow can read it unchanged.
- ``Grade.to_junit_xml()`` writes one ``testcase`` per exercise (``failure`` with the
  reason when points were lost): GitHub Classroom, GitLab and Jenkins show JUnit.

Attention: grading runs the learner's code. Run it in the sandbox your course CI gives
each submission; the time limits guard against endless loops, not against malice.
"""

from __future__ import annotations

import json
import re
import secrets
import shutil
import subprocess
import tempfile
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import asdict, dataclass, field
from pathlib import Path

__all__ = [
    "EXERCISES", "Exercise", "ExerciseGrade", "Grade", "GradingError", "chapter_of", "check_function",
    "exercises_for", "grade_notebook", "submission_chapter",
]


@dataclass(frozen=True)
class Exercise:
    """One graded exercise: where it is taught and how it is checked.

    Attributes:
        name: short id used in reports ("flip").
        chapter: the number of the chapter that teaches it ("06"; "08b" for the debugging lab).
        functions: the names the learner's notebook defines, passed to the check in order.
        check: the name of the ``halfedge_edu.exercises`` helper that judges them.
        points: what a passing check earns.
    """

    name: str
    chapter: str
    functions: tuple[str, ...]
    check: str
    points: float = 1.0


#: Every graded exercise, in chapter order. The function names are the ones each
#: chapter's exercise cell asks the learner to fill in.
EXERCISES: tuple[Exercise, ...] = (
    Exercise("fan", "01", ("fan",), "check_fan"),
    Exercise("obj_io", "01", ("read_obj", "write_obj"), "check_obj_io"),
    Exercise("build", "02", ("build",), "check_build"),
    Exercise("one_ring", "03", ("one_ring",), "check_one_ring"),
    Exercise("cut", "04", ("cut_bowtie",), "check_cut"),
    Exercise("laplacian_step", "05", ("laplacian_step",), "check_laplacian_step"),
    Exercise("flip", "06", ("my_flip",), "check_flip"),
    Exercise("collapse", "07", ("my_collapse",), "check_collapse"),
    Exercise("collapse_is_safe", "08", ("collapse_is_safe",), "check_collapse_is_safe"),
    Exercise("fixed_flip", "08b", ("fixed_flip",), "check_flip"),
    Exercise("fixed_collapse", "08b", ("fixed_collapse",), "check_collapse"),
    Exercise("fixed_one_ring", "08b", ("fixed_one_ring",), "check_one_ring"),
    Exercise("loop_rules", "09", ("edge_point", "vertex_point"), "check_loop_rules"),
    Exercise("plane_quadric", "10", ("plane_quadric",), "check_plane_quadric"),
    Exercise("optimal_point", "10", ("optimal_point",), "check_optimal_point"),
    Exercise("tangential_smoothing", "11", ("my_tangential_smoothing",), "check_tangential_smoothing"),
    Exercise("de_casteljau", "12", ("my_de_casteljau",), "check_de_casteljau"),
    Exercise("nonmanifold", "04", ("has_nonmanifold_edges", "has_nonmanifold_vertices"), "check_nonmanifold"),
    Exercise("vertex_normal", "11", ("my_vertex_normal",), "check_vertex_normal"),
    Exercise("bezier_patch", "12", ("my_patch_point",), "check_bezier_patch"),
    Exercise("upsample", "09", ("my_upsample",), "check_upsample_connectivity"),
    Exercise("downsample", "10", ("my_downsample",), "check_downsample"),
    Exercise("flip_improves", "11", ("my_flip_improves",), "check_flip_improves"),
    Exercise("split_long_edges", "11", ("my_split_long_edges",), "check_split_long_edges"),
)


class GradingError(ValueError):
    """The grader was asked for something it cannot do (e.g. a chapter with no exercises)."""


@dataclass
class ExerciseGrade:
    """Points for one exercise and why."""

    name: str
    chapter: str
    score: float
    max_score: float
    output: str

    @property
    def passed(self) -> bool:
        return self.score >= self.max_score


@dataclass
class Grade:
    """The grade of one submission: one :class:`ExerciseGrade` per exercise of its chapter.

    ``problem`` is set when something stopped the run as a whole (unreadable file, dead
    kernel, total time limit); the exercises that could not be checked then carry it as
    their reason.
    """

    submission: str
    chapter: str
    exercises: list[ExerciseGrade]
    seconds: float
    problem: str | None = None
    cell_errors: list[str] = field(default_factory=list)

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
            "output": self.problem or f"{self.submission}: {self.score:g} of {self.max_score:g} points",
            "tests": [
                {"name": f"{e.chapter} {e.name}", "score": e.score, "max_score": e.max_score,
                 "status": "passed" if e.passed else "failed", "output": e.output}
                for e in self.exercises
            ],
            "extra_data": {"submission": self.submission, "chapter": self.chapter,
                           "cell_errors": self.cell_errors},
        }
        return json.dumps(report, indent=2)

    def to_junit_xml(self) -> str:
        """The report as JUnit XML: one ``testcase`` per exercise, ``failure`` when points were lost."""
        failures = sum(not e.passed for e in self.exercises)
        suite = ElementTree.Element("testsuite", name=self.submission, tests=str(len(self.exercises)),
                                    failures=str(failures), errors="0", time=f"{self.seconds:.2f}")
        for exercise in self.exercises:
            case = ElementTree.SubElement(suite, "testcase", classname=f"chapter{exercise.chapter}",
                                          name=exercise.name, time="0")
            ElementTree.SubElement(case, "properties")
            for key, value in (("score", exercise.score), ("max_score", exercise.max_score)):
                ElementTree.SubElement(case.find("properties"), "property", name=key, value=f"{value:g}")
            if not exercise.passed:
                failure = ElementTree.SubElement(case, "failure", message=exercise.output[:500])
                failure.text = exercise.output
        suites = ElementTree.Element("testsuites")
        suites.append(suite)
        return ElementTree.tostring(suites, encoding="unicode", xml_declaration=True)


def exercises_for(chapter: str) -> list[Exercise]:
    """The graded exercises of ``chapter`` ("06"); GradingError if it has none."""
    found = [exercise for exercise in EXERCISES if exercise.chapter == chapter]
    if not found:
        graded = sorted({exercise.chapter for exercise in EXERCISES})
        raise GradingError(f"chapter {chapter!r} has no graded exercises; graded chapters: {', '.join(graded)}")
    return found


#: A chapter's number as its file name starts: "06", or "08b" for a chapter inserted after 08.
_CHAPTER = r"\d\d[a-z]?"


def chapter_of(notebook: dict, path: Path) -> str | None:
    """The chapter a submission belongs to: the notebook's ``halfedge_edu.chapter``
    metadata (the editions stamp it), else the number its file name starts with."""
    stamped = notebook.get("metadata", {}).get("halfedge_edu", {}).get("chapter")
    if isinstance(stamped, str) and re.fullmatch(_CHAPTER, stamped):
        return stamped
    return _chapter_from_name(path)


def _chapter_from_name(path: Path) -> str | None:
    match = re.match(rf"({_CHAPTER})_", path.name)
    return match.group(1) if match else None


def submission_chapter(path: str | Path, chapter: str | None = None) -> str:
    """The chapter ``path`` will be graded as (``chapter`` if given), checked to have exercises.

    Raises :class:`GradingError` when it cannot be told (no stamp, no ``NN_`` file name)
    or has no graded exercises: the grader's arguments are wrong, not the submission.
    A notebook that cannot be read is graded by its file name.
    """
    import nbformat

    path = Path(path)
    if chapter is None:
        try:
            chapter = chapter_of(nbformat.read(path, as_version=4), path)
        except Exception:  # unreadable: the file name may still say the chapter
            chapter = _chapter_from_name(path)
    if chapter is None:
        raise GradingError(f"{path}: cannot tell the chapter (no halfedge_edu.chapter metadata and the file "
                           f"name does not start with NN_); give it with --chapter (chapter=...)")
    exercises_for(chapter)
    return chapter


def check_function(exercise: Exercise):
    """The ``check_*`` helper that judges ``exercise``: from ``halfedge_edu.exercises``, or
    from :mod:`halfedge_edu.exercises.chapter_checks` for the checks of chapters 01, 04, 05, 08."""
    from halfedge_edu import exercises
    from halfedge_edu.exercises import chapter_checks

    found = getattr(exercises, exercise.check, None) or getattr(chapter_checks, exercise.check, None)
    if found is None:
        raise GradingError(f"exercise {exercise.name!r} names the check {exercise.check!r}, which does not exist")
    return found


# The cell the grader appends. It runs in the learner's kernel after their cells, so it
# sees the functions they defined; it prints one line, marked with a per-run key.
_GRADING_CELL = """\
def __halfedge_edu_grade():
    import json
    from halfedge_edu.exercises.grading import run_checks
    return json.dumps(run_checks(globals(), {names!r}))
print({key!r} + __halfedge_edu_grade())
"""


def run_checks(namespace: dict, exercise_names: list[str]) -> dict[str, dict]:
    """Run each named exercise's check on the functions found in ``namespace``.

    Used inside the learner's kernel by the grading cell; returns, per exercise,
    ``{"passed": bool, "output": str}``. A missing function or a check that itself
    fails is reported as a failed exercise with the reason, never raised.
    """
    by_name = {exercise.name: exercise for exercise in EXERCISES}
    results: dict[str, dict] = {}
    for name in exercise_names:
        exercise = by_name[name]
        missing = [f for f in exercise.functions if not callable(namespace.get(f))]
        if missing:
            results[name] = {"passed": False, "output": (
                f"no function named {', '.join(missing)} was defined: the exercise cell defines "
                f"{' and '.join(exercise.functions)}; keep those names")}
            continue
        try:
            result = check_function(exercise)(*(namespace[f] for f in exercise.functions))
        except BaseException as error:  # the check ran the learner's code; report, never crash
            results[name] = {"passed": False, "output": f"the check stopped: {type(error).__name__}: {error}"}
            continue
        results[name] = {"passed": bool(result), "output": str(result.message)}
    return results


def _text_of(outputs: list) -> str:
    parts = []
    for output in outputs:
        if output.get("output_type") == "stream":
            parts.append(output.get("text", ""))
    return "".join(parts)


def _cell_errors(cells: list) -> list[str]:
    """One line per learner cell that raised: 'cell 12: NameError: ...'."""
    found = []
    for number, cell in enumerate(cells):
        if cell.get("cell_type") != "code":
            continue
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                found.append(f"cell {number}: {output.get('ename')}: {output.get('evalue')}"[:300])
    return found


def grade_notebook(path: str | Path, *, chapter: str | None = None, cell_timeout: float = 60,
                   total_timeout: float = 600, kernel_name: str = "python3") -> Grade:
    """Run the notebook at ``path`` in a fresh kernel and grade its exercises.

    Args:
        path: the learner's ``.ipynb``.
        chapter: "06" and so on; by default from the notebook (see :func:`submission_chapter`).
        cell_timeout: seconds one cell may run before it is interrupted.
        total_timeout: seconds the whole run may take; past that the kernel is stopped
            and what was not checked scores zero.
        kernel_name: the Jupyter kernel to run it in (the course environment's).

    Returns:
        A :class:`Grade`. Raises :class:`GradingError` only for the grader's own
        arguments (a chapter that cannot be told or has no exercises); every problem of
        the submission is reported inside the grade.
    """
    import nbformat

    path = Path(path)
    started = time.monotonic()
    chosen = submission_chapter(path, chapter)
    try:
        notebook = nbformat.read(path, as_version=4)
    except Exception as error:  # any unreadable file is the submission's problem
        return _zero(path, chosen, f"the submission is not a readable notebook: {type(error).__name__}: {error}",
                     started)
    exercises = exercises_for(chosen)

    key = f"@@halfedge_edu-grade-{secrets.token_hex(8)}@@"
    names = [exercise.name for exercise in exercises]
    notebook.cells.append(nbformat.v4.new_code_cell(_GRADING_CELL.format(names=names, key=key)))
    problem = _execute(notebook, path, cell_timeout, total_timeout, kernel_name)

    found = None
    for output in notebook.cells[-1].get("outputs", []):
        if output.get("output_type") == "stream":
            for line in output.get("text", "").splitlines():
                if line.startswith(key):
                    found = json.loads(line[len(key):])
    if found is None:
        reason = problem or "the grading cell did not run (the kernel stopped before it)"
        return _zero(path, chosen, reason, started, _cell_errors(notebook.cells[:-1]))
    graded = [ExerciseGrade(e.name, e.chapter, e.points if found[e.name]["passed"] else 0.0, e.points,
                            found[e.name]["output"]) for e in exercises]
    return Grade(str(path), chosen, graded, time.monotonic() - started, problem,
                 _cell_errors(notebook.cells[:-1]))


def _zero(path: Path, chapter: str, reason: str, started: float, cell_errors: list[str] | None = None) -> Grade:
    exercises = [ExerciseGrade(e.name, e.chapter, 0.0, e.points, reason) for e in exercises_for(chapter)]
    return Grade(str(path), chapter, exercises, time.monotonic() - started, reason, cell_errors or [])


def _execute(notebook, path: Path, cell_timeout: float, total_timeout: float, kernel_name: str) -> str | None:
    """Run ``notebook`` in place in a temporary copy of its folder; a problem in words, or None."""
    import asyncio

    from nbclient import NotebookClient
    from nbclient.exceptions import DeadKernelError

    with tempfile.TemporaryDirectory(prefix="halfedge_edu-grade-") as folder:
        # The learner's notebook may read files beside it (their own OBJ, say).
        for sibling in path.parent.iterdir() if path.parent.is_dir() else []:
            if sibling.is_file() and sibling.suffix != ".ipynb" and sibling.stat().st_size < 50_000_000:
                shutil.copy2(sibling, Path(folder) / sibling.name)
        grading_cell = notebook.cells[-1]

        def timeout_of(cell) -> int:
            # The learner's cells get cell_timeout; the grader's own cell runs every check
            # (each learner call already has its own limit), so only the total bounds it.
            return int(total_timeout) if cell.source == grading_cell.source else int(cell_timeout)

        client = NotebookClient(
            notebook, timeout_func=timeout_of, interrupt_on_timeout=True, allow_errors=True,
            kernel_name=kernel_name, resources={"metadata": {"path": folder}},
        )

        async def run() -> bool:
            """Run the notebook; False when the total time ran out first."""
            # The kernel process's own stderr (not the cells') would only add noise to a CI log.
            task = asyncio.ensure_future(client.async_execute(stderr=subprocess.DEVNULL))
            done, _ = await asyncio.wait({task}, timeout=total_timeout)
            if not done:
                task.cancel()
                try:
                    await task
                except BaseException:  # the cancelled run's own clean-up errors do not matter
                    pass
                return False
            task.result()  # raises what the run raised
            return True

        try:
            if not asyncio.run(run()):
                return f"the notebook did not finish within {total_timeout:g} s and was stopped"
        except DeadKernelError:
            return "the kernel died while running the notebook (a crash, os._exit or running out of memory)"
        except Exception as error:  # nbclient's own failures: report, the grade goes on
            return f"the notebook could not be run: {type(error).__name__}: {error}"
        finally:
            _stop_kernel(client)
    return None


def _stop_kernel(client) -> None:
    """Make sure no kernel outlives a grade (after a time-out, nbclient may leave one running)."""
    import asyncio

    manager = getattr(client, "km", None)
    if manager is None or not manager.has_kernel:
        return
    try:
        asyncio.run(manager.shutdown_kernel(now=True))
    except Exception:  # already gone, or its process group ended with it
        pass


def summary_line(grade: Grade) -> str:
    """One line for a terminal: 'alice.ipynb  chapter 06  2/3  (collapse: Not yet. ...)'."""
    lost = [f"{e.name}: {e.output[:80]}" for e in grade.exercises if not e.passed]
    tail = f"  ({'; '.join(lost)})" if lost else ""
    return f"{Path(grade.submission).name}  chapter {grade.chapter}  {grade.score:g}/{grade.max_score:g}{tail}"


def as_dict(grade: Grade) -> dict:
    """The grade as plain data (for tests and custom reports)."""
    return asdict(grade)
