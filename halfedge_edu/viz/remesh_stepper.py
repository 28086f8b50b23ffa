"""Step through isotropic remeshing phase by phase, with quality histograms beside the mesh.

    from halfedge_edu.viz.remesh_stepper import RemeshStepper
    w = RemeshStepper(mesh, target_length=0.08, iterations=2)
    w                      # step 0: the input, its too-long and too-short edges marked
    w.step()               # iteration 1, split; then collapse, flip, smooth, project
    w.go("flip")           # the next flip phase; also "start", "end", "iteration", 4, (2, "smooth")
    print(w.describe())    # what the phase did, and the quality numbers now

The stepper runs :func:`~halfedge_edu.algorithms.remesh.remesh_step_by_step` once and
keeps every snapshot ``(iteration, phase, mesh)``, so each picture is the real
algorithm's state and going back costs nothing. The picture marks the edges longer
than 4/3 L (the next split's work), the edges shorter than 4/5 L (the next collapse's)
and the vertices whose degree is 2 or more away from the ideal (6 inside, 4 on a
boundary: the flips' work). Below it, three histograms compare the input (grey) with
the mesh now: edge length in units of L, vertex degree, and each triangle's smallest
angle. :func:`histogram_png` draws the same histograms for any meshes, for a
before/after picture in a notebook.
"""

from __future__ import annotations

import html
import io
from dataclasses import dataclass

import numpy as np

from ..algorithms.remesh import COLLAPSE_BELOW, SPLIT_ABOVE, quality_report, remesh_step_by_step
from .painted_scene import Layer, PaintedScene, legend_html
from .palette import BLUE, BLUISH_GREEN, ORANGE, REDDISH_PURPLE, VERMILLION, panel_css
from .pictures import grid_png
from .widgets import StepperWidget

TOO_LONG, TOO_SHORT, OFF_DEGREE = VERMILLION, BLUE, REDDISH_PURPLE
#: Colours of the histograms' outlines after the first (grey, filled) entry.
LINE_COLOURS = (BLUE, VERMILLION, BLUISH_GREEN, ORANGE, REDDISH_PURPLE)
#: What each phase does, in one sentence (the library's phase names).
PHASE_TEXT = {
    "input": "the mesh before remeshing",
    "split": "split every edge longer than 4/3 L at its midpoint",
    "collapse": "collapse edges shorter than 4/5 L, unless that makes an edge longer than 4/3 L",
    "flip": "flip edges where that brings the four vertices' degrees closer to 6 (4 on a boundary)",
    "smooth": "move every interior vertex towards its neighbours' centroid, in its tangent plane only",
    "project": "put every vertex back onto the input surface (boundary vertices onto its boundary)",
}


# ----------------------------------------------------------------------------------------
# Quality numbers of one mesh, relative to a target length
# ----------------------------------------------------------------------------------------

@dataclass
class PhaseQuality:
    """What the histograms and the text need to know about one mesh.

    ``lengths`` (E,) are in units of ``L``; ``degrees`` (V,) and ``on_boundary`` (V,)
    per live vertex; ``min_angles`` (F,) each face's smallest angle in degrees.
    ``degree_deviation`` and ``min_angle_mean`` are those of
    :func:`~halfedge_edu.algorithms.remesh.quality_report`.
    """

    n_vertices: int
    n_edges: int
    n_faces: int
    lengths: np.ndarray
    degrees: np.ndarray
    on_boundary: np.ndarray
    min_angles: np.ndarray
    degree_deviation: float
    min_angle_mean: float

    @property
    def n_long(self) -> int:
        """Edges longer than 4/3 L."""
        return int((self.lengths > SPLIT_ABOVE).sum())

    @property
    def n_short(self) -> int:
        """Edges shorter than 4/5 L."""
        return int((self.lengths < COLLAPSE_BELOW).sum())

    @property
    def n_off_degree(self) -> int:
        """Vertices whose degree is 2 or more away from the ideal (6 inside, 4 on a boundary)."""
        ideal = np.where(self.on_boundary, 4, 6)
        return int((np.abs(self.degrees - ideal) >= 2).sum())

    @property
    def in_range(self) -> float:
        """The fraction of edges between 4/5 L and 4/3 L."""
        return float(((self.lengths >= COLLAPSE_BELOW) & (self.lengths <= SPLIT_ABOVE)).mean())

    def summary(self) -> str:
        """One line: counts, edges in range, degrees, angles."""
        return (f"{self.n_vertices} vertices, {self.n_faces} faces | edges in [4/5 L, 4/3 L]: "
                f"{100 * self.in_range:.0f}% ({self.n_short} short, {self.n_long} long) | "
                f"mean |degree - ideal| {self.degree_deviation:.3f} | "
                f"smallest angle: mean {self.min_angle_mean:.1f} deg, below 30 deg in "
                f"{int((self.min_angles < 30.0).sum())} faces")


def phase_quality(mesh, target_length: float) -> PhaseQuality:
    """Measure ``mesh`` (only read) against the target edge length ``target_length``."""
    report = quality_report(mesh)
    live_edges = np.flatnonzero(~mesh.edge_deleted)
    ends = mesh.edge_vertices()[live_edges]                              # (E, 2)
    P = mesh.positions
    lengths = np.linalg.norm(P[ends[:, 0]] - P[ends[:, 1]], axis=1) / float(target_length)
    live_vertices = np.flatnonzero(~mesh.vertex_deleted)
    corners = P[mesh.face_vertices()[~mesh.face_deleted]]                # (F, 3, 3)
    along, back = np.roll(corners, -1, axis=1) - corners, np.roll(corners, 1, axis=1) - corners
    angles = np.degrees(np.arctan2(np.linalg.norm(np.cross(along, back), axis=2),
                                   np.einsum("fkd,fkd->fk", along, back)))
    return PhaseQuality(
        n_vertices=mesh.n_vertices, n_edges=mesh.n_edges, n_faces=mesh.n_faces,
        lengths=lengths,
        degrees=mesh.vertex_degrees()[live_vertices],
        on_boundary=mesh.vertex_is_boundary()[live_vertices],
        min_angles=angles.min(axis=1),
        degree_deviation=report.degree_deviation,
        min_angle_mean=report.min_angle_mean,
    )


# ----------------------------------------------------------------------------------------
# The histograms
# ----------------------------------------------------------------------------------------

def draw_histograms(figure, qualities, labels, *, max_length: float = 2.0) -> None:
    """Draw three histograms (edge length / L, degree, smallest angle) into ``figure``.

    The first entry is drawn filled in grey, the others as coloured outlines; the
    heights are percentages, so meshes of different sizes compare fairly. The legend
    (``labels``) is the last histogram's, above its axes.
    """
    axes = figure.subplots(1, 3)
    length_bins = np.linspace(0.0, max_length, 41)
    all_degrees = np.concatenate([q.degrees for q in qualities])
    degree_bins = np.arange(max(2, all_degrees.min()) - 0.5, min(12, all_degrees.max()) + 1.5)
    angle_bins = np.linspace(0.0, 60.0, 31)
    columns = [
        ("edge length / L (last bin: 2 and more)", lambda q: np.minimum(q.lengths, max_length), length_bins, "edges"),
        ("vertex degree", lambda q: np.clip(q.degrees, degree_bins[0] + 0.5, degree_bins[-1] - 0.5), degree_bins,
         "vertices"),
        ("smallest angle of each face (deg)", lambda q: np.minimum(q.min_angles, 60.0), angle_bins, "faces"),
    ]
    for axis, (title, values, bins, noun) in zip(axes, columns):
        for k, (quality, label) in enumerate(zip(qualities, labels)):
            data = values(quality)
            weights = np.full(len(data), 100.0 / max(len(data), 1))
            if k == 0:
                axis.hist(data, bins=bins, weights=weights, color="#C8C8C8", label=label)
            else:
                axis.hist(data, bins=bins, weights=weights, histtype="step", linewidth=2.0,
                          color=LINE_COLOURS[(k - 1) % len(LINE_COLOURS)], label=label)
        axis.set_xlabel(title)
        axis.set_ylabel(f"% of {noun}")
        axis.spines[["top", "right"]].set_visible(False)
    for x in (COLLAPSE_BELOW, 1.0, SPLIT_ABOVE):
        axes[0].axvline(x, color="#555555", linestyle=":" if x != 1.0 else "-", linewidth=1.0)
    axes[0].set_title("4/5 L  |  L  |  4/3 L", fontsize=9, color="#555555")
    axes[1].axvline(6, color="#555555", linewidth=1.0)
    axes[2].axvline(60, color="#555555", linewidth=1.0)
    # The legend goes above the last histogram, outside it, so it covers no bar whatever
    # the data (tight_layout makes room for it); from its right end, so that a long
    # label reaches left over the gap between the histograms, not out of the picture.
    axes[2].legend(loc="lower right", bbox_to_anchor=(1.0, 1.02), borderaxespad=0.0, fontsize=8, frameon=False)
    figure.tight_layout()


def histogram_png(meshes, labels, target_length: float, *, size=(8.4, 2.5), dpi: int = 80) -> bytes:
    """PNG bytes of :func:`draw_histograms` for ``meshes`` (or :class:`PhaseQuality` s).

    Drawn with matplotlib's Agg canvas directly (no pyplot), so nothing else is shown.
    """
    buffer = io.BytesIO()
    histogram_figure(meshes, labels, target_length, size=size, dpi=dpi).savefig(
        buffer, format="png", metadata={"Software": None})
    return buffer.getvalue()


def histogram_figure(meshes, labels, target_length: float, *, size=(8.4, 2.5), dpi: int = 80):
    """The matplotlib ``Figure`` (no pyplot) that :func:`histogram_png` draws."""
    from matplotlib.figure import Figure

    qualities = [m if isinstance(m, PhaseQuality) else phase_quality(m, target_length) for m in meshes]
    figure = Figure(figsize=size, dpi=dpi)
    draw_histograms(figure, qualities, labels)
    return figure


# ----------------------------------------------------------------------------------------
# The stepper
# ----------------------------------------------------------------------------------------

@dataclass(eq=False)
class _Snapshot:
    iteration: int
    phase: str
    mesh: object
    quality: PhaseQuality


class RemeshStepper(StepperWidget):
    """Isotropic remeshing, one phase at a time, with histograms of the quality.

    Args:
        mesh: the input (copied, never changed).
        target_length: the edge length L (default: the input's mean edge length, as
            :func:`~halfedge_edu.algorithms.remesh.remesh` takes it).
        iterations: how many iterations to run (each has 5 phases with ``project``).
        project: put the vertices back on the input after each smoothing.
        mode: ``"live"``, ``"static"`` or None (automatic).
        preset: ``"default"`` or ``"large"`` (a projector).
        window_size: picture size in pixels.
        view_direction: (3,) from the mesh toward the camera.
        histogram_size: the histograms' size in inches (at 80 dpi).
        zoom: magnify the first view by this factor (above 1 for long, thin shapes).

    ``snapshots`` holds every ``(iteration, phase, mesh, quality)``; ``step()``,
    ``back()`` and ``go(...)`` move; ``state`` is the mesh shown, ``result`` the last.

    Keys (mouse pointer over the panel below the buttons): → or space the next phase,
    ← one back, PgDn the same phase one iteration on, Home the input, End the result.
    """

    title = "Isotropic remeshing: phase by phase"
    KEYS = {**StepperWidget.KEYS, "PageDown": "iteration"}

    def __init__(self, mesh, target_length: float | None = None, iterations: int = 2, *, project: bool = True,
                 mode: str | None = None, preset="default", window_size=None, view_direction=None,
                 histogram_size=(8.4, 2.5), zoom: float = 1.0):
        import ipywidgets as widgets

        before = mesh.copy()
        if before.has_garbage:
            before.garbage_collect()
        if target_length is None:
            ends = before.edge_vertices()
            target_length = float(np.linalg.norm(before.positions[ends[:, 0]] - before.positions[ends[:, 1]],
                                                 axis=1).mean())
        self.target_length = float(target_length)
        self.iterations = int(iterations)
        self.snapshots = [_Snapshot(s.iteration, s.phase, s.mesh, phase_quality(s.mesh, self.target_length))
                          for s in remesh_step_by_step(before, self.target_length, self.iterations, project=project)]
        self.before = before
        self._step = 0
        self._view_direction = view_direction
        self._zoom = float(zoom)
        self._histogram_size = tuple(histogram_size)
        self._histograms = widgets.Image(format="png")
        super().__init__(before.copy(), mode=mode, preset=preset, labels=None, rings=0, window_size=window_size)
        self.widget = widgets.VBox([self.widget, self._histograms])

    # -- public --------------------------------------------------------------------------

    @property
    def n_steps(self) -> int:
        """Snapshots after the input: one per phase of every iteration."""
        return len(self.snapshots) - 1

    @property
    def iteration(self) -> int:
        return self.snapshots[self._step].iteration

    @property
    def phase(self) -> str:
        return self.snapshots[self._step].phase

    @property
    def quality(self) -> PhaseQuality:
        """The numbers of the mesh shown now."""
        return self.snapshots[self._step].quality

    @property
    def state(self):
        """A copy of the mesh shown now."""
        return self.snapshots[self._step].mesh.copy()

    @property
    def result(self):
        """A copy of the remeshed mesh (the last snapshot): what ``remesh`` returns."""
        return self.snapshots[-1].mesh.copy()

    def index_of(self, iteration: int, phase: str) -> int:
        """The step number of ``phase`` in ``iteration``."""
        for k, snapshot in enumerate(self.snapshots):
            if snapshot.iteration == iteration and snapshot.phase == phase:
                return k
        phases = sorted({s.phase for s in self.snapshots[1:]}, key=list(PHASE_TEXT).index)
        raise ValueError(f"there is no phase {phase!r} in iteration {iteration}: iterations run from 1 to "
                         f"{self.iterations}, phases are {', '.join(phases)}")

    _moves_help = "a step number, (iteration, phase), a phase name"

    def _named_moves(self) -> dict[str, int]:
        """Also "iteration": the same phase one iteration on. From the input (the end of
        iteration 0, so to speak) that is the end of iteration 1; in the last iteration
        it stays where it is (:meth:`go` says why)."""
        if self._step == 0:
            iteration_on = max(k for k, s in enumerate(self.snapshots) if s.iteration == 1)
        else:
            same_phase_next = [k for k, s in enumerate(self.snapshots)
                               if s.phase == self.phase and s.iteration == self.iteration + 1]
            iteration_on = same_phase_next[0] if same_phase_next else self._step
        return {**super()._named_moves(), "iteration": iteration_on}

    def go(self, target) -> int:
        """Go to a step: a number, ``(iteration, phase)``, a phase name, or a named move
        ("start", "back", "step", "iteration", "end"). Returns the step shown."""
        last_iteration = self._step > 0 and self.iteration == self.iterations
        shown = super().go(target)
        if last_iteration and isinstance(target, str) and target.strip().lower() == "iteration":
            self._say(f"iteration {self.iterations} is the last one: there is no iteration after it")
        return shown

    def _resolve(self, target) -> int | None:
        """``(iteration, phase)``, or a phase name: its next occurrence (else its first)."""
        if isinstance(target, tuple):
            return self.index_of(*target)
        if isinstance(target, str):
            later = [k for k, s in enumerate(self.snapshots) if s.phase == target.strip().lower()]
            if later:
                return next((k for k in later if k > self._step), later[0])
        return None

    def describe(self, step: int | None = None) -> str:
        """A phase in words and numbers (deterministic, for nbval and for reading): the
        one shown, or that of ``step`` (read without moving the widget).

        Raises:
            IndexError: ``step`` is not one of 0 .. ``n_steps``.
        """
        step = self._step if step is None else int(step)
        if not 0 <= step <= self.n_steps:
            raise IndexError(f"there is no step {step}: steps run from 0 to {self.n_steps}")
        snapshot = self.snapshots[step]
        where = "input" if snapshot.phase == "input" else f"iteration {snapshot.iteration}, {snapshot.phase}"
        lines = [f"Isotropic remeshing of {self.before.n_faces} faces, L = {self.target_length:.4g}, "
                 f"{self.iterations} iterations: step {step} of {self.n_steps}, {where}",
                 f"phase: {PHASE_TEXT[snapshot.phase]}"]
        if step:
            lines.append(f"did: {self._change_text(step)}")
        lines.append(f"now: {snapshot.quality.summary()}")
        return "\n".join(lines)

    # -- text ----------------------------------------------------------------------------

    def _change_text(self, step: int) -> str:
        """What the phase of ``step`` changed, measured against the snapshot before it."""
        old, new = self.snapshots[step - 1], self.snapshots[step]
        phase, L = new.phase, self.target_length
        dv, df = new.mesh.n_vertices - old.mesh.n_vertices, new.mesh.n_faces - old.mesh.n_faces
        if phase == "split":
            again = "; halves still too long were split again" if dv > old.quality.n_long else ""
            return (f"{dv} splits ({old.quality.n_long} edges were longer than 4/3 L = {SPLIT_ABOVE * L:.4g}"
                    f"{again}): +{dv} vertices, +{df} faces")
        if phase == "collapse":
            return (f"{-dv} edges collapsed ({old.quality.n_short} were shorter than 4/5 L = "
                    f"{COLLAPSE_BELOW * L:.4g}); {dv} vertices, {df} faces; longest edge now "
                    f"{new.quality.lengths.max():.3f} L")
        if phase == "flip":
            flipped = len(_edge_keys(new.mesh) - _edge_keys(old.mesh))
            return (f"{flipped} edges flipped; mean |degree - ideal| {old.quality.degree_deviation:.3f} -> "
                    f"{new.quality.degree_deviation:.3f}; vertices 2 or more off: {old.quality.n_off_degree} -> "
                    f"{new.quality.n_off_degree}")
        moved = np.linalg.norm(new.mesh.positions - old.mesh.positions, axis=1) / L
        if phase == "smooth":
            n_boundary = int(old.quality.on_boundary.sum())
            kept = f"; the {n_boundary} boundary vertices stayed put" if n_boundary else ""
            return f"vertices moved by {moved.mean():.3f} L on average, at most {moved.max():.3f} L{kept}"
        return f"vertices moved back by {moved.mean():.4f} L on average, at most {moved.max():.4f} L"

    # -- the picture ---------------------------------------------------------------------

    def _make_scene(self, mesh, **options) -> PaintedScene:
        scene = PaintedScene(mesh, preset=self.look, plotter=options["plotter"], window_size=options["window_size"],
                             view_direction=self._view_direction, vertex_labels=False)
        if self._zoom != 1.0:
            scene.plotter.camera.zoom(self._zoom)
        return scene

    def _layers(self) -> list[Layer]:
        snapshot = self.snapshots[self._step]
        mesh, quality = snapshot.mesh, snapshot.quality
        live_edges = np.flatnonzero(~mesh.edge_deleted)
        live_vertices = np.flatnonzero(~mesh.vertex_deleted)
        ideal = np.where(quality.on_boundary, 4, 6)
        return [
            Layer("longer than 4/3 L: to split", TOO_LONG, "edges", live_edges[quality.lengths > SPLIT_ABOVE], 3.0),
            Layer("shorter than 4/5 L: to collapse", TOO_SHORT, "edges",
                  live_edges[quality.lengths < COLLAPSE_BELOW], 3.0),
            Layer("degree 2 or more from the ideal", OFF_DEGREE, "vertices",
                  live_vertices[np.abs(quality.degrees - ideal) >= 2], 8.0),
        ]

    def _show(self) -> None:
        self.scene.paint(self.snapshots[self._step].mesh, layers=self._layers())

    def histogram_png(self) -> bytes:
        """The histograms of the input and of the mesh shown now, as PNG bytes."""
        labels = ["input"]
        if self._step:
            snapshot = self.snapshots[self._step]
            labels.append(f"iteration {snapshot.iteration}, {snapshot.phase}")
        qualities = [self.snapshots[0].quality] + ([self.quality] if self._step else [])
        return histogram_png(qualities, labels, self.target_length, size=self._histogram_size)

    def screenshot(self, path=None) -> bytes:
        """The view with the histograms below it, as PNG bytes (also written to ``path``)."""
        return grid_png([[super().screenshot()], [self.histogram_png()]], path=path)

    # -- panel ---------------------------------------------------------------------------

    def _controls(self) -> list:
        return self._button_row([
            ("start", "the input", lambda: self.go("start")),
            ("back", "one phase back", self.back),
            ("step", "the next phase", self.step),
            ("iteration", "the same phase, one iteration on", lambda: self.go("iteration")),
            ("end", "the remeshed mesh", lambda: self.go("end")),
        ])

    def _panel_html(self) -> str:
        size = panel_css(self.look)["font"]
        cell = "padding:2px 6px;border-bottom:1px solid #ddd;text-align:right;white-space:nowrap"
        header = "".join(f'<th style="{cell}">{h}</th>'
                         for h in ("", "phase", "V", "F", "short", "long", "|deg - ideal|", "min angle"))
        rows = []
        for k, snapshot in enumerate(self.snapshots):
            q = snapshot.quality
            style = "font-weight:bold;background:#FFF3D6;" if k == self._step else (
                "color:#AAAAAA;" if k > self._step else "")
            name = "input" if snapshot.phase == "input" else f"{snapshot.iteration} {snapshot.phase}"
            cells = (k, name, q.n_vertices, q.n_faces, q.n_short, q.n_long, f"{q.degree_deviation:.3f}",
                     f"{q.min_angle_mean:.1f}")
            rows.append("<tr>" + "".join(f'<td style="{cell};{style}">{html.escape(str(c))}</td>' for c in cells)
                        + "</tr>")
        table = (f'<table style="border-collapse:collapse;font-size:calc({size} * 0.9);font-family:monospace">'
                 f'{header}{"".join(rows)}</table>')
        text = "<br>".join(html.escape(line) for line in self.describe().splitlines()[1:-1])
        return (f'<div style="font-size:{size};max-width:38em;margin:4px 0">{text}</div>{table}')

    def _refresh_panel(self) -> None:
        self._info.value = self._panel_html()
        self._legend.value = legend_html(self.scene.legend_entries(), self.look)
        self._histograms.value = self.histogram_png()


def _edge_keys(mesh) -> set:
    """The live edges as a set of ``(low, high)`` vertex pairs."""
    ends = np.sort(mesh.edge_vertices()[~mesh.edge_deleted], axis=1)
    return set(map(tuple, ends.tolist()))
