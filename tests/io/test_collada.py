"""COLLADA (.dae), the format of the CMU and CS184 assignments' meshes, loads through
trimesh's reader (which needs pycollada, the ``io`` extra)."""

from __future__ import annotations

import numpy as np

import halfedge_edu as hx

# A tetrahedron, written by hand: one <triangles> list indexing four positions.
TETRAHEDRON_DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1" name="meter"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tet" name="tet">
      <mesh>
        <source id="tet-positions">
          <float_array id="tet-positions-array" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
          <technique_common>
            <accessor source="#tet-positions-array" count="4" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="tet-vertices"><input semantic="POSITION" source="#tet-positions"/></vertices>
        <triangles count="4">
          <input semantic="VERTEX" source="#tet-vertices" offset="0"/>
          <p>0 2 1  0 1 3  0 3 2  1 2 3</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
      <node id="tet-node"><instance_geometry url="#tet"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""


def triangles_by_position(mesh: hx.HalfedgeMesh) -> set[tuple]:
    """Each triangle as its corner positions, rotated to start at the smallest: trimesh's
    COLLADA reader numbers vertices by first use, so ids are not compared."""
    vertices, faces = mesh.to_arrays()
    triangles = set()
    for face in faces:
        corners = [tuple(np.round(vertices[v], 6)) for v in face]
        start = corners.index(min(corners))
        triangles.add(tuple(corners[start:] + corners[:start]))
    return triangles


def test_a_collada_tetrahedron_loads_as_a_closed_mesh(tmp_path):
    path = tmp_path / "tetrahedron.dae"
    path.write_text(TETRAHEDRON_DAE)
    mesh = hx.load(path)
    mesh.validate()
    assert (mesh.n_vertices, mesh.n_faces, mesh.is_closed) == (4, 4, True)
    assert triangles_by_position(mesh) == triangles_by_position(
        hx.HalfedgeMesh.from_faces([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                                   [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))


def test_a_mesh_saved_as_collada_loads_back(tmp_path):
    octahedron = hx.sample("octahedron")
    hx.save(octahedron, tmp_path / "octahedron.dae")
    again = hx.load(tmp_path / "octahedron.dae")
    assert (again.n_vertices, again.n_faces) == (6, 8)
    assert triangles_by_position(again) == triangles_by_position(octahedron)
