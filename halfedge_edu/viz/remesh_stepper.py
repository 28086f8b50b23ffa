"""Step through isotropic remeshing phase by phase, with quality histograms beside the mesh.

    from halfedge_edu.viz.remesh_stepper import RemeshStepper
    w = RemeshStepper(mesh, target_length=0.08, iterations=2)
    w                      # step 0: the input, its too-long and too-short edges marked
    w.step()               # iteration 1, split; then collapse, flip, smooth, project
    w.go("flip")           # the next flip phase; also "start", "end", "iteration", 4, (2, "smooth")
    print(w.describe())    # what the phase did, and the quality numbers now

:class:`RemeshSteps` runs :func:`~halfedge_edu.algorithms.remesh.remesh_step_by_step` once
and keeps every :class:`~halfedge_edu.algorithms.remesh.RemeshStep` ``(iteration, phase,
mesh)`` with its quality numbers, so each picture is the real algorithm's state and going
back costs nothing. :class:`RemeshPainter`'s picture marks the edges longer
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
from .steps import Stepper

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
# The stepper: its steps, its painter, the widget
# ----------------------------------------------------------------------------------------

@dataclass(eq=False)
class Snapshot:
    """One phase's mesh and its quality numbers."""

    iteration: int
    phase: str
    mesh: object
    quality: PhaseQuality


class RemeshSteps:
    """The :class:`~.steps.Steps` of isotropic remeshing: step 0 the input, then one step
    per phase of every iteration. ``snapshots`` holds a :class:`Snapshot` per step."""

    def __init__(self, mesh, target_length: float | None = None, iterations: int = 2, *, project: bool = True):
        before = mesh.copy()
        if before.has_garbage:
            before.garbage_collect()
        if target_length is None:
            ends = before.edge_vertices()
            target_length = float(np.linalg.norm(before.positions[ends[:, 0]] - before.positions[ends[:, 1]],
                                                 axis=1).mean())
        self.target_length = float(target_length)
        self.iterations = int(iterations)
        self.snapshots = [Snapshot(s.iteration, s.phase, s.mesh, phase_quality(s.mesh, self.target_length))
                          for s in remesh_step_by_step(before, self.target_length, self.iterations, project=project)]
        self.before = before

    @property
    def n_steps(self) -> int:
        return len(self.snapshots) - 1

    def mesh(self, k: int):
        return self.snapshots[k].mesh

    @property
    def result(self):
        return self.snapshots[-1].mesh.copy()

    def index_of(self, iteration: int, phase: str) -> int:
        """The step number of ``phase`` in ``iteration``."""
        for k, snapshot in enumerate(self.snapshots):
            if snapshot.iteration == iteration and snapshot.phase == phase:
                return k
        phases = sorted({s.phase for s in self.snapshots[1:]}, key=list(PHASE_TEXT).index)
        raise ValueError(f"there is no phase {phase!r} in iteration {iteration}: iterations run from 1 to "
                         f"{self.iterations}, phases are {', '.join(phases)}")

    def moves(self, k: int) -> dict[str, int]:
        """"iteration": the same phase one iteration on. From the input (the end of
        iteration 0, so to speak) that is the end of iteration 1; in the last iteration
        it stays where it is."""
        if k == 0:
            return {"iteration": max(j for j, s in enumerate(self.snapshots) if s.iteration == 1)}
        now = self.snapshots[k]
        same_phase_next = [j for j, s in enumerate(self.snapshots)
                           if s.phase == now.phase and s.iteration == now.iteration + 1]
        return {"iteration": same_phase_next[0] if same_phase_next else k}

    def resolve(self, target, k: int) -> int | None:
        """``(iteration, phase)``, or a phase name: its next occurrence (else its first)."""
        if isinstance(target, tuple):
            return self.index_of(*target)
        if isinstance(target, str):
            later = [j for j, s in enumerate(self.snapshots) if s.phase == target.strip().lower()]
            if later:
                return next((j for j in later if j > k), later[0])
        return None


class RemeshPainter:
    """How a phase of remeshing looks (a :class:`~.steps.Painter`): the edges to split and
    to collapse, the vertices off degree, and the words and table of the panel."""

    title = "Isotropic remeshing: phase by phase"
    keys = {"PageDown": "iteration"}
    buttons = (("start", "the input", "start"),
               ("back", "one phase back", "back"),
               ("step", "the next phase", "step"),
               ("iteration", "the same phase, one iteration on", "iteration"),
               ("end", "the remeshed mesh", "end"))
    moves_help = "a step number, (iteration, phase), a phase name"

    def __init__(self, steps: RemeshSteps, *, view_direction=None, zoom: float = 1.0, histogram_size=(8.4, 2.5)):
        self.steps = steps
        self.view_direction = view_direction
        self.zoom = float(zoom)
        self.histogram_size = tuple(histogram_size)

    def make_scene(self, mesh, look, **options) -> PaintedScene:
        scene = PaintedScene(mesh, preset=look, plotter=options["plotter"], window_size=options["window_size"],
                             view_direction=self.view_direction, vertex_labels=False)
        if self.zoom != 1.0:
            scene.plotter.camera.zoom(self.zoom)
        return scene

    def layers(self, k: int) -> list[Layer]:
        snapshot = self.steps.snapshots[k]
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

    def paint(self, scene, k: int) -> None:
        scene.paint(self.steps.snapshots[k].mesh, layers=self.layers(k))

    def legend_html(self, scene, look) -> str:
        return legend_html(scene.legend_entries(), look)

    def histogram_png(self, k: int) -> bytes:
        """The histograms of the input and of step ``k``, as PNG bytes."""
        snapshots = self.steps.snapshots
        labels = ["input"]
        if k:
            labels.append(f"iteration {snapshots[k].iteration}, {snapshots[k].phase}")
        qualities = [snapshots[0].quality] + ([snapshots[k].quality] if k else [])
        return histogram_png(qualities, labels, self.steps.target_length, size=self.histogram_size)

    def describe(self, k: int) -> str:
        steps = self.steps
        snapshot = steps.snapshots[k]
        where = "input" if snapshot.phase == "input" else f"iteration {snapshot.iteration}, {snapshot.phase}"
        lines = [f"Isotropic remeshing of {steps.before.n_faces} faces, L = {steps.target_length:.4g}, "
                 f"{steps.iterations} iterations: step {k} of {steps.n_steps}, {where}",
                 f"phase: {PHASE_TEXT[snapshot.phase]}"]
        if k:
            lines.append(f"did: {self.change_text(k)}")
        lines.append(f"now: {snapshot.quality.summary()}")
        return "\n".join(lines)

    def change_text(self, k: int) -> str:
        """What the phase of step ``k`` changed, measured against the step before it."""
        old, new = self.steps.snapshots[k - 1], self.steps.snapshots[k]
        phase, L = new.phase, self.steps.target_length
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

    def panel_html(self, stepper) -> str:
        k = stepper.step_index
        size = panel_css(stepper.look)["font"]
        cell = "padding:2px 6px;border-bottom:1px solid #ddd;text-align:right;white-space:nowrap"
        header = "".join(f'<th style="{cell}">{h}</th>'
                         for h in ("", "phase", "V", "F", "short", "long", "|deg - ideal|", "min angle"))
        rows = []
        for j, snapshot in enumerate(self.steps.snapshots):
            q = snapshot.quality
            style = "font-weight:bold;background:#FFF3D6;" if j == k else ("color:#AAAAAA;" if j > k else "")
            name = "input" if snapshot.phase == "input" else f"{snapshot.iteration} {snapshot.phase}"
            cells = (j, name, q.n_vertices, q.n_faces, q.n_short, q.n_long, f"{q.degree_deviation:.3f}",
                     f"{q.min_angle_mean:.1f}")
            rows.append("<tr>" + "".join(f'<td style="{cell};{style}">{html.escape(str(c))}</td>' for c in cells)
                        + "</tr>")
        table = (f'<table style="border-collapse:collapse;font-size:calc({size} * 0.9);font-family:monospace">'
                 f'{header}{"".join(rows)}</table>')
        text = "<br>".join(html.escape(line) for line in self.describe(k).splitlines()[1:-1])
        return (f'<div style="font-size:{size};max-width:38em;margin:4px 0">{text}</div>{table}')


class RemeshStepper(Stepper):
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

    def __init__(self, mesh, target_length: float | None = None, iterations: int = 2, *, project: bool = True,
                 mode: str | None = None, preset="default", window_size=None, view_direction=None,
                 histogram_size=(8.4, 2.5), zoom: float = 1.0):
        import ipywidgets as widgets

        steps = RemeshSteps(mesh, target_length, iterations, project=project)
        self._histograms = widgets.Image(format="png")
        super().__init__(steps, RemeshPainter(steps, view_direction=view_direction, zoom=zoom,
                                              histogram_size=histogram_size),
                         mode=mode, preset=preset, window_size=window_size)
        self.widget = widgets.VBox([self.widget, self._histograms])

    @property
    def before(self):
        return self.source.before

    @property
    def target_length(self) -> float:
        return self.source.target_length

    @property
    def iterations(self) -> int:
        return self.source.iterations

    @property
    def snapshots(self) -> list[Snapshot]:
        """Every step: ``(iteration, phase, mesh, quality)``."""
        return self.source.snapshots

    @property
    def iteration(self) -> int:
        return self.source.snapshots[self._step].iteration

    @property
    def phase(self) -> str:
        return self.source.snapshots[self._step].phase

    @property
    def quality(self) -> PhaseQuality:
        """The numbers of the mesh shown now."""
        return self.source.snapshots[self._step].quality

    def index_of(self, iteration: int, phase: str) -> int:
        """The step number of ``phase`` in ``iteration``."""
        return self.source.index_of(iteration, phase)

    def go(self, target) -> int:
        """Go to a step: a number, ``(iteration, phase)``, a phase name, or a named move
        ("start", "back", "step", "iteration", "end"). Returns the step shown."""
        last_iteration = self._step > 0 and self.iteration == self.iterations
        shown = super().go(target)
        if last_iteration and isinstance(target, str) and target.strip().lower() == "iteration":
            self._say(f"iteration {self.iterations} is the last one: there is no iteration after it")
        return shown

    def describe(self, step: int | None = None) -> str:
        """A phase in words and numbers (deterministic, for nbval and for reading): the
        one shown, or that of ``step`` (read without moving the widget).

        Raises:
            IndexError: ``step`` is not one of 0 .. ``n_steps``.
        """
        step = self._step if step is None else int(step)
        if not 0 <= step <= self.n_steps:
            raise IndexError(f"there is no step {step}: steps run from 0 to {self.n_steps}")
        return self.painter.describe(step)

    def histogram_png(self) -> bytes:
        """The histograms of the input and of the mesh shown now, as PNG bytes."""
        return self.painter.histogram_png(self._step)

    def screenshot(self, path=None) -> bytes:
        """The view with the histograms below it, as PNG bytes (also written to ``path``)."""
        return grid_png([[super().screenshot()], [self.histogram_png()]], path=path)

    def _refresh_panel(self) -> None:
        super()._refresh_panel()
        self._histograms.value = self.histogram_png()


def _edge_keys(mesh) -> set:
    """The live edges as a set of ``(low, high)`` vertex pairs."""
    ends = np.sort(mesh.edge_vertices()[~mesh.edge_deleted], axis=1)
    return set(map(tuple, ends.tolist()))
