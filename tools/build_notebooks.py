"""Turn the chapter sources into executed notebooks, so stored outputs come from today's code.

    python tools/build_notebooks.py                 # every chapter
    python tools/build_notebooks.py 03 07           # only chapters 03 and 07
    python tools/build_notebooks.py --check         # fail if a notebook is out of step with its source

Each chapter is written as ``notebooks/src/NN_topic.py`` in the "percent" format that
Jupytext, VS Code and Spyder understand: ``# %%`` starts a code cell, ``# %% [markdown]``
a markdown cell whose lines begin with ``# ``, and ``# %% tags=["raises-exception"]``
gives a cell tags. jupytext reads the source into cells; the script builds ``notebooks/NN_topic.ipynb`` from it and runs it
top to bottom in a fresh kernel, headless, with the same environment the tests use, so
nbval can later compare every text output with a fresh run.

Why sources at all: a ``.py`` diff is readable in review, and "run top to bottom in a
fresh kernel" is then the only way a notebook's outputs can come to exist.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
import tempfile
from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
SOURCES = NOTEBOOKS / "src"

_NEW_CELL = {
    "code": nbformat.v4.new_code_cell,
    "markdown": nbformat.v4.new_markdown_cell,
    "raw": nbformat.v4.new_raw_cell,
}


def cell_id(chapter: str, cell_type: str, source: str, taken: set[str]) -> str:
    """A cell id that depends only on the chapter and the cell's own text.

    nbformat would give every cell a random id on every build, so each rebuild rewrote
    every id and notebook diffs churned. An id made from the chapter and a hash of the
    cell stays put when the cell stays put, also when cells are inserted before it (an
    id from the cell's position would shift for every later cell). Two cells with the
    same text get ``-2``, ``-3`` ... so ids stay unique, as nbformat requires.
    """
    digest = hashlib.sha1(f"{cell_type}\n{source}".encode("utf-8")).hexdigest()[:12]
    base = f"{chapter}-{digest}"
    candidate, copy = base, 1
    while candidate in taken:
        copy += 1
        candidate = f"{base}-{copy}"
    taken.add(candidate)
    return candidate


def parse_source(text: str, chapter: str = "nb") -> list[nbformat.NotebookNode]:
    """Read a percent-format source into notebook cells, through jupytext.

    Only what the source says is kept: cell type, text and tags. jupytext's own
    bookkeeping (``lines_to_next_cell`` and the like) would only serve a round trip back
    to ``.py``, which the sources never make, so it is dropped. ``chapter`` (the two
    digits of the file name) goes into the cell ids, see `cell_id`.
    """
    cells: list[nbformat.NotebookNode] = []
    taken: set[str] = set()
    for read in jupytext.reads(text, fmt="py:percent").cells:
        cell = _NEW_CELL[read.cell_type](read.source, id=cell_id(chapter, read.cell_type, read.source, taken))
        if read.metadata.get("tags"):
            cell.metadata["tags"] = list(read.metadata["tags"])
        cells.append(cell)
    return cells


def headless_environment() -> dict[str, str]:
    """The variables from shared/notes/notebooks-headless.md (same as conftest.py)."""
    empty_wasm_dir = Path(tempfile.gettempdir()) / "halfedge_edu-vtk-wasm-empty"
    empty_wasm_dir.mkdir(exist_ok=True)
    env = {"PYVISTA_JUPYTER_BACKEND": "static", "VTK_WASM_DIR_OVERRIDE": str(empty_wasm_dir)}
    if sys.platform.startswith("linux"):
        env["VTK_DEFAULT_OPENGL_WINDOW"] = "vtkEGLRenderWindow"
    return env


def new_notebook(cells: list[nbformat.NotebookNode]) -> nbformat.NotebookNode:
    notebook = nbformat.v4.new_notebook(cells=cells)
    notebook.metadata = {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"},
    }
    return notebook


def build(source: Path) -> Path:
    """Build and execute one chapter; returns the notebook's path."""
    target = NOTEBOOKS / (source.stem + ".ipynb")
    notebook = new_notebook(parse_source(source.read_text(encoding="utf-8"), source.name[:2]))
    os.environ.update(headless_environment())
    client = NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(NOTEBOOKS)}},
        record_timing=False,
    )
    client.execute()
    for cell in notebook.cells:
        cell.metadata.pop("execution", None)
    nbformat.write(notebook, target)
    return target


def in_step(source: Path) -> str | None:
    """None if the notebook's cells equal the source's, else what differs."""
    target = NOTEBOOKS / (source.stem + ".ipynb")
    if not target.exists():
        return f"{target.name} is missing: run python tools/build_notebooks.py {source.stem[:2]}"
    stored = nbformat.read(target, as_version=4).cells
    wanted = parse_source(source.read_text(encoding="utf-8"), source.name[:2])
    if len(stored) != len(wanted):
        return f"{target.name} has {len(stored)} cells, its source {len(wanted)}"
    for index, (have, want) in enumerate(zip(stored, wanted)):
        if have.cell_type != want.cell_type or have.source != want.source:
            return f"{target.name} cell {index} differs from {source.name}"
        if have.metadata.get("tags", []) != want.metadata.get("tags", []):
            return f"{target.name} cell {index} has other tags than {source.name}"
    return None


def chapter_sources(chapters: list[str]) -> list[Path]:
    sources = sorted(SOURCES.glob("[0-9][0-9]_*.py"))
    if chapters:
        sources = [s for s in sources if s.name[:2] in chapters]
    return sources


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Build and execute the chapter notebooks.")
    parser.add_argument("chapters", nargs="*", help="two-digit chapter numbers (default: all)")
    parser.add_argument("--check", action="store_true", help="only check notebooks match their sources")
    args = parser.parse_args(argv)
    sources = chapter_sources(args.chapters)
    if not sources:
        print("no chapter sources found", file=sys.stderr)
        return 1
    if args.check:
        problems = [p for p in (in_step(s) for s in sources) if p]
        print("\n".join(problems) if problems else f"{len(sources)} notebooks match their sources")
        return 1 if problems else 0
    for source in sources:
        print(f"building {source.stem} ...", flush=True)
        build(source)
    return 0


if __name__ == "__main__":
    sys.exit(main())
