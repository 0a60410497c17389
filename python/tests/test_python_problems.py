# SPDX-License-Identifier: MIT
# Problems written in Python (dense NumPy and scipy.sparse Jacobians) run through the same
# solvers as the C++ ones.
import sys

import numpy as np
import pytest
import scipy.sparse as sp

import tessera
from conftest import REPOSITORY

sys.path.insert(0, str(REPOSITORY / "python" / "examples"))
from bvp_scipy import bratu_problem  # noqa: E402


@pytest.mark.parametrize("method", tessera.methods())
def test_python_sphere(sphere, method):
    mesh = tessera.mesh(sphere, method=method, tolerance=2e-3)
    assert np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1.0).max() < 1e-8
    assert mesh.summary["topology"]["euler_characteristic"] == 2
    assert mesh.summary["topology"]["closed"]
    area = mesh.summary["shape"]["area"]
    assert abs(area - 4 * np.pi) < 0.03 * 4 * np.pi
    report = tessera.check(mesh, sphere)
    assert report["passes"], report["failures"]


def test_python_sphere_matches_the_catalogue_sphere(sphere):
    # Same F, start and step: the same mesh, vertex for vertex.
    catalogue = tessera.Problem.from_catalogue("sphere")
    python = tessera.Problem(n=3, F=lambda x: [x @ x - 1.0], J=lambda x: [2.0 * x],
                             start=catalogue.start, step=catalogue.suggested_step)
    ours = tessera.mesh(python, method="front")
    theirs = tessera.mesh(catalogue, method="front")
    assert np.array_equal(ours.triangles, theirs.triangles)
    assert np.abs(ours.vertices - theirs.vertices).max() < 1e-12


def test_finite_difference_jacobian():
    problem = tessera.Problem(n=3, F=lambda x: x @ x - 1.0, start=[0, 0, 1], step=0.3)
    assert np.allclose(problem.J([0, 0, 1]), [[0, 0, 2]], atol=1e-8)
    mesh = tessera.mesh(problem, method="front")
    assert np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1.0).max() < 1e-8


def test_scipy_sparse_problem():
    N = 20
    problem = bratu_problem(N)
    assert problem.has_sparse_jacobian and problem.n == N + 2
    mesh = tessera.mesh(problem, method="front", max_vertices=120, allow_partial=True)
    assert mesh.termination == "vertex limit reached"
    residual = max(np.abs(problem.F(x)).max() for x in mesh.vertices)
    assert residual < 1e-8
    assert tessera.check(mesh, problem)["valid"]
    # The same run with the C++ problem makes the same mesh.
    reference = tessera.mesh(f"bvp:points={N}", method="front", max_vertices=120,
                             allow_partial=True)
    assert np.array_equal(mesh.triangles, reference.triangles)
    assert np.abs(mesh.vertices - reference.vertices).max() < 1e-9


def test_sparse_jacobians_in_any_scipy_format():
    # COO with duplicate entries, CSR, unsorted CSC: all must give J = [2x, 2y, 2z].
    def coo(x):
        return sp.coo_matrix(([x[0], x[0], 2 * x[1], 2 * x[2]], ([0, 0, 0, 0], [0, 0, 1, 2])),
                             shape=(1, 3))

    for make in (coo, lambda x: coo(x).tocsr(), lambda x: sp.csc_matrix(coo(x))):
        problem = tessera.Problem(n=3, F=lambda x: [x @ x - 1.0], J=make, start=[0, 0, 1],
                                  step=0.5)
        assert problem.has_sparse_jacobian
        mesh = tessera.mesh(problem, method="front")
        assert np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1.0).max() < 1e-8
