"""Sphinx configuration of the website (`make book`): chapters, command line, API.

The chapters are the executed notebooks, read by myst-nb and never executed again: their
stored outputs, including the picture each widget leaves beside its live view, are what
the pages show. Which edition (issue 24: the answers are not published):

- by default the **student edition**, docs/chapters (a link to ../notebooks/student):
  each exercise as a student gets it, without its answer. This is what `make book`
  builds and what may be put on a public website.
- with ``HALFEDGE_EDU_BOOK_EDITION=solutions`` (``make book EDITION=solutions``, into
  build/book-solutions) the **solution edition**, docs/solutions (a link to
  ../notebooks), for instructors only: index.md's chapter list is pointed there as it
  is read, and every page says it has the answers. Everything is local:
the default theme, no MathJax (no page has Sphinx math: the notebooks' two `$...$`
formulas stay as written), no ipywidgets scripts from a CDN, so the site builds and
displays without a network.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the checkout's halfedge_edu, as PYTHONPATH=$PWD does

project = "halfedge_edu"
author = "halfedge_edu contributors"
copyright = "halfedge_edu contributors, MIT license"

#: "student" (the default) or "solutions": which edition of the chapters the site shows.
EDITIONS = {"student": "chapters", "solutions": "solutions"}
EDITION = os.environ.get("HALFEDGE_EDU_BOOK_EDITION", "").strip().lower() or "student"
if EDITION not in EDITIONS:
    raise ValueError(f"HALFEDGE_EDU_BOOK_EDITION={EDITION!r}: use one of {', '.join(EDITIONS)}")
CHAPTERS = EDITIONS[EDITION]

# napoleon: the docstrings' Google-style "Args:", "Returns:", "Raises:" sections.
extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.viewcode", "sphinxarg.ext"]
# A source page links each object back to where it is documented. An object documented
# under a package that imports it (``halfedge_edu.viz.Stepper``) and a module documented
# on its own (``halfedge_edu.viz.steps``) would make one source page under two module
# names, linking to anchors that exist under the other; only real modules get pages.
viewcode_follow_imported_members = False
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}
# Only the chosen edition's chapter notebooks: not their Jupytext sources, checkpoints or
# scratch files, and never the other edition.
exclude_patterns = ["_build", "solutions/src", "solutions/student", "**/.ipynb_checkpoints"]
include_patterns = ["index.md", "cli.md", "api.md", "instructors.md", "coming_from_your_course.md",
                    "deploying.md", "headless.md", "performance.md", "contributing.md",
                    f"{CHAPTERS}/[0-9][0-9]*_*.ipynb"]

# Never run a notebook here: the stored outputs come from tools/build_notebooks.py.
nb_execution_mode = "off"
# Widgets: show their stored static picture (image/png), not a view that needs the
# ipywidgets JavaScript from a CDN.
nb_ipywidgets_js = {}
nb_mime_priority_overrides = [("html", "application/vnd.jupyter.widget-view+json", None)]

autodoc_member_order = "bysource"
autodoc_typehints = "description"
# Attributes as :ivar: fields: as directives they would document each dataclass field twice.
napoleon_use_ivar = True
# An :ivar: names its attribute, and element types share attribute names (Vertex.kind,
# Edge.kind ...): Sphinx then finds "more than one target" and links the first. Harmless.
suppress_warnings = ["ref.python"]

html_theme = "alabaster"
html_title = "halfedge_edu" if EDITION == "student" else "halfedge_edu, solution edition (instructors only)"
html_theme_options = {"page_width": "1100px", "sidebar_width": "240px", "show_powered_by": False}
# The executed notebooks are several MB each with their pictures: no copies as "sources".
html_copy_source = False
html_show_sourcelink = False
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}


def _point_the_chapter_list_at_the_edition(app, docname: str, source: list[str]) -> None:
    """index.md lists ``chapters/...`` (the student edition); for the solution edition
    the same list names ``solutions/...`` instead."""
    if docname == "index" and CHAPTERS != "chapters":
        source[0] = source[0].replace("\nchapters/[0-9]", f"\n{CHAPTERS}/[0-9]")


#: The longest alt text given to a chapter's picture (a screen reader reads all of it).
ALT_LENGTH = 300


def _describe_pictures(app, doctree, docname: str) -> None:
    """Give each picture a cell drew an alt text that says what it shows.

    myst-nb's alt text for a cell's picture is its file name (a hash). The chapters say
    what each picture shows in the paragraph just before the cell that draws it, so that
    paragraph becomes the alt text (the section's title where there is none).
    """
    from docutils import nodes

    for image in doctree.findall(nodes.image):
        alt = image.get("alt", "")
        if alt and not re.search(r"\.(png|jpe?g|gif|svg)$", alt, flags=re.I):
            continue
        cell = image
        while cell is not None and not (isinstance(cell, nodes.container) and "cell" in cell["classes"]):
            cell = cell.parent
        anchor = cell if cell is not None else image
        described = None
        sibling = anchor.previous_sibling() if hasattr(anchor, "previous_sibling") else None
        while sibling is not None and described is None:
            if isinstance(sibling, nodes.paragraph):
                described = sibling.astext()
            elif isinstance(sibling, nodes.section):
                break
            sibling = sibling.previous_sibling()
        if described is None:
            section = anchor.parent
            while section is not None and not isinstance(section, nodes.section):
                section = section.parent
            described = section[0].astext() if section is not None else docname
        described = " ".join(described.split())
        if len(described) > ALT_LENGTH:
            described = described[: ALT_LENGTH - 1].rsplit(" ", 1)[0] + "…"
        image["alt"] = f"Picture drawn by the code: {described}"


def setup(app) -> dict:
    app.connect("source-read", _point_the_chapter_list_at_the_edition)
    app.connect("doctree-resolved", _describe_pictures)
    return {"parallel_read_safe": True}
