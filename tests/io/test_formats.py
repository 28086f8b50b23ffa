"""load / save: the suffix picks the format; repair=True makes broken files loadable."""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import pytest
import trimesh

from halfedge_edu.core.errors import MeshInputError, MeshWarning
from halfedge_edu.core.mesh import HalfedgeMesh
from halfedge_edu.data import sample
from halfedge_edu.io import load, save, write_obj

MESHES = Path(__file__).resolve().parents[2] / "halfedge_edu" / "data"
MALFORMED = Path(__file__).resolve().parents[1] / "data" / "malformed"


@pytest.fixture
def spot() -> HalfedgeMesh:
    return sample("spot")


def assert_same_triangles(vertices, faces, expected_vertices, expected_faces):
    """The same oriented triangles, whatever the vertex and face order (positions to 1e-6)."""
    from scipy.spatial import cKDTree

    distance, match = cKDTree(expected_vertices).query(vertices)
    assert distance.max() < 1e-6

    def rotated(rows):  # each triangle starting at its smallest index, keeping orientation
        rows = np.asarray(rows)
        k = rows.argmin(axis=1)[:, None]
        return sorted(map(tuple, np.take_along_axis(rows, (k + np.arange(3)) % 3, axis=1).tolist()))

    assert rotated(match[faces]) == rotated(expected_faces)


def test_obj_save_then_load_is_exact(tmp_path, spot):
    save(spot, tmp_path / "spot.obj")
    again = load(tmp_path / "spot.obj")
    for before, after in zip(spot.to_arrays(), again.to_arrays()):
        np.testing.assert_array_equal(after, before)


def test_saving_is_io_s_job_the_mesh_knows_no_files(spot):
    # API.md: "hx.save(mesh, path) ... the mesh itself knows no files".
    assert not hasattr(spot, "save")


@pytest.mark.parametrize("suffix", [".ply", ".off", ".glb", ".gltf"])
def test_indexed_formats_round_trip_through_trimesh(tmp_path, spot, suffix):
    save(spot, tmp_path / f"spot{suffix}")
    again = load(tmp_path / f"spot{suffix}")
    vertices, faces = spot.to_arrays()
    again_vertices, again_faces = again.to_arrays()
    np.testing.assert_array_equal(again_faces, faces)
    np.testing.assert_allclose(again_vertices, vertices, atol=1e-6)  # ply and glb store float32


def test_stl_round_trip_merges_corners_back_into_shared_vertices(tmp_path, spot):
    save(spot, tmp_path / "spot.stl")
    again = load(tmp_path / "spot.stl")
    assert (again.n_vertices, again.n_edges, again.n_faces) == (spot.n_vertices, spot.n_edges, spot.n_faces)
    assert again.is_closed
    assert_same_triangles(*again.to_arrays(), *spot.to_arrays())


@pytest.mark.parametrize("suffix", [".ply", ".off", ".stl"])
def test_files_written_by_trimesh_load(tmp_path, suffix):
    sphere = trimesh.creation.icosphere(subdivisions=1)
    sphere.export(tmp_path / f"sphere{suffix}")
    mesh = load(tmp_path / f"sphere{suffix}")
    mesh.validate()
    assert (mesh.n_vertices, mesh.n_faces) == (42, 80)
    assert_same_triangles(*mesh.to_arrays(), sphere.vertices, sphere.faces)


def test_trimesh_interop_both_ways(spot):
    again = HalfedgeMesh.from_trimesh(spot.to_trimesh())
    for before, after in zip(spot.to_arrays(), again.to_arrays()):
        np.testing.assert_array_equal(after, before)


def test_unknown_suffix_is_refused_by_load_and_save(tmp_path, spot):
    (tmp_path / "mesh.xyz").write_text("1 2 3\n")
    with pytest.raises(MeshInputError, match="unknown file type '.xyz'"):
        load(tmp_path / "mesh.xyz")
    with pytest.raises(MeshInputError, match="unknown file type"):
        save(spot, tmp_path / "out.abc")
    assert sorted(os.listdir(tmp_path)) == ["mesh.xyz"]


def test_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="nowhere.ply"):
        load(tmp_path / "nowhere.ply")


def test_file_trimesh_cannot_read_is_a_mesh_input_error(tmp_path):
    (tmp_path / "broken.ply").write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 99\n\x00\x01")
    with pytest.raises(MeshInputError, match="broken.ply"):
        load(tmp_path / "broken.ply")


def test_file_without_triangles_is_a_mesh_input_error(tmp_path):
    trimesh.PointCloud(np.eye(3)).export(tmp_path / "points.ply")
    with pytest.raises(MeshInputError, match="points.ply"):
        load(tmp_path / "points.ply")


def test_polygons_are_triangulated_unless_asked_not_to(tmp_path):
    (tmp_path / "quad.obj").write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    assert load(tmp_path / "quad.obj").n_faces == 2
    with pytest.raises(MeshInputError, match="line 5"):
        load(tmp_path / "quad.obj", triangulate=False)


def test_loading_the_bunny_file_keeps_its_unreferenced_vertices_at_their_index():
    mesh = load(MESHES / "stanford-bunny.obj")
    assert (mesh.n_vertices, mesh.n_faces) == (35947, 69451)
    assert int(np.count_nonzero(mesh.vertex_halfedge == -1)) == 1113
    mesh.validate()


def test_loading_the_bunny_file_can_drop_its_unreferenced_vertices_with_a_warning():
    with pytest.warns(MeshWarning, match="1113 unreferenced vertices"):
        mesh = load(MESHES / "stanford-bunny.obj", drop_unreferenced=True)
    assert (mesh.n_vertices, mesh.n_faces) == (34834, 69451)


def broken_files(directory: Path) -> dict[str, Path]:
    """The non-manifold samples and some malformed-corpus meshes, as OBJ files."""
    paths = {}
    for name in ("nonmanifold_edge", "nonmanifold_vertex"):
        raw = sample(name)
        paths[name] = directory / f"{name}.obj"
        write_obj(paths[name], raw.vertices, raw.faces)
    for name in ("degenerate_face", "flipped_face", "nonmanifold_edge"):
        paths[f"corpus {name}"] = MALFORMED / f"{name}.obj"
    vertices, faces = sample("icosphere", subdivisions=1).to_arrays()
    faces = np.vstack([faces, faces[3], faces[7, ::-1]])
    faces[10] = faces[10, ::-1]
    paths["sphere with a flipped and two duplicated faces"] = directory / "sphere.obj"
    write_obj(paths["sphere with a flipped and two duplicated faces"], vertices, faces)
    return paths


def test_broken_files_load_with_repair_and_report_what_changed(tmp_path):
    for name, path in broken_files(tmp_path).items():
        with pytest.raises(MeshInputError):
            load(path)
        with pytest.warns(MeshWarning) as caught:
            mesh = load(path, repair=True)
        mesh.validate()
        assert mesh.repair_report, name
        messages = [str(warning.message) for warning in caught]
        assert f"{path.name}: repair_faces changed the mesh" in "\n".join(messages), name


def test_repair_of_the_sphere_flips_one_face_and_drops_two(tmp_path):
    with pytest.warns(MeshWarning, match=r"flipped faces \(1\): 10"):
        mesh = load(broken_files(tmp_path)["sphere with a flipped and two duplicated faces"], repair=True)
    report = mesh.repair_report
    assert report.flipped_faces.tolist() == [10]
    assert report.dropped_duplicate.tolist() == [80, 81]
    assert mesh.n_faces == 80 and mesh.is_closed


def test_repair_of_a_clean_file_changes_nothing_and_stays_quiet(tmp_path, spot):
    save(spot, tmp_path / "spot.obj")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mesh = load(tmp_path / "spot.obj", repair=True)
    assert not mesh.repair_report
    np.testing.assert_array_equal(mesh.to_arrays()[1], spot.to_arrays()[1])


def test_a_failed_save_leaves_an_existing_file_untouched(tmp_path, spot, monkeypatch):
    target = tmp_path / "spot.ply"
    target.write_bytes(b"the old file")

    def failing_export(*args, **kwargs):
        raise RuntimeError("exporter crashed")

    monkeypatch.setattr(trimesh.Trimesh, "export", failing_export)
    with pytest.raises(RuntimeError):
        save(spot, target)
    assert target.read_bytes() == b"the old file"
    assert os.listdir(tmp_path) == ["spot.ply"]


# ---------------------------------------------------------------- what each format can hold

SUFFIXES_WRITTEN = (".obj", ".ply", ".stl", ".off", ".glb", ".gltf")


def two_triangles_sharing_an_edge() -> HalfedgeMesh:
    return HalfedgeMesh.from_faces([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [2, 1, 3]])


@pytest.mark.parametrize("suffix", SUFFIXES_WRITTEN)
@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_every_format_refuses_a_non_finite_coordinate_and_writes_nothing(tmp_path, suffix, bad):
    mesh = two_triangles_sharing_an_edge()
    mesh.positions[2, 1] = bad
    with pytest.raises(MeshInputError, match="vertex 2 has a non-finite coordinate") as error:
        save(mesh, tmp_path / f"out{suffix}")
    assert error.value.element == ("vertex", 2)
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("suffix", [".ply", ".stl", ".glb", ".gltf"])
def test_float32_formats_refuse_coordinates_float32_turns_into_inf(tmp_path, suffix):
    mesh = two_triangles_sharing_an_edge()
    mesh.positions[3] = [1e39, 1, 0]
    with pytest.raises(MeshInputError, match=f"vertex 3 has a coordinate beyond float32's range .* {suffix}"):
        save(mesh, tmp_path / f"out{suffix}")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("suffix", [".obj", ".off"])
def test_float64_text_formats_keep_coordinates_beyond_float32(tmp_path, suffix):
    mesh = two_triangles_sharing_an_edge()
    mesh.positions[3] = [1e39, 1, 0]
    save(mesh, tmp_path / f"out{suffix}")
    np.testing.assert_array_equal(load(tmp_path / f"out{suffix}").to_arrays()[0], mesh.to_arrays()[0])


@pytest.mark.parametrize("suffix", [".glb", ".gltf", ".ply", ".stl"])
def test_float32_formats_store_float32_positions_as_documented(tmp_path, spot, suffix):
    mesh = spot.copy()
    mesh.positions[:] += 1 / 3  # digits float32 cannot hold
    save(mesh, tmp_path / f"spot{suffix}")
    again = load(tmp_path / f"spot{suffix}").to_arrays()[0]
    exact = mesh.to_arrays()[0]
    if suffix == ".stl":  # merging corners may renumber the vertices: compare sorted rows
        again, exact = np.unique(again, axis=0), np.unique(exact, axis=0)
    np.testing.assert_array_equal(again, exact.astype(np.float32).astype(np.float64))
    assert not np.array_equal(again, exact)


def test_stl_refuses_vertices_at_one_position_which_would_load_back_merged(tmp_path):
    # A non-manifold vertex split by repair: two vertices at the same place.
    bowtie = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]]
    vertices, faces = np.array(bowtie, dtype=float), np.array([[0, 1, 2], [0, 3, 4]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        (tmp_path / "bowtie.obj").write_text(
            "".join(f"v {x} {y} {z}\n" for x, y, z in vertices) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
        )
        repaired = load(tmp_path / "bowtie.obj", repair=True)
    assert repaired.n_vertices == 6  # vertex 0 was split into two copies
    with pytest.raises(MeshInputError, match=r"vertices 0 and 5 have the same position; .stl stores no shared"):
        save(repaired, tmp_path / "out.stl")
    assert sorted(os.listdir(tmp_path)) == ["bowtie.obj"]
    save(repaired, tmp_path / "out.ply")  # an indexed format keeps them apart
    assert load(tmp_path / "out.ply").n_vertices == 6


def test_stl_refuses_vertices_that_only_float32_makes_equal(tmp_path):
    mesh = two_triangles_sharing_an_edge()
    mesh.positions[3] = [1 + 1e-12, 0, 0]  # distinct from vertex 1 in float64, not in float32
    assert not np.array_equal(mesh.positions[3], mesh.positions[1])
    with pytest.raises(MeshInputError, match="vertices 1 and 3 have the same position"):
        save(mesh, tmp_path / "out.stl")


def test_load_arrays_gives_what_load_builds_from(tmp_path, spot):
    from halfedge_edu.io import load_arrays

    save(spot, tmp_path / "spot.stl")
    vertices, faces, face_lines = load_arrays(tmp_path / "spot.stl")
    assert face_lines is None
    assert (len(vertices), len(faces)) == (spot.n_vertices, spot.n_faces)  # corners merged back
    save(spot, tmp_path / "spot.obj")
    vertices, faces, face_lines = load_arrays(tmp_path / "spot.obj")
    np.testing.assert_array_equal(faces, spot.to_arrays()[1])
    assert face_lines.min() > spot.n_vertices  # every f line comes after the v lines


@pytest.mark.parametrize("suffix", [".obj", ".ply", ".stl"])
def test_load_refuses_a_fifo_and_a_device_for_every_format(tmp_path, suffix):
    os.mkfifo(tmp_path / f"pipe{suffix}")
    (tmp_path / f"zero{suffix}").symlink_to("/dev/zero")
    with pytest.raises(MeshInputError, match="is a FIFO"):
        load(tmp_path / f"pipe{suffix}")
    with pytest.raises(MeshInputError, match="is a device"):
        load(tmp_path / f"zero{suffix}")


# ---------------------------------------------------------------- the temporary file

def test_an_output_name_of_255_bytes_can_be_written(tmp_path, spot):
    target = tmp_path / ("m" * 251 + ".ply")
    save(spot, target)
    assert os.listdir(tmp_path) == [target.name]
    assert load(target).n_faces == spot.n_faces


def test_a_permission_error_names_the_target_not_the_temporary_file(tmp_path, spot, monkeypatch):
    import halfedge_edu.io.obj as obj

    def refused(path, *args, **kwargs):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(obj.os, "open", refused)
    with pytest.raises(PermissionError) as error:
        save(spot, tmp_path / "spot.ply")
    assert error.value.filename == str(tmp_path / "spot.ply")
    assert ".tmp" not in str(error.value)
