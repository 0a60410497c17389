# SPDX-License-Identifier: MIT
# Catalogue surfaces through the bindings give what the CLI gives.
import json
import subprocess

import numpy as np
import pytest

import tessera
from summary_compare import without_times


def test_torus_summary_is_the_cli_summary(cli, tmp_path):
    mesh = tessera.mesh("torus", tolerance=1e-3)
    summary_path = tmp_path / "torus.json"
    subprocess.run([str(cli), "mesh", "torus", "--tolerance", "1e-3", "-o",
                    str(tmp_path / "torus.ply"), "--summary", str(summary_path), "-q"],
                   check=True)
    assert without_times(mesh.summary) == without_times(json.loads(summary_path.read_text()))
    assert mesh.summary["run"]["termination"] == "completed"
    assert mesh.summary["topology"]["euler_characteristic"] == 0
    assert mesh.vertices.shape == (mesh.summary["counts"]["vertices"], 3)


def test_torus_vertices_lie_on_the_torus():
    problem = tessera.Problem.from_catalogue("torus")
    mesh = tessera.mesh(problem, tolerance=1e-3)
    residuals = np.array([problem.F(x)[0] for x in mesh.vertices])
    assert np.abs(residuals).max() < 1e-9


@pytest.mark.parametrize("method", tessera.methods())
def test_every_method_meshes_the_sphere(method):
    mesh = tessera.mesh("sphere", method=method)
    assert mesh.summary["run"]["method"] == method
    assert mesh.summary["topology"]["euler_characteristic"] == 2
    assert np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1.0).max() < 1e-8


def test_parameters_box_and_start():
    mesh = tessera.mesh(tessera.Problem.from_catalogue("sphere"), method="front",
                        box=[-2, 2, -2, 2, -0.5, 2], start=[0, 0, 1])
    assert mesh.vertices[:, 2].min() >= -0.5 - 1e-9
    assert mesh.summary["topology"]["euler_characteristic"] == 1


def test_box_on_named_coordinates():
    # The plane z = 0 over [-1, 1]^2, cut to x in [-0.5, 0.5] and y >= 0: area 1.
    mesh = tessera.mesh("plane", box={"x": (-0.5, 0.5), "y": (0, None)})
    assert mesh.vertices[:, 0].min() >= -0.5 and mesh.vertices[:, 0].max() <= 0.5
    assert mesh.vertices[:, 1].min() >= 0.0
    assert mesh.summary["shape"]["area"] == pytest.approx(1.0, abs=1e-9)
    with pytest.raises(ValueError, match="names coordinate 'w'"):
        tessera.mesh("plane", box={"w": (0, 1)})
    with pytest.raises(ValueError, match="must be \\(lower, upper\\)"):
        tessera.mesh("plane", box={"x": 0.5})


def test_problem_files_and_expressions(tmp_path):
    from_file = tessera.Problem.from_file(tessera_repository() / "examples/problems/sphere_cut.tsr",
                                          r=2)
    assert from_file.n == 3 and np.allclose(from_file.F([0, 0, 2]), 0)
    text = "variables x y z\nequation x^2 + y^2 + z^2 - 1\nstart 0 0 1\nstep 0.3\n"
    mesh = tessera.mesh(tessera.Problem.from_text(text), method="front")
    assert mesh.summary["topology"]["euler_characteristic"] == 2
    equations = tessera.Problem.from_equations("x y z", ["x^2 + y^2/4 + z^2 - 1"], [0, 0, 1],
                                               step=0.3)
    assert equations.coordinate_names == ["x", "y", "z"]
    assert np.allclose(equations.J([0, 2, 0]), [[0, 1, 0]])


def test_catalogue_listing():
    names = [entry["name"] for entry in tessera.problems()]
    assert "torus" in names and "bvp" in names
    torus = next(entry for entry in tessera.problems() if entry["name"] == "torus")
    assert "R" in torus["parameters"]


def tessera_repository():
    from conftest import REPOSITORY
    return REPOSITORY
