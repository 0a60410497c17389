# SPDX-License-Identifier: MIT
# Mesh arrays are views of the C++ storage (no copy), keep it alive, and survive every file
# format and meshio.
import gc

import meshio
import numpy as np
import pytest

import tessera


@pytest.fixture(scope="module")
def torus() -> tessera.Mesh:
    return tessera.mesh("torus", method="front", step=0.2)


def address(array: np.ndarray) -> int:
    return array.__array_interface__["data"][0]


def test_vertices_are_a_view_of_the_column_major_storage(torus):
    vertices = torus.vertices
    n = vertices.shape[1]
    assert vertices.dtype == np.float64 and n == 3
    assert vertices.flags["C_CONTIGUOUS"] and vertices.strides == (8 * n, 8)
    assert not vertices.flags["OWNDATA"] and not vertices.flags["WRITEABLE"]
    # The same buffer every time: no property access copies.
    assert address(vertices) == address(torus.vertices)
    assert np.shares_memory(vertices, torus.vertices)


def test_triangles_are_a_view(torus):
    triangles = torus.triangles
    assert triangles.shape[1] == 3 and triangles.dtype == np.int32
    assert address(triangles) == address(torus.triangles)
    assert not triangles.flags["OWNDATA"] and not triangles.flags["WRITEABLE"]
    assert triangles.min() == 0 and triangles.max() == torus.vertex_count - 1


def test_a_view_keeps_the_mesh_alive():
    mesh = tessera.mesh("sphere", method="front")
    vertices = mesh.vertices
    copy = np.array(vertices)
    del mesh
    gc.collect()
    tessera.mesh("torus", method="front")  # reuses freed memory if the view dangled
    assert np.array_equal(vertices, copy)


def test_views_are_read_only(torus):
    with pytest.raises(ValueError):
        torus.vertices[0, 0] = 1.0


def test_mesh_from_arrays_round_trip(torus):
    copy = tessera.Mesh(torus.vertices, torus.triangles)
    assert np.array_equal(copy.vertices, torus.vertices)
    assert np.array_equal(copy.triangles, torus.triangles)
    assert not np.shares_memory(copy.vertices, torus.vertices)
    report = tessera.check(copy, "torus")
    assert report["passes"], report["failures"]


def test_mesh_from_arrays_refuses_bad_indices():
    with pytest.raises(ValueError, match="vertex index 3, not in"):
        tessera.Mesh(np.zeros((3, 3)), [[0, 1, 3]])


@pytest.mark.parametrize("extension", [".ply", ".vtk", ".vtu", ".obj", ".npy"])
def test_every_format_is_written_and_read_back(torus, tmp_path, extension):
    path = tmp_path / ("torus" + extension)
    torus.write(path)
    back = tessera.read(path)
    assert np.array_equal(back.triangles, torus.triangles)
    # OBJ is text with fewer digits; the others keep the coordinates bit for bit.
    tolerance = 1e-6 if extension == ".obj" else 0.0
    assert np.abs(back.vertices - torus.vertices).max() <= tolerance
    if extension != ".npy":  # every mesh file opens in meshio (issue 34: .vtk too)
        loaded = meshio.read(path)
        assert loaded.points.shape == torus.vertices.shape
        assert np.allclose(loaded.points, torus.vertices, atol=max(tolerance, 1e-15))


def test_ascii_ply(torus, tmp_path):
    path = tmp_path / "torus.ply"
    torus.write(path, ascii=True)
    assert b"format ascii" in path.read_bytes()[:200]


def test_meshio_round_trip(torus):
    converted = torus.to_meshio()
    assert converted.cells[0].type == "triangle"
    back = tessera.from_meshio(converted)
    assert np.array_equal(back.vertices, torus.vertices)
    assert np.array_equal(back.triangles, torus.triangles)


def test_write_refuses_an_unknown_format(torus, tmp_path):
    with pytest.raises(ValueError, match=r"\.stl"):
        torus.write(tmp_path / "torus.stl")
