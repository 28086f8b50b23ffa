"""The grader: points per exercise with reasons, and never a crash on a bad submission.

Submissions here are small notebooks made on the spot (a real chapter would take
longer to run); the right answer is taken from chapter 06's own answer cell, so these
tests follow the chapter.
"""

from __future__ import annotations

import ast
import json
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import nbformat
import pytest

from halfedge_edu.exercises.grading import EXERCISES, GradingError, chapter_of, exercises_for, grade_notebook

ROOT = Path(__file__).resolve().parents[2]


def _answer(chapter_source: str, name: str, rename_to: str) -> str:
    """The source of function ``name`` in a chapter source, renamed to ``rename_to``."""
    text = (ROOT / "notebooks" / "src" / chapter_source).read_text()
    for node in ast.parse(text).body:
        if isinstance(node, ast.FunctionDef) and node.name == name:
            node.name = rename_to
            return ast.unparse(node)
    raise AssertionError(f"{chapter_source} has no function {name}")


RIGHT_FLIP = _answer("06_flip_and_split.py", "flip_answer", "my_flip")


def submission(tmp_path: Path, *cells: str, name: str = "06_flip_and_split.ipynb") -> Path:
    notebook = nbformat.v4.new_notebook()
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    notebook.cells = [nbformat.v4.new_code_cell(cell) for cell in cells]
    path = tmp_path / name
    nbformat.write(notebook, path)
    return path


def test_a_right_answer_earns_full_points(tmp_path):
    grade = grade_notebook(submission(tmp_path, RIGHT_FLIP))
    assert (grade.score, grade.max_score) == (1.0, 1.0)
    assert grade.exercises[0].output.startswith("All good!")
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
    assert report["score"] == 1.0
    assert [(t["name"], t["score"], t["max_score"], t["status"]) for t in report["tests"]] == \
        [("06 flip", 1.0, 1.0, "passed")]


def test_junit_report_has_one_testcase_per_exercise_and_a_failure_for_lost_points(tmp_path):
    stub = "def my_flip(mesh, e):\n    raise NotImplementedError"
    grade = grade_notebook(submission(tmp_path, stub))
    suite = ElementTree.fromstring(grade.to_junit_xml()).find("testsuite")
    assert suite.get("tests") == "1" and suite.get("failures") == "1"
    failure = suite.find("testcase").find("failure")
    assert "NotImplementedError" in failure.text


def test_the_chapter_comes_from_metadata_before_the_file_name():
    notebook = {"metadata": {"halfedge_edu": {"chapter": "07"}}}
    assert chapter_of(notebook, Path("06_flip_and_split.ipynb")) == "07"
    assert chapter_of({"metadata": {}}, Path("06_flip_and_split.ipynb")) == "06"
    assert chapter_of({"metadata": {}}, Path("alice.ipynb")) is None


def test_a_chapter_without_exercises_is_refused_by_name():
    with pytest.raises(GradingError, match="chapter '00' has no graded exercises"):
        exercises_for("00")


def test_every_exercise_names_a_check_the_package_has():
    from halfedge_edu import exercises

    for exercise in EXERCISES:
        assert callable(getattr(exercises, exercise.check)), exercise
