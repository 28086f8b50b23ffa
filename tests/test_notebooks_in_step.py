"""Every chapter notebook matches its source and was executed top to bottom.

nbval (run on notebooks/ by the same pytest command) then checks that today's code
prints what the stored outputs say. These tests catch the two ways that check could
be empty: a notebook edited by hand away from its source, or one stored unexecuted.
"""

from __future__ import annotations

import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from build_notebooks import chapter_sources, in_step, new_notebook, parse_source  # noqa: E402

SOURCES = chapter_sources([])


def test_there_are_chapters():
    assert len(SOURCES) >= 1


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_notebook_matches_its_source(source: Path):
    assert in_step(source) is None


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_notebook_was_run_top_to_bottom(source: Path):
    notebook = nbformat.read(ROOT / "notebooks" / (source.stem + ".ipynb"), as_version=4)
    code = [cell for cell in notebook.cells if cell.cell_type == "code" and cell.source.strip()]
    counts = [cell.execution_count for cell in code]
    assert None not in counts, "some code cells were never executed"
    assert counts == list(range(1, len(code) + 1)), "cells were not run once each, in order, in a fresh kernel"


@pytest.mark.parametrize("source", SOURCES, ids=[s.stem for s in SOURCES])
def test_cell_ids_are_the_same_on_every_build_and_valid(source: Path):
    text = source.read_text(encoding="utf-8")
    first = parse_source(text, source.name[:2])
    again = parse_source(text, source.name[:2])
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
