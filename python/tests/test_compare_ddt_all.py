# SPDX-License-Identifier: MIT
# `tessera compare` and `tessera ddt --all-criteria [--orders] [--compare-report]` from Python:
# the CLI's numbers as data.
import re
import subprocess

import numpy as np
import pytest

import tessera
from conftest import REPOSITORY

FRANKE33 = REPOSITORY / "examples" / "data" / "franke33.csv"


def franke33_points() -> np.ndarray:
    return np.loadtxt(FRANKE33, delimiter=",", comments="#", skiprows=2)


# --- compare ---------------------------------------------------------------------------------


def test_compare_runs_every_method():
    report = tessera.compare("torus")
    assert report["problem"] == "torus"
    assert report["expected_euler_characteristic"] == 0
    assert [row["method"] for row in report["methods"]] == tessera.methods()
    for row in report["methods"]:
        assert row["vertex_count"] > 0 and row["triangle_count"] > 0, row
        # A closed torus: V − E + T = 0 with E = 3T/2, so T = 2V.
        assert row["triangle_count"] == 2 * row["vertex_count"], row
        assert row["valid"] and row["completed"] and row["passes"], row
        assert row["termination"] == "completed" and row["message"] == ""
        assert row["euler_characteristic"] == 0
        assert 0 < row["max_distance"] < 0.1 and 0 < row["min_angle_degrees"] < 60
        assert row["wall_seconds"] > 0
    # Issue 34: every method runs to the same tolerance (the atlas's default without one), or
    # the rows are not comparable.
    assert report["tolerance"] > 0
    for row in report["methods"]:
        assert row["tolerance"] == report["tolerance"], row
        assert row["max_distance"] <= report["tolerance"], row
    assert report["passes"]


def test_compare_gives_the_cli_s_table(cli):
    report = tessera.compare("sphere", step=0.2, tolerance=0.01)
    output = subprocess.run([str(cli), "compare", "sphere", "--step", "0.2", "--tolerance",
                             "0.01"], capture_output=True, text=True, check=True).stdout
    for row in report["methods"]:
        line = re.search(rf"^{row['method']}\s+(\d+)\s+(\d+)\s", output, re.MULTILINE)
        assert line, output
        assert (int(line.group(1)), int(line.group(2))) == (row["vertex_count"],
                                                            row["triangle_count"])
        assert row["tolerance"] == 0.01
    assert "expected Euler characteristic: 2" in output


def test_compare_reports_failures_as_rows():
    # The CLI exits with status 1; the bindings give the table with passes False.
    report = tessera.compare("torus", max_vertices=50)
    assert not report["passes"]
    for row in report["methods"]:
        assert row["termination"] == "vertex limit reached", row
        assert not row["completed"] and not row["passes"] and row["message"]
        assert row["vertex_count"] > 0 and row["valid"]


def test_compare_box_and_bad_input():
    report = tessera.compare("sphere", box=[-1.5, 1.5, -1.5, 1.5, -0.5, 1.5])
    assert all(row["vertex_count"] > 0 for row in report["methods"])
    assert all(row["euler_characteristic"] == 1 for row in report["methods"])  # a cap: a disk
    with pytest.raises(ValueError, match="placement"):
        tessera.compare("torus", placement="square")
    with pytest.raises(ValueError, match="--box"):
        tessera.compare("torus", box=[0, 1])
    with pytest.raises(ValueError, match="max_vertices"):
        tessera.compare("torus", max_vertices=3)


# --- ddt --all-criteria ----------------------------------------------------------------------


def hull_boundary_points(points: np.ndarray) -> set:
    """Indices of the points on the boundary of the convex hull, collinear ones included
    (Andrew's monotone chain keeping points on the hull's edges)."""
    order = sorted(range(len(points)), key=lambda i: (points[i, 0], points[i, 1]))

    def cross(o, a, b):
        return ((points[a, 0] - points[o, 0]) * (points[b, 1] - points[o, 1]) -
                (points[a, 1] - points[o, 1]) * (points[b, 0] - points[o, 0]))

    def chain(indices):
        kept = []
        for i in indices:
            while len(kept) >= 2 and cross(kept[-2], kept[-1], i) < -1e-12:
                kept.pop()
            kept.append(i)
        return kept

    return set(chain(order)) | set(chain(order[::-1]))


def assert_triangulates_the_points(mesh: tessera.Mesh, points: np.ndarray) -> None:
    n = len(points)
    assert np.array_equal(mesh.vertices[:, :2], points)
    triangles = np.asarray(mesh.triangles)
    assert set(triangles.ravel()) == set(range(n))  # every point used
    hull = hull_boundary_points(points)
    assert mesh.triangle_count == 2 * n - 2 - len(hull)
    # Consistently oriented, none degenerate, and together exactly the hull: no overlap, no hole.
    a, b, c = (points[triangles[:, k]] for k in range(3))
    areas = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) -
                   (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    assert np.all(areas * np.sign(areas.sum()) > 1e-12)
    edges = {}
    for triangle in triangles:
        for k in range(3):
            edge = tuple(sorted((triangle[k], triangle[(k + 1) % 3])))
            edges[edge] = edges.get(edge, 0) + 1
    assert max(edges.values()) == 2
    boundary = {v for edge, count in edges.items() if count == 1 for v in edge}
    assert boundary == hull


def test_all_criteria_with_values_gives_one_triangulation_per_criterion():
    data = franke33_points()
    points, values = data[:, :2], np.sin(4 * data[:, 0]) * data[:, 1]
    results = tessera.ddt(points, values, all_criteria=True)
    # The CLI's table without a function: every criterion but equid, in the table's order.
    assert list(results) == ["delaunay", "mwt3d-2 global", "abn-1 global", "abn-2 global",
                             "jnd-1 global", "jnd-2 global", "pf-1 global", "pf-2 global",
                             "pd-1 global", "pd-2 global"]
    for label, mesh in results.items():
        assert mesh.summary["criterion"] == label
        assert mesh.summary["norm"] == ("l1" if label.split()[0].endswith("-1") else "l2")
        assert "error" not in mesh.summary and "orders" not in mesh.summary
        assert np.allclose(mesh.vertices[:, 2], values)
        assert_triangulates_the_points(mesh, points)
    # The data-dependent criteria do change the triangulation.
    delaunay = {tuple(sorted(t)) for t in results["delaunay"].triangles}
    assert any({tuple(sorted(t)) for t in mesh.triangles} != delaunay
               for mesh in results.values())


def test_all_criteria_orders_and_report_are_the_cli_s(cli):
    points = franke33_points()
    results = tessera.ddt(points, function="F2", all_criteria=True, orders=3, compare_report=33)
    assert len(results) == 11 and list(results)[-1] == "equid-2 global"
    for mesh in results.values():
        assert_triangulates_the_points(mesh, points)
        orders, report = mesh.summary["orders"], mesh.summary["report"]
        assert orders["count"] == 3
        assert orders["lowest_mean"] <= mesh.summary["error"]["mean"] <= orders["highest_mean"]
        assert report["table"] == 1 and 0 < report["mean"] < 0.02
        assert isinstance(report["in_spread"], bool)
    assert results["delaunay"].summary["report"]["mean"] == 0.01604  # Malcolm's Table 1, F2
    assert results["delaunay"].summary["report"]["in_spread"]
    output = subprocess.run([str(cli), "ddt", str(FRANKE33), "--function", "F2",
                             "--all-criteria", "--orders", "3", "--compare-report", "33"],
                            capture_output=True, text=True, check=True).stdout
    for label, mesh in results.items():
        line = re.search(rf"^{re.escape(label)}\s+mean (\S+)\s+orders (\S+) … (\S+)\s+report "
                         rf"(\S+) \((in|outside) spread\)", output, re.MULTILINE)
        assert line, (label, output)
        summary = mesh.summary
        assert float(line.group(1)) == pytest.approx(summary["error"]["mean"], abs=5e-6)
        assert float(line.group(2)) == pytest.approx(summary["orders"]["lowest_mean"], abs=5e-6)
        assert float(line.group(3)) == pytest.approx(summary["orders"]["highest_mean"], abs=5e-6)
        assert float(line.group(4)) == summary["report"]["mean"]
        assert (line.group(5) == "in") == summary["report"]["in_spread"]


def test_all_criteria_defaults_and_refusals():
    points = franke33_points()
    results = tessera.ddt(points, function="F1", all_criteria=True)
    # Defaults as the CLI: one sweep order, no report.
    assert all("orders" not in m.summary and "report" not in m.summary for m in results.values())
    assert all("error" in m.summary for m in results.values())
    report = tessera.ddt(points, function="F1", all_criteria=True, compare_report=100)
    assert report["delaunay"].summary["report"] == {"table": 2, "mean": 0.01637}
    with pytest.raises(ValueError, match="only with all_criteria"):
        tessera.ddt(points, function="F1", orders=3)
    with pytest.raises(ValueError, match="only with all_criteria"):
        tessera.ddt(points, function="F1", compare_report=33)
    with pytest.raises(ValueError, match="need function"):
        tessera.ddt(points, np.zeros(len(points)), all_criteria=True, orders=2)
    with pytest.raises(ValueError, match="33, 100"):
        tessera.ddt(points, function="F1", all_criteria=True, compare_report=50)
    with pytest.raises(ValueError, match="orders"):
        tessera.ddt(points, function="F1", all_criteria=True, orders=0)
    with pytest.raises(ValueError, match="not with all_criteria"):
        tessera.ddt(points, function="F1", all_criteria=True, criterion="pf")
