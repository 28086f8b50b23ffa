"""Every widget of chapters 08 to 13, driven as a student would: the second half of
test_lab_widgets.py's chapters, in a module of its own so that pytest-xdist
(``--dist loadfile``, conftest.py) gives each half to a worker."""

from __future__ import annotations

import pytest

from tests.browser.test_lab_widgets import CHAPTERS, SPLIT_AT, drive_every_widget

pytestmark = pytest.mark.browser


@pytest.mark.parametrize("notebook", [notebook for notebook in sorted(CHAPTERS) if notebook >= SPLIT_AT])
def test_every_widget_survives_a_students_clicks(notebook, lab, browser_context, screenshot_dir):
    drive_every_widget(notebook, lab, browser_context, screenshot_dir)
