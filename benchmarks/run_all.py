"""Run every benchmark script in this folder, one after another, each in its own process.

    python benchmarks/run_all.py            # full sizes, print the tables
    python benchmarks/run_all.py --docs     # and write docs/benchmark-run.md, if the run was quiet (make bench)
    python benchmarks/run_all.py --quick    # smaller sizes, where a script supports it

Each ``bench_*.py`` prints its own table with the peers beside our figures. Separate
processes keep one benchmark's memory and caches from colouring the next.

The run starts with the machine it is on (CPU, cores, load) and ends with it again and
with a verdict per script: its figures may go into the docs only if other processes
used less than a tenth of the machine's CPU time while it ran (``_common.OtherWork``;
the load average cannot tell a benchmark's own work from a neighbour's). With
``--docs`` the whole output goes to ``docs/benchmark-run.md``, the page the figures in
docs/performance.md come from, but only from a full run of committed code in which
every script ran quiet and none failed; otherwise that page is left as it was, the
output goes to ``build/bench/benchmark-run.md`` and the run says why. The exit code is
1 if a script failed, else 0: a busy run is said, not hidden.
"""

from __future__ import annotations

import argparse
import datetime
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import OtherWork, machine_report  # noqa: E402 - after the path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
DOCS_PAGE = ROOT / "docs" / "benchmark-run.md"
REFUSED_PAGE = ROOT / "build" / "bench" / "benchmark-run.md"
COMMAND = "make bench  (python benchmarks/run_all.py --docs)"


@dataclass
class ScriptRun:
    """One benchmark script's run: its output, exit code, and what else the machine did meanwhile."""

    name: str
    output: str
    returncode: int
    other: OtherWork

    @property
    def fit(self) -> bool:
        return self.returncode == 0 and self.other.verdict()[0]

    def verdict(self) -> str:
        if self.returncode != 0:
            return f"failed with exit code {self.returncode}"
        return self.other.verdict()[1]


def benchmark_scripts() -> list[Path]:
    """Every ``bench_*.py`` of this folder, in name order."""
    return sorted(HERE.glob("bench_*.py"))


def run_script(script: Path, extra: list[str]) -> ScriptRun:
    """Run ``script`` in its own process, echo its output as it comes, and keep it.

    Its orphaned descendants that have exited are reaped before the count stops (see
    :func:`_common.adopt_orphans`); one still running then counts as other work.
    """
    lines: list[str] = []
    with OtherWork(adopt_orphans=True) as other:
        process = subprocess.Popen([sys.executable, "-u", str(script), *extra], stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, text=True, errors="replace")
        assert process.stdout is not None
        for line in process.stdout:
            sys.stdout.write(line)
            sys.stdout.flush()
            lines.append(line)
        returncode = process.wait()              # waited for: its CPU time counts as ours, not other work
    return ScriptRun(script.name, "".join(lines), returncode, other)


def code_state() -> tuple[str, list[str]]:
    """The commit measured and the tracked files outside docs/ changed since (uncommitted code)."""
    def git(*args: str) -> str:
        try:
            return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout
        except (OSError, subprocess.CalledProcessError):
            return ""

    commit = git("rev-parse", "--short", "HEAD").strip() or "unknown"
    changed = [line[3:] for line in git("status", "--porcelain", "--untracked-files=no").splitlines()
               if not line[3:].startswith("docs/")]
    return commit, changed


def reasons_not_fit(runs: list[ScriptRun], full_run: bool, commit: str, changed: list[str]) -> list[str]:
    """Why this run's output may not become docs/benchmark-run.md (empty: it may)."""
    reasons = [f"{run.name}: {run.verdict()}" for run in runs if not run.fit]
    if not full_run:
        reasons.append("not a full run (--quick or --only): the docs' figures are the full sizes of every script")
    if commit == "unknown":
        reasons.append("the commit measured is unknown (not a git checkout)")
    if changed:
        reasons.append(f"uncommitted changes to the code measured: {', '.join(changed[:5])}"
                       + (" ..." if len(changed) > 5 else ""))
    return reasons


def render_page(runs: list[ScriptRun], machine_before: str, machine_after: str, commit: str,
                started: datetime.datetime) -> str:
    """docs/benchmark-run.md: the command, the machine, each script's verdict and its whole output."""
    lines = [
        "# The benchmark run",
        "",
        "Written by the command below, not by hand; the figures in [performance](performance.md)",
        "come from it. It is rewritten only by a full run of committed code in which other",
        "processes used less than a tenth of the machine's CPU time while each script ran.",
        "",
        f"- command: `{COMMAND}`",
        f"- started: {started:%Y-%m-%d %H:%M} UTC, commit `{commit}`",
        f"- {machine_before}",
        f"- at the end: {machine_after.removeprefix('machine: ')}",
        "",
        "| script | seconds | other processes' CPU | 1-min load before -> after | verdict |",
        "|---|---:|---:|---|---|",
    ]
    for run in runs:
        share = run.other.share()
        lines.append(f"| {run.name} | {run.other.seconds:.0f} | "
                     f"{'?' if share is None else f'{100 * share:.1f}%'} | "
                     f"{run.other.load_before:.2f} -> {run.other.load_after:.2f} | "
                     f"{'fit' if run.fit else 'NOT fit'} |")
    for run in runs:
        lines += ["", f"## {run.name}", "", "```text", run.output.rstrip("\n"), "```"]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--docs", action="store_true",
                        help="write docs/benchmark-run.md if the run was quiet (else build/bench/)")
    parser.add_argument("--only", default="", help="comma-separated script names (bench_build,...) to run")
    args, extra = parser.parse_known_args(argv)
    only = {name.strip().removesuffix(".py") for name in args.only.split(",") if name.strip()}

    started = datetime.datetime.now(datetime.timezone.utc)
    machine_before = machine_report()
    print(machine_before, flush=True)
    runs = []
    for script in benchmark_scripts():
        if only and script.stem not in only:
            continue
        print(f"\n=== {script.name} ===", flush=True)
        runs.append(run_script(script, extra))
    machine_after = machine_report()
    print()
    print(machine_after)
    for run in runs:
        print(f"{run.name}: {run.verdict()}")

    if args.docs:
        commit, changed = code_state()
        reasons = reasons_not_fit(runs, full_run=not only and not extra, commit=commit, changed=changed)
        page = render_page(runs, machine_before, machine_after, commit, started)
        if reasons:
            REFUSED_PAGE.parent.mkdir(parents=True, exist_ok=True)
            REFUSED_PAGE.write_text(page, encoding="utf-8")
            print(f"\n{DOCS_PAGE.relative_to(ROOT)} NOT written (left as it was); this run is in "
                  f"{REFUSED_PAGE.relative_to(ROOT)}. Why:")
            for reason in reasons:
                print(f"  - {reason}")
        else:
            DOCS_PAGE.write_text(page, encoding="utf-8")
            print(f"\nwrote {DOCS_PAGE.relative_to(ROOT)}: every script ran quiet")
    return 1 if any(run.returncode != 0 for run in runs) else 0


if __name__ == "__main__":
    sys.exit(main())
