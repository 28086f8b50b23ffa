"""Keyboard stepping for the widgets: a key does what one of the widget's buttons does.

    area = KeyArea([status, table], buttons, {"n": "next", "ArrowRight": "step"}, look)
    area.widget          # the hint "keys (pointer over here): n next · → step" above the children
    area.press("n")      # the same as pressing n in the Lab, and as clicking "next"

In a lecture the explorer and the steppers are driven from the keyboard, as the CMU
15-462 MeshEdit viewer is (N: next halfedge, T: twin): ``n`` / ``p`` / ``t`` walk the
explorer, the arrows, space, Home and End step a stepper. Each widget lists its keys in
its class attribute ``KEYS`` (key -> button label) and shows them in a hint line.

How a key arrives: an ``ipyevents.Event`` watches ``keydown`` on the area. While the
mouse pointer is over the area, the browser sends every key pressed to the kernel instead
of to JupyterLab (so ``n`` moves the explorer rather than a notebook cell); moving the
pointer away gives the keyboard back to the notebook. There is no text box inside the
area: its keys would be taken too.

What a key does: it clicks the button it is bound to, through the button's own handler
(:func:`~halfedge_edu.viz.widgets.panel_button`). So a key runs on the kernel's main
thread like a click (see :mod:`.main_thread`: ipykernel 7 delivers widget messages on a
subshell thread, and VTK may only draw on the main one), and a step that fails shows
its error in the status line and leaves the widget where it was, like a click. A key
that is not bound, or pressed with Ctrl, Alt or Meta (a browser or Lab shortcut), is
ignored: nothing in this module raises into the kernel for a key.
"""

from __future__ import annotations

import html

from .palette import Preset, panel_css

#: How the hint line writes a key name (``KeyboardEvent.key``); other names as they are.
KEY_SYMBOLS = {"ArrowRight": "→", "ArrowLeft": "←", "ArrowUp": "↑", "ArrowDown": "↓",
               "Space": "space", "PageDown": "PgDn", "PageUp": "PgUp"}
#: Modifiers that make a key someone else's shortcut (Shift is part of the key: "+", "N").
SHORTCUT_MODIFIERS = ("ctrlKey", "altKey", "metaKey")


def key_name(event: dict) -> str | None:
    """The key of an ipyevents ``keydown`` event as the keymaps name it, or None.

    The name is the browser's ``KeyboardEvent.key`` ("ArrowRight", "Home", "n"), with
    letters in lower case (Caps Lock or Shift still give "n") and the space bar as
    "Space". None for any other event, and for a key pressed with Ctrl, Alt or Meta.
    """
    if event.get("event", "keydown") != "keydown" or any(event.get(m) for m in SHORTCUT_MODIFIERS):
        return None
    key = event.get("key")
    if not isinstance(key, str) or not key:
        return None
    if key == " ":
        return "Space"
    return key.lower() if len(key) == 1 else key


class KeyArea:
    """A part of a widget's panel that answers keys by clicking the widget's buttons.

    Args:
        children: the widgets shown in the area (a status line, a table, a legend).
        buttons: the widget's buttons by label (``widget.buttons``).
        keys: key name (see :func:`key_name`) -> the label of the button it clicks; a
            key whose button the widget does not have (a refused operation has none) is
            left out.
        look: the preset, for the hint's font size.

    ``widget`` is the area: the hint line, then ``children``. ``keys`` the keys it
    answers; ``event`` the ``ipyevents.Event`` (None when no key is bound: then there is
    no hint either).
    """

    def __init__(self, children: list, buttons: dict, keys: dict[str, str], look: Preset):
        import ipywidgets as widgets

        self.buttons = buttons
        self.keys = {key: label for key, label in keys.items() if label in buttons}
        self.event = None
        self.hint = widgets.HTML(self.hint_html(look))
        self.widget = widgets.VBox([self.hint, *children] if self.keys else list(children))
        if self.keys:
            import ipyevents

            self.event = ipyevents.Event(source=self.widget, watched_events=["keydown"],
                                         ignore_modifier_key_events=True)
            self.event.on_dom_event(self.handle)

    def hint_html(self, look: Preset) -> str:
        """The keys in one line, grouped by button: "keys (pointer over here): → space step · ← back"."""
        by_label: dict[str, list[str]] = {}
        for key, label in self.keys.items():
            by_label.setdefault(label, []).append(KEY_SYMBOLS.get(key, key))
        if not by_label:
            return ""
        kbd = "padding:0 4px;border:1px solid #999;border-radius:3px;background:#F4F4F4;font-family:monospace"
        parts = [" ".join(f'<kbd style="{kbd}">{html.escape(k)}</kbd>' for k in keys) + f" {html.escape(label)}"
                 for label, keys in by_label.items()]
        return (f'<div style="font-size:calc({panel_css(look)["font"]} * 0.9);color:#555;margin:2px 0 4px 0">'
                f'keys (pointer over here): {" · ".join(parts)}</div>')

    def handle(self, event: dict) -> str | None:
        """Answer an ipyevents event: click the button its key is bound to.

        Returns the label of the button clicked, or None (an unbound key, another event).
        The click runs the button's handler, which catches a refused step's error.
        """
        label = self.keys.get(key_name(event) or "")
        if label is None:
            return None
        self.buttons[label].click()
        return label

    def press(self, key: str) -> str | None:
        """What pressing ``key`` does (for code and tests): see :meth:`handle`."""
        return self.handle({"event": "keydown", "key": key})

    def close(self) -> None:
        """Stop listening (the event widget is closed with the area)."""
        if self.event is not None:
            self.event.close()
