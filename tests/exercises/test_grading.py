"""The grader: points per exercise with reasons, and never a crash on a bad submission.

Submissions here are small notebooks made on the spot (a real chapter would take
longer to run); the right answer is taken from chapter 06's own exercise cell (the
solution edition's), so these tests follow the chapter.
"""

from __future__ import annotations

import ast
import inspect
import json
import textwrap
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import nbformat
import pytest

from halfedge_edu.exercises.grading import (
    ANSWER_KEYS, EXERCISES, GradingError, chapter_of, check_function, exercises_for, grade_notebook,
)

ROOT = Path(__file__).resolve().parents[2]


def _exercise_function(chapter_source: str, name: str) -> str:
    """The source of function ``name`` as the solution edition of a chapter defines it (comments dropped)."""
    text = (ROOT / "notebooks" / "src" / chapter_source).read_text()
    for node in ast.parse(text).body:
        if isinstance(node, ast.FunctionDef) and node.name == name:
            return ast.unparse(node)
    raise AssertionError(f"{chapter_source} has no function {name}")


RIGHT_FLIP = _exercise_function("06_flip_and_split.py", "my_flip")
RIGHT_SPLIT = _exercise_function("06_flip_and_split.py", "my_split")


def submission(tmp_path: Path, *cells: str, name: str = "06_flip_and_split.ipynb") -> Path:
    notebook = nbformat.v4.new_notebook()
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    notebook.cells = [nbformat.v4.new_code_cell(cell) for cell in cells]
    path = tmp_path / name
    nbformat.write(notebook, path)
    return path


def test_a_right_answer_earns_full_points(tmp_path):
    grade = grade_notebook(submission(tmp_path, RIGHT_FLIP, RIGHT_SPLIT))
    assert (grade.score, grade.max_score) == (2.0, 2.0)
    assert [exercise.name for exercise in grade.exercises] == ["flip", "split"]
    assert all(exercise.output.startswith("All good!") for exercise in grade.exercises), grade.to_json()
    assert grade.problem is None and grade.cell_errors == []


def test_a_stub_earns_nothing_with_the_reason_not_implemented(tmp_path):
    stub = "def my_flip(mesh, e):\n    raise NotImplementedError('fill in steps 1 to 4')"
    grade = grade_notebook(submission(tmp_path, stub))
    assert grade.score == 0.0
    assert "NotImplementedError" in grade.exercises[0].output


def test_a_wrong_answer_earns_nothing_and_names_the_mistake(tmp_path):
    # Drop step 4 (the vertex's outgoing halfedge), the chapter's own "buggy" example.
    wrong = RIGHT_FLIP.split("    if mesh.vertex_halfedge[v0] == h0:")[0]
    grade = grade_notebook(submission(tmp_path, wrong))
    assert grade.score == 0.0
    assert grade.exercises[0].output.startswith("Not yet.")
    assert "vertex" in grade.exercises[0].output


def test_a_missing_function_is_named(tmp_path):
    grade = grade_notebook(submission(tmp_path, "def flip_it(mesh, e):\n    pass"))
    assert grade.score == 0.0
    assert "no function named my_flip" in grade.exercises[0].output


def test_a_cell_that_raises_does_not_stop_the_run(tmp_path):
    grade = grade_notebook(submission(tmp_path, "def broken(:", "1 / 0", RIGHT_FLIP))
    assert grade.score == 1.0
    assert [line.split(":")[1].strip() for line in grade.cell_errors] == ["SyntaxError", "ZeroDivisionError"]


def test_an_endless_cell_is_interrupted_and_later_cells_still_count(tmp_path):
    grade = grade_notebook(submission(tmp_path, "while True:\n    pass", RIGHT_FLIP), cell_timeout=3)
    assert grade.score == 1.0
    assert "KeyboardInterrupt" in grade.cell_errors[0]


def test_a_run_past_the_total_limit_scores_zero_with_the_reason(tmp_path):
    grade = grade_notebook(submission(tmp_path, RIGHT_FLIP, "import time\ntime.sleep(60)"),
                           cell_timeout=120, total_timeout=8)
    assert grade.score == 0.0
    assert "did not finish within 8 s" in grade.problem
    assert grade.exercises[0].output == grade.problem


def test_a_dead_kernel_scores_zero_with_the_reason(tmp_path):
    grade = grade_notebook(submission(tmp_path, RIGHT_FLIP, "import os\nos._exit(3)"))
    assert grade.score == 0.0
    assert "kernel died" in grade.problem


def test_an_unreadable_file_scores_zero_with_the_reason(tmp_path):
    path = tmp_path / "06_flip_and_split.ipynb"
    path.write_text("{ this is not json")
    grade = grade_notebook(path)
    assert grade.score == 0.0 and "not a readable notebook" in grade.problem


def test_printing_a_fake_result_does_not_count(tmp_path):
    stub = "def my_flip(mesh, e):\n    raise NotImplementedError"
    fake = "print('@@halfedge_edu-grade-0000000000000000@@' + '{\"flip\": {\"passed\": true, \"output\": \"\"}}')"
    grade = grade_notebook(submission(tmp_path, stub, fake))
    assert grade.score == 0.0


def test_json_report_follows_the_gradescope_schema(tmp_path):
    grade = grade_notebook(submission(tmp_path, RIGHT_FLIP))
    report = json.loads(grade.to_json())
    assert (report["score"], report["max_score"]) == (1.0, 2.0)
    assert [(t["name"], t["score"], t["max_score"], t["status"]) for t in report["tests"]] == \
        [("06 flip", 1.0, 1.0, "passed"), ("06 split", 0.0, 1.0, "failed")]


def test_junit_report_has_one_testcase_per_exercise_and_a_failure_for_lost_points(tmp_path):
    stub = "def my_flip(mesh, e):\n    raise NotImplementedError"
    grade = grade_notebook(submission(tmp_path, stub))
    suite = ElementTree.fromstring(grade.to_junit_xml()).find("testsuite")
    assert suite.get("tests") == "2" and suite.get("failures") == "2"
    failure = suite.find("testcase").find("failure")
    assert "NotImplementedError" in failure.text


def test_the_chapter_comes_from_the_file_name_before_the_notebooks_own_stamp():
    notebook = {"metadata": {"halfedge_edu": {"chapter": "07"}}}
    assert chapter_of(notebook, Path("06_flip_and_split.ipynb")) == "06"
    assert chapter_of(notebook, Path("alice.ipynb")) == "07"
    assert chapter_of({"metadata": {}}, Path("06_flip_and_split.ipynb")) == "06"
    assert chapter_of({"metadata": {}}, Path("alice.ipynb")) is None


def test_a_chapter_without_exercises_is_refused_by_name():
    with pytest.raises(GradingError, match="chapter '00' has no graded exercises"):
        exercises_for("00")


def test_every_exercise_names_a_check_the_package_has():
    for exercise in EXERCISES:
        assert check_function(exercise).__name__ == exercise.check, exercise


def test_every_module_that_defines_a_check_is_forbidden_to_every_exercise():
    # A check's reference code (patch_point, warren_beta, a right version of the lab's
    # bugs ...) is an answer: each module that defines a check_* is in ANSWER_KEYS, so
    # that splitting a check module cannot leave its new part callable by a learner.
    import importlib
    import pkgutil

    import halfedge_edu.exercises as package
    from halfedge_edu.exercises.harness import CheckResult

    defining = set()
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        if any(name.startswith("check_") and getattr(value, "__module__", None) == module.__name__
               and inspect.signature(value).return_annotation in ("CheckResult", CheckResult)
               for name, value in vars(module).items()):
            defining.add(module.__name__)
    assert {check_function(exercise).__module__ for exercise in EXERCISES} <= defining
    assert defining <= set(ANSWER_KEYS), sorted(defining - set(ANSWER_KEYS))


# --------------------------------------------------------------------------------------
# Real editions of a chapter, submissions made of the debugging lab's bugs, the command
# --------------------------------------------------------------------------------------

def _edition(tmp_path: Path, chapter_source: str, edition: str) -> Path:
    """Chapter ``chapter_source`` in ``edition``, as the builder makes it (unexecuted: the grader runs it)."""
    import sys

    sys.path.insert(0, str(ROOT / "tools"))
    from build_notebooks import chapter_id, new_notebook, parse_source

    source = ROOT / "notebooks" / "src" / chapter_source
    chapter = chapter_id(source)
    notebook = new_notebook(parse_source(source.read_text(encoding="utf-8"), chapter, edition), chapter, edition)
    path = tmp_path / edition / f"{source.stem}.ipynb"
    path.parent.mkdir()
    nbformat.write(notebook, path)
    return path


def test_the_solution_edition_of_a_chapter_earns_full_points(tmp_path):
    path = _edition(tmp_path, "06_flip_and_split.py", "solution")
    grade = grade_notebook(path)
    assert grade.max_score > 0 and grade.score == grade.max_score, grade.to_json()
    assert grade.problem is None
    cells = nbformat.read(path, as_version=4).cells
    raised = [int(line.split(":")[0].split()[1]) for line in grade.cell_errors]  # "cell 15: ...", counted from 1
    assert all("raises-exception" in cells[n - 1].metadata.get("tags", []) for n in raised), grade.cell_errors


def test_the_student_edition_of_a_chapter_earns_nothing_because_it_is_not_implemented(tmp_path):
    grade = grade_notebook(_edition(tmp_path, "06_flip_and_split.py", "student"))
    assert grade.score == 0.0 and grade.max_score > 0
    for exercise in grade.exercises:
        assert exercise.output.startswith("Not yet.") and "raised NotImplementedError" in exercise.output


def _lab_submission(tmp_path: Path, name: str, flip: str, collapse: str, one_ring: str) -> Path:
    """A chapter 08b submission whose three fixed_* functions are the named classic_bugs functions,
    written out in the notebook as a learner would: their source and that of the helpers they call."""
    from halfedge_edu.exercises import classic_bugs

    header = "\n".join(line for line in inspect.getsource(classic_bugs).splitlines()
                       if line.startswith(("import ", "from ")) and "__future__" not in line)
    written: dict[str, str] = {}

    def write_out(function_name: str) -> None:
        function = getattr(classic_bugs, function_name)
        codes, names = [function.__code__], set()
        while codes:  # the names it uses, nested functions included
            code = codes.pop()
            names.update(code.co_names)
            codes += [c for c in code.co_consts if inspect.iscode(c)]
        for used in sorted(names):
            helper = getattr(classic_bugs, used, None)
            if inspect.isfunction(helper) and helper.__module__ == classic_bugs.__name__ and used not in written:
                write_out(used)
        written.setdefault(function_name, textwrap.dedent(inspect.getsource(function)))

    for bug in (flip, collapse, one_ring):
        write_out(bug)
    renames = f"fixed_flip = {flip}\nfixed_collapse = {collapse}\nfixed_one_ring = {one_ring}"
    return submission(tmp_path, header, *written.values(), renames, name=name)


@pytest.mark.parametrize(("flip", "collapse", "one_ring", "score", "rules"), [
    ("flip_forgetting_vertex_halfedge", "collapse_right", "one_ring_right", 2.0,
     {"fixed_flip": "vertex-halfedge-origin"}),
    ("flip_right", "collapse_reading_neighbours_too_early", "one_ring_endless_at_the_boundary", 1.0,
     {"fixed_collapse": "deleted-reference", "fixed_one_ring": "never comes back to its start halfedge"}),
])
def test_a_submission_made_of_lab_bugs_gets_a_partial_grade_naming_each_rule(tmp_path, flip, collapse, one_ring,
                                                                             score, rules):
    grade = grade_notebook(_lab_submission(tmp_path, "08b_debugging_lab.ipynb", flip, collapse, one_ring))
    assert (grade.score, grade.max_score) == (score, 3.0)
    lost = {exercise.name: exercise.output for exercise in grade.exercises if not exercise.passed}
    assert set(lost) == set(rules)
    for name, rule in rules.items():
        assert rule in lost[name], lost[name]


def test_the_grade_command_writes_both_reports_and_a_summary_line(tmp_path, capsys):
    from halfedge_edu import cli

    path = submission(tmp_path, RIGHT_FLIP, RIGHT_SPLIT, name="alice.ipynb")
    out = tmp_path / "reports"
    assert cli.main(["grade", str(path), "--out", str(out), "--chapter", "06", "--cell-timeout", "30"]) == 0
    report = json.loads((out / "alice.json").read_text())
    assert (report["score"], report["max_score"]) == (2.0, 2.0)
    assert ElementTree.fromstring((out / "alice.xml").read_text()).find("testsuite").get("failures") == "0"
    assert capsys.readouterr().out == "alice.ipynb  chapter 06  2/2\n"


def test_the_grade_command_exits_0_whatever_the_score(tmp_path, capsys):
    from halfedge_edu import cli

    path = submission(tmp_path, "def my_flip(mesh, e):\n    raise NotImplementedError")
    assert cli.main(["grade", str(path), "--out", str(tmp_path / "reports")]) == 0
    assert "chapter 06  0/2" in capsys.readouterr().out


@pytest.mark.parametrize(("arguments", "said"), [
    (["missing.ipynb", "--out", "{tmp}/r"], "missing.ipynb: no such file"),
    (["{nb}", "--out", "{nb}"], "exists and is not a folder"),
    (["{nb}", "--out", "{tmp}/r", "--chapter", "00"], "chapter '00' has no graded exercises"),
    (["{nb}", "--out", "{tmp}/r", "--timeout", "-1"], "must be a positive number of seconds"),
    (["{nb}"], "--out"),
])
def test_bad_grade_arguments_are_one_line_and_exit_2(tmp_path, capsys, arguments, said):
    from halfedge_edu import cli

    notebook = submission(tmp_path, "x = 1")
    submission(tmp_path, "x = 1", name="alice.ipynb")
    filled = [a.format(tmp=tmp_path, nb=notebook) for a in arguments]
    try:
        status = cli.main(["grade", *filled])
    except SystemExit as usage_error:  # argparse's own errors end the same way, through exit()
        status = usage_error.code
    assert status == 2
    err = capsys.readouterr().err
    assert err.startswith("halfedge-edu: error: ") and said in err and err.count("\n") == 1, err
    assert not (tmp_path / "r").exists()


def test_chapter_01s_obj_exercise_earns_its_point_in_the_solution_edition(tmp_path):
    grade = grade_notebook(_edition(tmp_path, "01_polygon_soup_and_obj.py", "solution"))
    points = {exercise.name: (exercise.score, exercise.output) for exercise in grade.exercises}
    assert points["obj_io"][0] == 1.0 and points["obj_io"][1].startswith("All good!"), points
    assert grade.score == grade.max_score, grade.to_json()


def test_chapter_01s_obj_exercise_earns_nothing_in_the_student_edition_because_it_is_not_implemented(tmp_path):
    grade = grade_notebook(_edition(tmp_path, "01_polygon_soup_and_obj.py", "student"))
    obj_io = next(exercise for exercise in grade.exercises if exercise.name == "obj_io")
    assert obj_io.score == 0.0 and obj_io.output.startswith("Not yet.")
    assert "read_obj is not finished yet (NotImplementedError: write read_obj" in obj_io.output


# --------------------------------------------------------------------------------------
# Other courses' right answers, through the sandbox and the judge
# --------------------------------------------------------------------------------------

def test_right_answers_in_other_conventions_cross_to_the_judge_and_pass(tmp_path):
    """UChicago's build (3f + c, twins None, vertex halfedges a list) and CMU's clockwise
    one-ring of Vertex handles: their answers are lists, None and handles, not the
    package's own types, and must reach the judge as they are."""
    from . import test_checks

    uchicago = textwrap.dedent(inspect.getsource(test_checks.uchicago_build)).replace("uchicago_build", "build", 1)
    cmu = ("def one_ring(mesh, v):\n"
           "    start = v.halfedge\n    ring, h = [], start\n"
           "    while True:\n        ring.append(h.tip)\n        h = h.twin.next\n"
           "        if h == start:\n            return ring")
    build = grade_notebook(submission(tmp_path, uchicago, name="02_building_halfedges.ipynb"))
    ring = grade_notebook(submission(tmp_path, cmu, name="03_navigating.ipynb"))
    assert build.score == 1.0, build.exercises[0].output
    assert ring.score == 1.0 and "clockwise" in ring.exercises[0].output, ring.exercises[0].output
