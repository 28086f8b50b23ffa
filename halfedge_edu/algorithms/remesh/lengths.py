"""The band of edge lengths that remeshing aims for, and how an edge is measured.

Remeshing to a target length ``L`` splits the edges longer than ``4/3 L``
(:data:`SPLIT_ABOVE`) and collapses those shorter than ``4/5 L`` (:data:`COLLAPSE_BELOW`).

Why 4/3 and 4/5: splitting an edge of length ``l`` leaves two of ``l/2``, which are
nearer to L than ``l`` was exactly when ``l > 4/3 L``; 4/5 is Botsch and Kobbelt's
matching bound below L. A collapse may not make an edge longer than ``4/3 L``, which
keeps it from making work for the next split, so the two phases never undo each other.
"""

from __future__ import annotations

import numpy as np

#: Split edges longer than this times L; collapse edges shorter than ``COLLAPSE_BELOW * L``.
SPLIT_ABOVE = 4.0 / 3.0
COLLAPSE_BELOW = 4.0 / 5.0


def edge_lengths(vertices: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """(E,) the length of each edge (E, 2) between ``vertices`` (n, 3). ``np.take`` gathers
    the rows: the same numbers as ``vertices[edges[:, 0]]``, without fancy indexing's
    general machinery."""
    d = np.take(vertices, edges[:, 0], axis=0) - np.take(vertices, edges[:, 1], axis=0)
    return np.sqrt(np.einsum("ij,ij->i", d, d))
