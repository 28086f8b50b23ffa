"""Shared fixtures (small named meshes, after pmp-library's tests) and hypothesis profiles.

Hypothesis profiles: ``dev`` (the default: 25 examples), ``ci`` (50 examples, chosen
automatically when ``CI`` is set) and ``thorough`` (500 examples). Pick one with
``HYPOTHESIS_PROFILE=thorough pytest ...``. None has a deadline: the first example of a
run pays for imports (trimesh, scipy), which would trip a per-example deadline.

Every mesh fixture is built fresh for each test, so tests may edit it freely. The
shapes themselves live in ``tests/strategies.py``.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

import halfedge_edu as hx
from tests import strategies as shapes

settings.register_profile("dev", max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
_in_ci = os.environ.get("CI", "").lower() not in ("", "0", "false", "no")
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if _in_ci else "dev"))


def _mesh(arrays) -> hx.HalfedgeMesh:
    return hx.HalfedgeMesh.from_faces(*arrays)


# ---- closed meshes -------------------------------------------------------------------

@pytest.fixture
def tetrahedron() -> hx.HalfedgeMesh:
    """4 vertices, 6 edges, 4 faces, closed, genus 0."""
    return _mesh(shapes.tetrahedron())


@pytest.fixture
def octahedron() -> hx.HalfedgeMesh:
    """6 vertices of degree 4, 12 edges, 8 faces, closed."""
    return _mesh(shapes.octahedron())


@pytest.fixture
def icosphere() -> hx.HalfedgeMesh:
    """trimesh's icosphere with one subdivision: 42 vertices, 80 faces."""
    return _mesh(shapes.icosphere(1))


@pytest.fixture
def uv_sphere() -> hx.HalfedgeMesh:
    """8 around, 3 rings: 26 vertices, 48 faces, poles of degree 8."""
    return _mesh(shapes.uv_sphere(8, 3))


@pytest.fixture
def torus() -> hx.HalfedgeMesh:
    """A 6 x 4 torus grid: 24 vertices, 72 edges, 48 faces, genus 1."""
    return _mesh(shapes.torus(6, 4))


@pytest.fixture
def two_spheres() -> hx.HalfedgeMesh:
    """An octahedron and a tetrahedron side by side (two components)."""
    return _mesh(shapes.disjoint_union(shapes.octahedron(), shapes.tetrahedron()))


# ---- meshes with boundary -----------------------------------------------------------

@pytest.fixture
def square() -> hx.HalfedgeMesh:
    """Two triangles ``[0, 1, 2]`` and ``[0, 2, 3]`` forming the unit square."""
    return _mesh(shapes.square())


@pytest.fixture
def single_triangle() -> hx.HalfedgeMesh:
    return _mesh((np.eye(3), [[0, 1, 2]]))


@pytest.fixture
def grid() -> hx.HalfedgeMesh:
    """A flat 3 x 2 grid of quads split along ``a-c``: 12 vertices, 12 faces."""
    return _mesh(shapes.grid(3, 2))


@pytest.fixture
def vertex_onering() -> hx.HalfedgeMesh:
    """A closed fan: interior vertex 0 with six rim vertices 1..6 CCW (pmp's fixture name)."""
    return _mesh(shapes.fan(6))


@pytest.fixture
def edge_onering() -> hx.HalfedgeMesh:
    """A 3 x 2 grid whose interior vertices 4 and 7 are joined: both ends of edge (4, 7) are interior."""
    return _mesh(shapes.grid(3, 2))


@pytest.fixture
def open_fan() -> hx.HalfedgeMesh:
    """Three triangles around boundary vertex 0 (a half disc)."""
    return _mesh(shapes.open_fan(3))


@pytest.fixture
def annulus() -> hx.HalfedgeMesh:
    """A flat ring, 8 quads around and 2 out: genus 0, two boundary loops."""
    return _mesh(shapes.annulus(8, 2))


@pytest.fixture
def open_cone() -> hx.HalfedgeMesh:
    """A cone without its base (pmp's name): apex 0 above a rim of five vertices."""
    vertices, faces = shapes.fan(5)
    vertices = vertices.copy()
    vertices[0, 2] = 1.0
    return _mesh((vertices, faces))
