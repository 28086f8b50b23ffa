"""Named actors in a PyVista plotter whose geometry is swapped in place.

A scene adds each of its parts (surface, arrows, dots, labels) once, under a name, and
later only refills that part's dataset: the actor, its style and the camera stay, and
nothing is rebuilt on the VTK side but the arrays. An empty part is hidden, not removed.
"""

from __future__ import annotations


class Actors:
    """The parts of one scene, by name, in ``plotter``."""

    def __init__(self, plotter):
        self.plotter = plotter
        self.actors: dict[str, object] = {}
        self.datasets: dict[str, object] = {}

    def __contains__(self, name: str) -> bool:
        return name in self.actors

    def add(self, name: str, data, **style) -> None:
        """Add (or replace) the part ``name`` drawing ``data`` with pyvista's ``add_mesh`` style."""
        self.datasets[name] = data
        self.actors[name] = self.plotter.add_mesh(data, name=name, reset_camera=False, **style)

    def add_labels(self, name: str, data, **style) -> None:
        """Add the part ``name``: the texts in ``data.point_data["labels"]`` at its points."""
        self.datasets[name] = data
        self.actors[name] = self.plotter.add_point_labels(
            data, "labels", name=name, show_points=False, always_visible=True,
            margin=2, reset_camera=False, render=False, **style,
        )

    def set(self, name: str, data) -> None:
        """Swap the geometry of part ``name`` in place (hidden when ``data`` is None or empty)."""
        actor = self.actors[name]
        if data is None or data.n_points == 0:
            actor.SetVisibility(False)
            return
        self.datasets[name].copy_from(data, deep=False)
        actor.SetVisibility(True)

    def refill(self, name: str, data) -> None:
        """Copy ``data`` deeply into part ``name`` and show it (for actors that read their
        dataset's arrays later, such as labels)."""
        self.datasets[name].copy_from(data)
        self.actors[name].SetVisibility(True)

    def hide(self, name: str) -> None:
        """Hide part ``name``."""
        self.actors[name].SetVisibility(False)

    def visible(self, name: str) -> bool:
        """True when part ``name`` is drawn now."""
        return bool(self.actors[name].GetVisibility())

    def data(self, name: str):
        """The dataset part ``name`` draws (change its arrays to recolour in place)."""
        return self.datasets[name]
