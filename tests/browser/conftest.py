"""Fixtures for the browser tests: a real JupyterLab and a headless Chromium driving it.

How the Lab is started and the browser launched (the chapters written from their
sources, `make lab`'s environment, Debian's chromium and its flags) is in lab_server.py,
which benchmarks/bench_clicks.py shares; these fixtures give each test module its own.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.browser.lab_server import Lab, LabStartError, chromium_path, launch_chromium, start_lab, stop_lab

SKIP_REASON = "Chromium not installed: apt-get install chromium (see docs/headless.md)"


@pytest.fixture(scope="session")
def chromium_executable() -> str:
    path = chromium_path()
    if path is None:
        pytest.skip(SKIP_REASON)
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        pytest.skip("the playwright package is not installed: make test installs it (the dev extra)")
    return path


@pytest.fixture(scope="module")
def lab(chromium_executable, tmp_path_factory) -> Lab:
    """A JupyterLab on 127.0.0.1 (free port, random token) serving the chapters, each
    written from its source."""
    try:
        the_lab, server = start_lab(tmp_path_factory.mktemp("lab"))
    except LabStartError as error:
        pytest.fail(str(error))
    try:
        yield the_lab
    finally:
        stop_lab(server)


@pytest.fixture(scope="module")
def browser_context(chromium_executable, tmp_path_factory):
    """A headless Chromium with a fresh profile; one page per test."""
    from playwright.sync_api import sync_playwright

    profile = tmp_path_factory.mktemp("chromium-profile")
    with sync_playwright() as p:
        context = launch_chromium(p, profile, chromium_executable)
        try:
            yield context
        finally:
            context.close()


@pytest.fixture(scope="session")
def screenshot_dir(tmp_path_factory) -> Path:
    """Where the screenshots go: $HALFEDGE_EDU_SCREENSHOTS, else pytest's temporary
    folder (kept for the last three runs; the test prints the path when it fails)."""
    chosen = os.environ.get("HALFEDGE_EDU_SCREENSHOTS")
    if not chosen:
        return tmp_path_factory.mktemp("screenshots")
    folder = Path(chosen)
    folder.mkdir(parents=True, exist_ok=True)
    return folder
