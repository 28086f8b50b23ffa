"""Run a learner's notebook top to bottom inside its sandbox, then let the judge call its functions.

    python -m halfedge_edu.exercises.runner NOTEBOOK.ipynb --socket PATH --functions my_flip ...

The grader starts this inside the submission's :class:`~halfedge_edu.exercises.sandbox.Sandbox`.
It executes the notebook in a fresh kernel (``nbclient``) with a time limit per cell and
one for the whole run; a cell that raises does not stop the run (a later cell may still
define an exercise's function). It then appends one cell that calls
:func:`halfedge_edu.exercises.serve.serve`, so the judge can call the learner's functions.

Everything it prints is the learner's side of the story (which cell raised what, whether
the kernel died and in which cell); the grader shows it to the learner as the reason for
a lost point but never takes a score from it. Its one line of output starts with
``REPORT_PREFIX``. Printed cell output beyond ``--max-output`` bytes is dropped, so a
notebook that prints a gigabyte cannot make the run hold it.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import re
import subprocess
import sys
import time

REPORT_PREFIX = "@@halfedge_edu-runner@@"

# The cell appended to the learner's notebook; it runs in their kernel after their cells.
SERVING_CELL = """\
from halfedge_edu.exercises.serve import serve as __halfedge_edu_serve
__halfedge_edu_serve(globals(), {address!r}, {forbids!r})
"""


def _first_line(source: str) -> str:
    for line in source.splitlines():
        if line.strip():
            return line.strip()[:60]
    return ""


def cell_errors(cells: list) -> list[dict]:
    """Each learner cell that raised: its number (1-based, as a reader counts), first line and error."""
    found = []
    for number, cell in enumerate(cells, start=1):
        if cell.get("cell_type") != "code":
            continue
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                found.append({"cell": number, "first_line": _first_line(cell.get("source", "")),
                              "error": f"{output.get('ename')}: {output.get('evalue')}"[:500],
                              "traceback": _plain("\n".join(output.get("traceback", [])))[-3000:]})
                break
    return found


def _plain(text: str) -> str:
    """A traceback without the terminal's colour codes."""
    return re.sub(r"\x1b\[[0-9;]*[A-Za-z]", "", text)


def defining_cells(cells: list, names: list[str]) -> dict[str, int]:
    """For each function name, the (1-based) number of the last cell whose source defines it."""
    found: dict[str, int] = {}
    for number, cell in enumerate(cells, start=1):
        if cell.get("cell_type") != "code":
            continue
        for name in names:
            if re.search(rf"^\s*(async\s+)?def\s+{re.escape(name)}\b|^\s*{re.escape(name)}\s*=",
                         cell.get("source", ""), re.M):
                found[name] = number
    return found


def run(path: str, address: str, functions: list[str], forbids: dict, cell_timeout: float, total_timeout: float,
        kernel_name: str, max_output: int) -> dict:
    """Execute the notebook and serve the judge; the learner's side of the story as plain data."""
    # nbformat imports jsonschema, whose optional IRI checker (rfc3987_syntax) compiles a
    # grammar for 2-3 s at import. Notebooks never use that format; this process is new for
    # every submission, so skipping it is most of the difference to grading in one process.
    sys.modules.setdefault("rfc3987_syntax", None)
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import DeadKernelError

    report: dict = {"problem": None, "cell_errors": [], "defines": {}, "dead_cell": None}
    try:
        notebook = nbformat.read(path, as_version=4)
        learner_cells = list(notebook.cells)
    except Exception as error:  # any unreadable file is the submission's problem
        report["problem"] = f"the submission is not a readable notebook: {type(error).__name__}: {error}"[:500]
        return report
    report["defines"] = defining_cells(learner_cells, functions)
    notebook.cells.append(nbformat.v4.new_code_cell(SERVING_CELL.format(address=address, forbids=forbids)))
    serving_index = len(notebook.cells) - 1
    started = time.monotonic()
    current = {"cell": None}

    class BoundedClient(NotebookClient):
        """nbclient's client, keeping at most ``max_output`` bytes of what the cells print."""

        kept = 0

        def output(self, outs, msg, display_id, cell_index):
            size = len(json.dumps(msg.get("content", {}), default=str))
            BoundedClient.kept += size
            if BoundedClient.kept > max_output and msg.get("msg_type") != "error":
                return None
            return super().output(outs, msg, display_id, cell_index)

    def timeout_of(cell) -> int:
        if cell is notebook.cells[serving_index]:
            return max(1, int(total_timeout - (time.monotonic() - started)))
        return int(cell_timeout)

    def on_cell_start(cell, cell_index, **_):
        current["cell"] = cell_index

    client = BoundedClient(
        notebook, timeout_func=timeout_of, interrupt_on_timeout=True, allow_errors=True,
        kernel_name=kernel_name, resources={"metadata": {"path": "."}}, on_cell_start=on_cell_start,
        shutdown_kernel="immediate",
    )

    async def execute() -> bool:
        task = asyncio.ensure_future(client.async_execute(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        done, _ = await asyncio.wait({task}, timeout=total_timeout)
        if not done:
            task.cancel()
            try:
                await task
            except BaseException:  # the cancelled run's own clean-up errors do not matter
                pass
            return False
        task.result()
        return True

    try:
        if not asyncio.run(execute()):
            report["problem"] = f"the notebook did not finish within {total_timeout:g} s and was stopped"
    except DeadKernelError:
        cell = current["cell"]
        report["dead_cell"] = None if cell is None or cell >= serving_index else cell + 1
        report["problem"] = "the kernel died"
    except Exception as error:  # nbclient's own failures: report, the grade goes on
        report["problem"] = f"the notebook could not be run: {type(error).__name__}: {error}"[:500]
    report["cell_errors"] = cell_errors(notebook.cells[:serving_index])[:50]
    return report


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m halfedge_edu.exercises.runner")
    parser.add_argument("notebook")
    parser.add_argument("--socket", required=True)
    parser.add_argument("--functions", default="")
    parser.add_argument("--forbids", default="{}", help="JSON: exercise -> forbidden entries")
    parser.add_argument("--cell-timeout", type=float, default=60)
    parser.add_argument("--total-timeout", type=float, default=600)
    parser.add_argument("--kernel", default="python3")
    parser.add_argument("--max-output", type=int, default=8 * 1024 * 1024)
    args = parser.parse_args(argv)
    report = run(args.notebook, args.socket, [f for f in args.functions.split(",") if f], json.loads(args.forbids),
                 args.cell_timeout, args.total_timeout, args.kernel, args.max_output)
    sys.stdout.write(REPORT_PREFIX + json.dumps(report) + "\n")
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
