# SPDX-License-Identifier: MIT
# `improve` and `ddt` as the CLI's commands.
import numpy as np
import pytest

import tessera


def test_improve_returns_a_better_new_mesh():
    mesh = tessera.mesh("torus", method="front", step=0.15)
    vertices_before = np.array(mesh.vertices)
    triangles_before = np.array(mesh.triangles)
    better = tessera.improve(mesh, criterion="angle", smooth=2)
    summary = better.summary
    assert summary["after"]["is_valid"]
    assert summary["after"]["min_angle_degrees"] >= summary["before"]["min_angle_degrees"]
    assert summary["smoothing_passes"] == 2
    # The given mesh (and any view of it) did not change.
    assert np.array_equal(mesh.vertices, vertices_before)
    assert np.array_equal(mesh.triangles, triangles_before)
    assert tessera.check(better)["passes"]


def test_improve_refuses_a_mesh_of_another_dimension():
    with pytest.raises(ValueError, match="R\\^3 but problem 'bvp:points=5' is in R\\^7"):
        tessera.improve(tessera.mesh("sphere", method="front"), "bvp:points=5")


def test_ddt_with_a_franke_function():
    points = np.random.default_rng(1).random((100, 2))
    delaunay = tessera.ddt(points, function="F1", criterion="delaunay")
    abn = tessera.ddt(points, function="F1", criterion="abn", norm="l2")
    assert abn.vertices.shape == (100, 3) and abn.triangle_count == delaunay.triangle_count
    assert abn.summary["error"]["mean"] <= delaunay.summary["error"]["mean"] * 1.05


def test_ddt_with_values_and_errors(tmp_path):
    points = np.random.default_rng(2).random((40, 2))
    values = np.sin(3 * points[:, 0]) * points[:, 1]
    triangulation = tessera.ddt(points, values)
    assert np.allclose(triangulation.vertices[:, 2], values)
    triangulation.write(tmp_path / "ddt.ply")
    with pytest.raises(ValueError, match="criterion 'best' is unknown"):
        tessera.ddt(points, values, criterion="best")
    with pytest.raises(ValueError, match="equid needs function"):
        tessera.ddt(points, values, criterion="equid")
