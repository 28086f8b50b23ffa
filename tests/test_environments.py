"""The semester lock and the README on the package index.

- constraints/*.txt pins every package `make test` installs, each pin inside
  pyproject.toml's bounds, and (when `make test` installed with it, which it records for
  HALFEDGE_EDU_LOCK) the environment running these tests is exactly the lock.
- README.md's relative links name files that exist, and setup.py makes them absolute
  under ``[project.urls] Repository`` for the package index.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.version import Version

if sys.version_info >= (3, 11):
    import tomllib
else:  # pytest itself depends on tomli before 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
LOCKS = sorted((ROOT / "constraints").glob("*.txt"))
# What `make test` installs (the dev extra pulls in notebooks, docs and hub); bench floats.
LOCKED_EXTRAS = ("notebooks", "dev", "docs", "hub")


def normalise(name: str) -> str:
    """PEP 503 name: lower case, runs of -_. as one dash."""
    return re.sub(r"[-_.]+", "-", name).lower()


def requirements(extras: tuple[str, ...]) -> dict[str, Requirement]:
    lines = list(PROJECT["dependencies"]) + [line for extra in extras for line in PROJECT["optional-dependencies"][extra]]
    found = {normalise(Requirement(line).name): Requirement(line) for line in lines}
    found.pop(normalise(PROJECT["name"]))
    return found


def read_lock(path: Path) -> dict[str, Version]:
    """name -> pinned version; fails on anything but `name==version` lines and comments."""
    pins = {}
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        match = re.fullmatch(r"([A-Za-z0-9][A-Za-z0-9._-]*)==([^\s;]+)", line)
        assert match, f"{path.name}:{number}: not a name==version pin: {line!r}"
        pins[normalise(match.group(1))] = Version(match.group(2))
    return pins


def load_setup_py():
    """setup.py as a module (its setup() call only runs as __main__)."""
    spec = importlib.util.spec_from_file_location("halfedge_edu_setup", ROOT / "setup.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_there_is_a_lock_and_the_makefile_uses_it_by_default():
    assert LOCKS, "no constraints/*.txt"
    makefile = (ROOT / "Makefile").read_text()
    semester = re.search(r"^SEMESTER \?= (\S+)$", makefile, flags=re.M).group(1)
    assert ROOT / "constraints" / f"{semester}.txt" in LOCKS
    assert re.search(r"^LOCK \?= constraints/\$\(SEMESTER\)\.txt$", makefile, flags=re.M)
    assert '-c "$(LOCK)"' in makefile


@pytest.mark.parametrize("lock", LOCKS, ids=[p.name for p in LOCKS])
def test_lock_pins_everything_make_test_installs_within_pyprojects_bounds(lock):
    pins = read_lock(lock)
    assert normalise(PROJECT["name"]) not in pins, "the lock must not pin halfedge_edu itself"
    wanted = requirements(LOCKED_EXTRAS)
    unpinned = sorted(set(wanted) - set(pins))
    assert not unpinned, f"{lock.name} does not pin {unpinned}: run `make lock` after `make test` passes"
    outside = {name: (str(pins[name]), str(req.specifier)) for name, req in wanted.items() if pins[name] not in req.specifier}
    assert not outside, f"{lock.name} pins outside pyproject.toml's bounds: {outside}"


def test_this_environment_is_the_lock_it_was_installed_with():
    """`make test` passes the lock it installed with; a bare pytest checks the bounds instead."""
    lock = os.environ.get("HALFEDGE_EDU_LOCK", "")
    wanted = requirements(LOCKED_EXTRAS)
    installed = {}
    for name in wanted:
        try:
            installed[name] = Version(version(name))
        except PackageNotFoundError:
            pytest.fail(f"{name} is not installed: run `make test` (it installs the dev extra)")
    if lock:
        pins = read_lock(ROOT / lock)
        differ = {name: (str(installed[name]), str(pins[name])) for name in wanted if installed[name] != pins[name]}
        assert not differ, f"installed differs from {lock} (installed, pinned): {differ}"
    else:
        outside = {name: str(installed[name]) for name, req in wanted.items() if installed[name] not in req.specifier}
        assert not outside, f"installed versions outside pyproject.toml's bounds: {outside}"


def test_every_upper_bound_says_why():
    """Each requirement with an upper bound has a comment line right above it in pyproject.toml."""
    lines = (ROOT / "pyproject.toml").read_text().splitlines()
    bounded = [i for i, line in enumerate(lines) if re.match(r'\s*"[^"]*<[^"]*",', line)]
    assert bounded, "no upper bounds in pyproject.toml"
    unexplained = [lines[i].strip() for i in bounded if not lines[i - 1].strip().startswith("#")]
    assert not unexplained, f"upper bounds without a comment saying why: {unexplained}"


README = (ROOT / "README.md").read_text(encoding="utf-8")


def test_every_relative_readme_link_names_a_file_in_the_repository():
    setup_py = load_setup_py()
    targets = [m.group(3) for m in setup_py.MARKDOWN_LINK.finditer(README)]
    relative = [t for t in targets if setup_py.is_relative(t)]
    assert relative, "the README links no files: the check below would prove nothing"
    missing = [t for t in relative if not (ROOT / t.split("#")[0]).exists()]
    assert not missing, f"README links files that do not exist: {missing}"


def test_readme_for_the_package_index_has_only_absolute_links():
    setup_py = load_setup_py()
    repository = "https://github.com/a-course/halfedge_edu"
    rewritten = setup_py.readme_for_index(README, repository)
    targets = [m.group(3) for m in setup_py.MARKDOWN_LINK.finditer(rewritten)]
    assert targets and not [t for t in targets if setup_py.is_relative(t)]
    assert f"{repository}/raw/main/figures/navigation.png" in rewritten
    assert f"{repository}/blob/main/notebooks/03_navigating.ipynb" in rewritten
    assert setup_py.readme_for_index("[a](#speed) [b](https://x.org/y)", repository) == "[a](#speed) [b](https://x.org/y)"


def test_no_made_up_address_is_published():
    """The repository's address comes from whoever builds for the index
    ($HALFEDGE_EDU_REPOSITORY); without it the README stays as written and the package
    names no URL, rather than a placeholder."""
    assert "urls" not in PROJECT and "urls" in PROJECT["dynamic"]
    for name in ("pyproject.toml", "setup.py", "README.md", "docs/index.md"):
        assert "example.org" not in (ROOT / name).read_text(encoding="utf-8"), name
    setup_py = load_setup_py()
    assert setup_py.readme_for_index(README, "") == README
