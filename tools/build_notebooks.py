"""Turn the chapter sources into executed notebooks, so stored outputs come from today's code.

    python tools/build_notebooks.py                 # every chapter, both editions
    python tools/build_notebooks.py 03 07           # only chapters 03 and 07
    python tools/build_notebooks.py 06 --edition student    # one edition only
    python tools/build_notebooks.py --check         # fail if a notebook is out of step with its source

Each chapter is written as ``notebooks/src/NN_topic.py`` in the "percent" format that
Jupytext, VS Code and Spyder understand: ``# %%`` starts a code cell, ``# %% [markdown]``
a markdown cell whose lines begin with ``# ``, and ``# %% tags=["raises-exception"]``
gives a cell tags. jupytext reads the source into cells; the script builds ``notebooks/NN_topic.ipynb`` from it and runs it
top to bottom in a fresh kernel, headless, with the same environment the tests use, so
nbval can later compare every text output with a fresh run.

Why sources at all: a ``.py`` diff is readable in review, and "run top to bottom in a
fresh kernel" is then the only way a notebook's outputs can come to exist.

Two editions from one source:

- the **solution edition**, ``notebooks/NN_topic.ipynb``: the source as written, each
  exercise answered in its own cell (so grading it gives full points);
- the **student edition**, ``notebooks/student/NN_topic.ipynb``: what a class gets
  (``halfedge-edu course`` hands it out). In every code cell, each region between the
  lines ``### BEGIN SOLUTION`` and ``### END SOLUTION`` becomes
  ``# YOUR CODE HERE`` and ``raise NotImplementedError("write NAME ...")`` at the
  marker's indentation (``NAME`` is the function the region sits in); a region made
  only of one-line assignments and returns becomes blanks instead, ``h = ...  # hint`` (chapter 02's
  fill-in-the-blanks). Hints, comments and "done for you" lines outside the markers
  stay. Cells tagged ``solution`` (the answers' explanations) are left out.

The markers are nbgrader's: ``nbgrader generate_assignment`` replaces exactly these lines
(the stripped line must equal ``### BEGIN SOLUTION``) with the same kind of stub, so an
instructor can also run the solution edition through nbgrader. otter-grader's
``otter assign`` looks for ``# BEGIN SOLUTION`` with a single ``#`` and does not see
the three-hash form; for otter, replace ``### `` by ``# `` on those lines first.

Both editions are executed and checked by nbval: a stub only defines a function that
raises when called, and the chapter's check cells call the learner's function through a
``check_*`` helper, which reports "not finished yet" in words instead of raising. Each
notebook's metadata says what it is: ``halfedge_edu.chapter`` ("06") and
``halfedge_edu.edition`` ("solution" or "student"); the grader reads the chapter there.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import re
import sys
import tempfile
from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
SOURCES = NOTEBOOKS / "src"

#: Where each edition's notebooks are written.
EDITION_FOLDERS = {"solution": NOTEBOOKS, "student": NOTEBOOKS / "student"}
EDITIONS = tuple(EDITION_FOLDERS)

BEGIN_SOLUTION = "### BEGIN SOLUTION"
END_SOLUTION = "### END SOLUTION"
#: Cells with this tag exist only for the solution edition (answers and their explanations).
SOLUTION_TAG = "solution"

_FUNCTION_LINE = re.compile(r"^(\s*)def (\w+)\(")
# One assignment or return, ``target = value  # comment``: a blank in the student edition.
_ASSIGNMENT = re.compile(r"^(?P<indent>\s*)(?P<target>return|[\w.\[\]]+ =) (?P<value>[^=#][^#]*?)(?P<comment>\s+#.*)?$")

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


def _blanks(region: list[str]) -> list[str] | None:
    """A region of single assignments and returns as blanks (``h = ...  # hint``, ``return ...``),
    or None if it holds anything else."""
    blanks = []
    for line in region:
        assignment = _ASSIGNMENT.match(line)
        if assignment is None:
            return None
        blank = f"{assignment['indent']}{assignment['target']} ..."
        if assignment["comment"]:
            column = len(line) - len(assignment["comment"].lstrip())
            blank = blank.ljust(max(column, len(blank) + 2)) + assignment["comment"].lstrip()
        blanks.append(blank)
    return blanks


def _stub(region: list[str], indent: str, function: str | None) -> list[str]:
    """What the student edition shows instead of a solution region (see the module docstring)."""
    blanks = _blanks(region)
    if blanks:
        return blanks
    task = f"write {function}" if function else "your code here"
    return [f"{indent}# YOUR CODE HERE", f'{indent}raise NotImplementedError("{task}: replace this line with your code")']


def student_stub(source: str, where: str = "cell") -> str:
    """``source`` (one code cell) with each solution region replaced by a stub.

    A region of single assignments (or returns) becomes blanks, ``h = ...`` with the line's hint
    comment kept (otter-grader's ``# SOLUTION`` lines become ``...`` the same way).
    Any other region becomes nbgrader's stub at the ``### BEGIN SOLUTION`` line's
    indentation, naming the function the region sits in so the learner's error says
    what to write: ``raise NotImplementedError("write my_flip: replace this line with
    your code")``. Raises ``ValueError`` naming ``where`` for an unclosed or nested region.
    """
    kept: list[str] = []
    region: list[str] | None = None
    function = indent = None
    for number, line in enumerate(source.split("\n"), start=1):
        stripped = line.strip()
        defined = _FUNCTION_LINE.match(line)
        if defined and region is None:
            function = defined.group(2)
        if stripped == BEGIN_SOLUTION:
            if region is not None:
                raise ValueError(f"{where}, line {number}: {BEGIN_SOLUTION} inside another solution region")
            region, indent = [], line[: len(line) - len(line.lstrip())]
        elif stripped == END_SOLUTION:
            if region is None:
                raise ValueError(f"{where}, line {number}: {END_SOLUTION} without {BEGIN_SOLUTION}")
            kept += _stub(region, indent, function)
            region = None
        elif region is not None:
            region.append(line)
        else:
            kept.append(line)
    if region is not None:
        raise ValueError(f"{where}: {BEGIN_SOLUTION} without {END_SOLUTION}")
    return "\n".join(kept)


def has_solution_region(source: str) -> bool:
    return any(line.strip() == BEGIN_SOLUTION for line in source.split("\n"))


def parse_source(text: str, chapter: str = "nb", edition: str = "solution") -> list[nbformat.NotebookNode]:
    """Read a percent-format source into the cells of one edition, through jupytext.

    Only what the source says is kept: cell type, text and tags. jupytext's own
    bookkeeping (``lines_to_next_cell`` and the like) would only serve a round trip back
    to ``.py``, which the sources never make, so it is dropped. ``chapter`` (the two
    digits of the file name) goes into the cell ids, see `cell_id`. For
    ``edition="student"``, solution-tagged cells are left out and solution regions
    become stubs (see the module docstring); the solution edition keeps the markers.
    """
    if edition not in EDITIONS:
        raise ValueError(f"unknown edition {edition!r}; editions: {', '.join(EDITIONS)}")
    cells: list[nbformat.NotebookNode] = []
    taken: set[str] = set()
    for number, read in enumerate(jupytext.reads(text, fmt="py:percent").cells):
        tags = list(read.metadata.get("tags", []))
        source = read.source
        if edition == "student":
            if SOLUTION_TAG in tags:
                continue
            if read.cell_type == "code" and has_solution_region(source):
                source = student_stub(source, f"chapter {chapter}, cell {number}")
        cell = _NEW_CELL[read.cell_type](source, id=cell_id(chapter, read.cell_type, source, taken))
        if tags:
            cell.metadata["tags"] = tags
        cells.append(cell)
    return cells


def headless_environment() -> dict[str, str]:
    """The variables of docs/headless.md (the same as conftest.py sets)."""
    empty_wasm_dir = Path(tempfile.gettempdir()) / "halfedge_edu-vtk-wasm-empty"
    empty_wasm_dir.mkdir(exist_ok=True)
    env = {"PYVISTA_JUPYTER_BACKEND": "static", "VTK_WASM_DIR_OVERRIDE": str(empty_wasm_dir)}
    if sys.platform.startswith("linux"):
        env["VTK_DEFAULT_OPENGL_WINDOW"] = "vtkEGLRenderWindow"
    return env


def new_notebook(cells: list[nbformat.NotebookNode], chapter: str | None = None,
                 edition: str = "solution") -> nbformat.NotebookNode:
    """A notebook of ``cells``; with ``chapter``, stamped ``halfedge_edu.chapter``/``.edition``."""
    notebook = nbformat.v4.new_notebook(cells=cells)
    notebook.metadata = {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"},
    }
    if chapter is not None:
        notebook.metadata["halfedge_edu"] = {"chapter": chapter, "edition": edition}
    return notebook


def merged_streams(outputs: list) -> list:
    """``outputs`` with each run of stream outputs of one name (stdout, stderr) joined
    into one.

    How a cell's printing is cut into stream messages depends on when the kernel
    flushes, so the same cell run twice can store one output or three; joined, a
    rebuilt chapter differs from the stored one only where its text does (nbval joins
    them the same way before comparing).
    """
    merged: list = []
    for output in outputs:
        if (output.get("output_type") == "stream" and merged and merged[-1].get("output_type") == "stream"
                and merged[-1].get("name") == output.get("name")):
            merged[-1]["text"] = "".join(merged[-1]["text"]) + "".join(output["text"])
        else:
            merged.append(output)
    return merged


def target_of(source: Path, edition: str) -> Path:
    """Where ``source``'s notebook of ``edition`` is written."""
    return EDITION_FOLDERS[edition] / (source.stem + ".ipynb")


def build(source: Path, edition: str = "solution") -> Path:
    """Build and execute one chapter in one edition; returns the notebook's path."""
    target = target_of(source, edition)
    target.parent.mkdir(exist_ok=True)
    chapter = chapter_id(source)
    notebook = new_notebook(parse_source(source.read_text(encoding="utf-8"), chapter, edition), chapter, edition)
    os.environ.update(headless_environment())
    client = NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(target.parent)}},
        record_timing=False,
    )
    client.execute()
    for cell in notebook.cells:
        cell.metadata.pop("execution", None)
        if cell.cell_type == "code":
            cell.outputs = merged_streams(cell.outputs)
    nbformat.write(notebook, target)
    return target


def in_step(source: Path, edition: str = "solution") -> str | None:
    """None if the ``edition`` notebook's cells and stamp equal the source's, else what differs."""
    target = target_of(source, edition)
    name = target.relative_to(NOTEBOOKS).as_posix()
    if not target.exists():
        return f"{name} is missing: run python tools/build_notebooks.py {chapter_id(source)}"
    notebook = nbformat.read(target, as_version=4)
    stored = notebook.cells
    wanted = parse_source(source.read_text(encoding="utf-8"), chapter_id(source), edition)
    if len(stored) != len(wanted):
        return f"{name} has {len(stored)} cells, its source {len(wanted)}"
    for index, (have, want) in enumerate(zip(stored, wanted)):
        if have.cell_type != want.cell_type or have.source != want.source:
            return f"{name} cell {index} differs from {source.name}"
        if have.metadata.get("tags", []) != want.metadata.get("tags", []):
            return f"{name} cell {index} has other tags than {source.name}"
    stamp = notebook.metadata.get("halfedge_edu", {})
    if stamp != {"chapter": chapter_id(source), "edition": edition}:
        return f"{name} is stamped {stamp!r}, not chapter {chapter_id(source)}, edition {edition}"
    return None


def chapter_id(source: Path) -> str:
    """The chapter's number as its file name starts: "06" for 06_flip_and_split.py, "08b" for 08b_...."""
    return source.name.split("_", 1)[0]


def chapter_sources(chapters: list[str]) -> list[Path]:
    sources = sorted(SOURCES.glob("[0-9][0-9]*_*.py"))
    if chapters:
        sources = [s for s in sources if chapter_id(s) in chapters]
    return sources


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Build and execute the chapter notebooks.")
    parser.add_argument("chapters", nargs="*", help="chapter numbers as the file names start: 03 08b (default: all)")
    parser.add_argument("--check", action="store_true", help="only check notebooks match their sources")
    parser.add_argument("--edition", choices=EDITIONS, action="append",
                        help="build or check only this edition (default: both)")
    args = parser.parse_args(argv)
    sources = chapter_sources(args.chapters)
    editions = args.edition or list(EDITIONS)
    if not sources:
        print("no chapter sources found", file=sys.stderr)
        return 1
    if args.check:
        problems = [p for p in (in_step(s, e) for s in sources for e in editions) if p]
        count = len(sources) * len(editions)
        print("\n".join(problems) if problems else f"{count} notebooks match their sources")
        return 1 if problems else 0
    for source in sources:
        for edition in editions:
            print(f"building {source.stem} ({edition} edition) ...", flush=True)
            build(source, edition)
    return 0


if __name__ == "__main__":
    sys.exit(main())
