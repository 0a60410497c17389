# SPDX-License-Identifier: MIT
# mesh(checkpoint=...), tessera.resume and tessera.extend (docs/checkpoints.md, "From Python"):
# a run stopped from its progress callable and resumed gives the same mesh, bit for bit, as the
# run never stopped; a cap of the sphere is extended to a larger box and to a finer tolerance;
# a Problem written in Python must be given again and must be the same; bad extensions and the
# command line's checkpoints are refused with ValueError.
import math
import subprocess

import numpy as np
import pytest

import tessera

SMALL_CAP = [-2, 2, -2, 2, 0.2, 2]
LARGE_CAP = [-2, 2, -2, 2, -0.5, 2]


def same_mesh(a: tessera.Mesh, b: tessera.Mesh) -> bool:
    return (a.vertices.shape == b.vertices.shape and
            np.array_equal(a.vertices.view(np.uint64), b.vertices.view(np.uint64)) and
            np.array_equal(a.triangles, b.triangles))


@pytest.mark.parametrize("method", ["atlas", "front"])
def test_a_stopped_run_resumes_to_the_same_mesh(tmp_path, method):
    whole = tessera.mesh("bvp:points=200", method=method, report_samples=50,
                         checkpoint=tmp_path / "whole.tsc", progress=False)

    class Stop(Exception):
        pass

    def stop_in_the_build(record):
        if record["stage"] == "build" and record["vertex_count"] >= 1000:
            raise Stop()

    with pytest.raises(Stop):
        tessera.mesh("bvp:points=200", method=method, report_samples=50,
                     checkpoint=tmp_path / "run.tsc", progress=stop_in_the_build)
    resumed = tessera.resume(tmp_path / "run.tsc", progress=False)
    resumed_from = resumed.summary["run"]["resumed_from"]
    assert resumed_from["charts" if method == "atlas" else "vertices"] >= 1000
    assert same_mesh(resumed, whole)


def test_extend_grows_a_cap_into_a_larger_box_and_refines_it(tmp_path):
    small = tessera.mesh("sphere", start=[0, 0, 1], box=SMALL_CAP, checkpoint=tmp_path / "cap.tsc",
                         progress=False)
    large = tessera.extend(tmp_path / "cap.tsc", box=LARGE_CAP, checkpoint=tmp_path / "large.tsc",
                           progress=False)
    run = large.summary["run"]
    assert run["resumed_from"]["charts"] == small.summary["run"]["atlas"]["charts"]
    assert run["atlas"]["charts"] > run["resumed_from"]["charts"]
    assert large.summary["valid"] and large.summary["topology"]["euler_characteristic"] == 1
    assert large.summary["shape"]["area"] == pytest.approx(2 * math.pi * 1.5, rel=0.01)
    assert large.vertices[:, 2].min() < 0.2 - 0.5  # it reaches below the old box
    # The extended checkpoint records the extended call: resumed, it gives the same mesh.
    assert same_mesh(tessera.resume(tmp_path / "large.tsc", progress=False), large)

    finer = tessera.extend(tmp_path / "cap.tsc", tolerance=0.0015, checkpoint=tmp_path / "f.tsc",
                           progress=False)
    assert finer.summary["run"]["atlas"]["charts"] == small.summary["run"]["atlas"]["charts"]
    assert small.summary["run"]["max_sampled_distance"] > 0.0015
    assert finer.summary["run"]["max_sampled_distance"] <= 0.0015
    assert finer.vertex_count > small.vertex_count


@pytest.mark.parametrize("options, message", [
    ({"box": [-2, 2, -2, 2, 0.4, 2]}, "does not contain the checkpoint's"),
    ({"tolerance": 0.01}, "is not finer than the run's"),
    ({}, "give a larger box, a finer tolerance"),
])
def test_bad_extensions_are_refused(tmp_path, options, message):
    tessera.mesh("sphere", start=[0, 0, 1], box=SMALL_CAP, checkpoint=tmp_path / "cap.tsc",
                 progress=False)
    before = (tmp_path / "cap.tsc").read_bytes()
    with pytest.raises(ValueError, match=message):
        tessera.extend(tmp_path / "cap.tsc", progress=False, **options)
    assert (tmp_path / "cap.tsc").read_bytes() == before


def test_a_python_problem_must_be_given_again_and_be_the_same(tmp_path, sphere):
    first = tessera.mesh(sphere, checkpoint=tmp_path / "p.tsc", progress=False)
    with pytest.raises(ValueError, match="give it again"):
        tessera.resume(tmp_path / "p.tsc")
    assert same_mesh(tessera.resume(tmp_path / "p.tsc", problem=sphere, progress=False), first)
    other = tessera.Problem(n=3, F=lambda x: [x @ x - 1.1], J=lambda x: [2.0 * x],
                            start=[0.1, 0.2, 1.1], step=0.3, name="python_sphere")
    with pytest.raises(ValueError, match="differs from the checkpoint's"):
        tessera.resume(tmp_path / "p.tsc", problem=other, progress=False)


def test_checkpoints_of_the_command_line_and_of_python_are_told_apart(tmp_path, cli):
    subprocess.run([str(cli), "mesh", "sphere", "-q", "-o", str(tmp_path / "m.ply"),
                    "--checkpoint", str(tmp_path / "cli.tsc")], check=True)
    with pytest.raises(ValueError, match="tessera resume"):
        tessera.resume(tmp_path / "cli.tsc")
    tessera.mesh("sphere", checkpoint=tmp_path / "py.tsc", progress=False)
    refused = subprocess.run([str(cli), "resume", str(tmp_path / "py.tsc")], capture_output=True,
                             text=True)
    assert refused.returncode == 2
    assert "tessera.resume" in refused.stderr


def test_checkpoints_are_for_the_atlas_and_the_front(tmp_path):
    with pytest.raises(ValueError, match="supported for methods 'atlas' and 'front'"):
        tessera.mesh("sphere", method="bezier", checkpoint=tmp_path / "f.tsc", progress=False)
    tessera.mesh("sphere", method="front", checkpoint=tmp_path / "front.tsc", progress=False)
    with pytest.raises(ValueError, match="extend continues an atlas"):
        tessera.extend(tmp_path / "front.tsc", tolerance=1e-4, progress=False)
    with pytest.raises(ValueError, match="must end in .tsc"):
        tessera.mesh("sphere", checkpoint=tmp_path / "f.ply", progress=False)
