"""docs/coming_from_your_course.md lists every graded exercise as the registered checks say."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from halfedge_edu.exercises import check_cut
from halfedge_edu.exercises.course_map import ACCEPTS, BEGIN, END, exercises_table
from halfedge_edu.exercises.grading import EXERCISES

PAGE = Path(__file__).resolve().parents[2] / "docs" / "coming_from_your_course.md"


def test_the_pages_table_is_the_generated_one():
    text = PAGE.read_text()
    assert BEGIN in text and END in text
    table = text.split(BEGIN, 1)[1].split(END, 1)[0].strip()
    assert table == exercises_table(), "run: python -m halfedge_edu.exercises.course_map --write"


def test_every_registered_check_says_what_it_accepts_and_nothing_else_is_listed():
    assert {exercise.check for exercise in EXERCISES} == set(ACCEPTS)


def test_every_registered_exercise_has_a_row():
    table = exercises_table()
    for exercise in EXERCISES:
        assert f"| {exercise.chapter} | {exercise.name} |" in table


def test_the_copy_on_the_first_fan_is_accepted_as_the_table_says():
    result = check_cut(lambda vertices, faces: (np.vstack([vertices, vertices[0]]), [[5, 1, 2], [0, 3, 4]]))
    assert result.passed, result.message


def test_the_instructors_page_table_is_every_registered_exercise_in_chapter_order():
    # The table under "The graded exercises" is EXERCISES in chapter order, row for row:
    # no row missing and none left over from an exercise that is gone or renamed.
    text = (PAGE.parent / "instructors.md").read_text()
    table = text.split("The graded exercises", 1)[1].split("\n\n", 2)[1]
    rows = table.splitlines()[2:]                            # past the header and the |---| line
    wanted = []
    for exercise in sorted(EXERCISES, key=lambda exercise: exercise.chapter):
        functions = ", ".join(f"`{name}`" for name in exercise.functions)
        wanted.append(f"| {exercise.chapter} | {exercise.name} | {functions} | `{exercise.check}` |")
    assert rows == wanted
