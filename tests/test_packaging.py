"""The packaging promises: one dependency list in two files, a light import, the
README's two commands, and CI running exactly what the README says.
"""

from __future__ import annotations

import fnmatch
import re
import subprocess
import sys
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

import pytest
import yaml
from packaging.requirements import Requirement
from packaging.specifiers import SpecifierSet

if sys.version_info >= (3, 11):
    import tomllib
else:  # pytest itself depends on tomli before 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
PROJECT = PYPROJECT["project"]
# Each conda file and the pyproject.toml extras it must list, no more and no fewer:
# students get the notebooks only, contributors everything.
ENVIRONMENT_FILES = {
    "environment.yml": ("notebooks",),
    "environment-dev.yml": ("notebooks", "dev", "docs", "hub", "bench"),
}
README = (ROOT / "README.md").read_text()

EXTRAS = ("notebooks", "dev", "docs", "hub", "bench")
# Imported by the notebooks and widgets only; `import halfedge_edu` must not pull them in.
PLOTTING_MODULES = ("pyvista", "vtk", "vtkmodules", "trame", "trame_pyvista", "ipywidgets", "matplotlib")


def normalise(name: str) -> str:
    """PEP 503 name: lower case, runs of -_. as one dash."""
    return re.sub(r"[-_.]+", "-", name).lower()


def pyproject_requirements(extras: tuple[str, ...] = EXTRAS) -> dict[str, SpecifierSet]:
    """Core and the given extras, by normalised name (the self-reference left out)."""
    lines = list(PROJECT["dependencies"])
    for extra in extras:
        lines += PROJECT["optional-dependencies"][extra]
    found = {}
    for line in lines:
        requirement = Requirement(line)
        if normalise(requirement.name) != normalise(PROJECT["name"]):
            found[normalise(requirement.name)] = requirement.specifier
    return found


def load_environment(filename: str) -> dict:
    return yaml.safe_load((ROOT / filename).read_text())


def environment_requirements(filename: str) -> tuple[dict[str, SpecifierSet], dict[str, SpecifierSet]]:
    """(conda, pip) packages of a conda environment file by normalised name; pip options skipped."""
    conda, pip = {}, {}
    for entry in load_environment(filename)["dependencies"]:
        if isinstance(entry, dict):
            for line in entry["pip"]:
                if not line.startswith("-"):
                    requirement = Requirement(line)
                    pip[normalise(requirement.name)] = requirement.specifier
        else:
            name, spec = re.fullmatch(r"([A-Za-z0-9_.\-]+)\s*(.*)", entry).groups()
            conda[normalise(name)] = SpecifierSet(spec)
    return conda, pip


@pytest.mark.parametrize("filename", ENVIRONMENT_FILES)
def test_every_pyproject_dependency_is_in_the_environment_file_with_the_same_bounds(filename):
    conda, pip = environment_requirements(filename)
    in_environment = {**conda, **pip}
    wanted = pyproject_requirements(ENVIRONMENT_FILES[filename])
    missing = sorted(set(wanted) - set(in_environment))
    assert not missing, f"add to {filename}: {missing}"
    differ = {name: (str(wanted[name]), str(in_environment[name])) for name in wanted if wanted[name] != in_environment[name]}
    assert not differ, f"bounds differ (pyproject, {filename}): {differ}"


@pytest.mark.parametrize("filename", ENVIRONMENT_FILES)
def test_environment_file_lists_nothing_that_its_extras_lack(filename):
    conda, pip = environment_requirements(filename)
    extra = sorted((set(conda) | set(pip)) - set(pyproject_requirements(ENVIRONMENT_FILES[filename])) - {"python", "pip"})
    assert not extra, f"in {filename} but not in pyproject.toml's {ENVIRONMENT_FILES[filename]}: {extra}"


@pytest.mark.parametrize("filename", ENVIRONMENT_FILES)
def test_environment_file_python_matches_requires_python(filename):
    conda, _ = environment_requirements(filename)
    assert conda["python"] == SpecifierSet(PROJECT["requires-python"])


@pytest.mark.parametrize("filename", ENVIRONMENT_FILES)
def test_environment_file_installs_this_package(filename):
    pip_lines = next(e["pip"] for e in load_environment(filename)["dependencies"] if isinstance(e, dict))
    assert "-e ." in pip_lines


def test_environment_files_have_different_names():
    names = [load_environment(filename)["name"] for filename in ENVIRONMENT_FILES]
    assert len(set(names)) == len(names), names


def test_students_environment_has_no_contributor_tools():
    conda, pip = environment_requirements("environment.yml")
    contributor_only = set(pyproject_requirements(("dev", "docs", "bench"))) - set(pyproject_requirements(("notebooks",)))
    assert not (set(conda) | set(pip)) & contributor_only


def test_dev_extra_includes_the_notebooks_docs_and_hub_extras():
    assert "halfedge_edu[notebooks,docs,hub]" in PROJECT["optional-dependencies"]["dev"]


def test_import_does_not_load_the_plotting_stack():
    code = (
        "import sys, halfedge_edu\n"
        f"loaded = sorted(m for m in sys.modules if m.split('.')[0] in {PLOTTING_MODULES!r})\n"
        "print(' '.join(loaded))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "", f"`import halfedge_edu` imported: {result.stdout.strip()}"


def test_console_script_points_at_the_cli():
    try:
        scripts = distribution("halfedge_edu").entry_points
    except PackageNotFoundError:
        pytest.fail("halfedge_edu is not installed: run `make test` (or pip install -e '.[dev]')")
    script = {ep.name: ep.value for ep in scripts if ep.group == "console_scripts"}
    assert script.get("halfedge-edu") == "halfedge_edu.cli:main"


def test_package_data_covers_every_bundled_data_file():
    globs = PYPROJECT["tool"]["setuptools"]["package-data"]["halfedge_edu"]
    data = ROOT / "halfedge_edu" / "data"
    files = [p for p in data.rglob("*") if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".py"]
    unshipped = [
        str(p.relative_to(data.parent))
        for p in files
        if not any(fnmatch.fnmatch(str(p.relative_to(data.parent)), g) for g in globs)
    ]
    assert not unshipped, f"not in [tool.setuptools.package-data]: {unshipped}"


def test_pytest_does_not_spread_notebook_cells_over_xdist_workers():
    addopts = PYPROJECT["tool"]["pytest"]["ini_options"]["addopts"]
    assert "--nbval" in addopts
    assert not any(opt == "-n" or opt.startswith(("-n=", "--numprocesses")) for opt in addopts)


def readme_section(title: str) -> str:
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", README, flags=re.M | re.S)
    assert match, f"README has no '## {title}' section"
    return match.group(1)


def test_readme_quickstart_is_exactly_make_lab_and_make_test():
    blocks = re.findall(r"```\w*\n(.*?)```", readme_section("Quickstart"), flags=re.S)
    commands = [line.strip() for block in blocks for line in block.splitlines() if line.strip()]
    assert commands == ["make lab", "make test"]


def test_ci_runs_exactly_the_readme_test_command():
    script = (ROOT / ".ci" / "run").read_text().splitlines()
    assert script[0].startswith("#!") and "bash" in script[0]
    assert "set -euo pipefail" in script
    commands = [line.strip() for line in script[1:] if line.strip() and not line.lstrip().startswith("#")]
    assert commands[-1] == "make test"


def test_readme_chapter_table_matches_the_notebooks_folder():
    rows = [line for line in readme_section("Chapters").splitlines() if line.startswith("|")]
    linked = {}
    for row in rows:
        target = re.search(r"\]\((notebooks/\d\d[a-z]?_\w+\.ipynb)\)", row)
        if target:
            linked[target.group(1)] = row
    numbers = [Path(p).name.split("_")[0] for p in linked]
    # Chapters 00-13, in order; a lettered chapter (08b, the debugging lab) follows its number.
    assert [int(n[:2]) for n in numbers if n.isdigit()] == list(range(14)), "chapters 00-13, in order"
    assert numbers == sorted(numbers), f"chapters out of order: {numbers}"
    on_disk = {f"notebooks/{p.name}" for p in (ROOT / "notebooks").glob("*.ipynb")}
    assert not on_disk - set(linked), f"notebooks missing from the README table: {sorted(on_disk - set(linked))}"
    not_there = [p for p, row in linked.items() if p not in on_disk and "in progress" not in row]
    assert not not_there, f"README links these as ready, but they do not exist: {not_there}"


def test_nbval_sanitize_patterns_hide_only_what_changes_between_runs():
    from nbval.plugin import get_sanitize_patterns

    patterns = get_sanitize_patterns((ROOT / "nbval_sanitize.cfg").read_text())
    assert len(patterns) >= 3

    def sanitize(text: str) -> str:
        for regex, replace in patterns:
            text = re.sub(regex, replace, text)
        return text

    same = [
        ("<PIL.Image.Image image mode=RGB size=1024x768 at 0x7F4A0C2B3D90>",
         "<PIL.Image.Image image mode=RGB size=1024x768 at 0x7F11AA22BB33>"),
        ('<iframe src="http://localhost:41233/index.html?ui=P_0x7f3a1c2b5d90_0&reconnect=auto">',
         '<iframe src="http://localhost:38001/index.html?ui=P_0x7f99e0e0e0e0_3&reconnect=auto">'),
        ("100%|##########| 12/12 [00:01<00:00,  9.87it/s]", "100%|##########| 12/12 [00:03<00:00,  3.21it/s]"),
        ("1.23 ms ± 45.6 µs per loop (mean ± std. dev. of 7 runs, 1,000 loops each)",
         "980 µs ± 12 µs per loop (mean ± std. dev. of 7 runs, 1,000 loops each)"),
    ]
    for first, second in same:
        assert sanitize(first) == sanitize(second), (first, second)

    different = [
        ("vertices: 8, faces: 12", "vertices: 8, faces: 14"),
        ("100%|##########| 12/12 [00:01<00:00,  9.87it/s]", "100%|##########| 11/12 [00:01<00:00,  9.87it/s]"),
        ("size=1024x768", "size=1280x768"),
        ("flag 0x1F", "flag 0x2F"),
    ]
    for first, second in different:
        assert sanitize(first) != sanitize(second), (first, second)


# ------------------------------------------------------------------ true floors (issue 27)

def test_vtk_floor_excludes_the_versions_whose_headless_rendering_aborts():
    vtk = pyproject_requirements(("notebooks",))["vtk"]
    assert "9.3.1" not in vtk and "9.4.1" not in vtk and "9.4.2" in vtk


def test_pillow_is_declared_with_the_floor_chapter_07_needs():
    pillow = pyproject_requirements(("notebooks",))["pillow"]
    assert "10.0.1" not in pillow and "10.1.0" in pillow


def test_lowest_constraints_pin_every_floor_of_the_notebooks_extra():
    lowest = subprocess.run([sys.executable, str(ROOT / "constraints" / "lowest.py"), "notebooks"],
                            capture_output=True, text=True, check=True).stdout.split()
    pins = dict(line.split("==") for line in lowest)
    floors = pyproject_requirements(("notebooks",))
    assert set(pins) == {name for name, spec in floors.items() if any(s.operator == ">=" for s in spec)}
    for name, version in pins.items():
        assert version in floors[name], f"{name}=={version} is not allowed by pyproject.toml"
    assert pins["vtk"] == "9.4.2" and pins["pillow"] == "10.1"


def make_dry_run(target: str, tmp_path: Path) -> str:
    """What `make TARGET` would run in a clone without a virtual environment yet."""
    return subprocess.run(["make", "-n", target, f"VENV={tmp_path / 'venv'}"], cwd=ROOT,
                          capture_output=True, text=True, check=True).stdout


def test_make_lab_installs_the_notebooks_extra_not_the_developers_tools(tmp_path):
    lab = make_dry_run("lab", tmp_path)
    assert 'install -e ".[notebooks]"' in lab
    assert ".[dev" not in lab


def test_make_test_installs_the_dev_extra(tmp_path):
    assert 'install -e ".[dev]"' in make_dry_run("test", tmp_path)


def test_make_dist_builds_both_and_checks_their_metadata(tmp_path):
    dist = make_dry_run("dist", tmp_path)
    assert "-m build" in dist and "twine check --strict dist/*" in dist


# ----------------------------------------------- install lines that work as written (issue 27)

INSTALL_DOCS = ("README.md", "docs/index.md", "docs/deploying.md")
# `pip install` of the package by name, from the package index (not a wheel file, not a path).
INDEX_INSTALL = re.compile(r"pip install [\"']?halfedge_edu(\[[a-z,]+\])?[\"']?(?![-\w.])")


@pytest.mark.parametrize("name", INSTALL_DOCS)
def test_an_install_from_the_package_index_is_only_shown_as_what_works_once_published(name):
    """The package is not on the index: a line that installs it from there fails ("No
    matching distribution found"). Each paragraph that shows one says so."""
    text = (ROOT / name).read_text(encoding="utf-8")
    paragraphs = re.split(r"\n\s*\n", text)
    unmarked = [paragraph.strip()[:120] for paragraph in paragraphs
                if INDEX_INSTALL.search(paragraph) and "published" not in paragraph]
    assert not unmarked, f"{name}: an index install line not marked as working once published: {unmarked}"


def test_the_wheel_install_line_names_the_wheel_make_dist_builds():
    version = PROJECT["version"]
    for name in ("README.md", "docs/index.md"):
        text = (ROOT / name).read_text(encoding="utf-8")
        assert f'pip install "halfedge_edu-{version}-py3-none-any.whl[notebooks]"' in text, name
