"""Print pip constraints that pin each direct requirement to its lowest allowed version.

    python constraints/lowest.py [EXTRA ...] > lowest.txt     (default extra: notebooks)

The library's dependencies and the named extras of pyproject.toml, each ``name==floor``
where ``floor`` is its ``>=`` bound (a requirement without one is left out: pip picks
it). ``make test-lowest`` installs with these constraints and runs the library tests and
one chapter, so that a floor in pyproject.toml is a version that was seen to work, not a
guess. Standard library only (Python 3.11+ for tomllib, like `make test-lowest`).
"""

from __future__ import annotations

import re
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# name[extras] then the version specifiers; markers are not used in pyproject.toml.
REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9_.\-]+)(\[[^\]]*\])?\s*(.*)$")


def floors(extras: list[str]) -> dict[str, str]:
    """{name: lowest allowed version} for the core requirements and ``extras``."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    lines = list(project["dependencies"])
    for extra in extras:
        lines += project["optional-dependencies"][extra]
    found = {}
    for line in lines:
        name, _, specifiers = REQUIREMENT.match(line).groups()
        if name.replace("-", "_").lower() == project["name"].lower():
            continue
        lowest = [spec[2:].strip() for spec in specifiers.split(",") if spec.strip().startswith(">=")]
        if lowest:
            found[name.lower()] = lowest[0]
    return found


if __name__ == "__main__":
    for name, version in floors(sys.argv[1:] or ["notebooks"]).items():
        print(f"{name}=={version}")
