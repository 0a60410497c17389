# SPDX-License-Identifier: MIT
# tessera.mesh(..., folds=...): the fold curves of `tessera mesh --folds` from Python, on the
# pleat's exact curve, for a problem written in Python too, and bad planes refused as ValueError.
import numpy as np
import pytest

import tessera


def test_pleat_fold_curve_is_exact_and_has_its_cusp_at_the_origin():
    mesh = tessera.mesh("whitney_pleat", tolerance=0.01, folds="lambda,mu")
    folds = mesh.summary["folds"]
    assert folds["columns"] == ["x", "lambda", "mu"]
    assert folds["unrefined_points"] == 0
    (curve,) = mesh.fold_curves
    x, lam, mu = curve.T
    np.testing.assert_allclose(lam, 3 * x**2, atol=1e-8)
    np.testing.assert_allclose(mu, -2 * x**3, atol=1e-8)
    (cusp,) = folds["cusps"]
    assert abs(cusp["point"]["x"]) < 1e-8


def test_a_python_problem_has_the_same_folds():
    pleat = tessera.Problem(n=3, F=lambda p: [p[0] ** 3 - p[1] * p[0] - p[2]],
                            J=lambda p: [[3 * p[0] ** 2 - p[1], -p[0], -1.0]],
                            start=[0.0, 0.5, 0.0], step=0.1, box=[-1, 1] * 3,
                            coordinate_names=["x", "lambda", "mu"], name="python_pleat")
    mesh = tessera.mesh(pleat, tolerance=0.01, folds="lambda,mu")
    (curve,) = mesh.fold_curves
    np.testing.assert_allclose(curve[:, 1], 3 * curve[:, 0] ** 2, atol=1e-8)
    assert len(mesh.summary["folds"]["cusps"]) == 1


def test_a_plane_that_cannot_fold_is_a_value_error():
    with pytest.raises(ValueError, match="not differentiable"):
        tessera.mesh("bvp:points=20", folds="lambda,max:u")
    with pytest.raises(ValueError, match="two functionals"):
        tessera.mesh("whitney_pleat", folds="lambda")
    assert tessera.mesh("whitney_pleat", tolerance=0.05).fold_curves == []
