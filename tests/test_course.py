"""`halfedge-edu course DEST`: the chapters' student edition, without outputs, out of the installed package.

The wheel test is the promise a pip user relies on: a wheel built from this checkout,
installed with its notebooks extra into a fresh virtual environment (no editable
install, no repository beside it), copies all the chapters and runs one. It builds the
sdist, the wheel and the venv, so it takes 2-3 minutes.
"""

from __future__ import annotations

import fnmatch
import json
import os
import shutil
import subprocess
import sys
import tarfile
import venv
from pathlib import Path

import pytest

from halfedge_edu import cli, course

ROOT = Path(__file__).resolve().parents[1]
STUDENT = ROOT / "notebooks" / "student"
CHAPTERS = sorted(p.name for p in STUDENT.glob(course.CHAPTER_GLOB))


def test_the_course_is_every_chapter_of_the_student_edition():
    sources = sorted(p.stem for p in (ROOT / "notebooks" / "src").glob("[0-9][0-9]*_*.py"))
    assert [Path(name).stem for name in CHAPTERS] == sources
    assert course.REPOSITORY_NOTEBOOKS == STUDENT


def assert_is_a_clean_chapter(path: Path) -> None:
    """Valid notebook JSON of the student edition whose code cells have no outputs and no execution counts."""
    notebook = json.loads(path.read_text(encoding="utf-8"))
    assert notebook["nbformat"] == 4, path
    assert notebook["metadata"]["halfedge_edu"]["edition"] == "student", f"{path.name} is not the student edition"
    assert "widgets" not in notebook["metadata"], f"{path.name} keeps saved widget state"
    code = [cell for cell in notebook["cells"] if cell["cell_type"] == "code"]
    assert code, f"{path.name} has no code cells"
    dirty = [i for i, cell in enumerate(code) if cell["outputs"] or cell["execution_count"] is not None]
    assert not dirty, f"{path.name}: code cells {dirty} keep outputs"


def test_strip_outputs_keeps_sources_and_removes_outputs():
    notebook = json.loads((STUDENT / CHAPTERS[3]).read_text(encoding="utf-8"))
    stripped = course.strip_outputs(notebook)
    assert [c["source"] for c in stripped["cells"]] == [c["source"] for c in notebook["cells"]]
    assert any(c.get("outputs") for c in notebook["cells"]), "the stored chapter has outputs to remove"
    assert all(not c.get("outputs") for c in stripped["cells"])
    assert stripped["metadata"]["kernelspec"] == notebook["metadata"]["kernelspec"]


def test_course_command_copies_every_chapter_without_outputs(tmp_path, capsys):
    destination = tmp_path / "my-course"
    assert cli.main(["course", str(destination)]) == cli.EXIT_OK
    assert sorted(p.name for p in destination.iterdir()) == CHAPTERS
    for path in destination.iterdir():
        assert_is_a_clean_chapter(path)
    out = capsys.readouterr().out
    assert f"copied {len(CHAPTERS)} chapters" in out
    assert f"jupyter lab {destination}" in out


def test_the_course_command_loads_neither_numpy_nor_the_library(tmp_path):
    """Copying notebooks is the standard library's work: ``course`` imports nothing more."""
    code = ("import sys\nfrom halfedge_edu.cli import main\nstatus = main(sys.argv[1:])\n"
            "print(' '.join(sorted(m for m in sys.modules if m.startswith(('numpy', 'halfedge_edu')))))\n"
            "sys.exit(status)")
    result = subprocess.run([sys.executable, "-c", code, "course", str(tmp_path / "c")],
                            capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert result.returncode == cli.EXIT_OK, result.stderr
    loaded = set(result.stdout.splitlines()[-1].split())
    assert {"halfedge_edu.cli.course", "halfedge_edu.course"} <= loaded
    assert not {"numpy", "halfedge_edu.core", "halfedge_edu.io", "halfedge_edu.algorithms"} & loaded
    assert sorted(p.name for p in (tmp_path / "c").iterdir()) == CHAPTERS


def test_setup_py_strips_the_chapters_without_the_package(tmp_path):
    """setup.py's build step (``_course_module().write_chapters``), in an interpreter where
    ``halfedge_edu`` cannot be imported: course.py must need the standard library only."""
    code = (
        "import importlib.util, sys\nfrom pathlib import Path\n"
        "sys.modules['halfedge_edu'] = None\n"
        f"spec = importlib.util.spec_from_file_location('halfedge_edu_setup', {str(ROOT / 'setup.py')!r})\n"
        "setup_py = importlib.util.module_from_spec(spec)\nspec.loader.exec_module(setup_py)\n"
        f"print(len(setup_py._course_module().write_chapters(Path({str(STUDENT)!r}), Path({str(tmp_path)!r}))))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == str(len(CHAPTERS))
    for path in tmp_path.glob(course.CHAPTER_GLOB):
        assert_is_a_clean_chapter(path)


def students_work(path: Path) -> bytes:
    """Write a valid notebook at ``path``, as JupyterLab saves a student's edited chapter; return its bytes."""
    notebook = json.loads((STUDENT / path.name).read_text(encoding="utf-8")) if (STUDENT / path.name).exists() \
        else {"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": []}
    notebook["cells"].append({"cell_type": "code", "id": "mine", "metadata": {}, "execution_count": None,
                              "outputs": [], "source": ["my_answer = 42\n"]})
    data = json.dumps(notebook).encode("utf-8")
    path.write_bytes(data)
    return data


def test_course_command_never_overwrites_a_students_work(tmp_path, capsys):
    work = tmp_path / CHAPTERS[0]
    mine = students_work(work)
    assert cli.main(["course", str(tmp_path)]) == cli.EXIT_OK
    assert work.read_bytes() == mine
    assert f"kept 1 already there: {CHAPTERS[0]}" in capsys.readouterr().out
    assert len(list(tmp_path.glob(course.CHAPTER_GLOB))) == len(CHAPTERS)


def test_course_into_a_file_is_one_line_error(tmp_path, capsys):
    not_a_folder = tmp_path / "notes.txt"
    not_a_folder.write_text("x", encoding="utf-8")
    assert cli.main(["course", str(not_a_folder)]) == cli.EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("halfedge-edu: error: ") and "notes.txt" in err and "not a folder" in err
    assert err.count("\n") == 1


def docker_context(destination: Path) -> Path:
    """Copy into ``destination`` the files .dockerignore lets into the image's build (the
    rules it uses: ``*``, then ``!path`` exceptions, then ``**/name`` exclusions, each
    also matching everything under a folder it names, as Docker matches them)."""
    rules = [line.strip() for line in (ROOT / ".dockerignore").read_text().splitlines()
             if line.strip() and not line.lstrip().startswith("#")]

    def matches(pattern: str, path: str) -> bool:
        pattern = pattern.rstrip("/")
        parts = path.split("/")
        prefixes = ["/".join(parts[: i + 1]) for i in range(len(parts))]
        if pattern.startswith("**/"):
            return any(fnmatch.fnmatchcase(part, pattern[3:]) for part in parts)
        return any(fnmatch.fnmatchcase(prefix, pattern) for prefix in prefixes)

    for path in sorted(ROOT.rglob("*")):
        relative = path.relative_to(ROOT).as_posix()
        if path.is_dir() or relative.startswith((".git/", ".venv/")):
            continue
        excluded = False
        for rule in rules:
            if rule.startswith("!") and matches(rule[1:], relative):
                excluded = False
            elif not rule.startswith("!") and matches(rule, relative):
                excluded = True
        if not excluded:
            target = destination / relative
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, target)
    return destination


def run(command: list, **kwargs) -> subprocess.CompletedProcess:
    result = subprocess.run([str(part) for part in command], capture_output=True, text=True, **kwargs)
    assert result.returncode == 0, f"{command}: {result.stdout[-2000:]}{result.stderr[-3000:]}"
    return result


def test_the_published_wheel_installs_in_a_clean_venv_copies_the_course_and_runs_a_chapter(tmp_path):
    """The install line of a built wheel, as a newcomer runs it: ``make dist``'s sdist and
    wheel built from exactly the image's build context (.dockerignore), their metadata
    checked, the wheel with its notebooks extra installed into a fresh virtual environment
    (no editable install, no checkout beside it, the semester lock), ``halfedge-edu
    course`` from it, and chapter 00 executed headless there. About 2-3 minutes, most of
    it pip installing the notebooks extra (the pip cache is warm in CI)."""
    context = docker_context(tmp_path / "context")
    shipped = sorted(p.relative_to(context).as_posix() for p in context.rglob("*.ipynb"))
    assert shipped == [f"notebooks/student/{name}" for name in CHAPTERS], "the image gets the student edition only"
    assert not (context / "notebooks" / "src").exists() and not (context / ".venv").exists()

    # Without PYTHONPATH: it may point at this checkout, which pip would take for an install.
    clean_env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    dist = tmp_path / "dist"
    run([sys.executable, "-m", "build", "--outdir", dist, context], timeout=600, env=clean_env)
    (wheel,) = dist.glob("halfedge_edu-*.whl")
    (sdist,) = dist.glob("halfedge_edu-*.tar.gz")
    run([sys.executable, "-m", "twine", "check", "--strict", wheel, sdist], timeout=120)
    with tarfile.open(sdist) as archive:
        notebooks = [name.split("/", 1)[1] for name in archive.getnames() if name.endswith(".ipynb")]
    assert sorted(notebooks) == [f"notebooks/student/{name}" for name in CHAPTERS], "no solution edition in the sdist"

    environment = tmp_path / "venv"
    venv.create(environment, with_pip=True)
    python = environment / "bin" / "python"
    run([python, "-m", "pip", "install", "--quiet", "--disable-pip-version-check", "--no-compile",
         "-c", ROOT / "constraints" / "2026-fall.txt", f"{wheel}[notebooks]"], timeout=900, env=clean_env)

    destination = tmp_path / "x"
    # Run from tmp_path so that neither this checkout nor its notebooks/ can be found.
    run([environment / "bin" / "halfedge-edu", "course", destination], timeout=120, cwd=tmp_path, env=clean_env)
    where = run([python, "-c", "import halfedge_edu.course as c; print(c.chapter_source())"],
                timeout=120, cwd=tmp_path, env=clean_env)
    assert str(environment) in where.stdout, f"chapters did not come from the wheel: {where.stdout}"
    assert sorted(p.name for p in destination.iterdir()) == CHAPTERS
    for path in destination.iterdir():
        assert_is_a_clean_chapter(path)
    run([python, "-m", "halfedge_edu", "course", tmp_path / "y"], timeout=120, cwd=tmp_path, env=clean_env)
    assert sorted(p.name for p in (tmp_path / "y").iterdir()) == CHAPTERS

    # Chapter 00 headless in that environment (the settings of docs/contributing.md, "Headless settings").
    headless = dict(clean_env, PYVISTA_JUPYTER_BACKEND="static", VTK_DEFAULT_OPENGL_WINDOW="vtkEGLRenderWindow",
                    VTK_WASM_DIR_OVERRIDE=str(tmp_path / "wasm"), JUPYTER_PLATFORM_DIRS="1")
    (tmp_path / "wasm").mkdir()
    run([environment / "bin" / "jupyter", "nbconvert", "--to", "notebook", "--execute",
         "--ExecutePreprocessor.timeout=600", "--output", "ran.ipynb", destination / CHAPTERS[0]],
        timeout=900, cwd=destination, env=headless)
    ran = json.loads((destination / "ran.ipynb").read_text(encoding="utf-8"))
    outputs = [output for cell in ran["cells"] if cell["cell_type"] == "code" for output in cell["outputs"]]
    assert outputs and not [output for output in outputs if output["output_type"] == "error"]


@pytest.mark.parametrize("name", ["setup.py", "MANIFEST.in"])
def test_the_sdist_and_wheel_build_files_name_the_notebooks(name):
    assert "notebooks" in (ROOT / name).read_text(encoding="utf-8")


# ----------------------------------------------------------------- errata: version and --update

def test_each_copied_chapter_is_stamped_with_the_package_version(tmp_path):
    import halfedge_edu

    result = course.copy_course(tmp_path)
    assert result.version == halfedge_edu.__version__
    for name in CHAPTERS:
        notebook = json.loads((tmp_path / name).read_text(encoding="utf-8"))
        stamp = notebook["metadata"]["halfedge_edu"]["course"]
        assert stamp["version"] == halfedge_edu.__version__
        assert stamp["cells_sha256"] == course.cells_digest(notebook)
        title = next(cell for cell in notebook["cells"] if cell["cell_type"] == "markdown")
        assert f"halfedge_edu {halfedge_edu.__version__}" in course._source_text(title).split("\n", 3)[2], name


@pytest.fixture()
def next_release(tmp_path, monkeypatch):
    """The course copied by this version into tmp_path/course; then the installed package
    becomes version 9.9.9, whose chapter 00 has an erratum."""
    destination = tmp_path / "course"
    course.copy_course(destination)
    newer = tmp_path / "newer"
    newer.mkdir()
    for name in CHAPTERS:
        notebook = json.loads((STUDENT / name).read_text(encoding="utf-8"))
        if name == CHAPTERS[0]:
            notebook["cells"].append({"cell_type": "markdown", "id": "erratum", "metadata": {},
                                      "source": ["Erratum: the fixed sentence.\n"]})
        (newer / name).write_text(json.dumps(notebook), encoding="utf-8")
    monkeypatch.setattr(course, "chapter_source", lambda: newer)
    monkeypatch.setattr(course, "package_version", lambda: "9.9.9")
    return destination


def has_erratum(path: Path) -> bool:
    return "Erratum: the fixed sentence." in path.read_text(encoding="utf-8")


def test_a_rerun_without_update_keeps_older_chapters_and_says_update_brings_the_new_ones(next_release, capsys):
    assert cli.main(["course", str(next_release)]) == cli.EXIT_OK
    assert not has_erratum(next_release / CHAPTERS[0])
    out = capsys.readouterr().out
    assert f"kept {len(CHAPTERS)} from another version" in out and "--update" in out and "9.9.9" in out


def test_update_replaces_a_chapter_nobody_edited(next_release, capsys):
    # Running cells changes outputs, not sources: still "not edited".
    chapter = next_release / CHAPTERS[0]
    notebook = json.loads(chapter.read_text(encoding="utf-8"))
    code = next(cell for cell in notebook["cells"] if cell["cell_type"] == "code")
    code["outputs"], code["execution_count"] = [{"output_type": "stream", "name": "stdout", "text": ["ran\n"]}], 1
    chapter.write_text(json.dumps(notebook), encoding="utf-8")

    assert cli.main(["course", str(next_release), "--update"]) == cli.EXIT_OK
    assert has_erratum(chapter)
    updated = json.loads(chapter.read_text(encoding="utf-8"))
    assert updated["metadata"]["halfedge_edu"]["course"]["version"] == "9.9.9"
    assert f"updated {len(CHAPTERS)} unedited chapters to 9.9.9" in capsys.readouterr().out
    assert sorted(p.name for p in next_release.iterdir()) == CHAPTERS


def test_update_keeps_an_edited_chapter_and_writes_the_newer_one_beside_it(next_release, capsys):
    chapter = next_release / CHAPTERS[0]
    notebook = json.loads(chapter.read_text(encoding="utf-8"))
    code = next(cell for cell in notebook["cells"] if cell["cell_type"] == "code")
    code["source"] = "my_answer = 42\n"
    mine = json.dumps(notebook, indent=1)
    chapter.write_text(mine, encoding="utf-8")

    assert cli.main(["course", str(next_release), "--update"]) == cli.EXIT_OK
    assert chapter.read_text(encoding="utf-8") == mine
    beside = next_release / f"{chapter.stem}-9.9.9.ipynb"
    assert has_erratum(beside)
    out = capsys.readouterr().out
    assert f"{CHAPTERS[0]} has your edits and was kept; the 9.9.9 version is beside it: {beside.name}" in out
    # A second --update changes nothing more.
    before = {p.name: p.read_bytes() for p in next_release.iterdir()}
    assert cli.main(["course", str(next_release), "--update"]) == cli.EXIT_OK
    assert {p.name: p.read_bytes() for p in next_release.iterdir()} == before


# ---------------------------------------------- never half a chapter, never outside DEST (issue 25)

def test_a_truncated_chapter_is_repaired_on_a_rerun_and_the_broken_file_kept_aside(tmp_path, capsys):
    course.copy_course(tmp_path)
    chapter = tmp_path / CHAPTERS[3]
    whole = chapter.read_bytes()
    chapter.write_bytes(whole[: len(whole) // 2])        # what kill -9 or a full disk left before
    work = tmp_path / CHAPTERS[4]
    mine = students_work(work)

    assert cli.main(["course", str(tmp_path)]) == cli.EXIT_OK
    assert chapter.read_bytes() == whole
    assert (tmp_path / f"{CHAPTERS[3]}.broken").read_bytes() == whole[: len(whole) // 2]
    assert work.read_bytes() == mine
    assert f"{CHAPTERS[3]} was not a valid notebook; copied it again" in capsys.readouterr().out


@pytest.mark.parametrize("kind", ["dangling", "loop", "to a file outside"])
def test_a_symbolic_link_in_dest_is_never_followed_and_the_other_chapters_are_copied(tmp_path, capsys, kind):
    destination, outside = tmp_path / "course", tmp_path / "outside"
    destination.mkdir()
    outside.mkdir()
    link = destination / CHAPTERS[2]
    if kind == "dangling":
        link.symlink_to(outside / "stolen.ipynb")
    elif kind == "loop":
        link.symlink_to(link.name)
    else:
        (outside / "notes.ipynb").write_text("not a notebook", encoding="utf-8")
        link.symlink_to(outside / "notes.ipynb")

    assert cli.main(["course", str(destination)]) == cli.EXIT_ERROR
    assert link.is_symlink()
    assert sorted(p.name for p in outside.iterdir()) == ([] if kind != "to a file outside" else ["notes.ipynb"])
    if kind == "to a file outside":
        assert (outside / "notes.ipynb").read_text(encoding="utf-8") == "not a notebook"
    copied = sorted(p.name for p in destination.iterdir() if not p.is_symlink())
    assert copied == [name for name in CHAPTERS if name != CHAPTERS[2]]
    captured = capsys.readouterr()
    assert f"copied {len(CHAPTERS) - 1} chapters" in captured.out
    (line,) = captured.err.splitlines()
    assert line.startswith("halfedge-edu: error: ") and CHAPTERS[2] in line and "symbolic link" in line


def test_a_chapter_that_cannot_be_read_is_skipped_with_a_message_and_the_rest_copied(tmp_path, monkeypatch):
    real_read = Path.read_text

    def read_text(path, *args, **kwargs):
        if path.name == CHAPTERS[5]:
            raise PermissionError(13, "Permission denied", str(path))
        return real_read(path, *args, **kwargs)

    monkeypatch.setattr(Path, "read_text", read_text)
    result = course.copy_course(tmp_path)
    assert result.skipped == ((CHAPTERS[5], "Permission denied"),)
    assert len(result.copied) == len(CHAPTERS) - 1
    assert not (tmp_path / CHAPTERS[5]).exists()


def test_a_write_that_fails_midway_leaves_no_partial_chapter_and_no_temporary_file(tmp_path, monkeypatch):
    real_fsync = os.fsync

    def fsync(descriptor):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(course.os, "fsync", fsync)
    result = course.copy_course(tmp_path)
    monkeypatch.setattr(course.os, "fsync", real_fsync)
    assert [reason for _, reason in result.skipped] == ["No space left on device"] * len(CHAPTERS)
    assert list(tmp_path.iterdir()) == []


def test_a_file_size_limit_cuts_no_chapter_and_a_rerun_copies_them_all(tmp_path):
    """The command line under a 20 KB file-size limit (ulimit -f): the chapters larger than
    that are skipped whole with a message each, never left truncated; a rerun without the
    limit copies them, with nothing to repair."""
    destination = tmp_path / "course"
    limited = (
        "import resource, signal, sys\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))\n"
        "from halfedge_edu.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    run = subprocess.run([sys.executable, "-c", limited, "course", str(destination)],
                         capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert run.returncode == cli.EXIT_ERROR, run.stderr
    too_large = [line for line in run.stderr.splitlines() if "not copied: File too large" in line]
    assert too_large and len(too_large) == len(run.stderr.splitlines()), run.stderr
    present = sorted(p.name for p in destination.iterdir())
    assert len(present) == len(CHAPTERS) - len(too_large)
    for name in present:
        assert_is_a_clean_chapter(destination / name)

    rerun = subprocess.run([sys.executable, "-m", "halfedge_edu", "course", str(destination)],
                           capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert rerun.returncode == cli.EXIT_OK, rerun.stderr
    assert f"copied {len(too_large)} chapters" in rerun.stdout and "not a valid notebook" not in rerun.stdout
    assert sorted(p.name for p in destination.iterdir()) == CHAPTERS
