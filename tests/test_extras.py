"""Without the notebooks extra, `import halfedge_edu.viz` says which pip command to run.

Each case runs in a fresh interpreter in which a module is made unimportable the way
Python itself blocks one (``sys.modules[name] = None``), as if it were not installed.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pytest itself depends on tomli before 3.11
    import tomli as tomllib

import pytest
from packaging.requirements import Requirement

from halfedge_edu import _extras

ROOT = Path(__file__).resolve().parents[1]
INSTALL_HINT = 'pip install "halfedge_edu[notebooks]"'


def import_viz_without(*blocked: str) -> subprocess.CompletedProcess:
    code = (
        "import sys\n"
        f"for name in {blocked!r}:\n"
        "    sys.modules[name] = None\n"
        "try:\n"
        "    import halfedge_edu.viz\n"
        "except ModuleNotFoundError as error:\n"
        "    print(type(error).__name__, error.name)\n"
        "    print(error)\n"
        "else:\n"
        "    print('imported')\n"
    )
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)


@pytest.mark.parametrize("blocked", [("pyvista",), ("ipywidgets",), ("pyvista", "ipywidgets")])
def test_viz_without_the_notebooks_extra_names_the_extra(blocked):
    result = import_viz_without(*blocked)
    assert result.returncode == 0, result.stderr
    kind, message = result.stdout.splitlines()
    assert kind == f"MissingExtraError {blocked[0]}"
    assert INSTALL_HINT in message
    assert all(name in message for name in blocked)


def test_viz_imports_with_the_extra_installed():
    result = import_viz_without()
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "imported"


def test_missing_extra_error_is_caught_as_module_not_found():
    assert issubclass(_extras.MissingExtraError, ModuleNotFoundError)
    assert issubclass(_extras.MissingExtraError, ImportError)


def test_every_extra_module_is_a_requirement_of_that_extra_in_pyproject():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    for extra, modules in _extras.EXTRA_MODULES.items():
        names = {Requirement(line).name.lower() for line in extras[extra]}
        assert set(modules) <= names, f"{extra}: {sorted(set(modules) - names)} not in the extra"


# ------------------------------------------- the command line names the extra (issue 27)

def run_cli_without(blocked: tuple[str, ...], *arguments: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    """``halfedge-edu ARGUMENTS`` in a fresh interpreter in which ``blocked`` cannot be imported."""
    code = (
        "import sys\n"
        f"for name in {blocked!r}:\n"
        "    sys.modules[name] = None\n"
        "from halfedge_edu.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    return subprocess.run([sys.executable, "-c", code, *arguments], capture_output=True, text=True,
                          cwd=cwd, timeout=120)


def test_a_command_missing_a_module_of_the_notebooks_extra_names_the_extra_not_an_internal_error(capsys):
    """What ``grade`` gave without the notebooks extra: "internal error (ModuleNotFoundError
    ...)". Any command that meets a module an extra brings now names the extra."""
    import argparse

    from halfedge_edu import cli

    def needs_nbclient(args):
        raise ModuleNotFoundError("No module named 'nbclient'", name="nbclient")

    args = argparse.Namespace(run=needs_nbclient, command="grade", debug=False, file=None)
    assert cli._run(args) == cli.EXIT_ERROR
    (line,) = capsys.readouterr().err.splitlines()
    assert line == f"halfedge-edu: error: grade needs nbclient, which is not installed: {INSTALL_HINT}"


def test_a_missing_module_no_extra_brings_is_still_an_internal_error(capsys):
    import argparse

    from halfedge_edu import cli

    def needs_something_else(args):
        raise ModuleNotFoundError("No module named 'left_pad'", name="left_pad")

    args = argparse.Namespace(run=needs_something_else, command="grade", debug=False, file=None)
    assert cli._run(args) == cli.EXIT_ERROR
    assert "internal error" in capsys.readouterr().err


TETRAHEDRON = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"


def test_progress_without_tqdm_names_the_extra(tmp_path):
    (tmp_path / "in.obj").write_text(TETRAHEDRON)
    result = run_cli_without(("tqdm",), "smooth", str(tmp_path / "in.obj"),
                             str(tmp_path / "out.obj"), "--progress")
    assert result.returncode == 2, result.stderr
    (line,) = result.stderr.splitlines()
    assert line == f"halfedge-edu: error: --progress needs tqdm, which is not installed: {INSTALL_HINT}"
    assert not (tmp_path / "out.obj").exists()


def test_without_tqdm_the_default_simply_draws_no_bar(tmp_path):
    (tmp_path / "in.obj").write_text(TETRAHEDRON)
    result = run_cli_without(("tqdm",), "smooth", str(tmp_path / "in.obj"),
                             str(tmp_path / "out.obj"))
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "out.obj").exists()


def test_every_module_the_command_line_names_comes_with_its_extra():
    for extra, modules in _extras.BROUGHT_MODULES.items():
        for module in modules:
            assert _extras.extra_for(module) == extra
    assert _extras.extra_for("pyvista.plotting") == "notebooks"
    assert _extras.extra_for("numpy") is None
