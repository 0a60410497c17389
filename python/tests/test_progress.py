# SPDX-License-Identifier: MIT
# mesh(progress=...): a callable receives the run's records; None prints them on stderr as the
# CLI does (a status line on a terminal, lines elsewhere once a run lasts 5 s); True always,
# False never. The GIL is released while C++ works and taken for each record.
import time

import numpy as np
import pytest

import tessera

STAGES = ["build", "clip", "refine", "validate", "patches", "report", "analyses"]


def test_records_name_the_stage_and_the_time():
    records = []
    mesh = tessera.mesh("sphere_cut", method="front", step=0.05, progress=records.append)
    assert {"stage", "vertex_count", "triangle_count", "front_size", "seconds"} == set(records[0])
    stages = [record["stage"] for record in records]
    # The build first (every 1000 vertices or every second), then each later stage once, in order.
    assert stages[0] == "build" and stages.count("build") >= mesh.vertex_count // 1000
    later = [stage for stage in stages if stage != "build"]
    assert later == sorted(set(later), key=STAGES.index)
    assert {"clip", "validate", "report"} <= set(later) and "analyses" not in later
    assert stages.index(later[0]) == stages.count("build")
    seconds = [record["seconds"] for record in records]
    assert seconds == sorted(seconds) and seconds[0] >= 0
    build = [record for record in records if record["stage"] == "build"]
    assert [r["vertex_count"] for r in build] == sorted(r["vertex_count"] for r in build)
    assert all(r["front_size"] > 0 for r in build)
    # A later stage reports the mesh as it begins.
    validate = records[stages.index("validate")]
    assert validate["front_size"] == 0 and validate["triangle_count"] > 0
    assert records[-1]["stage"] == "report"
    assert records[-1]["vertex_count"] == mesh.vertex_count
    # Folds are an analysis of the finished mesh: one more stage.
    records.clear()
    tessera.mesh("whitney_pleat", folds="lambda,mu", progress=records.append)
    assert [record["stage"] for record in records][-2:] == ["report", "analyses"]


def test_a_slow_build_reports_every_second():
    # A sphere whose Jacobian takes 5 ms for the first 2.5 s: the build lasts seconds far from
    # 1000 vertices (a vertex costs a few Jacobians), as a build at large n does, and still
    # reports about once a second.
    first_call = []

    def J(x):
        first_call.append(first_call[0] if first_call else time.monotonic())
        if time.monotonic() - first_call[0] < 2.5:
            time.sleep(0.005)
        return 2 * np.asarray(x)[None, :]

    sphere = tessera.Problem(n=3, F=lambda x: [x @ x - 1.0], J=J, start=[0, 0, 1], step=0.1)
    records = []
    tessera.mesh(sphere, method="front", progress=records.append)
    build = [record for record in records if record["stage"] == "build"]
    assert len(build) >= 2 and build[0]["vertex_count"] < 1000
    assert build[0]["seconds"] == pytest.approx(1.0, abs=0.5)
    assert build[1]["seconds"] - build[0]["seconds"] == pytest.approx(1.0, abs=0.5)


def test_true_prints_on_stderr_false_and_short_default_runs_do_not(capsys):
    tessera.mesh("sphere_cut", progress=True)
    printed = capsys.readouterr().err
    assert "tessera: clip: " in printed and "tessera: validate: " in printed
    assert printed.rstrip().splitlines()[-1].startswith("tessera: finished after")
    tessera.mesh("sphere_cut", progress=False)
    tessera.mesh("sphere_cut")  # not a terminal, and over in well under 5 s
    assert capsys.readouterr().err == ""


def test_progress_is_a_callable_or_a_bool():
    for wrong in (3, "yes", [print]):
        with pytest.raises(TypeError, match="progress must be a callable"):
            tessera.mesh("sphere", progress=wrong)
