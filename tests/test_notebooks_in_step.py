"""Every chapter notebook, in both editions, matches its source and was executed top to bottom.

nbval (run on notebooks/ and notebooks/student/ by the same pytest command) then checks
that today's code prints what the stored outputs say. These tests catch the two ways
that check could be empty: a notebook edited by hand away from its source, or one stored
unexecuted. The solution edition is ``notebooks/NN_*.ipynb``, the student edition
``notebooks/student/NN_*.ipynb`` (see tools/build_notebooks.py).
"""

from __future__ import annotations

import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from build_notebooks import (  # noqa: E402
    EDITIONS, chapter_id, chapter_sources, in_step, merged_streams, new_notebook, parse_source, student_stub,
    target_of,
)

SOURCES = chapter_sources([])
EACH_EDITION = [(source, edition) for source in SOURCES for edition in EDITIONS]
EACH_EDITION_IDS = [f"{source.stem}-{edition}" for source, edition in EACH_EDITION]


def test_there_are_chapters():
    assert len(SOURCES) >= 1


@pytest.mark.parametrize(("source", "edition"), EACH_EDITION, ids=EACH_EDITION_IDS)
def test_notebook_matches_its_source(source: Path, edition: str):
    assert in_step(source, edition) is None


@pytest.mark.parametrize(("source", "edition"), EACH_EDITION, ids=EACH_EDITION_IDS)
def test_notebook_was_run_top_to_bottom(source: Path, edition: str):
    notebook = nbformat.read(target_of(source, edition), as_version=4)
    code = [cell for cell in notebook.cells if cell.cell_type == "code" and cell.source.strip()]
    counts = [cell.execution_count for cell in code]
    assert None not in counts, "some code cells were never executed"
    assert counts == list(range(1, len(code) + 1)), "cells were not run once each, in order, in a fresh kernel"


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_cell_ids_are_the_same_on_every_build_and_valid(source: Path):
    text = source.read_text(encoding="utf-8")
    first = parse_source(text, chapter_id(source))
    again = parse_source(text, chapter_id(source))
    assert [cell.id for cell in first] == [cell.id for cell in again]
    assert len({cell.id for cell in first}) == len(first)
    nbformat.validate(new_notebook(first))


def test_a_cell_inserted_in_front_leaves_the_later_ids_alone():
    text = "# %%\nx = 1\n\n# %% [markdown]\n# Some words\n\n# %%\nx = 1\n"
    before = parse_source(text, "99")
    after = parse_source("# %%\nnew = 0\n\n" + text, "99")
    assert [cell.id for cell in after[1:]] == [cell.id for cell in before]
    assert before[0].id != before[2].id, "two cells with the same text share an id"


def test_the_parser_keeps_tags_and_nothing_else_in_cell_metadata():
    cells = parse_source('# %% tags=["raises-exception"]\n1 / 0\n\n# %%\nx = 1\n', "99")
    assert [dict(cell.metadata) for cell in cells] == [{"tags": ["raises-exception"]}, {}]


SOURCE_WITH_AN_EXERCISE = """\
# %%
def my_flip(mesh, e):
    h0 = 2 * e  # done for you
    # 1. turn the edge
    ### BEGIN SOLUTION
    mesh.halfedge_vertex[h0] = 3
    mesh.topology_changed()
    ### END SOLUTION
    return mesh

# %% [markdown] tags=["solution"]
# ## Answer
# Step 1 turns the edge.
"""


def test_the_student_edition_replaces_the_answer_and_keeps_the_hints():
    (cell,) = parse_source(SOURCE_WITH_AN_EXERCISE, "99", "student")
    assert cell.source.splitlines() == [
        "def my_flip(mesh, e):",
        "    h0 = 2 * e  # done for you",
        "    # 1. turn the edge",
        "    # YOUR CODE HERE",
        '    raise NotImplementedError("write my_flip: replace this line with your code")',
        "    return mesh",
    ]


def test_a_region_of_single_assignments_becomes_blanks_with_their_hints():
    source = (
        "def build(faces):\n"
        "    if new:\n"
        "        ### BEGIN SOLUTION\n"
        "        h = 2 * e        # 1. which halfedge?\n"
        "        next_[made[n]] = made[(n + 1) % 3]\n"
        "        ### END SOLUTION\n"
        "    return h"
    )
    assert student_stub(source).splitlines() == [
        "def build(faces):",
        "    if new:",
        "        h = ...          # 1. which halfedge?",
        "        next_[made[n]] = ...",
        "    return h",
    ]


def test_the_solution_edition_keeps_the_answer_and_the_solution_cells():
    code, answer = parse_source(SOURCE_WITH_AN_EXERCISE, "99", "solution")
    assert "mesh.halfedge_vertex[h0] = 3" in code.source and "### BEGIN SOLUTION" in code.source
    assert answer.metadata["tags"] == ["solution"]


@pytest.mark.parametrize("broken", [
    "### BEGIN SOLUTION\nx = 1",
    "x = 1\n### END SOLUTION",
    "### BEGIN SOLUTION\n### BEGIN SOLUTION\n### END SOLUTION",
])
def test_a_broken_solution_region_is_refused_by_place(broken):
    with pytest.raises(ValueError, match="chapter 99, cell 0"):
        student_stub(broken, "chapter 99, cell 0")


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_the_student_edition_has_no_answer_left(source: Path):
    cells = parse_source(source.read_text(encoding="utf-8"), chapter_id(source), "student")
    assert not [cell for cell in cells if "solution" in cell.metadata.get("tags", [])]
    assert not [cell for cell in cells if "BEGIN SOLUTION" in cell.source or "END SOLUTION" in cell.source]


def test_notebooks_are_stamped_with_chapter_and_edition():
    notebook = new_notebook([], "06", "student")
    assert notebook.metadata["halfedge_edu"] == {"chapter": "06", "edition": "student"}


def test_runs_of_one_stream_are_joined_and_nothing_else_is():
    out = nbformat.v4.new_output
    outputs = [out("stream", name="stdout", text="a\n"), out("stream", name="stdout", text="b\n"),
               out("stream", name="stderr", text="warned\n"), out("stream", name="stdout", text="c\n"),
               out("execute_result", data={"text/plain": "1"}, execution_count=1),
               out("stream", name="stdout", text="d\n"), out("stream", name="stdout", text="e")]
    merged = merged_streams(outputs)
    assert [(o.output_type, o.get("name"), o.get("text")) for o in merged] == [
        ("stream", "stdout", "a\nb\n"), ("stream", "stderr", "warned\n"), ("stream", "stdout", "c\n"),
        ("execute_result", None, None), ("stream", "stdout", "d\ne"),
    ]
