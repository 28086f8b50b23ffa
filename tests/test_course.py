"""`halfedge-edu course DEST`: the chapters' student edition, without outputs, out of the installed package.

The last test is the promise a pip user relies on: a wheel built from this checkout,
installed into a fresh virtual environment (no editable install, no repository beside
it), copies all the chapters. It builds the wheel and the venv, so it takes 20-40 s.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
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


def test_course_command_never_overwrites_a_students_work(tmp_path, capsys):
    work = tmp_path / CHAPTERS[0]
    work.write_text("my answers", encoding="utf-8")
    assert cli.main(["course", str(tmp_path)]) == cli.EXIT_OK
    assert work.read_text(encoding="utf-8") == "my answers"
    assert f"kept 1 already there: {CHAPTERS[0]}" in capsys.readouterr().out
    assert len(list(tmp_path.glob(course.CHAPTER_GLOB))) == len(CHAPTERS)


def test_course_into_a_file_is_one_line_error(tmp_path, capsys):
    not_a_folder = tmp_path / "notes.txt"
    not_a_folder.write_text("x", encoding="utf-8")
    assert cli.main(["course", str(not_a_folder)]) == cli.EXIT_ERROR
    err = capsys.readouterr().err
    assert err.startswith("halfedge-edu: error: ") and "notes.txt" in err and "not a folder" in err
    assert err.count("\n") == 1


def test_course_from_a_wheel_in_a_fresh_venv(tmp_path):
    wheels = tmp_path / "wheels"
    build = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", str(wheels), str(ROOT)],
        capture_output=True, text=True, timeout=300,
    )
    assert build.returncode == 0, build.stderr[-3000:]
    (wheel,) = wheels.glob("halfedge_edu-*.whl")

    # Without PYTHONPATH: it may point at this checkout, which pip would take for an install.
    clean_env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    environment = tmp_path / "venv"
    venv.create(environment, with_pip=True)
    python = environment / "bin" / "python"
    install = subprocess.run(
        [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
         "--no-deps", str(wheel), "numpy", "scipy", "trimesh"],
        capture_output=True, text=True, timeout=300, env=clean_env,
    )
    assert install.returncode == 0, install.stderr[-3000:]

    destination = tmp_path / "x"
    # Run from tmp_path so that neither this checkout nor its notebooks/ can be found.
    run = subprocess.run(
        [str(environment / "bin" / "halfedge-edu"), "course", str(destination)],
        capture_output=True, text=True, timeout=120, cwd=tmp_path, env=clean_env,
    )
    assert run.returncode == 0, run.stderr
    where = subprocess.run(
        [str(python), "-c", "import halfedge_edu.course as c; print(c.chapter_source())"],
        capture_output=True, text=True, timeout=120, cwd=tmp_path, env=clean_env,
    )
    assert str(environment) in where.stdout, f"chapters did not come from the wheel: {where.stdout}{where.stderr}"
    assert sorted(p.name for p in destination.iterdir()) == CHAPTERS
    for path in destination.iterdir():
        assert_is_a_clean_chapter(path)
    module = subprocess.run(
        [str(python), "-m", "halfedge_edu", "course", str(tmp_path / "y")],
        capture_output=True, text=True, timeout=120, cwd=tmp_path, env=clean_env,
    )
    assert module.returncode == 0, module.stderr
    assert sorted(p.name for p in (tmp_path / "y").iterdir()) == CHAPTERS


@pytest.mark.parametrize("name", ["setup.py", "MANIFEST.in"])
def test_the_sdist_and_wheel_build_files_name_the_notebooks(name):
    assert "notebooks" in (ROOT / name).read_text(encoding="utf-8")
