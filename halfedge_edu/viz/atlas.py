"""Chapters 07 and 08's atlas: the collapse cases side by side, stepped together one
phase at a time, and the collapses the link condition refuses, each with its reason.

    from halfedge_edu.viz import CollapseAtlas
    atlas = CollapseAtlas()
    atlas                  # every case at "gather the elements", the refused ones below
    atlas.step()           # every case to the end of the next phase of the collapse
    print(atlas.describe())

Each case is a :class:`~halfedge_edu.viz.steppers.CollapseStepper` (``atlas.steppers``).
"""

from __future__ import annotations

import html

import numpy as np

from .keys import KeyArea
from .palette import panel_css, preset as _preset
from .pictures import grid_png, legend_png
from .renderer import widget_bundle
from .screen import unit
from .steppers import CHANGED, NEW, OLD, CollapseStepper
from .widgets import legend_html, panel_button


class CollapseAtlas:
    """The collapse cases side by side, stepped together one phase at a time, and the
    collapses the link condition refuses, each with its reason (chapters 07 and 08).

    Args:
        cases: ``(title, mesh, edge)`` of the allowed collapses to compare; by default
            the removed vertex of degree 3 (the cube's edge 0) and of degree > 3 (the
            single-collapse mesh's edge 0).
        refused: ``(title, mesh, edge)`` of collapses that are refused; by default the
            tetrahedron, the figure-8 strip and the lone triangle.
        mode, preset: as for every widget. The refused cases are small still pictures.

    ``atlas.step()`` (or ``go("phase")``) moves every case to the end of the next phase
    of the collapse; ``go("start")``, ``go("end")``, ``go("back")`` or a phase number.
    Each case is a :class:`CollapseStepper` (``atlas.steppers``) and can also be
    stepped on its own.

    Keys (mouse pointer over the two lines under the buttons: the keys and the phase):
    → space or PgDn the next phase, ← one back, Home the start, End the end;
    ``atlas.key_area.press(key)`` from code.
    """

    KEYS = {"ArrowRight": "phase", "Space": "phase", "PageDown": "phase", "ArrowLeft": "back",
            "Home": "start", "End": "end"}

    title = "Edge collapse: the cases side by side"

    def __init__(self, cases=None, refused=None, *, mode: str | None = None, preset="default"):
        import ipywidgets as widgets

        from ..data import sample
        from .renderer import choose_mode

        self.mode = choose_mode(mode)
        self.look = _preset(preset)
        large = self.look.name == "large"
        if cases is None:
            cases = [("removed vertex of degree 3", sample("cube"), 0),
                     ("removed vertex of degree > 3", sample("single_collapse"), 0)]
        if refused is None:
            refused = [("tetrahedron", sample("tetrahedron"), 0), ("figure 8", sample("figure8"), 0),
                       ("lone triangle", sample("lone_triangle"), 0)]
        case_size = (600, 450) if large else (440, 330)
        thumb_size = (400, 300) if large else (300, 225)
        self.titles = [title for title, _, _ in cases]
        self.steppers = [CollapseStepper(mesh, edge, mode=self.mode, preset=self.look, window_size=case_size)
                         for _, mesh, edge in cases]
        self.refused_titles = [title for title, _, _ in refused]
        self.refused = [CollapseStepper(mesh, edge, mode="static", preset=self.look, window_size=thumb_size)
                        for _, mesh, edge in refused]
        for stepper in self.refused:
            self._show_refused(stepper)
        self.phases = [title for _, title in self.steppers[0].log.phases] if self.steppers else []
        self._phase = 0

        css = panel_css(self.look)
        self._status = widgets.HTML()
        self._legend = widgets.HTML(layout=widgets.Layout(margin="0 0 0 12px"))
        self._captions = [widgets.HTML(layout=widgets.Layout(width=f"{case_size[0]}px")) for _ in self.steppers]
        buttons = widgets.HBox([
            self._button("start", lambda: self.go("start")),
            self._button("back", self.back),
            self._button("phase", self.step),
            self._button("end", lambda: self.go("end")),
        ])
        self.buttons = {b.description: b for b in buttons.children}
        columns = widgets.HBox([
            widgets.VBox([widgets.HTML(f'<b style="font-size:{css["font"]}">{html.escape(title)}</b>'),
                          stepper.view.widget, caption])
            for title, stepper, caption in zip(self.titles, self.steppers, self._captions)
        ] + [self._legend], layout=widgets.Layout(flex_flow="row wrap"))     # narrow: the legend goes below
        refusals = widgets.HBox([
            widgets.VBox([widgets.HTML(f'<b style="font-size:{css["font"]}">{html.escape(title)}</b>'),
                          stepper.view.widget,
                          widgets.HTML(f'<div style="font-size:{css["font"]};width:{thumb_size[0]}px">'
                                       f'<code>{html.escape(str(stepper.check.rule))}</code>: '
                                       f"{html.escape(stepper.check.reason)}</div>")],
                         layout=widgets.Layout(margin="0 12px 0 0"))
            for title, stepper in zip(self.refused_titles, self.refused)
        ], layout=widgets.Layout(flex_flow="row wrap"))
        heading = f'<b style="font-size:calc({css["font"]} * 1.25)">{html.escape(self.title)}</b>'
        self.key_area = KeyArea([self._status], self.buttons, self.KEYS, self.look)
        self.widget = widgets.VBox([
            widgets.HTML(heading), buttons, self.key_area.widget, columns,
            widgets.HTML(f'<b style="font-size:calc({css["font"]} * 1.15)">Refused: the link condition and '
                         f"the boundary rules</b>"),
            refusals,
        ])
        self._refresh()

    def _button(self, label: str, action):
        return panel_button(self.look, label, "", action)

    @staticmethod
    def _show_refused(stepper) -> None:
        """Show a refused collapse so its reason can be followed: the edge and its ends'
        neighbours fill the picture, seen at a slant (a tetrahedron seen along its edge is
        a flat rhombus), and every vertex there is labelled, as the reason names vertices."""
        mesh, scene = stepper.before, stepper.scene
        edge = next(index for kind, index in stepper.check.elements if kind == "edge")
        ends = mesh.edge_vertices()[edge]                                      # (2,)
        neighbours = [h.tip.index for v in ends for h in mesh.vertex(int(v)).outgoing()]
        near = np.unique(np.concatenate([ends, neighbours]))
        points = mesh.positions[near]                                         # (k, 3)
        centre = mesh.positions[ends].mean(axis=0)
        _, spread, axes = np.linalg.svd(points - points.mean(axis=0))
        if spread[-1] < 1e-9 * spread[0]:
            direction = axes[2]                  # a flat patch: straight onto its plane
        else:
            # A solid: from outside the edge, turned aside and a little along the edge.
            along = unit(mesh.positions[ends[1]] - mesh.positions[ends[0]])
            outward = unit(centre - mesh.positions[~mesh.vertex_deleted].mean(axis=0))
            side = unit(np.cross(along, outward))
            direction = unit(outward + 0.3 * along + 0.3 * side)
        camera = scene.plotter.camera
        camera.focal_point = tuple(centre)
        camera.position = tuple(centre + direction)
        scene.plotter.reset_camera(bounds=np.column_stack([points.min(axis=0), points.max(axis=0)]).ravel())
        scene.set_roles(scene.roles, names={("vertex", int(v)): f"v{int(v)}" for v in near})
        stepper.view.update()

    @property
    def phase(self) -> int:
        """0 (gathered) to ``len(self.phases)`` (done): every phase up to this one is applied."""
        return self._phase

    def _end_of_phase(self, stepper, phase: int) -> int:
        """The step of ``stepper`` at which its phases up to ``phase`` are all applied."""
        if phase == 0:
            return 0
        phases = stepper.log.phases
        stop = phases[phase][0] if phase < len(phases) else len(stepper.log.changes)
        return sum(1 for _, end in stepper.groups if end <= stop)

    def go(self, target) -> int:
        """Show every case at the end of a phase: "phase" (next), "back", "start", "end", or a number."""
        last, move = len(self.phases), None
        if isinstance(target, str):
            moves = {"phase": self._phase + 1, "next": self._phase + 1, "step": self._phase + 1,
                     "back": self._phase - 1, "start": 0, "end": last}
            if target not in moves:
                raise ValueError(f"unknown move {target!r}: use {', '.join(repr(m) for m in moves)} or a phase number")
            move, target = target, min(max(moves[target], 0), last)
            if target == self._phase:
                self._refresh(f"{move}: phase {self._phase} of {last} is the "
                              + ("last one; ← back or Home to go through it again" if target == last
                                 else "start; → or space goes forward"))
                return self._phase
        target = int(target)
        if not 0 <= target <= last:
            raise IndexError(f"there is no phase {target}: phases run from 0 to {last}")
        self._phase = target
        for stepper in self.steppers:
            stepper.go(self._end_of_phase(stepper, target))
            if target and self._end_of_phase(stepper, target) == self._end_of_phase(stepper, target - 1):
                self._without_changes(stepper)
        self._refresh()
        return self._phase

    @staticmethod
    def _without_changes(stepper) -> None:
        """Take the "changes now" highlight off a case that changes nothing in this phase
        (it would still show the last change of an earlier phase)."""
        scene = stepper.scene
        now = {*CHANGED.values(), *OLD.values(), *NEW.values()}
        scene.set_roles({role: members for role, members in scene.roles.items() if role not in now},
                        names=scene.names)
        stepper.view.update()

    def step(self) -> int:
        """Every case to the end of the next phase."""
        return self.go("phase")

    def back(self) -> int:
        return self.go("back")

    def _phase_title(self) -> str:
        if self._phase == 0:
            return "gather the elements"
        return self.phases[self._phase - 1]

    def _refresh(self, note: str = "") -> None:
        """The phase in words, and ``note`` (why a move did not move) below it."""
        size = panel_css(self.look)["font"]
        self._status.value = (f'<div style="font-size:{size}">phase {self._phase} of {len(self.phases)}: '
                              f"<i>{html.escape(self._phase_title())}</i></div>"
                              + (f'<div style="font-size:{size};color:#555">{html.escape(note)}</div>' if note else ""))
        self._legend.value = legend_html(self.legend_entries(), self.look)
        for caption, stepper in zip(self._captions, self.steppers):
            state = stepper.state
            notes = "".join(f"<div>{html.escape(n)}</div>" for n in stepper.log.notes)
            caption.value = (f'<div style="font-size:{size}">{notes}<div>V - E + F = {state.n_vertices} - '
                             f"{state.n_edges} + {state.n_faces} = {state.euler_characteristic}</div></div>")

    def describe(self) -> str:
        """Each case at the current phase, then each refused case with its reason."""
        lines = [f"phase {self._phase} of {len(self.phases)}: {self._phase_title()}"]
        for title, stepper in zip(self.titles, self.steppers):
            state = stepper.state
            lines.append(f"{title}: collapse of edge {stepper.log.edge}, step {stepper.step_index} of "
                         f"{stepper.n_steps}; V - E + F = {state.n_vertices} - {state.n_edges} + "
                         f"{state.n_faces} = {state.euler_characteristic}")
            lines += [f"  {note}" for note in stepper.log.notes]
        for title, stepper in zip(self.refused_titles, self.refused):
            lines.append(f"refused, {title} ({stepper.check.rule}): {stepper.check.reason}")
        return "\n".join(lines)

    def legend_entries(self) -> list[tuple[str, str, str]]:
        """What the colours of every picture of the atlas mean now, each once:
        ``(text, "#RRGGBB", kind)`` as :meth:`HalfedgeScene.legend_entries`."""
        entries: dict[tuple[str, str, str], None] = {}
        for stepper in self.steppers + self.refused:
            entries.update(dict.fromkeys(stepper.scene.legend_entries()))
        return list(entries)

    def screenshot(self, path=None) -> bytes:
        """Every picture of the atlas in one PNG, titled: the cases in a row with the
        legend beside them, the refusals below."""
        phase = f"phase {self._phase} of {len(self.phases)}"
        return grid_png([[s.screenshot() for s in self.steppers] + [legend_png(self.legend_entries())],
                         [s.screenshot() for s in self.refused]],
                        [[f"{title} ({phase})" for title in self.titles] + ["legend"],
                         [f"refused: {title}" for title in self.refused_titles]], path=path)

    def close(self) -> None:
        self.key_area.close()
        self.widget.close()
        for stepper in self.steppers + self.refused:
            stepper.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        steppers = self.steppers + self.refused
        for stepper in steppers:                       # their pictures are part of this widget
            stepper.view.shown()
        return widget_bundle(self.widget, self.describe(), [stepper.scene.plotter for stepper in steppers],
                             self.screenshot, include, exclude)
