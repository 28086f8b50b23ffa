"""What isotropic remeshing improves, measured: edge lengths, vertex degrees, angles.

:func:`quality_report` measures one mesh (:class:`MeshQuality`): how spread the edge
lengths are around their mean, how far the vertex degrees are from 6 (4 on the
boundary), and how small the smallest angle of each face is, with histograms of each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.corner_table import edge_table
from ...core.errors import MeshInputError
from ...core.mesh import HalfedgeMesh
from ..arguments import check_mesh, whole_number
from .lengths import edge_lengths


@dataclass
class MeshQuality:
    """What isotropic remeshing improves, measured on one mesh.

    ``degree_histogram[d]`` counts the vertices of degree ``d``; ``min_angle_histogram``
    is ``(counts, bin_edges)`` of each face's smallest angle in degrees (``np.histogram``);
    ``edge_length_histogram`` likewise for the edge lengths. ``degree_deviation`` is
    the mean of ``|degree - 6|`` over interior vertices and ``|degree - 4|`` over boundary
    ones (on a closed mesh: the mean of ``|degree - 6|``).
    """

    n_vertices: int
    n_faces: int
    edge_length_mean: float
    edge_length_std: float
    edge_length_histogram: tuple[np.ndarray, np.ndarray]
    degree_histogram: np.ndarray
    degree_deviation: float
    min_angle_mean: float
    min_angle_histogram: tuple[np.ndarray, np.ndarray]

    @property
    def edge_length_spread(self) -> float:
        """The ``std / mean`` of the edge lengths, 0 when all edges are equally long."""
        return self.edge_length_std / self.edge_length_mean

    def __str__(self) -> str:
        return (
            f"{self.n_faces} faces, edge length {self.edge_length_mean:.4g} +- {self.edge_length_std:.2g} "
            f"(spread {self.edge_length_spread:.3f}), mean |degree - ideal| {self.degree_deviation:.3f}, "
            f"mean smallest angle {self.min_angle_mean:.1f} deg"
        )


def quality_report(mesh: HalfedgeMesh, bins: int = 30) -> MeshQuality:
    """Edge lengths, vertex degrees and smallest face angles of ``mesh``, with histograms.

    Args:
        mesh: the mesh (only read).
        bins: how many bins the edge-length histogram (from 0 to the longest edge) and the
            smallest-angle histogram (0 to 60 degrees) have.

    Raises:
        MeshInputError: the mesh has no faces (there is nothing to measure).
    """
    check_mesh(mesh)
    whole_number(bins, "bins", minimum=1)
    if mesh.n_faces == 0:
        raise MeshInputError("quality_report: the mesh has no faces, so there are no edges or angles to measure")
    vertices, faces = mesh.to_arrays()
    table = edge_table(faces, len(vertices))
    lengths = edge_lengths(vertices, table.edges)
    degree = np.bincount(table.edges.reshape(-1), minlength=len(vertices))
    ideal = np.where(table.boundary_vertices(len(vertices)), 4, 6)
    p = vertices[faces]                                                 # (F, 3, 3)
    along, back = np.roll(p, -1, axis=1) - p, np.roll(p, 1, axis=1) - p
    angles = np.degrees(np.arctan2(np.linalg.norm(np.cross(along, back), axis=2),
                                   np.einsum("fkd,fkd->fk", along, back)))
    smallest = angles.min(axis=1)
    return MeshQuality(
        n_vertices=len(vertices),
        n_faces=len(faces),
        edge_length_mean=float(lengths.mean()),
        edge_length_std=float(lengths.std()),
        edge_length_histogram=np.histogram(lengths, bins=bins, range=(0.0, max(float(lengths.max()), 1e-300))),
        degree_histogram=np.bincount(degree),
        degree_deviation=float(np.abs(degree - ideal).mean()),
        min_angle_mean=float(smallest.mean()),
        # A smallest angle is at most 60 degrees; rounding can put an equilateral one a hair above.
        min_angle_histogram=np.histogram(np.minimum(smallest, 60.0), bins=bins, range=(0.0, 60.0)),
    )
