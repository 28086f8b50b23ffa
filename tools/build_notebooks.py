"""Turn the chapter sources into executed notebooks, so stored outputs come from today's code.

    python tools/build_notebooks.py                 # every chapter
    python tools/build_notebooks.py 03 07           # only chapters 03 and 07
    python tools/build_notebooks.py --check         # fail if a notebook is out of step with its source

Each chapter is written as ``notebooks/src/NN_topic.py`` in the "percent" format that
Jupytext, VS Code and Spyder understand: ``# %%`` starts a code cell, ``# %% [markdown]``
a markdown cell whose lines begin with ``# ``, and ``# %% tags=["raises-exception"]``
gives a cell tags. The script builds ``notebooks/NN_topic.ipynb`` from it and runs it
top to bottom in a fresh kernel, headless, with the same environment the tests use, so
nbval can later compare every text output with a fresh run.

Why sources at all: a ``.py`` diff is readable in review, and "run top to bottom in a
fresh kernel" is then the only way a notebook's outputs can come to exist.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import tempfile
from pathlib import Path

import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
SOURCES = NOTEBOOKS / "src"

_CELL_START = re.compile(r"^# %%(?P<markdown> \[markdown\])?(?: tags=(?P<tags>\[.*\]))?\s*$")


def parse_source(text: str) -> list[nbformat.NotebookNode]:
    """Split a percent-format source into notebook cells (markdown and code)."""
    cells: list[nbformat.NotebookNode] = []
    kind, tags, lines = None, [], []

    def finish() -> None:
        if kind is None:
            return
        body = "\n".join(lines).strip("\n")
        if kind == "markdown":
            body = "\n".join(line[2:] if line.startswith("# ") else line.lstrip("#") for line in body.split("\n"))
            cell = nbformat.v4.new_markdown_cell(body)
        else:
            cell = nbformat.v4.new_code_cell(body)
        if tags:
            cell.metadata["tags"] = tags
        cells.append(cell)

    for line in text.split("\n"):
        match = _CELL_START.match(line)
        if match:
            finish()
            kind = "markdown" if match.group("markdown") else "code"
            tags = json.loads(match.group("tags")) if match.group("tags") else []
            lines = []
        elif kind is not None:
            lines.append(line)
    finish()
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
    notebook = new_notebook(parse_source(source.read_text(encoding="utf-8")))
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
    wanted = parse_source(source.read_text(encoding="utf-8"))
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
