"""The README's links and the docs' module list are true: the front door leads somewhere.

* Every link and image in README.md (and the other pages at the top, CHANGELOG.md) and
  docs/*.md that is not a web address resolves to a file or folder of the repository,
  without leaving it (``../`` past the root, an absolute path, ``file:``); a link's
  ``#anchor`` is ignored. Web addresses must be
  ``http(s)://`` (or ``mailto:``): nothing points at a machine's own files.
* Every page a table of contents (```` ```{toctree} ````) in docs/*.md lists exists.
* docs/api.md names every public module of ``halfedge_edu`` (the files of the package,
  no part of the name starting with ``_``), and every module it names exists.

The graded-exercise tables of docs/instructors.md and docs/coming_from_your_course.md
are checked against ``grading.EXERCISES`` in tests/exercises/test_course_map.py.
"""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import unquote

import pytest

import halfedge_edu

ROOT = Path(__file__).resolve().parents[1]
PACKAGE_DIR = Path(halfedge_edu.__file__).resolve().parent
PAGES = [*sorted(ROOT.glob("*.md")), *sorted((ROOT / "docs").glob("*.md"))]   # README.md, CHANGELOG.md, docs

#: ``[text](target)`` and ``![alt](target "title")``, the target up to a space or ``)``
#: or written in ``<...>``; ``<img src="...">`` and ``<a href="...">`` in the pages' HTML;
#: ``[name]: target`` reference definitions. Each has one group, ``target``.
_LINKS = [
    re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(?:<(?P<target>[^>]+)>|(?P<bare>[^)\s]+))(?:\s+\"[^\"]*\")?\s*\)"),
    re.compile(r"""<(?:img|a|source)\b[^>]*?\b(?:src|href)\s*=\s*["'](?P<target>[^"']+)["']""", re.IGNORECASE),
    re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(?P<target>[^\s>]+)>?", re.MULTILINE),
]
_FENCE = re.compile(r"^(```|~~~).*?^\1", re.MULTILINE | re.DOTALL)
_CODE_SPAN = re.compile(r"`[^`\n]*`")
_WEB = ("http://", "https://", "mailto:")


def links_in(text: str) -> list[str]:
    """Every link target in markdown ``text``, in the order they appear; code blocks and
    code spans (which only show link syntax) left out."""
    prose = _CODE_SPAN.sub(lambda span: " " * len(span.group()), _FENCE.sub("", text))
    found = [(match.start(), match.group("target") or match.groupdict().get("bare"))
             for pattern in _LINKS for match in pattern.finditer(prose)]
    return [target for _, target in sorted(found)]


def problem_with(page: Path, target: str) -> str | None:
    """Why ``target``, a link on ``page``, does not lead to a file of the repository; None if it does."""
    if target.startswith(_WEB):
        return None
    if target.startswith("#"):
        return None                                           # an anchor on the page itself
    if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
        return f"{target!r} is neither a web address (http, https) nor a path in the repository"
    path = unquote(target.split("#", 1)[0].split("?", 1)[0])
    if path.startswith("/"):
        return f"{target!r} is an absolute path: it points at the reader's machine, not the repository"
    resolved = (page.parent / path).resolve()
    if not resolved.is_relative_to(ROOT):
        return f"{target!r} leads outside the repository"
    if not resolved.exists():
        return f"{target!r} names {resolved.relative_to(ROOT)}, which does not exist"
    return None


@pytest.mark.parametrize("page", PAGES, ids=[str(page.relative_to(ROOT)) for page in PAGES])
def test_every_link_on_the_page_leads_to_a_file_of_the_repository_or_the_web(page):
    problems = [problem for target in links_in(page.read_text(encoding="utf-8"))
                if (problem := problem_with(page, target)) is not None]
    assert not problems, f"{page.relative_to(ROOT)}:\n" + "\n".join(problems)


def toctree_entries(text: str) -> list[str]:
    """The pages a ```` ```{toctree} ```` block of ``text`` lists (options and blank lines left out)."""
    blocks = re.findall(r"^```\{toctree\}[^\n]*\n(.*?)^```", text, flags=re.MULTILINE | re.DOTALL)
    return [line.strip() for block in blocks for line in block.splitlines()
            if line.strip() and not line.strip().startswith(":")]


DOCS = [page for page in PAGES if page.parent.name == "docs"]


@pytest.mark.parametrize("page", DOCS, ids=[str(page.relative_to(ROOT)) for page in DOCS])
def test_every_page_a_table_of_contents_lists_exists(page):
    missing = []
    for entry in toctree_entries(page.read_text(encoding="utf-8")):
        found = [*page.parent.glob(entry + ".md"), *page.parent.glob(entry + ".ipynb")]
        if not found:
            missing.append(entry)
    assert not missing, f"{page.relative_to(ROOT)}'s table of contents lists pages that do not exist: {missing}"


def test_the_website_lists_the_reference_pages_and_the_chapters():
    entries = toctree_entries((ROOT / "docs" / "index.md").read_text(encoding="utf-8"))
    assert {"api", "performance", "contributing"} <= set(entries)
    assert any(entry.startswith("chapters/") for entry in entries)


def test_the_link_finder_sees_links_images_html_and_references_but_not_code():
    text = ('See [the api](api.md#top), ![a picture](../figures/a.png "title") and [`x`](<b c.md>).\n'
            '<img src="figures/b.svg" width=300> <a href="https://example.org">site</a>\n'
            "[ref]: docs/c.md\n"
            "`[not](a-link.md)`\n```\n[nor](this.md)\n```\n")
    assert links_in(text) == ["api.md#top", "../figures/a.png", "b c.md", "figures/b.svg", "https://example.org",
                              "docs/c.md"]


def test_a_link_outside_the_repository_or_to_a_missing_file_is_a_problem():
    page = ROOT / "docs" / "api.md"
    assert problem_with(page, "../README.md") is None
    assert problem_with(page, "https://example.org/x") is None
    assert "outside" in problem_with(page, "../../elsewhere.md")
    assert "absolute" in problem_with(page, "/etc/passwd")
    assert "neither" in problem_with(page, "file:///etc/passwd")
    assert "does not exist" in problem_with(page, "no_such_page.md")


def public_modules() -> set[str]:
    """The dotted names of the package's modules and packages, from its files (nothing
    imported), leaving out any whose name has a part starting with ``_``."""
    found = set()
    for path in PACKAGE_DIR.rglob("*.py"):
        parts = ["halfedge_edu", *path.relative_to(PACKAGE_DIR).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts.pop()
        if not any(part.startswith("_") for part in parts):
            found.add(".".join(parts))
    return found


def modules_named_in(text: str) -> set[str]:
    """The ``halfedge_edu...`` names docs/api.md gives as modules: automodule directives
    and the first column of its module table."""
    named = set(re.findall(r"^\.\. automodule:: (halfedge_edu[\w.]*)", text, flags=re.MULTILINE))
    named |= set(re.findall(r"^\| `(halfedge_edu[\w.]*)` \|", text, flags=re.MULTILINE))
    return named


def test_api_page_names_every_public_module():
    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    missing = sorted(public_modules() - modules_named_in(text))
    assert not missing, "docs/api.md: add a row for each to the module table: " + ", ".join(missing)


def test_every_module_the_api_page_names_exists():
    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    gone = sorted(modules_named_in(text) - public_modules())
    assert not gone, "docs/api.md names modules the package does not have: " + ", ".join(gone)


def test_the_module_walk_finds_modules_and_packages_but_no_private_ones():
    modules = public_modules()
    assert {"halfedge_edu", "halfedge_edu.core", "halfedge_edu.core.validate", "halfedge_edu.core.ops.flip"} <= modules
    assert not any(part.startswith("_") for name in modules for part in name.split("."))
