"""HALFEDGE_EDU_LIVE_BACKEND: the one setting a hub uses to choose where live views draw."""

from __future__ import annotations

import pytest

from halfedge_edu import live_backend


def test_unset_or_empty_keeps_the_server_rendered_view(monkeypatch):
    monkeypatch.delenv(live_backend.ENV_VARIABLE, raising=False)
    assert live_backend.trame_mode() == "server"
    monkeypatch.setenv(live_backend.ENV_VARIABLE, " ")
    assert live_backend.trame_mode() == "server"


@pytest.mark.parametrize(("setting", "mode"), [("server", "server"), ("client", "client"), (" Client ", "client")])
def test_the_variable_chooses_the_trame_mode(monkeypatch, setting, mode):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, setting)
    assert live_backend.trame_mode() == mode


def test_an_argument_wins_over_the_variable(monkeypatch):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, "client")
    assert live_backend.trame_mode("server") == "server"


def test_a_wrong_value_names_the_variable_and_the_value(monkeypatch):
    monkeypatch.setenv(live_backend.ENV_VARIABLE, "wasm")
    with pytest.raises(ValueError, match=r"HALFEDGE_EDU_LIVE_BACKEND='wasm'"):
        live_backend.trame_mode()
    with pytest.raises(ValueError, match=r"setting='gpu'"):
        live_backend.trame_mode("gpu")


# A client-side view's arrays in a real kernel (trame runs only inside one). The kernel
# prints one JSON line; trame-vtk's own release rule is applied with time_window=-1, i.e.
# as if every cached array were older than its 20 s window.
KEEPS_SHOWN_ARRAYS = r"""
import json
import halfedge_edu as hx
from halfedge_edu import live_backend
from halfedge_edu.viz import HalfedgeExplorer
from trame_vtk.modules.vtk.serializers import extract_array_hash

def shown(explorer):
    viewer = explorer.view.widget.viewer
    key = live_backend._scene_state_key(next(iter(viewer.views)))
    return {entry["hash"] for entry in extract_array_hash(viewer.server.state[key])}

def cached(hashes):
    return sorted(digest for digest in hashes if digest in context.data_array_cache)

explorer = HalfedgeExplorer(hx.sample("open_patch"), halfedge=7)
context = live_backend._array_cache_context(explorer.view.widget.viewer.server)
first = shown(explorer)
explorer.go("next")
explorer.go("twin")
now = shown(explorer)
other = HalfedgeExplorer(hx.sample("cube"), halfedge=0)
other.go("next")     # another view's update: where trame-vtk releases arrays
context.check_for_arrays_to_release(time_window=-1)
print(json.dumps({"first": len(first), "now": len(now), "now_cached": len(cached(now)),
                  "old": len(first - now - shown(other)), "old_cached": len(cached(first - now - shown(other)))}))
"""


def test_a_client_view_keeps_the_arrays_its_scene_names_and_releases_the_old_ones(tmp_path):
    import json

    counts = json.loads(_run_in_kernel(KEEPS_SHOWN_ARRAYS, tmp_path, HALFEDGE_EDU_LIVE_BACKEND="client"))
    # Everything the view's current scene names can still be fetched by a browser ...
    assert counts["now"] > 0 and counts["now_cached"] == counts["now"], counts
    # ... while the cell arrays of the scenes before the two steps were released.
    assert counts["old"] > 0 and counts["old_cached"] == 0, counts


SERVER_VIEW_KINDS = r"""
import json
import halfedge_edu as hx
from halfedge_edu.viz import HalfedgeExplorer

explorer = HalfedgeExplorer(hx.sample("open_patch"), halfedge=7)
explorer.go("next")
viewer = explorer.view.widget.viewer
print(json.dumps(sorted({cls.__name__ for view in viewer.views for cls in type(view).__mro__})))
"""


def _run_in_kernel(code: str, tmp_path, **variables: str) -> str:
    """What ``code`` printed in a fresh kernel with ``variables`` set (live views)."""
    import os

    from jupyter_client.manager import start_new_kernel

    env = {name: value for name, value in os.environ.items()
           if name not in ("PYVISTA_JUPYTER_BACKEND", live_backend.ENV_VARIABLE)}
    env.update(HALFEDGE_EDU_VIZ="live", **variables)
    manager, client = start_new_kernel(kernel_name="python3", env=env, cwd=str(tmp_path))
    printed, errors = [], []

    def collect(message):
        if message["header"]["msg_type"] == "stream":
            printed.append(message["content"]["text"])
        elif message["header"]["msg_type"] == "error":
            errors.append("\n".join(message["content"]["traceback"]))

    try:
        client.execute_interactive(code, output_hook=collect, timeout=240)
    finally:
        manager.shutdown_kernel(now=True)
    assert not errors, errors[0]
    return "".join(printed).strip().splitlines()[-1]


def test_the_default_server_view_has_no_hidden_vtk_js_view_to_sync(tmp_path):
    """trame-pyvista's "trame" mode puts a vtk.js view beside the server's pictures and
    sends it the scene at every step; the default setting gives the server view alone."""
    import json

    kinds = set(json.loads(_run_in_kernel(SERVER_VIEW_KINDS, tmp_path)))
    assert "VtkRemoteView" in kinds, kinds
    assert not kinds & {"VtkRemoteLocalView", "VtkLocalView"}, kinds


def test_the_installed_trame_vtk_has_every_private_name_live_backend_patches():
    from importlib.metadata import version

    assert live_backend.missing_private_api() == [], (
        f"trame-vtk {version('trame-vtk')} moved what halfedge_edu/live_backend.py patches: "
        "fix live_backend and the trame-vtk bounds in pyproject.toml together"
    )


def test_a_moved_private_name_is_named(monkeypatch):
    monkeypatch.setattr(live_backend, "TRAME_VTK_PRIVATE_API", (
        *live_backend.TRAME_VTK_PRIVATE_API,
        ("trame_vtk.modules.vtk.serializers", "renamed_in_a_future_release"),
        ("trame_vtk.widgets.vtk.common", "VtkLocalView.__init__ sets __scene_name"),
    ))
    assert live_backend.missing_private_api() == [
        "trame_vtk.modules.vtk.serializers:renamed_in_a_future_release",
        "trame_vtk.widgets.vtk.common:VtkLocalView.__init__ sets __scene_name",
    ]


def test_pyproject_bounds_trame_vtk_below_the_next_minor():
    import sys
    from pathlib import Path

    from packaging.requirements import Requirement

    tomllib = __import__("tomllib") if sys.version_info >= (3, 11) else __import__("tomli")
    pyproject = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml").read_text())
    (line,) = [line for line in pyproject["project"]["optional-dependencies"]["notebooks"]
               if Requirement(line).name == "trame-vtk"]
    specifier = Requirement(line).specifier
    assert "2.11.17" in specifier and "2.12.0" not in specifier and "2.7.0" not in specifier


# -- a server view's picture, as soon as it is encoded ---------------------------------

class EncodingPublisher:
    """A trame-vtk picture publisher whose JPEG encoder needs ``looks`` more looks
    before the new picture is done; it records what it published."""

    def __init__(self, looks: int):
        from trame_vtk.modules.vtk.protocols import vtkWebPublishImageDelivery

        class Publisher(vtkWebPublishImageDelivery):
            def still_render(inner, options):
                inner.renders += 1
                done = inner.renders > looks
                # Like vtkWebApplication: the image only when newer than ``mtime``.
                image = b"new" if done and options["mtime"] < 2 else (b"old" if options["mtime"] < 1 else None)
                return {"image": image, "stale": not done, "mtime": 2 if done else 1}

        self.publisher = Publisher(decode=False)
        self.publisher.renders, self.sent = 0, []
        # What a wslink server hands a protocol: how to publish, how to attach bytes.
        self.publisher.init(lambda topic, reply: self.sent.append(reply["image"]), lambda payload: payload, None)
        self.publisher.tracking_views["7"] = {"enabled": True, "mtime": 0, "quality": 100,
                                              "originalSize": [40, 30], "ratio": 1}
        self.publisher.stale_handler_count["7"] = 0

    def click(self, seconds: float) -> list[bytes]:
        """One step's push_render, then ``seconds`` of trame's event loop; what was sent."""
        import asyncio

        async def run():
            self.publisher.push_render("7")
            await asyncio.sleep(seconds)

        asyncio.run(run())
        return self.sent


def test_a_server_view_sends_the_new_picture_once_it_is_encoded():
    publishing = EncodingPublisher(looks=6)
    live_backend.poll_for_encoded_pictures(publishing.publisher)
    # The old picture at once (all there is), the new one after six looks ~10 ms apart.
    assert publishing.click(0.5) == [b"old", b"new"]
    assert publishing.publisher.delta_stale_time_before_render == live_backend.STALE_PICTURE_POLL


def test_trame_vtk_alone_loses_that_picture_with_a_short_delay():
    """Why the retry itself is replaced, not only the 0.5 s delay: trame-vtk's retry
    gives up at its second look, so a picture that needs more looks is never sent."""
    publishing = EncodingPublisher(looks=3)
    publishing.publisher.delta_stale_time_before_render = live_backend.STALE_PICTURE_POLL
    assert publishing.click(0.5) == [b"old"]


def test_a_view_that_is_always_stale_is_looked_at_a_bounded_number_of_times():
    publishing = EncodingPublisher(looks=10**9)
    live_backend.poll_for_encoded_pictures(publishing.publisher)
    publishing.click(live_backend.STALE_PICTURE_POLL * live_backend.STALE_PICTURE_LOOKS * 3)
    assert publishing.publisher.renders == live_backend.STALE_PICTURE_LOOKS + 1


SERVER_VIEW_POLLS = r"""
import json
import halfedge_edu as hx
from halfedge_edu import live_backend
from halfedge_edu.viz import HalfedgeExplorer

explorer = HalfedgeExplorer(hx.sample("open_patch"), halfedge=7)
explorer.go("next")
delivery = live_backend._image_delivery(explorer.view.widget.viewer.server)
print(json.dumps({"delay": delivery.delta_stale_time_before_render,
                  "patched": delivery.render_stale_image.__func__ is live_backend._look_again_for_the_picture}))
"""


def test_a_live_server_view_in_a_kernel_polls_for_its_pictures(tmp_path):
    import json

    found = json.loads(_run_in_kernel(SERVER_VIEW_POLLS, tmp_path))
    assert found == {"delay": live_backend.STALE_PICTURE_POLL, "patched": True}, found
