"""Sphinx configuration of the website (`make book`): chapters, command line, API.

The chapters are the executed notebooks (docs/chapters is a link to ../notebooks), read
by myst-nb and never executed again: their stored outputs, including the picture each
widget leaves beside its live view, are what the pages show. Everything is local:
the default theme, no MathJax (no page has Sphinx math: the notebooks' two `$...$`
formulas stay as written), no ipywidgets scripts from a CDN, so the site builds and
displays without a network.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the checkout's halfedge_edu, as PYTHONPATH=$PWD does

project = "halfedge_edu"
author = "halfedge_edu contributors"
copyright = "halfedge_edu contributors, MIT license"

extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.viewcode", "sphinxarg.ext"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}
# Only the chapter notebooks: not their Jupytext sources, checkpoints or scratch files.
exclude_patterns = ["_build", "chapters/src", "chapters/student", "**/.ipynb_checkpoints"]
include_patterns = ["index.md", "cli.md", "api.md", "instructors.md", "coming_from_your_course.md",
                    "chapters/[0-9][0-9]*_*.ipynb"]

# Never run a notebook here: the stored outputs come from tools/build_notebooks.py.
nb_execution_mode = "off"
# Widgets: show their stored static picture (image/png), not a view that needs the
# ipywidgets JavaScript from a CDN.
nb_ipywidgets_js = {}
nb_mime_priority_overrides = [("html", "application/vnd.jupyter.widget-view+json", None)]

autodoc_member_order = "bysource"
autodoc_typehints = "description"

html_theme = "alabaster"
html_title = "halfedge_edu"
html_theme_options = {"page_width": "1100px", "sidebar_width": "240px", "show_powered_by": False}
# The executed notebooks are several MB each with their pictures: no copies as "sources".
html_copy_source = False
html_show_sourcelink = False
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}
