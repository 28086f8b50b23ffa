"""Fingerprints of every algorithm's output on the sample meshes, to show a refactor or a
speed change left the outputs as they were (bit for bit).

    .venv/bin/python tools/output_hashes.py            # print one line per output
    .venv/bin/python tools/output_hashes.py > before.txt; ...; diff before.txt <(... )

Each line is ``name  sha256-of-(vertices bytes + faces bytes + halfedge arrays)``. The
halfedge arrays are included so that a change of storage order shows too, not only a
change of geometry.
"""

from __future__ import annotations

import hashlib
import sys
import warnings

import numpy as np

from halfedge_edu import HalfedgeMesh
from halfedge_edu.algorithms import loop_subdivide, remesh, simplify, smooth
from halfedge_edu.data import sample


def fingerprint(mesh: HalfedgeMesh) -> str:
    """SHA-256 of the mesh's compacted vertices and faces and its halfedge storage."""
    digest = hashlib.sha256()
    vertices, faces = mesh.to_arrays()
    for array in (vertices, faces):
        digest.update(np.ascontiguousarray(array).tobytes())
    for name in ("_positions", "_vertex_halfedge", "_halfedge_next", "_halfedge_prev",
                 "_halfedge_vertex", "_halfedge_face", "_face_halfedge"):
        stored = getattr(mesh, name)  # (slots,) or (V, 3): the storage as it is, spare capacity cut
        digest.update(np.ascontiguousarray(stored).tobytes())
    return digest.hexdigest()[:16]


def outputs() -> dict[str, HalfedgeMesh]:
    """Every algorithm on the meshes the chapters and benchmarks use."""
    bunny, spot, ico = sample("bunny"), sample("spot"), sample("icosphere", subdivisions=3)
    patch = sample("open_patch")
    found: dict[str, HalfedgeMesh] = {}
    for name, mesh in (("bunny", bunny), ("spot", spot), ("icosphere3", ico), ("open_patch", patch)):
        vertices, faces = mesh.to_arrays()
        found[f"build {name}"] = HalfedgeMesh.from_faces(vertices, faces)
        shuffled = np.random.default_rng(0).permutation(len(faces))
        found[f"build shuffled {name}"] = HalfedgeMesh.from_faces(vertices, faces[shuffled])
    for name, mesh in (("spot", spot), ("icosphere3", ico), ("open_patch", patch)):
        found[f"loop {name}"] = loop_subdivide(mesh)
        found[f"smooth uniform {name}"] = smooth(mesh, 3)
        found[f"smooth cotangent {name}"] = smooth(mesh, 3, weights="cotangent")
        found[f"remesh {name}"] = remesh(mesh, iterations=3)
    found["remesh bunny"] = remesh(bunny, iterations=2)
    for name, mesh in (("bunny", bunny), ("spot", spot), ("icosphere3", ico)):
        found[f"simplify 10% {name}"] = simplify(mesh, max(4, mesh.n_faces // 10))
    found["simplify 50% open_patch"] = simplify(patch, 10)
    return found


def main() -> int:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, mesh in outputs().items():
            print(f"{name:28s} {fingerprint(mesh)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
