"""`make book`'s website, opened page by page in headless Chromium.

Builds the site from docs/ (Sphinx + myst-nb over the executed notebooks, about 20 s),
serves it on 127.0.0.1, then follows every link from the start page: every page loads,
every picture on it loads, every link inside the site names a page or file that exists
(and an anchor on it that exists), and nothing is fetched from anywhere but the site
itself (the website works offline).
"""

from __future__ import annotations

import functools
import subprocess
import sys
import threading
import urllib.error
import urllib.request
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import unquote, urldefrag, urlsplit

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = sorted(p.stem for p in (ROOT / "notebooks").glob("[0-9][0-9]*_*.ipynb"))


class QuietHandler(SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args) -> None:
        """No access log on stderr."""


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> str:
    """The website built into a temporary folder and served; yields its base URL."""
    out = tmp_path_factory.mktemp("book")
    build = subprocess.run(
        [sys.executable, "-m", "sphinx", "-q", "-b", "html", str(ROOT / "docs"), str(out)],
        capture_output=True, text=True, timeout=600, cwd=ROOT,
    )
    assert build.returncode == 0, build.stderr[-4000:]
    server = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(QuietHandler, directory=str(out)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


def exists_on_server(url: str) -> bool:
    try:
        with urllib.request.urlopen(url, timeout=30) as response:
            return response.status == 200
    except urllib.error.URLError:
        return False


def test_every_page_loads_with_its_pictures_and_no_link_is_broken(site, browser_context):
    origin = urlsplit(site).netloc
    outside, failed = [], []
    browser_context.route(
        "**/*",
        lambda route: (outside.append(route.request.url), route.abort())
        if urlsplit(route.request.url).netloc != origin else route.continue_(),
    )
    page = browser_context.new_page()
    page.on("requestfailed", lambda request: failed.append(request.url))
    page.on("response", lambda response: failed.append(f"{response.status} {response.url}") if response.status >= 400 else None)

    to_visit, visited = [site + "index.html"], {}
    anchors_wanted: list[tuple[str, str, str]] = []  # (from page, target page, fragment)
    files_wanted: list[tuple[str, str]] = []          # (from page, non-HTML file)
    broken_pictures = {}
    while to_visit:
        url = to_visit.pop()
        if url in visited:
            continue
        response = page.goto(url, wait_until="load")
        assert response is not None and response.status == 200, f"{url}: {response and response.status}"
        broken = page.evaluate("Array.from(document.images).filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.src)")
        if broken:
            broken_pictures[url] = broken
        visited[url] = {
            "ids": set(page.evaluate("Array.from(document.querySelectorAll('[id]')).map(e => e.id)")),
            "pictures": page.evaluate("document.images.length"),
        }
        for href in page.evaluate("Array.from(document.querySelectorAll('a[href]')).map(a => a.href)"):
            target, fragment = urldefrag(href)
            if urlsplit(target).netloc != origin:
                continue
            if target.endswith("/"):
                target += "index.html"
            if target.endswith(".html"):
                to_visit.append(target)
                if fragment:
                    anchors_wanted.append((url, target, unquote(fragment)))
            else:
                files_wanted.append((url, target))

    assert not outside, f"the site fetched from outside itself: {sorted(set(outside))[:10]}"
    assert not failed, f"requests that failed: {sorted(set(failed))[:10]}"
    assert not broken_pictures, f"pictures that did not load: {broken_pictures}"
    missing_anchors = [(source, target, fragment) for source, target, fragment in anchors_wanted
                       if fragment not in visited[target]["ids"]]
    assert not missing_anchors, f"links to anchors that do not exist: {missing_anchors[:10]}"
    missing_files = [(source, target) for source, target in files_wanted if not exists_on_server(target)]
    assert not missing_files, f"links to files that do not exist: {missing_files[:10]}"

    chapter_pages = {Path(urlsplit(url).path).stem: info for url, info in visited.items() if "/chapters/" in url}
    assert sorted(chapter_pages) == CHAPTERS, "every chapter is a page reached from the start page"
    without_pictures = [name for name, info in chapter_pages.items() if info["pictures"] == 0]
    assert not without_pictures, f"chapters with no picture (their stored outputs are missing): {without_pictures}"
    for reference in ("cli", "api"):
        assert site + f"{reference}.html" in visited, f"{reference}.html is not linked from the start page"
