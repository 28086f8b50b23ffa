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
