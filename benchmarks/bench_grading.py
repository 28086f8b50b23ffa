"""What containment costs: grading N submissions of chapter 06, sandboxed, against the grader before it.

    python benchmarks/bench_grading.py                      # 30 submissions, 2 rounds, against 8de50bc
    python benchmarks/bench_grading.py --submissions 10 --rounds 1 --before 8de50bc

The grader before containment (``--before``, a commit of this repository) ran every
notebook in one process, with the checks inside the learner's kernel. Today's runs
each one in a sandbox (bubblewrap where it works) and checks it from a separate judge
process. Both grade the same N small submissions (chapter 06's answer, a markdown cell
and two small cells), one ``halfedge-edu grade`` command each, interleaved round by
round; the table gives each round's wall time, the medians and their ratio. The goal of
issue 24: at most 1.5x.

``--before`` is checked out with ``git worktree`` into a temporary folder and run
through ``PYTHONPATH`` with this environment's packages.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]


def right_answer(name: str) -> str:
    """Chapter 06's solution of exercise function ``name`` (``my_flip``, ``my_split``)."""
    text = (ROOT / "notebooks" / "src" / "06_flip_and_split.py").read_text()
    for node in ast.parse(text).body:
        if isinstance(node, ast.FunctionDef) and node.name == name:
            return ast.unparse(node)
    raise SystemExit(f"chapter 06 has no {name}")


def submissions(folder: Path, count: int) -> list[Path]:
    paths = []
    for number in range(count):
        book = nbformat.v4.new_notebook()
        book.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
        book.cells = [nbformat.v4.new_markdown_cell("# Flip"), nbformat.v4.new_code_cell("import halfedge_edu as hx"),
                      nbformat.v4.new_code_cell(right_answer("my_flip")), nbformat.v4.new_code_cell(right_answer("my_split")),
                      nbformat.v4.new_code_cell("mesh = hx.sample('cube')")]
        path = folder / f"06_student{number:03d}.ipynb"
        nbformat.write(book, path)
        paths.append(path)
    return paths


def grade(paths: list[Path], out: Path, pythonpath: str | None) -> float:
    env = dict(os.environ)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    started = time.monotonic()
    result = subprocess.run([sys.executable, "-m", "halfedge_edu", "grade", *map(str, paths), "--out", str(out)],
                            env=env, capture_output=True, text=True)
    seconds = time.monotonic() - started
    # Full marks: "n/n" (2/2 today, where chapter 06 grades flip and split; 1/1 before split was graded).
    full = sum(bool(re.search(r"\s(\d+)/\1$", line.rstrip())) for line in result.stdout.splitlines())
    if result.returncode != 0 or full != len(paths):
        raise SystemExit(f"grading failed ({pythonpath or 'today'}): exit {result.returncode}, {full} full marks\n"
                         f"{result.stdout[-2000:]}{result.stderr[-2000:]}")
    return seconds


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--submissions", type=int, default=30)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--before", default="8de50bc", help="the commit of the grader before containment")
    parser.add_argument("--quick", action="store_true", help="5 submissions, 1 round")
    args = parser.parse_args()
    if args.quick:
        args.submissions, args.rounds = 5, 1
    with tempfile.TemporaryDirectory(prefix="bench-grading-") as scratch:
        scratch = Path(scratch)
        before = scratch / "before"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(before), args.before],
                       check=True, capture_output=True)
        try:
            paths = submissions(scratch, args.submissions)
            load = os.getloadavg()[0]
            times: dict[str, list[float]] = {"before": [], "today": []}
            for round_number in range(args.rounds):
                for name, pythonpath in (("before", str(before)), ("today", None)):
                    seconds = grade(paths, scratch / f"out-{name}-{round_number}", pythonpath)
                    times[name].append(seconds)
                    print(f"round {round_number + 1}: {name:6s} {seconds:7.1f} s "
                          f"({seconds / len(paths):.2f} s per submission)", flush=True)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(before)],
                           capture_output=True)
    before_median, today_median = statistics.median(times["before"]), statistics.median(times["today"])
    from halfedge_edu.exercises.sandbox import choose_isolation

    print(f"\n{args.submissions} submissions of chapter 06, {args.rounds} rounds, interleaved; "
          f"isolation today: {choose_isolation('auto')}; {os.cpu_count()} cores; "
          f"load {load:.2f} before, {os.getloadavg()[0]:.2f} after")
    print(f"| grader | median | per submission |\n|---|---:|---:|\n"
          f"| before ({args.before}) | {before_median:.1f} s | {before_median / args.submissions:.2f} s |\n"
          f"| today | {today_median:.1f} s | {today_median / args.submissions:.2f} s |")
    print(f"ratio today / before: {today_median / before_median:.2f}x (goal <= 1.5x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
