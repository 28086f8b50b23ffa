"""Hostile submissions: each attack on the grader ends at zero, reaches no one else, leaves nothing behind.

Each notebook here is built in the test and holds a *wrong* answer (or the package's own
answer) plus one trick an instructor has seen students try. Most are graded together in
one run of ``halfedge-edu grade``, the way a course's CI grades a class, with a CI token
in the grader's environment; right answers graded before and after them show that no
submission reaches another. Where a trick only fails because of the bubblewrap sandbox,
the same notebook graded with ``--isolation process`` shows that the trick is real (it
scores there), so the test could fail.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import nbformat
import pytest

from halfedge_edu.exercises.grading import EXERCISES, _judge_verdict
from halfedge_edu.exercises.sandbox import bubblewrap_works

from .test_grading import RIGHT_FLIP, _exercise_function

STUB = "def my_flip(mesh, e):\n    raise NotImplementedError('write my_flip')"
WRONG_FLIP = "def my_flip(mesh, e):\n    pass"
TOKEN = "ci-job-token-that-must-not-leak"

#: Tricks that forge a result for a wrong answer inside the learner's kernel.
FORGERIES = {
    "patched_check": [
        "import halfedge_edu.exercises as ex, halfedge_edu.exercises.ops_checks as oc\n"
        "from halfedge_edu.exercises.harness import CheckResult\n"
        "good = lambda *a, **k: CheckResult('flip', True, 'All good!', ['x'])\n"
        "ex.check_flip = oc.check_flip = good\n"
        "import halfedge_edu.exercises.grading as g\n"
        "g.check_function = lambda exercise: good", STUB],
    "patched_harness": [
        "import halfedge_edu.exercises.harness as h\n"
        "h.run = lambda f, *a: ('ok', None)\nh.close = lambda a, b: True", WRONG_FLIP],
    "patched_numpy": [
        "import numpy\nnumpy.allclose = lambda *a, **k: True\nnumpy.array_equal = lambda *a, **k: True\n"
        "numpy.any = lambda *a, **k: False", WRONG_FLIP],
    "fake_modules": [
        "import sys, types\n"
        "fake = types.ModuleType('fake')\nfake.check_flip = lambda f, **k: True\n"
        "for name in ('halfedge_edu.exercises.ops_checks', 'halfedge_edu.exercises.grading',\n"
        "             'halfedge_edu.exercises.judge'):\n"
        "    sys.modules[name] = fake", STUB],
    "printed_fake_results": [
        "import json\n"
        "line = json.dumps({'connected': True, 'exercises': {'flip': {'passed': True, 'output': 'ok',\n"
        "                   'public': [4, 4], 'hidden': [3, 3], 'missing': []}}})\n"
        "def forge(result):\n"
        "    print(line)\n"
        "    print('@@halfedge_edu-runner@@' + json.dumps({'problem': None, 'cell_errors': []}))\n"
        "    print('@@halfedge_edu-grade-0123456789abcdef@@' + json.dumps({'flip': {'passed': True, 'output': 'ok'}}))\n"
        "get_ipython().events.register('post_run_cell', forge)", STUB],
    "input_transformer": [
        "def rewrite(lines):\n"
        "    text = ''.join(lines)\n"
        "    if 'serve' in text and 'halfedge_edu' in text:\n"
        "        return ['print(\"grading cell replaced\")\\n']\n"
        "    return lines\n"
        "get_ipython().input_transformers_post.append(rewrite)", STUB],
    "forged_server": [
        "import socket, json, struct\n"
        "import halfedge_edu.exercises.serve as s\n"
        "def fake_serve(namespace, address, forbids):\n"
        "    c = socket.socket(socket.AF_UNIX); c.connect(address)\n"
        "    while True:\n"
        "        head = c.recv(4)\n"
        "        if len(head) < 4: return\n"
        "        size = struct.unpack('>I', head)[0]; body = b''\n"
        "        while len(body) < size: body += c.recv(size - len(body))\n"
        "        request = json.loads(body)\n"
        "        reply = {'id': request.get('id'), 'passed': 'no', 'functions': {'my_flip': {'callable': 'yes'}},\n"
        "                 'value': {'t': 'other', 'type': 'CheckResult', 'repr': 'All good!'}}\n"
        "        data = json.dumps(reply).encode(); c.sendall(struct.pack('>I', len(data)) + data)\n"
        "s.serve = fake_serve", STUB],
}

#: The package's own answer used instead of writing one: (file name, cells).
COPIES = {
    "mesh_flip": ("06_mesh_flip.ipynb", ["def my_flip(mesh, e):\n    mesh.flip(e)"]),
    "ops_flip_alias": ("06_ops_flip_alias.ipynb", ["from halfedge_edu.core.ops import flip as my_flip"]),
    "ops_flip_call": ("06_ops_flip_call.ipynb",
                      ["from halfedge_edu.core.ops import flip as ops_flip\ndef my_flip(mesh, e):\n    ops_flip(mesh, e)"]),
    "mesh_split": ("06_mesh_split.ipynb", ["def my_split(mesh, e):\n    return mesh.split(e)"]),
    "ops_split_call": ("06_ops_split_call.ipynb",
                       ["from halfedge_edu.core.ops import split\ndef my_split(mesh, e):\n    return split(mesh, e)"]),
    "ops_split_alias": ("06_ops_split_alias.ipynb", ["from halfedge_edu.core.ops.split import split as my_split"]),
    "mesh_collapse": ("07_mesh_collapse.ipynb",
                      ["def my_collapse(mesh, h):\n    mesh.collapse(mesh.halfedge(h))"]),
    "neighbors": ("03_neighbors.ipynb", ["def one_ring(mesh, v):\n    return mesh.vertex(int(v)).neighbors()"]),
    "rings_only": ("08_rings_only.ipynb", [
        "def rings_only(mesh, e):\n"
        "    a, b = mesh.edge(e).vertices\n"
        "    shared = {v.index for v in a.neighbors()} & {v.index for v in b.neighbors()}\n"
        "    return len(shared) == 2",
        "def collapse_is_safe(mesh, e):\n    return rings_only(mesh, e)"]),
    "link_condition": ("08_link_condition.ipynb", [
        "from halfedge_edu.core.ops import link_condition\n"
        "def collapse_is_safe(mesh, e):\n    return bool(link_condition(mesh, e))"]),
    "de_casteljau": ("12_de_casteljau.ipynb",
                     ["from halfedge_edu.exercises.bezier_checks import _de_casteljau as my_de_casteljau"]),
    "lab_right": ("08b_lab_right.ipynb", [
        "from halfedge_edu.exercises import classic_bugs\n"
        "fixed_flip = classic_bugs.flip_right\nfixed_collapse = classic_bugs.collapse_right\n"
        "fixed_one_ring = classic_bugs.one_ring_right"]),
}

#: A notebook that takes the answer from the solution edition beside the package, where it can see it.
FROM_SOLUTION_EDITION = (
    "import ast, json, pathlib, halfedge_edu\n"
    "edition = pathlib.Path(halfedge_edu.__file__).resolve().parents[1] / 'notebooks' / '06_flip_and_split.ipynb'\n"
    "try:\n"
    "    for cell in json.loads(edition.read_text())['cells']:\n"
    "        source = ''.join(cell['source'])\n"
    "        if 'def my_flip' in source:\n"
    "            exec(source)\n"
    "except OSError:\n"
    "    pass"
)

#: Looks for other students' files, the grader's command line and the CI token; defines the
#: right answer only if it found any of them, so a score of 1 means it reached beyond its sandbox.
SNOOP = (
    "import os, pathlib\n"
    f"token = {TOKEN!r}\n"
    "seen = []\n"
    "for entry in pathlib.Path('/proc').iterdir():\n"
    "    try:\n"
    "        seen.append((entry / 'cmdline').read_bytes() + (entry / 'environ').read_bytes())\n"
    "    except OSError:\n"
    "        pass\n"
    "reached = any(b'06_alice' in s or token.encode() in s for s in seen) or token in str(os.environ)\n"
    "print('reached beyond the sandbox:', reached)"
)

#: Finds the grader's command line and rewrites the reports and notebooks it names, plants
#: an IPython startup file for later kernels, and leaves a detached process behind.
SABOTAGE = (
    "import os, pathlib, subprocess, json\n"
    "for entry in pathlib.Path('/proc').iterdir():\n"
    "    try:\n"
    "        words = (entry / 'cmdline').read_bytes().split(b'\\0')\n"
    "    except OSError:\n"
    "        continue\n"
    "    if b'grade' not in words:\n"
    "        continue\n"
    "    out = pathlib.Path(os.fsdecode(words[words.index(b'--out') + 1]))\n"
    "    for report in out.glob('*alice*.json'):\n"
    "        report.write_text(json.dumps({'score': 0, 'max_score': 1, 'tests': []}))\n"
    "    for word in words:\n"
    "        if word.endswith(b'06_carol.ipynb'):\n"
    "            pathlib.Path(os.fsdecode(word)).write_text('{}')\n"
    "startup = 'import os\\nif os.environ.get(\"HALFEDGE_EDU_GRADE_RUN\"):\\n    my_flip = None\\n'\n"
    "for folder in (pathlib.Path.home() / '.ipython', pathlib.Path(os.environ.get('IPYTHONDIR', '/nonexistent'))):\n"
    "    try:\n"
    "        (folder / 'profile_default' / 'startup').mkdir(parents=True, exist_ok=True)\n"
    "        (folder / 'profile_default' / 'startup' / '00-sabotage.py').write_text(startup)\n"
    "    except OSError:\n"
    "        pass\n"
    "subprocess.Popen(['sleep', '987651'], start_new_session=True)\n"
    "subprocess.Popen(['sh', '-c', 'sleep 987652 </dev/null >/dev/null 2>&1 &'], start_new_session=True)\n"
    "pathlib.Path(os.environ.get('HOME', '.'), 'left-behind-987653').write_text('x')"
)

#: Kills every process it can see that is not its own kernel (the grader, if visible).
KILL_THE_GRADER = (
    "import os, signal, pathlib\n"
    "for entry in pathlib.Path('/proc').iterdir():\n"
    "    if entry.name.isdigit() and int(entry.name) != os.getpid():\n"
    "        try:\n"
    "            if b'halfedge' in (entry / 'cmdline').read_bytes():\n"
    "                os.kill(int(entry.name), signal.SIGKILL)\n"
    "        except OSError:\n"
    "            pass"
)


def notebook(path: Path, *cells: str, chapter: str | None = None) -> Path:
    book = nbformat.v4.new_notebook()
    book.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    if chapter is not None:
        book.metadata["halfedge_edu"] = {"chapter": chapter}
    book.cells = [nbformat.v4.new_code_cell(cell) for cell in cells]
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(book, path)
    return path


def grade(paths: list, out: Path, *options: str, timeout: float = 900) -> subprocess.CompletedProcess:
    """``halfedge-edu grade`` as a course's CI runs it, with a CI token in its environment."""
    env = dict(os.environ, CI_JOB_TOKEN=TOKEN)
    return subprocess.run([sys.executable, "-m", "halfedge_edu", "grade", *map(os.fsdecode, paths), "--out", str(out),
                           "--cell-timeout", "30", "--timeout", "120", *options],
                          env=env, capture_output=True, timeout=timeout)


def report(out: Path, name: str) -> dict:
    return json.loads((out / f"{name}.json").read_text())


def processes_with(argument: str) -> list[int]:
    """Processes on this machine whose command line holds ``argument``."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and argument.encode() in (entry / "cmdline").read_bytes().replace(b"\0", b" "):
                found.append(int(entry.name))
        except OSError:
            continue
    return found


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """One grading run over the whole hostile class; right answers before, between and after."""
    assert bubblewrap_works(), "these tests need Debian's bubblewrap: apt-get install bubblewrap (.ci/run does)"
    folder = tmp_path_factory.mktemp("class")
    paths = [notebook(folder / "06_alice.ipynb", RIGHT_FLIP)]
    for name, cells in FORGERIES.items():
        paths.append(notebook(folder / f"06_forgery_{name}.ipynb", *cells))
    for name, (file_name, cells) in COPIES.items():
        paths.append(notebook(folder / file_name, *cells))
    paths.append(notebook(folder / "06_from_solution.ipynb", STUB, FROM_SOLUTION_EDITION))
    paths.append(notebook(folder / "06_snoop.ipynb", STUB, SNOOP, f"if reached:\n{_indented(RIGHT_FLIP)}"))
    paths.append(notebook(folder / "06_mallory.ipynb", STUB, SABOTAGE))
    paths.append(notebook(folder / "06_killer.ipynb", RIGHT_FLIP, KILL_THE_GRADER))
    paths.append(notebook(folder / "06_stamped_12.ipynb", _exercise_function("12_bezier.py", "my_de_casteljau"),
                          chapter="12"))
    paths.append(notebook(folder / "alice_stamped_13.ipynb", RIGHT_FLIP, chapter="13"))
    paths.append(notebook(folder / "06_nul_and_escape.ipynb",
                          "def my_flip(mesh, e):\n    raise ValueError('bad \\x00 byte and \\x1b[31m colour')"))
    paths.append(notebook(folder / "06_syntax.ipynb", "x = 1", "def my_flip(mesh, e)\n    pass"))
    paths.append(notebook(folder / "06_name_error.ipynb", "y = undefined_name\n" + RIGHT_FLIP))
    paths.append(notebook(folder / "06_dies.ipynb", "x = 1", "import os\nos._exit(3)", RIGHT_FLIP))
    odd = os.fsencode(folder) + b"/06_caf\xe9.ipynb"
    notebook(Path(os.fsdecode(odd)), RIGHT_FLIP)
    paths.append(odd)
    paths.append(notebook(folder / "06_esc\x1b[31m.ipynb", RIGHT_FLIP))
    paths.append(notebook(folder / "a" / "06_same.ipynb", RIGHT_FLIP))
    paths.append(notebook(folder / "b" / "06_same.ipynb", STUB))
    (folder / "unreadable.obj").write_text("v 0 0 0\n")
    (folder / "unreadable.obj").chmod(0)
    paths.append(notebook(folder / "06_carol.ipynb", RIGHT_FLIP))
    out = folder / "reports"
    started = time.monotonic()
    run = grade(paths, out, "--isolation", "bubblewrap")
    seconds = time.monotonic() - started
    time.sleep(1)  # long enough for a surviving detached process to act
    return {"run": run, "out": out, "seconds": seconds, "paths": paths,
            "stdout": run.stdout.decode("utf-8", "replace")}


def _indented(code: str) -> str:
    return "\n".join("    " + line for line in code.splitlines())


def test_the_batch_ends_with_exit_0_and_a_report_for_every_submission(batch):
    assert batch["run"].returncode == 0, batch["run"].stderr.decode()
    names = {path.name[:-len(".json")] for path in batch["out"].glob("*.json")}
    assert len(names) == len(batch["paths"]), names
    assert len(batch["stdout"].splitlines()) == len(batch["paths"]), batch["stdout"]
    for path in batch["out"].iterdir():
        if path.suffix == ".json":
            json.loads(path.read_text())
        elif path.suffix == ".xml":
            ElementTree.parse(path)  # well-formed, NUL and ESC included
        else:
            raise AssertionError(f"a stray file in the reports: {path.name}")


def test_right_answers_before_and_after_every_attack_keep_full_marks(batch):
    for name in ("06_alice", "06_carol"):
        assert report(batch["out"], name)["score"] == 1.0, report(batch["out"], name)


@pytest.mark.parametrize("name", sorted(FORGERIES))
def test_a_forged_result_for_a_wrong_answer_scores_zero(batch, name):
    found = report(batch["out"], f"06_forgery_{name}")
    assert (found["score"], found["max_score"]) == (0.0, 2.0), found


@pytest.mark.parametrize("name", sorted(COPIES))
def test_the_packages_own_answer_scores_zero_with_this_is_the_exercise(batch, name):
    found = report(batch["out"], COPIES[name][0][:-len(".ipynb")])
    assert found["score"] == 0.0 and found["max_score"] > 0, found
    said = " ".join(test["output"] for test in found["tests"])
    assert "This is the exercise" in said and "write it yourself" in said, said


def test_the_solution_edition_beside_the_package_is_out_of_reach(batch):
    assert report(batch["out"], "06_from_solution")["score"] == 0.0


def test_other_students_the_grader_and_the_ci_token_are_out_of_sight(batch):
    assert report(batch["out"], "06_snoop")["score"] == 0.0
    assert TOKEN not in "".join(path.read_text() for path in batch["out"].glob("*.json"))


def files_named(name: str, top: Path) -> list[Path]:
    """Every file or folder called ``name`` under ``top``. Unlike ``Path.glob("**/...")``
    it does not stop at a folder that vanishes while it looks (another worker's grader
    removes its temporary folders at any moment)."""
    import os

    found = []
    for folder, folders, files in os.walk(top, onerror=lambda error: None):
        found += [Path(folder) / entry for entry in (*folders, *files) if entry == name]
    return found


def test_a_sabotaging_submission_changes_no_other_report_or_notebook_and_leaves_nothing_running(batch):
    assert report(batch["out"], "06_mallory")["score"] == 0.0
    assert report(batch["out"], "06_alice")["score"] == 1.0   # written before her run
    assert report(batch["out"], "06_carol")["score"] == 1.0   # graded after her, with her startup file planted
    assert nbformat.read(batch["paths"][-1], as_version=4).cells  # carol's notebook is untouched
    for argument in ("987651", "987652"):
        assert processes_with(f"sleep {argument}") == [], f"a detached 'sleep {argument}' outlived the grader"
    assert not files_named("left-behind-987653", Path("/tmp"))
    assert not (Path.home() / ".ipython" / "profile_default" / "startup" / "00-sabotage.py").exists()


def test_a_submission_that_kills_what_it_sees_only_ends_its_own_run(batch):
    found = report(batch["out"], "06_killer")
    assert found["score"] == 0.0 and "killed" in found["tests"][0]["output"], found


def test_the_file_name_picks_the_chapter_not_the_notebooks_stamp(batch):
    found = report(batch["out"], "06_stamped_12")
    assert found["extra_data"]["chapter"] == "06" and found["score"] == 0.0, found
    thirteen = report(batch["out"], "alice_stamped_13")
    assert thirteen["max_score"] == 0 and "has no graded exercises" in thirteen["output"], thirteen


def test_odd_file_names_and_control_characters_give_clean_reports_and_lines(batch):
    assert report(batch["out"], "06_caf")["score"] == 1.0
    assert report(batch["out"], "06_esc_31m")["score"] == 1.0
    assert "\x1b" not in batch["stdout"] and "\\x1b" in batch["stdout"]
    failure = ElementTree.parse(batch["out"] / "06_nul_and_escape.xml").find(".//failure")
    assert "\\x00" in failure.text and "\\x1b" in failure.text


def test_two_files_of_one_name_in_two_folders_get_two_reports(batch):
    same = sorted(path.name for path in batch["out"].glob("*06_same.json"))
    assert len(same) == 2, same
    assert sorted(report(batch["out"], name[:-5])["score"] for name in same) == [0.0, 1.0]


@pytest.mark.parametrize(("name", "said"), [
    ("06_syntax", "SyntaxError"), ("06_name_error", "NameError"), ("06_dies", "died while running cell 2")])
def test_the_real_reason_reaches_the_student_in_the_visible_output(batch, name, said):
    output = report(batch["out"], name)["tests"][0]["output"]
    assert said in output and "keep those names" not in output, output


def test_process_isolation_shows_the_sandbox_is_what_stops_the_reaching_tricks(tmp_path):
    """Control: without bubblewrap the same snooping and the solution edition do reach (so the
    tests above could fail); only the notebook's own folder, environment and limits hold."""
    paths = [notebook(tmp_path / "06_alice.ipynb", RIGHT_FLIP),
             notebook(tmp_path / "06_snoop.ipynb", STUB, SNOOP, f"if reached:\n{_indented(RIGHT_FLIP)}"),
             notebook(tmp_path / "06_from_solution.ipynb", STUB, FROM_SOLUTION_EDITION)]
    run = grade(paths, tmp_path / "out", "--isolation", "process")
    assert run.returncode == 0, run.stderr
    assert report(tmp_path / "out", "06_snoop")["score"] == 1.0
    assert report(tmp_path / "out", "06_from_solution")["score"] == 1.0
    assert TOKEN not in report(tmp_path / "out", "06_snoop")["output"]


def test_limits_on_memory_output_files_and_processes_end_only_the_offender(tmp_path):
    paths = [
        notebook(tmp_path / "06_hog.ipynb", RIGHT_FLIP, "import numpy\nhog = numpy.ones(400_000_000)"),
        notebook(tmp_path / "06_flood.ipynb", RIGHT_FLIP, "chunk = 'x' * 1_000_000\nfor _ in range(300):\n    print(chunk)"),
        notebook(tmp_path / "06_big_file.ipynb", "open('big', 'wb').write(b'x' * 20_000_000)", RIGHT_FLIP),
        notebook(tmp_path / "06_fork.ipynb", RIGHT_FLIP,
                 "import subprocess\nfor _ in range(300):\n    subprocess.Popen(['sleep', '987654'])"),
        notebook(tmp_path / "06_bob.ipynb", RIGHT_FLIP),
    ]
    run = grade(paths, tmp_path / "out", "--isolation", "bubblewrap", "--memory", "1024", "--output", "1",
                "--file-size", "8", "--processes", "96")
    assert run.returncode == 0, run.stderr
    hog = report(tmp_path / "out", "06_hog")
    if Path("/sys/fs/cgroup/memory/memory.limit_in_bytes").exists() or Path("/sys/fs/cgroup/cgroup.controllers").exists():
        assert hog["score"] == 0.0 and "out of memory" in hog["output"], hog   # a cgroup: the kernel is stopped
    else:
        assert "MemoryError" in str(hog["extra_data"]["cell_errors"]), hog    # the address-space limit
    assert report(tmp_path / "out", "06_flood")["score"] == 1.0   # 300 MB printed, 1 MB kept
    big = report(tmp_path / "out", "06_big_file")
    assert big["score"] == 1.0 and big["extra_data"]["cell_errors"], big   # the write failed, the answer counts
    fork = report(tmp_path / "out", "06_fork")   # stopped well before its 300th process
    assert "BlockingIOError" in str(fork["extra_data"]["cell_errors"]), fork
    assert processes_with("sleep 987654") == []
    assert report(tmp_path / "out", "06_bob")["score"] == 1.0


@pytest.mark.parametrize(("sent", "status"), [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_sigterm_and_ctrl_c_stop_the_grader_with_no_report_for_the_interrupted_student(tmp_path, sent, status):
    first = notebook(tmp_path / "06_first.ipynb", RIGHT_FLIP)
    slow = notebook(tmp_path / "06_slow.ipynb", RIGHT_FLIP,
                    "import subprocess, time\nsubprocess.Popen(['sleep', '987655'])\ntime.sleep(60)")
    out = tmp_path / "out"
    grader = subprocess.Popen([sys.executable, "-m", "halfedge_edu", "grade", str(first), str(slow), "--out", str(out),
                               "--isolation", "bubblewrap"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while not processes_with("sleep 987655") and time.monotonic() < deadline:
        time.sleep(0.2)
    assert processes_with("sleep 987655"), "the slow notebook never started"
    grader.send_signal(sent)
    grader.communicate(timeout=60)
    assert grader.returncode == status
    assert report(out, "06_first")["score"] == 1.0
    assert not (out / "06_slow.json").exists() and not (out / "06_slow.xml").exists()
    assert processes_with("sleep 987655") == []


def test_a_report_that_cannot_be_written_is_said_and_the_others_are_still_written(tmp_path):
    paths = [notebook(tmp_path / "06_blocked.ipynb", RIGHT_FLIP), notebook(tmp_path / "06_next.ipynb", RIGHT_FLIP)]
    (tmp_path / "out" / "06_blocked.json").mkdir(parents=True)  # a folder where the report should go
    run = grade(paths, tmp_path / "out", "--isolation", "process")
    assert run.returncode == 1
    assert "06_blocked: the report could not be written" in run.stderr.decode()
    assert report(tmp_path / "out", "06_next")["score"] == 1.0


def test_a_stopped_grader_is_out_of_reach_and_a_stopped_run_ends_at_the_time_limit(tmp_path):
    stopper = notebook(tmp_path / "06_stopper.ipynb", RIGHT_FLIP,
                       "import os, signal\nos.kill(os.getppid(), signal.SIGSTOP)\nimport time\ntime.sleep(30)")
    after = notebook(tmp_path / "06_after.ipynb", RIGHT_FLIP)
    run = grade([stopper, after], tmp_path / "out", "--isolation", "bubblewrap", "--timeout", "8", timeout=120)
    assert run.returncode == 0, run.stderr
    assert report(tmp_path / "out", "06_stopper")["score"] == 0.0
    assert report(tmp_path / "out", "06_after")["score"] == 1.0


# --------------------------------------------------------------------------------------
# The judge's verdict as data, and the forbidden lists
# --------------------------------------------------------------------------------------

FLIP = [exercise for exercise in EXERCISES if exercise.name == "flip"]


@pytest.mark.parametrize("forged", [
    {"exercises": {"flip": {"passed": "yes", "output": "", "public": [1, 1], "hidden": [1, 1]}}},
    {"exercises": {"flip": {"passed": 1, "output": "", "public": [1, 1], "hidden": [1, 1]}}},
])
def test_a_pass_is_exactly_true(forged):
    assert _judge_verdict(json.dumps(forged).encode(), FLIP)["flip"]["passed"] is False


@pytest.mark.parametrize("broken", [
    b"", b"not json", b"[]", json.dumps({"exercises": {}}).encode(),
    json.dumps({"exercises": {"flip": {"passed": True, "output": 3, "public": [1, 1], "hidden": [1, 1]}}}).encode(),
    json.dumps({"exercises": {"flip": {"passed": True, "output": "", "public": [-1, 1], "hidden": [1, 1]}}}).encode(),
])
def test_a_verdict_of_the_wrong_shape_counts_as_no_verdict(broken):
    assert _judge_verdict(broken, FLIP) is None


def test_every_forbidden_entry_names_something_the_package_or_chapter_has():
    from halfedge_edu.exercises.serve import ALLOWED, NOTEBOOK, functions_forbidden, resolve

    for exercise in EXERCISES:
        for key in exercise.forbids:
            if key.startswith(NOTEBOOK):
                continue
            found = resolve(key.removeprefix(ALLOWED), {})
            assert found is not None, f"{exercise.name}: {key} names nothing"
            assert callable(found) or type(found).__name__ == "module", key
            if key.startswith(ALLOWED):   # an exemption: a function of a module the exercise forbids
                assert key[len(ALLOWED):] not in functions_forbidden(list(exercise.forbids), {}), key
                assert key[len(ALLOWED):] in functions_forbidden([key.rsplit(".", 1)[0][len(ALLOWED):]], {}), key
