"""`make bench` names the machine it ran on and writes the docs' page only from a quiet run."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import _common  # noqa: E402 - benchmarks/ is not a package
import run_all  # noqa: E402


def test_the_machine_report_names_cpu_cores_load_and_versions():
    line = _common.machine_report()
    assert line.startswith("machine: ") and "logical cores" in line and "load " in line
    assert _common.cpu_model() in line and "numpy " in line


def test_a_quiet_run_is_fit_for_the_docs_and_a_busy_one_is_said_not_to_be():
    fit, words = _common.fit_for_the_docs(0.02, 0.1, 0.3, 60.0, cores=2)
    assert fit and "fit for the docs" in words and "2.0%" in words
    for share in (0.10, 0.35, 1.0):
        fit, words = _common.fit_for_the_docs(share, 0.1, 0.1, 60.0, cores=2)
        assert not fit and "NOT fit" in words, share
    fit, words = _common.fit_for_the_docs(None, 0.1, 0.1, 60.0, cores=2)   # nothing to measure with
    assert not fit and "could not be measured" in words


def scripted(monkeypatch, busy: list[float], own: list[float]) -> None:
    """Make the machine's and this process's CPU counters return these values, in turn."""
    monkeypatch.setattr(_common, "busy_cpu_seconds", lambda: busy.pop(0))
    monkeypatch.setattr(_common, "own_cpu_seconds", lambda: own.pop(0))


def test_other_work_is_the_machines_busy_time_minus_our_own(monkeypatch):
    # The machine was busy 30 s, 28 of them ours: 2 s of other work.
    scripted(monkeypatch, busy=[100.0, 130.0], own=[5.0, 33.0])
    with _common.OtherWork() as other:
        time.sleep(0.05)
    assert other.other_cpu_seconds == pytest.approx(2.0)
    assert other.share(cores=2) == pytest.approx(2.0 / (other.seconds * 2))
    assert not other.verdict(cores=2)[0]           # 2 s in a 0.05 s block is a busy machine
    # Our own work alone, however much, leaves the run quiet (the load average would not).
    scripted(monkeypatch, busy=[100.0, 100.5], own=[5.0, 5.5])
    other = _common.OtherWork().start()
    time.sleep(0.5)
    other.stop()
    assert other.other_cpu_seconds == pytest.approx(0.0) and other.verdict(cores=2)[0]


def test_a_process_not_waited_for_counts_as_other_work():
    """A real neighbour: a process that burns CPU seconds and is not ours (not waited for yet)."""
    spin = "import time\nwhile time.process_time() < 0.6: pass\n"
    other = _common.OtherWork().start()
    neighbour = subprocess.Popen([sys.executable, "-c", spin])
    while True:            # wait for it to finish without reaping it (its time is not ours yet)
        try:
            with open(f"/proc/{neighbour.pid}/stat", encoding="ascii") as stat:
                if stat.read().split(") ")[1].split()[0] == "Z":
                    break
        except FileNotFoundError:
            break
        time.sleep(0.02)
    other.stop()
    neighbour.wait()
    assert other.other_cpu_seconds is not None and other.other_cpu_seconds >= 0.5


def fake_run(name: str, share: float, returncode: int = 0) -> run_all.ScriptRun:
    other = _common.OtherWork()
    other.seconds, other.other_cpu_seconds = 10.0, share * 10.0 * 2
    return run_all.ScriptRun(name, f"{name} table\n", returncode, other)


def test_run_all_writes_the_docs_page_only_from_a_quiet_full_run_of_committed_code(monkeypatch, tmp_path, capsys):
    docs_page, refused_page = tmp_path / "docs" / "benchmark-run.md", tmp_path / "build" / "benchmark-run.md"
    docs_page.parent.mkdir()
    docs_page.write_text("the page of the last quiet run\n")
    monkeypatch.setattr(run_all, "ROOT", tmp_path)
    monkeypatch.setattr(run_all, "DOCS_PAGE", docs_page)
    monkeypatch.setattr(run_all, "REFUSED_PAGE", refused_page)
    monkeypatch.setattr(run_all, "code_state", lambda: ("abc1234", []))
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    monkeypatch.setattr(run_all, "benchmark_scripts", lambda: [Path("bench_build.py"), Path("bench_simplify.py")])
    quiet = [fake_run("bench_build.py", 0.01), fake_run("bench_simplify.py", 0.02)]
    busy = [fake_run("bench_build.py", 0.01), fake_run("bench_simplify.py", 0.40)]
    failed = [fake_run("bench_build.py", 0.01), fake_run("bench_simplify.py", 0.01, returncode=1)]

    for runs, why in ((busy, "bench_simplify.py: other processes used 40.0%"),
                      (failed, "bench_simplify.py: failed with exit code 1")):
        monkeypatch.setattr(run_all, "run_script", lambda script, extra, runs=iter(runs * 10): next(runs))
        run_all.main(["--docs"])
        said = capsys.readouterr().out
        assert "NOT written (left as it was)" in said and why in said, said
        assert docs_page.read_text() == "the page of the last quiet run\n"
        assert "bench_simplify.py table" in refused_page.read_text()

    monkeypatch.setattr(run_all, "run_script", lambda script, extra, runs=iter(quiet): next(runs))
    assert run_all.main(["--docs"]) == 0
    page = docs_page.read_text()
    assert "wrote docs/benchmark-run.md" in capsys.readouterr().out
    assert "`make bench  (python benchmarks/run_all.py --docs)`" in page and "commit `abc1234`" in page
    assert "machine: " in page and "| bench_simplify.py | 10 | 2.0% |" in page and "bench_build.py table" in page


def test_run_all_refuses_a_partial_run_and_uncommitted_code():
    quiet = [fake_run("bench_build.py", 0.01)]
    assert run_all.reasons_not_fit(quiet, True, "abc1234", []) == []
    assert "not a full run" in run_all.reasons_not_fit(quiet, False, "abc1234", [])[0]
    assert "uncommitted changes to the code measured: halfedge_edu/core/build.py" in \
        run_all.reasons_not_fit(quiet, True, "abc1234", ["halfedge_edu/core/build.py"])[0]


ORPHAN_SPINNER = """
import os, time
if os.fork() == 0:                # the child leaves a grandchild behind and exits at once
    if os.fork() == 0:
        while time.process_time() < 0.6:
            pass                  # the orphan's CPU time: the benchmark's own work
    os._exit(0)
os.wait()
time.sleep(1.5)                   # the script outlives its orphan, as a grader outlives a sandbox
"""


def test_run_all_counts_a_benchmarks_orphaned_descendants_as_its_own_work(tmp_path):
    """A grandchild whose parent exited (bubblewrap's sandbox does this) is reaped by
    run_all, not init, so its CPU time is the benchmark's, not other work. In a process
    of its own: a subreaper changes how every later orphan of the process is reaped."""
    script = tmp_path / "bench_orphan.py"
    script.write_text(ORPHAN_SPINNER)
    measure = ("import sys; from pathlib import Path; import run_all, _common\n"
               "sys.stdout = open('/dev/null', 'w')\n"
               "before = _common.own_cpu_seconds()\n"
               "run_all.OtherWork = lambda adopt_orphans: _common.OtherWork(adopt_orphans=SUBREAPER)\n"
               "run = run_all.run_script(Path(SCRIPT), [])\n"
               "sys.stderr.write(f'{_common.own_cpu_seconds() - before} {run.other.other_cpu_seconds}')\n")
    measure = measure.replace("SCRIPT", repr(str(script)))
    benchmarks = Path(run_all.__file__).parent
    for subreaper in (True, False):
        done = subprocess.run([sys.executable, "-c", measure.replace("SUBREAPER", str(subreaper))], cwd=benchmarks,
                              capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        own, other = (float(value) for value in done.stderr.split()[-2:])
        if subreaper:
            assert own >= 0.55, (own, other)        # the orphan's 0.6 s came back to us
        else:
            assert own < 0.5 and other >= 0.5, (own, other)   # without: init reaped it, a "neighbour"


def test_the_docs_benchmark_page_is_one_quiet_full_run_of_code_in_this_history():
    """docs/benchmark-run.md is written by run_all, never by hand: every script of this
    folder, each one judged quiet, from a commit this checkout descends from; and the
    performance page quotes that run."""
    page = run_all.DOCS_PAGE.read_text(encoding="utf-8")
    assert page.startswith("# The benchmark run\n") and f"- command: `{run_all.COMMAND}`" in page
    rows = {line.split(" | ")[0].removeprefix("| "): line for line in page.splitlines()
            if line.startswith("| bench_")}
    assert set(rows) == {script.name for script in run_all.benchmark_scripts()}
    assert all(line.endswith("| fit |") for line in rows.values()), rows
    for name in rows:
        assert f"\n## {name}\n\n```text\n" in page, name
    started = page.split("- started: ", 1)[1].split(" UTC, commit `", 1)
    commit = started[1].split("`", 1)[0]
    assert len(commit) >= 7 and all(c in "0123456789abcdef" for c in commit), commit
    shallow = subprocess.run(["git", "rev-parse", "--is-shallow-repository"], cwd=run_all.ROOT,
                             capture_output=True, text=True)
    if shallow.returncode == 0 and shallow.stdout.strip() == "false":   # a checkout with its whole history
        ancestor = subprocess.run(["git", "merge-base", "--is-ancestor", commit, "HEAD"], cwd=run_all.ROOT)
        assert ancestor.returncode == 0, f"{commit} is not in this checkout's history"
    performance = (run_all.ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    assert f"[the benchmark run](benchmark-run.md) of {started[0]} UTC" in performance
