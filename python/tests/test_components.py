# SPDX-License-Identifier: MIT
# mesh(components="all") and several start points: the components in the summary, as the CLI's
# `--components all` and `--start` given more than once (docs/components.md).
import json
import subprocess

import numpy as np
import pytest

import tessera
from summary_compare import without_times


def test_every_component_of_the_torus_and_sphere_is_the_cli_run(cli, tmp_path):
    mesh = tessera.mesh("torus_and_sphere", components="all", component_seeds=256)
    components = mesh.summary["run"]["components"]
    assert [c["euler_characteristic"] for c in components] == [0, 2]
    assert [c["genus"] for c in components] == [1, 0]
    assert mesh.summary["counts"]["components"] == 2
    assert mesh.summary["valid"]
    summary_path = tmp_path / "ts.json"
    subprocess.run([str(cli), "mesh", "torus_and_sphere", "--components", "all",
                    "--component-seeds", "256", "-o", str(tmp_path / "ts.ply"), "--summary",
                    str(summary_path), "-q"], check=True)
    assert without_times(mesh.summary) == without_times(json.loads(summary_path.read_text()))


def test_several_starts_say_which_component_each_reached():
    mesh = tessera.mesh("two_spheres", method="front",
                        start=[[1, 0, 0.5], [-1, 0, 0.6], [1.2, 0.4, 0]])
    starts = mesh.summary["run"]["starts"]
    assert [s["component"] for s in starts] == [1, 2, 1]
    assert [s["started_component"] for s in starts] == [True, True, False]
    problem = tessera.Problem.from_catalogue("two_spheres")
    residuals = np.array([problem.F(x)[0] for x in mesh.vertices])
    assert np.abs(residuals).max() < 1e-9


def test_every_component_needs_a_bounded_region():
    with pytest.raises(ValueError, match="bounded region"):
        tessera.mesh("sphere", components="all")
    with pytest.raises(ValueError, match="components"):
        tessera.mesh("two_spheres", components="every")
