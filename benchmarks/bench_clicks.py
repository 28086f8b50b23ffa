"""How long a click on a widget takes to answer in a live JupyterLab: text and picture.

    python benchmarks/bench_clicks.py                  # 20 clicks per widget and backend
    python benchmarks/bench_clicks.py --quick          # 6 clicks
    python benchmarks/bench_clicks.py --clicks 50 --backends server --widgets explorer
    python benchmarks/bench_clicks.py --trame-stale-retry  # the server view as trame-vtk alone sends it

A script, not a timed test (issue 29): it starts a real JupyterLab and Debian's
Chromium (headless, driven by the ``playwright`` package, as the browser tests do:
tests/browser/lab_server.py), once per live backend:

- ``server``: ``HALFEDGE_EDU_LIVE_BACKEND`` unset, what ``make lab`` gives a student:
  the kernel renders with VTK and trame sends JPEG pictures to the view's iframe;
- ``client``: ``HALFEDGE_EDU_LIVE_BACKEND=client``, the hub's option: the kernel sends
  the scene and vtk.js draws it with WebGL in the browser (here SwiftShader, the
  software WebGL of a Chromium started with --disable-gpu).

In each Lab it opens a chapter, runs every cell, and clicks a widget's buttons ``N``
times in turn (the explorer of chapter 03: next, twin, prev; the QEM stepper of
chapter 10 and the Loop stepper of chapter 09: step, back), each click once the
previous one has settled (its text and picture arrived, then no new picture for
``QUIET`` seconds). Two clicks before the measured ones warm the widget up (a stepper's
first is "start"). Times are wall-clock ``Date.now()`` in the browser (milliseconds,
one clock for the page and the view's iframe, which is another origin: the trame
server's port), from the ``click`` event on the button (capture phase, in the page):

- click-to-text: until the widget's text in the page changes (a MutationObserver on
  the output area, started just before the click, sees its ``textContent`` differ from
  before the click): the DOM change, one animation frame (~16 ms) before it is painted.
- click-to-picture, server backend: until the view's iframe receives the picture the
  click leads to. The trame remote view puts each decoded JPEG it receives into an
  ``<img>`` (``src`` set to a blob URL; a MutationObserver in the iframe records the
  time and then a hash of the JPEG's bytes). "Picture changed" is the last image whose
  bytes differ from the image shown before the click, among those received until the
  view is quiet; "first" is the first such image.
- click-to-picture, client backend: until vtk.js has drawn the new scene. WebGL's draw
  calls (``drawArrays``/``drawElements`` wrapped on the iframe's WebGL prototypes) are
  grouped into renders, one per task; "picture changed" is the end of the last render
  after the click before the view is quiet ("first": the end of the first render). The
  canvas is composited at the next animation frame after that.

For each backend and widget the script prints median and p95 (nearest rank) of both
latencies and, from the kernel (a cell run through the Lab's kernel connection), the
median of the parts of one step: the widget's whole ``go``; its state and panel
(``_show`` and ``_refresh_panel``, which also sends the panel's text to the browser);
the VTK render alone (``render_window.Render()``); and ``plotter.render()`` (the render
and trame's update: with the server view a second render, the read-back and a JPEG
encode; with the client view the scene's serialisation). Browser-side latency minus
the kernel's ``go`` is the rest: messages, trame's delivery and the browser.

The machine line (CPU, cores, load) is printed before and after, with whether the
figures may go into the docs (``_common.OtherWork``: the share of the CPU other
processes used meanwhile). Exits 0 with one line when Chromium or the playwright
package is missing.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT))

from _common import OtherWork, machine_report  # noqa: E402 - after the path

QUIET = 1.0              # seconds without a new picture after which a click has settled
CLICK_TIMEOUT = 20.0     # seconds a click may take to settle before it counts as lost
POLL = 0.05              # seconds between looks at the page while a click settles


@dataclass(frozen=True)
class Widget:
    key: str             # the name on the command line
    label: str
    notebook: str
    title: str           # the widget's panel title, which finds its output area
    variable: str        # the chapter's variable holding the widget (for the kernel timings)
    buttons: tuple[str, ...]
    warm_up: tuple[str, ...]


WIDGETS = {
    "explorer": Widget("explorer", "explorer (ch. 03)", "03_navigating.ipynb", "Halfedge explorer",
                       "explorer", ("next", "twin", "prev"), ("next", "prev")),
    "qem": Widget("qem", "QEM stepper (ch. 10)", "10_quadric_simplification.ipynb",
                  "Quadric error simplification: the queue", "stepper", ("step", "back"), ("start", "step")),
    "loop": Widget("loop", "Loop stepper (ch. 09)", "09_loop_subdivision.ipynb",
                   "Loop subdivision: step by step", "stepper", ("step", "back"), ("start", "step")),
}
BACKENDS = {"server": {}, "client": {"HALFEDGE_EDU_LIVE_BACKEND": "client"}}


# -- in the page and in the view's iframe --------------------------------------------

# Before each click, on the widget's output area: the click's time and the first change
# of its text.
ARM_TEXT_JS = """(output) => {
    const b = window.__benchClick = {click: null, text: null};
    const before = output.textContent;
    const observer = new MutationObserver(() => {
        if (b.text === null && output.textContent !== before) { b.text = Date.now(); observer.disconnect(); }
    });
    observer.observe(output, {subtree: true, childList: true, characterData: true});
    output.addEventListener('click', () => { if (b.click === null) b.click = Date.now(); },
                            {capture: true, once: true});
}"""

# Once, in the view's iframe: every picture the remote view shows (time, hash of its
# bytes) and every WebGL render (start, end, draw calls).
INSTRUMENT_FRAME_JS = """() => {
    if (window.__bench) return false;
    const b = window.__bench = {frames: [], renders: [], open: null};
    const hashOf = (entry, src) => fetch(src).then(r => r.arrayBuffer()).then(buffer => {
        const bytes = new Uint8Array(buffer);
        let h = 2166136261;
        for (let i = 0; i < bytes.length; i++) { h ^= bytes[i]; h = Math.imul(h, 16777619); }
        entry.hash = (h >>> 0).toString(16) + ':' + bytes.length;
    }).catch(error => { entry.hash = 'unread:' + error; });
    const record = (img) => {
        const entry = {t: Date.now(), hash: null};
        b.frames.push(entry);
        hashOf(entry, img.src);
    };
    document.querySelectorAll('img').forEach(img => { if (img.src.startsWith('blob:')) record(img); });
    new MutationObserver(records => {
        for (const r of records) {
            if (r.target.tagName === 'IMG' && r.target.src.startsWith('blob:')) record(r.target);
        }
    }).observe(document, {subtree: true, attributes: true, attributeFilter: ['src']});
    const protos = [window.WebGLRenderingContext, window.WebGL2RenderingContext]
        .filter(Boolean).map(c => c.prototype);
    for (const proto of protos) {
        for (const name of ['drawArrays', 'drawElements', 'drawArraysInstanced', 'drawElementsInstanced']) {
            const original = proto[name];
            if (!original) continue;
            proto[name] = function (...args) {
                const now = Date.now();
                if (b.open === null) {
                    b.open = {start: now, end: now, calls: 0};
                    b.renders.push(b.open);
                    queueMicrotask(() => { b.open = null; });
                }
                b.open.end = now;
                b.open.calls += 1;
                return original.apply(this, args);
            };
        }
    }
    return true;
}"""

FRAME_LOG_JS = """() => window.__bench ? {frames: window.__bench.frames,
    renders: window.__bench.renders.map(r => ({start: r.start, end: r.end, calls: r.calls}))} : null"""

# Runs code in the notebook's kernel and returns what it printed.
KERNEL_RUN_JS = """async (code) => {
    const kernel = window.jupyterapp.shell.currentWidget.sessionContext.session.kernel;
    const future = kernel.requestExecute({code, silent: false, store_history: false});
    let out = '';
    future.onIOPub = (msg) => {
        if (msg.header.msg_type === 'stream') out += msg.content.text;
        if (msg.header.msg_type === 'error') out += 'ERROR ' + msg.content.ename + ': ' + msg.content.evalue + '\\n';
    };
    await future.done;
    return out;
}"""


# -- in the kernel -------------------------------------------------------------------

KERNEL_TIMING = """
import json as _json, statistics as _statistics, time as _time
def _bench_ms(action, repeats):
    times = []
    for _ in range(repeats):
        start = _time.perf_counter()
        action()
        times.append(1000.0 * (_time.perf_counter() - start))
    return round(_statistics.median(times), 1)
_widget = {variable}
_plotter = _widget.scene.plotter
_moves = iter({buttons!r} * 1000)
_report = {{
    "go": _bench_ms(lambda: _widget.go(next(_moves)), {repeats}),
    "state and panel": _bench_ms(lambda: (_widget._show(), _widget._refresh_panel()), {repeats}),
    "VTK render": _bench_ms(_plotter.render_window.Render, {repeats}),
    "plotter.render()": _bench_ms(_plotter.render, {repeats}),
    "suppress_rendering": bool(getattr(_plotter, "suppress_rendering", False)),
}}
print("BENCH" + _json.dumps(_report))
del _widget, _plotter, _moves, _report
"""

# The --trame-stale-retry comparison: halfedge_edu.live_backend.answer_clicks_promptly
# makes a server view look for a step's picture every 10 ms until its JPEG is encoded;
# trame-vtk alone sends the previous picture and looks again after 0.5 s. This puts
# trame-vtk's own retry back in the kernel, to measure the difference in one run.
RESTORE_TRAME_RETRY = """
import gc as _gc
_found = [o for o in _gc.get_objects() if type(o).__name__ == "vtkWebPublishImageDelivery"]
for _o in _found:
    _o.__dict__.pop("render_stale_image", None)
    _o.delta_stale_time_before_render = 0.5
print("BENCH" + str(len(_found)))
del _found
"""


# -- measuring -----------------------------------------------------------------------

def percentile(values: list[float], share: float) -> float:
    """The nearest-rank percentile (``share`` in 0..1) of ``values``."""
    ordered = sorted(values)
    return ordered[max(0, math.ceil(share * len(ordered)) - 1)]


def summary(values: list[float]) -> str:
    if not values:
        return "      -        -"
    return f"{statistics.median(values):7.0f}  {percentile(values, 0.95):7.0f}"


def find_view_frame(output):
    """The trame view's iframe of a widget's output area, as a Playwright Frame."""
    handle = output.locator("iframe").first.element_handle(timeout=60_000)
    frame = handle.content_frame()
    if frame is None:
        raise RuntimeError("the live view's iframe has no document")
    frame.wait_for_load_state("load", timeout=60_000)
    return frame


def picture_times(log: dict, backend: str, click: float) -> tuple[float | None, float | None, int]:
    """(first, last) time after ``click`` at which the view's picture changed, and how
    many pictures (server) or renders (client) arrived after the click."""
    if backend == "server":
        before = [f for f in log["frames"] if f["t"] < click]
        after = [f for f in log["frames"] if f["t"] >= click]
        shown = before[-1]["hash"] if before else None
        changed = [f["t"] for f in after if f["hash"] != shown]
        return (changed[0] if changed else None), (changed[-1] if changed else None), len(after)
    renders = [r for r in log["renders"] if r["start"] >= click]
    if not renders:
        return None, None, 0
    return renders[0]["end"], renders[-1]["end"], len(renders)


def click_once(page, frame, output, button: str, backend: str) -> dict:
    """Click ``button`` once the page is ready, wait until the click settled, and return
    its times in ms (None where nothing came within CLICK_TIMEOUT)."""
    from tests.browser.lab_page import click_in_place

    output.evaluate(ARM_TEXT_JS)
    click_in_place(output.get_by_role("button", name=button, exact=True))
    deadline = time.monotonic() + CLICK_TIMEOUT
    while True:
        time.sleep(POLL)
        marks = page.evaluate("() => window.__benchClick")
        log = frame.evaluate(FRAME_LOG_JS)
        if log is None:
            raise RuntimeError("the view's iframe was reloaded during the clicks")
        click = marks["click"]
        if click is not None:
            first, last, count = picture_times(log, backend, click)
            pending = any(f["hash"] is None for f in log["frames"])
            newest = max([f["t"] for f in log["frames"]] + [r["end"] for r in log["renders"]], default=0)
            quiet = (page.evaluate("() => Date.now()") - newest) / 1000.0 >= QUIET
            if marks["text"] is not None and last is not None and quiet and not pending:
                break
        if time.monotonic() > deadline:
            break
    click = marks["click"]
    if click is None:
        return {"text": None, "picture": None, "first picture": None, "pictures": 0}
    first, last, count = picture_times(log, backend, click)
    return {
        "text": None if marks["text"] is None else marks["text"] - click,
        "picture": None if last is None else last - click,
        "first picture": None if first is None else first - click,
        "pictures": count,
    }


def run_kernel(page, code: str) -> str:
    """What ``code`` printed after "BENCH" in the open notebook's kernel."""
    out = page.evaluate(KERNEL_RUN_JS, code)
    for line in out.splitlines():
        if line.startswith("BENCH"):
            return line[len("BENCH"):]
    raise RuntimeError(f"the kernel cell printed no result:\n{out}")


def measure_widget(context, lab, widget: Widget, backend: str, clicks: int,
                   trame_retry: bool) -> dict:
    """Open the widget's chapter, run it, and click the widget ``clicks`` times."""
    from tests.browser.lab_page import ExplorerInLab, StepperInLab, click_in_place, open_and_run_all

    page = context.new_page()
    try:
        open_and_run_all(page, lab, widget.notebook)
        shown = (ExplorerInLab(page, Path(tempfile.gettempdir())) if widget.key == "explorer"
                 else StepperInLab(page, widget.title))
        shown.wait_for_live_view(widget.label)
        output = shown.output
        frame = find_view_frame(output)
        # The view has drawn its first picture before the clicks start.
        time.sleep(2.0)
        frame.evaluate(INSTRUMENT_FRAME_JS)
        patched = None
        if trame_retry and backend == "server":
            patched = int(run_kernel(page, RESTORE_TRAME_RETRY))
        for button in widget.warm_up:
            click_in_place(output.get_by_role("button", name=button, exact=True))
            time.sleep(QUIET + 1.0)
        results = []
        for k in range(clicks):
            button = widget.buttons[k % len(widget.buttons)]
            results.append(click_once(page, frame, output, button, backend))
        kernel = json.loads(run_kernel(page, KERNEL_TIMING.format(
            variable=widget.variable, buttons=widget.buttons, repeats=max(5, min(clicks, 20)))))
        return {"clicks": results, "kernel": kernel, "patched": patched}
    finally:
        page.close()


def report(backend: str, widget: Widget, measured: dict) -> None:
    clicks = measured["clicks"]
    texts = [c["text"] for c in clicks if c["text"] is not None]
    pictures = [c["picture"] for c in clicks if c["picture"] is not None]
    firsts = [c["first picture"] for c in clicks if c["first picture"] is not None]
    lost = sum(1 for c in clicks if c["text"] is None or c["picture"] is None)
    per_click = statistics.mean(c["pictures"] for c in clicks) if clicks else 0
    unit = "pictures" if backend == "server" else "renders"
    print(f"{backend:7s} {widget.label:24s} {summary(texts)}  {summary(pictures)}  {summary(firsts)}"
          f"  {per_click:5.1f} {unit}/click, {len(clicks)} clicks" + (f", {lost} unsettled" if lost else ""))
    kernel = measured["kernel"]
    parts = ", ".join(f"{name} {kernel[name]:.0f}" for name in ("go", "state and panel", "VTK render", "plotter.render()"))
    print(f"{'':7s} {'':24s} kernel, median ms: {parts}"
          + (" (rendering suppressed: vtk.js draws)" if kernel["suppress_rendering"] else ""))
    if pictures:
        rest = statistics.median(pictures) - kernel["go"]
        print(f"{'':7s} {'':24s} median click-to-picture {statistics.median(pictures):.0f} ms = kernel go "
              f"{kernel['go']:.0f} ms ({kernel['go'] / statistics.median(pictures):.0%}) + {rest:.0f} ms messages, "
              f"delivery and browser")
    if measured["patched"] is not None:
        print(f"{'':7s} {'':24s} (trame-vtk's own 0.5 s stale-picture retry put back in {measured['patched']} image deliveries)")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="6 clicks per widget instead of 20")
    parser.add_argument("--clicks", type=int, default=None, help="clicks per widget and backend (default 20)")
    parser.add_argument("--backends", default="server,client", help="comma-separated: server, client")
    parser.add_argument("--widgets", default="explorer,qem,loop", help=f"comma-separated: {', '.join(WIDGETS)}")
    parser.add_argument("--per-click", action="store_true", help="also print each click's times")
    parser.add_argument("--trame-stale-retry", action="store_true",
                        help="server backend: put trame-vtk's own retry back (a picture whose JPEG was "
                             "not encoded yet is looked for again after 0.5 s), to compare with "
                             "halfedge_edu's 10 ms polling (see RESTORE_TRAME_RETRY)")
    args = parser.parse_args()
    clicks = args.clicks or (6 if args.quick else 20)
    backends = [b.strip() for b in args.backends.split(",") if b.strip()]
    widgets = [WIDGETS[w.strip()] for w in args.widgets.split(",") if w.strip()]

    from tests.browser.lab_server import chromium_path

    chromium = chromium_path()
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        print("bench_clicks: skipped, the playwright package is not installed (pip install -e '.[dev]')")
        return 0
    if chromium is None:
        print("bench_clicks: skipped, Chromium is not installed (apt-get install chromium)")
        return 0

    import pytest
    from playwright.sync_api import sync_playwright

    from tests.browser.lab_server import LabStartError, launch_chromium, start_lab, stop_lab

    print(machine_report(), flush=True)
    other_work = OtherWork(adopt_orphans=True).start()  # other processes' CPU time while this runs
    print(f"{clicks} clicks per widget and backend, each after the last settled ({QUIET:.1f} s without a new picture)"
          + ("; server view with trame-vtk's own 0.5 s stale-picture retry" if args.trame_stale_retry else ""))
    print(f"{'backend':7s} {'widget':24s} {'click-to-text ms':>16s}  {'click-to-picture ms':>16s}  "
          f"{'first picture ms':>16s}")
    print(f"{'':7s} {'':24s} {'median':>7s}  {'p95':>7s}  {'median':>7s}  {'p95':>7s}  {'median':>7s}  {'p95':>7s}")
    failures = 0
    with sync_playwright() as p:
        for backend in backends:
            with tempfile.TemporaryDirectory(prefix=f"bench-clicks-{backend}-") as folder:
                try:
                    lab, server = start_lab(Path(folder), BACKENDS[backend])
                except LabStartError as error:
                    print(f"{backend:7s} JupyterLab did not start: {error}")
                    failures += 1
                    continue
                context = launch_chromium(p, Path(folder) / "chromium-profile", chromium)
                try:
                    for widget in widgets:
                        try:
                            measured = measure_widget(context, lab, widget, backend, clicks, args.trame_stale_retry)
                        # pytest.fail.Exception: lab_page's waits fail the way a test does.
                        except (Exception, pytest.fail.Exception) as error:  # noqa: BLE001 - report it, go on
                            print(f"{backend:7s} {widget.label:24s} failed: {type(error).__name__}: {error}")
                            print(lab.log_tail(15))
                            failures += 1
                            continue
                        report(backend, widget, measured)
                        if args.per_click:
                            for k, times in enumerate(measured["clicks"], start=1):
                                print(f"{'':7s} {'':24s} click {k}: {times}")
                        sys.stdout.flush()
                finally:
                    context.close()
                    stop_lab(server)
    print(machine_report())
    print(other_work.stop().verdict()[1])
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
