"""Colours and sizes for the pictures: one colour per *role*, safe for colour-blind eyes.

Every highlight in a scene names a role ("current", "twin", "next" ...), never a colour,
so a picture and its legend always agree. The role colours are the Okabe-Ito palette
(Okabe & Ito, "Color Universal Design", 2008), which stays distinguishable with the
common forms of colour blindness; neighbouring roles also differ in lightness, so they
survive a washed-out projector or a grey-scale print.

Two presets size everything: ``"default"`` for a screen, ``"large"`` for a lecture hall
(big labels, thick arrows, a larger image, darker lines for contrast).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# The Okabe-Ito colours, by name.
BLACK = "#000000"
ORANGE = "#E69F00"
SKY_BLUE = "#56B4E9"
BLUISH_GREEN = "#009E73"
YELLOW = "#F0E442"
BLUE = "#0072B2"
VERMILLION = "#D55E00"
REDDISH_PURPLE = "#CC79A7"


@dataclass(frozen=True)
class Role:
    """What a highlighted element is, how it is coloured and what the legend calls it."""

    name: str
    kind: str  # "vertex", "halfedge" or "face" ("edge": lines drawn over the mesh)
    color: str
    legend: str


_ROLE_LIST = [
    # A check's finding (chapters 06-08): the pointer that is wrong, its value, the right one.
    Role("wrong_owner", "halfedge", VERMILLION, "its pointer is wrong"),
    Role("wrong_vertex", "vertex", VERMILLION, "its pointer is wrong"),
    Role("wrong", "halfedge", REDDISH_PURPLE, "the wrong value"),
    Role("right", "halfedge", BLUISH_GREEN, "the right value"),
    # Navigation from one halfedge h (chapter 03).
    Role("current", "halfedge", VERMILLION, "h (current)"),
    Role("twin", "halfedge", BLUE, "h.twin"),
    Role("next", "halfedge", BLUISH_GREEN, "h.next"),
    Role("prev", "halfedge", REDDISH_PURPLE, "h.prev"),
    Role("origin", "vertex", ORANGE, "h.vertex (origin)"),
    Role("tip", "vertex", SKY_BLUE, "h.tip"),
    Role("face", "face", YELLOW, "h.face"),
    # One-ring of a vertex v.
    Role("center", "vertex", ORANGE, "v"),
    Role("outgoing", "halfedge", BLUE, "outgoing halfedges of v"),
    Role("neighbor", "vertex", SKY_BLUE, "neighbours of v"),
    Role("ring_face", "face", "#F8F2A6", "faces around v"),
    # Operation steppers (chapters 06-08): what changes now, its old and new value,
    # what the operation deletes or creates, and what it gathered first.
    Role("changed", "halfedge", VERMILLION, "changes now"),
    Role("changed_vertex", "vertex", VERMILLION, "changes now"),
    Role("changed_face", "face", "#F5B38A", "changes now"),
    Role("old_target", "halfedge", REDDISH_PURPLE, "old value"),
    Role("old_vertex", "vertex", REDDISH_PURPLE, "old value"),
    Role("old_face", "face", "#EBCFE0", "old value"),
    Role("new_target", "halfedge", BLUISH_GREEN, "new value"),
    Role("new_vertex", "vertex", BLUISH_GREEN, "new value"),
    Role("new_face", "face", "#BFE6D6", "new value"),
    Role("doomed", "halfedge", BLACK, "to be deleted"),
    Role("doomed_vertex", "vertex", BLACK, "to be deleted"),
    Role("doomed_face", "face", "#B8B8B8", "to be deleted"),
    Role("created", "halfedge", SKY_BLUE, "created"),
    Role("created_vertex", "vertex", SKY_BLUE, "created"),
    Role("created_face", "face", "#CBE7F7", "created"),
    Role("named", "halfedge", BLUE, "gathered"),
    Role("named_vertex", "vertex", BLUE, "gathered"),
    Role("named_face", "face", "#DCD3EE", "gathered"),
    # An edge an operation refuses, with the elements the reason names.
    Role("refused", "halfedge", VERMILLION, "refused edge"),
    Role("refused_vertex", "vertex", VERMILLION, "named in the reason"),
    # The link condition of an edge a - b (chapter 08, viz.link_viewer): drawn as lines
    # and dots over the mesh, not as halfedge arrows.
    Role("link_edge", "edge", "#222222", "the edge a - b"),
    Role("link_a", "edge", ORANGE, "link(a)"),
    Role("link_b", "edge", SKY_BLUE, "link(b)"),
    Role("link_shared", "vertex", BLUISH_GREEN, "shared, and in link(ab)"),
    Role("link_extra", "edge", VERMILLION, "shared, not in link(ab)"),
]

#: Every role by name, in legend order; where an element has two roles, the earlier wins.
ROLES: dict[str, Role] = {role.name: role for role in _ROLE_LIST}


@dataclass(frozen=True)
class Preset:
    """Sizes and base colours of a scene. Lengths in pixels unless noted."""

    name: str
    window_size: tuple[int, int]
    background: str
    surface: str
    edge: str
    edge_width: float
    plain_arrow: str          # halfedges with no role
    boundary_arrow: str       # boundary halfedges with no role
    vertex: str
    vertex_size: float
    highlight_vertex_size: float
    arrow_width: float        # relative: 1.0 is the normal thickness
    label_size: int
    rewiring_face: str        # a face whose pointers are half changed (steppers)
    legend_size: tuple[float, float]  # fraction of the window
    text: str


PRESETS: dict[str, Preset] = {
    "default": Preset(
        name="default",
        window_size=(600, 450),
        background="#FFFFFF",
        surface="#E9E6DF",
        edge="#9A968E",
        edge_width=1.0,
        plain_arrow="#8A8A8A",
        boundary_arrow="#2B2B2B",
        vertex="#4D4D4D",
        vertex_size=7.0,
        highlight_vertex_size=16.0,
        arrow_width=1.0,
        label_size=12,
        rewiring_face="#F6D7BF",
        legend_size=(0.27, 0.27),
        text="#1A1A1A",
    ),
    # For a projector: everything larger, lines darker, the surface a touch lighter.
    "large": Preset(
        name="large",
        window_size=(1024, 768),
        background="#FFFFFF",
        surface="#F2F0EA",
        edge="#4A4A4A",
        edge_width=2.5,
        plain_arrow="#5E5E5E",
        boundary_arrow="#000000",
        vertex="#1A1A1A",
        vertex_size=12.0,
        highlight_vertex_size=28.0,
        arrow_width=1.7,
        label_size=22,
        rewiring_face="#F3C9A6",
        legend_size=(0.32, 0.32),
        text="#000000",
    ),
}


def preset(name_or_preset: "str | Preset") -> Preset:
    """The preset called ``name`` ("default" or "large"); a Preset is passed through."""
    if isinstance(name_or_preset, Preset):
        return name_or_preset
    try:
        return PRESETS[name_or_preset]
    except KeyError:
        raise ValueError(f"unknown preset {name_or_preset!r}; choose one of {sorted(PRESETS)}") from None


def rgb(color: str) -> np.ndarray:
    """(3,) uint8 of a ``#RRGGBB`` colour."""
    color = color.lstrip("#")
    return np.array([int(color[i : i + 2], 16) for i in (0, 2, 4)], dtype=np.uint8)


def panel_css(look: Preset) -> dict[str, str]:
    """Widget panel sizes for a preset (font, button height and width, table cell
    padding): the "large" one is readable from the back of a hall."""
    if look.name == "large":
        return {"font": "20px", "button_height": "52px", "button_width": "150px", "cell": "6px 12px"}
    return {"font": "14px", "button_height": "32px", "button_width": "96px", "cell": "2px 8px"}
