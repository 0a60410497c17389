# SPDX-License-Identifier: MIT
# tessera.mesh(..., stability=, hopf=, level=, diagram=): the stability, Hopf and level curves of
# `tessera mesh` from Python, checked against closed forms computed here in NumPy; problems
# written in Python with dynamics=, and bad dynamics refused as ValueError naming the field.
import numpy as np
import pytest

import tessera
from conftest import REPOSITORY

BETA = 0.5  # the CSTR's heat transfer coefficient, in the catalogue and in examples/problems


def pleat_in_python(**dynamics):
    """Whitney's pleat x³ − λx − μ = 0 as the catalogue has it (start, step, box)."""
    return tessera.Problem(n=3, F=lambda p: [p[0] ** 3 - p[1] * p[0] - p[2]],
                           J=lambda p: [[3 * p[0] ** 2 - p[1], -p[0], -1.0]],
                           start=[0.1, 0.1, 0.1], step=0.1, box=[-1.5, 1.5] * 3,
                           coordinate_names=["x", "lambda", "mu"], name="python_pleat",
                           **dynamics)


def cstr_in_python(dynamics):
    """The CSTR of examples/problems/cstr.tsr (same F, start, step and box)."""
    def F(x):
        x1, x2, Da, B = x
        reaction = Da * (1 - x1) * np.exp(x2)
        return [-x1 + reaction, -(1 + BETA) * x2 + B * reaction]

    def J(x):
        x1, x2, Da, B = x
        e = np.exp(x2)
        return [[-1 - Da * e, Da * (1 - x1) * e, (1 - x1) * e, 0.0],
                [-B * Da * e, -(1 + BETA) + B * Da * (1 - x1) * e, B * (1 - x1) * e,
                 Da * (1 - x1) * e]]

    return tessera.Problem(n=4, F=F, J=J, start=[0.1, 0.1, 0.1, 5], step=0.1,
                           box=[0.02, 1, 0, 8, 0, 0.3, 1, 12],
                           coordinate_names=["x1", "x2", "Da", "B"], name="python_cstr",
                           dynamics=dynamics)


def cstr_trace_and_det(x1, B):
    """Trace and determinant of the CSTR's 2×2 state Jacobian on M, where Da·e^x2 = a."""
    a = x1 / (1 - x1)
    return B * x1 - (2 + BETA) - a, (1 + BETA) / (1 - x1) - B * x1


# ---- stability ------------------------------------------------------------------------------


def test_pleat_is_stable_on_the_outer_sheets_and_of_index_one_on_the_middle():
    mesh = tessera.mesh("whitney_pleat", tolerance=0.01, stability=True)
    x, lam = mesh.vertices[:, 0], mesh.vertices[:, 1]
    # x' = −(x³ − λx − μ): the one eigenvalue is −(3x² − λ).
    curvature = 3 * x**2 - lam
    away = np.abs(curvature) > 1e-9  # on the fold the eigenvalue is 0 up to rounding
    assert away.sum() > 0.99 * len(x)
    np.testing.assert_array_equal(mesh.unstable_count[away], (curvature < 0)[away].astype(int))
    np.testing.assert_allclose(mesh.leading_real_part, -curvature, atol=1e-12)
    assert mesh.stability_certain.all()
    assert all(len(values) == 1 for values in mesh.eigenvalues)
    stability = mesh.summary["stability"]
    assert stability["parameters"] == ["lambda", "mu"]
    assert stability["method"] == "dense"
    assert stability["vertices"] == mesh.vertex_count
    assert stability["stable_vertices"] == int((mesh.unstable_count == 0).sum())
    assert sum(stability["vertices_by_index"]) == mesh.vertex_count
    # Without stability there is nothing per vertex.
    plain = tessera.mesh("whitney_pleat", tolerance=0.05)
    assert plain.unstable_count is None and plain.eigenvalues is None
    assert "stability" not in plain.summary


def test_stability_is_written_as_point_data(tmp_path):
    mesh = tessera.mesh("whitney_pleat", tolerance=0.05, stability=True)
    path = tmp_path / "pleat.ply"
    mesh.write(path, ascii=True)
    header = path.read_text().split("end_header")[0]
    for name in ("unstable_count", "leading_real_part", "stability_certain"):
        assert f"property double {name}" in header or f"property float {name}" in header, header


def test_python_pleat_with_dynamics_has_the_catalogues_counts():
    catalogue = tessera.mesh("whitney_pleat", method="front", stability=True)
    python = tessera.mesh(pleat_in_python(dynamics={"parameters": ("lambda", "mu"), "sign": -1}),
                          method="front", stability=True)
    assert python.vertex_count == catalogue.vertex_count
    assert (python.summary["stability"]["vertices_by_index"]
            == catalogue.summary["stability"]["vertices_by_index"])
    np.testing.assert_array_equal(python.unstable_count, catalogue.unstable_count)
    # B = 2 halves the eigenvalue and keeps its sign; indices (1, 2) name the same parameters.
    heavy = tessera.mesh(pleat_in_python(dynamics=tessera.Dynamics((1, 2), sign=-1, mass=[2.0])),
                         method="front", stability=True)
    np.testing.assert_array_equal(heavy.unstable_count, catalogue.unstable_count)
    np.testing.assert_allclose(heavy.leading_real_part, catalogue.leading_real_part / 2,
                               atol=1e-12)


def test_every_problem_tells_its_dynamics():
    pleat = tessera.Problem.from_catalogue("whitney_pleat").dynamics
    assert (pleat.parameters, pleat.sign, pleat.mass) == (("lambda", "mu"), -1, None)
    cstr = tessera.Problem.from_file(REPOSITORY / "examples/problems/cstr.tsr").dynamics
    assert (cstr.parameters, cstr.sign, cstr.mass) == (("Da", "B"), 1, None)
    text = ("variables x1 x2 Da B\nequation x1 - Da\nequation x2 - B\nstart 0 0 0 0\n"
            "dynamics parameters Da B mass 1 0\n")
    algebraic = tessera.Problem.from_text(text).dynamics
    np.testing.assert_array_equal(algebraic.mass, [1.0, 0.0])
    python = cstr_in_python(tessera.Dynamics(("Da", "B"), mass=np.diag([1.0, 3.0])))
    assert python.dynamics.parameters == ("Da", "B")
    np.testing.assert_array_equal(python.dynamics.mass.toarray(), np.diag([1.0, 3.0]))
    assert tessera.Problem.from_catalogue("sphere").dynamics is None


# ---- Hopf curves and the Bogdanov-Takens point ------------------------------------------------


def check_cstr_hopf(mesh):
    hopf = mesh.summary["hopf"]
    assert hopf["columns"] == ["x1", "x2", "Da", "B", "omega", "l1"]
    assert hopf["plane"] == ["Da", "B"]
    assert hopf["unrefined_points"] == 0
    curves = mesh.hopf_curves
    assert len(curves) >= 1
    problem = mesh.problem
    for curve in curves:
        x1, B, omega = curve[:, 0], curve[:, 3], curve[:, 4]
        trace, det = cstr_trace_and_det(x1, B)
        np.testing.assert_allclose(trace, 0.0, atol=1e-8)
        np.testing.assert_allclose(omega**2, det, atol=1e-8)
        assert max(np.abs(problem.F(point[:4])).max() for point in curve) < 1e-8
    (bt,) = mesh.special_points
    assert bt["kind"] == "bogdanov_takens"
    assert abs(bt["point"]["x1"] - 2 / 3) < 1e-8
    assert abs(bt["point"]["B"] - 6.75) < 1e-8
    assert abs(bt["point"]["x2"] - 3.0) < 1e-8
    assert abs(bt["plane"]["Da"] - 2 * np.exp(-3)) < 1e-8  # Da = a·e^(−x2) with a = 2
    # The neutral saddles (real pairs ±κ) have trace 0 and det = −κ² < 0.
    for curve in mesh.neutral_saddle_curves:
        trace, det = cstr_trace_and_det(curve[:, 0], curve[:, 3])
        np.testing.assert_allclose(trace, 0.0, atol=1e-8)
        np.testing.assert_allclose(-curve[:, 4] ** 2, det, atol=1e-8)


def test_cstr_hopf_points_have_zero_trace_and_meet_at_the_bogdanov_takens_point():
    mesh = tessera.mesh("cstr", hopf=True)
    check_cstr_hopf(mesh)
    assert mesh.unstable_count is not None  # hopf implies stability


def test_cstr_problem_file_and_python_dynamics_find_the_same_hopf_curves():
    from_file = tessera.mesh(REPOSITORY / "examples/problems/cstr.tsr", hopf=True)
    check_cstr_hopf(from_file)
    python = tessera.mesh(cstr_in_python({"parameters": ("Da", "B")}), hopf=True)
    check_cstr_hopf(python)
    assert (python.summary["stability"]["vertices_by_index"]
            == from_file.summary["stability"]["vertices_by_index"])


# ---- level curves and the diagram -------------------------------------------------------------


def test_pleat_level_curve_lies_on_the_level_and_on_m():
    mesh = tessera.mesh("whitney_pleat", tolerance=0.01, level="x=0.5")
    assert mesh.summary["level"]["columns"] == ["x", "lambda", "mu"]
    assert mesh.level_curves, mesh.summary["level"]
    for curve in mesh.level_curves:
        x, lam, mu = curve.T
        np.testing.assert_allclose(x, 0.5, atol=1e-8)
        np.testing.assert_allclose(mu, x**3 - lam * x, atol=1e-8)
    assert tessera.mesh("whitney_pleat", tolerance=0.05).level_curves == []


@pytest.mark.parametrize("suffix, magic", [(".png", b"\x89PNG"), (".svg", b"<?xml")])
def test_cstr_diagram_is_drawn(tmp_path, suffix, magic):
    path = tmp_path / f"cstr{suffix}"
    mesh = tessera.mesh("cstr", diagram=path)
    assert path.read_bytes().startswith(magic)
    # As --diagram: the folds over the dynamics' parameters and the Hopf curves.
    assert mesh.summary["folds"]["plane"] == "Da, B" and mesh.fold_curves
    assert mesh.hopf_curves


# ---- errors -----------------------------------------------------------------------------------


@pytest.mark.parametrize("dynamics, error, match", [
    ({"parameters": ("lambda", "nu")}, ValueError,
     r"dynamics.parameters: 'nu' is not a coordinate \(coordinates: x, lambda, mu\)"),
    ({"parameters": ("mu", "mu")}, ValueError,
     r"dynamics.parameters: coordinate 'mu' is given twice"),
    ({"parameters": (1, 3)}, ValueError, r"dynamics.parameters: index 3 is not a coordinate index"),
    ({"parameters": "lambda"}, ValueError, r"dynamics.parameters must be two coordinates"),
    ({"parameters": ("lambda", 1.5)}, ValueError, r"1.5 is neither a coordinate name nor an index"),
    ({"parameters": ("lambda", "mu"), "sign": 2}, ValueError, r"dynamics.sign must be 1 or -1"),
    ({"parameters": ("lambda", "mu"), "mass": [1, 1]}, ValueError,
     r"dynamics.mass has shape \(2,\), expected \(1,\)"),
    ({"parameters": ("lambda", "mu"), "mass": [-1]}, ValueError,
     r"dynamics.mass\[0\] = -1.0 must be a finite number >= 0"),
    ({"parameters": ("lambda", "mu"), "mass": [np.nan]}, ValueError, r"dynamics.mass\[0\]"),
    ({"parameters": ("lambda", "mu"), "masses": [1]}, ValueError,
     r"dynamics: unknown key 'masses' \(keys: parameters, sign, mass\)"),
    ({"sign": -1}, ValueError, r"dynamics: 'parameters' is required"),
    (("lambda", "mu"), TypeError, r"dynamics must be a tessera.Dynamics or a dict"),
])
def test_bad_dynamics_are_refused_naming_the_field(dynamics, error, match):
    with pytest.raises(error, match=match):
        pleat_in_python(dynamics=dynamics)


def test_bad_requests_are_value_errors_before_any_computation(tmp_path, sphere):
    with pytest.raises(ValueError, match="'python_sphere' does not say what its equations"):
        tessera.mesh(sphere, stability=True)
    with pytest.raises(ValueError, match="hopf: problem 'torus' does not say"):
        tessera.mesh("torus", hopf=True)
    with pytest.raises(ValueError, match="a picture is .png or .svg"):
        tessera.mesh("cstr", diagram=tmp_path / "cstr.pdf")
    with pytest.raises(ValueError, match="eigenvalues"):
        tessera.mesh("cstr", stability=True, eigenvalues=0)
    with pytest.raises(ValueError, match="--level w=1"):
        tessera.mesh("whitney_pleat", level="w=1")
    # A sparse mass matrix of the right size is taken, one of the wrong size is not.
    sparse = pytest.importorskip("scipy.sparse")
    assert cstr_in_python({"parameters": ("Da", "B"), "mass": sparse.identity(2)}).dynamics
    with pytest.raises(ValueError, match=r"dynamics.mass has shape \(2, 2\), expected \(1,\)"):
        pleat_in_python(dynamics={"parameters": ("lambda", "mu"), "mass": sparse.identity(2)})
