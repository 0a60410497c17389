# SPDX-License-Identifier: MIT
# Errors are Python exceptions with the CLI's messages; failed runs carry their partial mesh.
import re
import subprocess

import numpy as np
import pytest

import tessera


def cli_error(cli, *arguments) -> str:
    run = subprocess.run([str(cli), *arguments], capture_output=True, text=True)
    assert run.returncode != 0
    return run.stderr.strip().removeprefix("tessera: error: ")


def test_unknown_catalogue_name_has_the_cli_message(cli, tmp_path):
    with pytest.raises(ValueError) as error:
        tessera.mesh("no_such_surface")
    assert str(error.value) == cli_error(cli, "mesh", "no_such_surface", "-o",
                                         str(tmp_path / "x.ply"))


def test_wrong_start_length_has_the_cli_message(cli, tmp_path):
    with pytest.raises(ValueError) as error:
        tessera.mesh("torus", start=[0, 1])
    assert str(error.value) == cli_error(cli, "mesh", "torus", "--start", "0,1", "-o",
                                         str(tmp_path / "x.ply"))


@pytest.mark.parametrize("options, match", [
    ({"step": -1.0}, "step: '-1.0' is not a finite number > 0"),
    ({"tolerance": float("nan")}, "tolerance"),
    ({"method": "marching"}, "method"),
    ({"max_valence": 13, "method": "front"}, "max_valence: value 13 not in range 6 to 12"),
    ({"placement": "hexagonal", "method": "front"}, "placement: only for method 'atlas'"),
    ({"refine": 2, "method": "front"}, "method 'bezier'"),
    ({"box": [0, 1]}, "--box has 2 values, expected 6"),
])
def test_bad_options_raise_value_error(options, match):
    with pytest.raises(ValueError, match=match):
        tessera.mesh("sphere", **options)


def test_messages_name_no_source_file(cli, tmp_path):
    # Issue 34: ValueError said "(start_and_box.cpp:113)"; the place is for TESSERA_DEBUG=1.
    for options in ({"box": [0, 1]}, {"start": [0, 1]}, {"box": {"w": (0, 1)}}):
        with pytest.raises(ValueError) as error:
            tessera.mesh("sphere", **options)
        assert not re.search(r"\.(cpp|h):\d+", str(error.value)), str(error.value)
    assert str(error.value) == cli_error(cli, "mesh", "sphere", "--box", "w=0:1", "-o",
                                         str(tmp_path / "x.ply"))


def test_an_exception_in_F_propagates():
    def F(x):
        if x[2] < 0:
            raise ZeroDivisionError("F is not defined below z = 0")
        return [x @ x - 1.0]

    problem = tessera.Problem(n=3, F=F, J=lambda x: [2 * x], start=[0, 0, 1], step=0.3)
    with pytest.raises(ZeroDivisionError, match="below z = 0"):
        tessera.mesh(problem, method="front")


def test_wrong_shapes_from_F_and_J_are_value_errors():
    with pytest.raises(ValueError, match=r"F\(x\) returned shape \(2,\), expected \(1,\)"):
        bad_F = tessera.Problem(n=3, F=lambda x: [0.0, 0.0], J=lambda x: [2 * x],
                                start=[0, 0, 1])
        tessera.mesh(bad_F)
    with pytest.raises(ValueError, match=r"J\(x\) returned shape \(2, 3\), expected \(1, 3\)"):
        bad_J = tessera.Problem(n=3, F=lambda x: [x @ x - 1], J=lambda x: np.zeros((2, 3)),
                                start=[0, 0, 1])
        tessera.mesh(bad_J)


def test_vertex_limit_raises_with_the_partial_mesh():
    with pytest.raises(tessera.ComputationFailed, match="stopped early") as error:
        tessera.mesh("torus", method="front", max_vertices=100)
    partial = error.value.mesh
    assert error.value.termination == "vertex limit reached"
    assert 0 < partial.vertex_count <= 101
    assert tessera.check(partial)["valid"]
    kept = tessera.mesh("torus", method="front", max_vertices=100, allow_partial=True)
    assert kept.summary["run"]["termination"] == "vertex limit reached"


def test_start_failure_gives_an_empty_mesh():
    far = tessera.Problem(n=3, F=lambda x: [x @ x - 1], J=lambda x: [2 * x],
                          start=[0, 0, 1], step=0.3)
    with pytest.raises(tessera.ComputationFailed) as error:
        tessera.mesh(far, start=[0, 0, 50], max_start_distance=0.1)
    assert error.value.mesh.vertex_count == 0
    with pytest.raises(ValueError, match="empty"):
        error.value.mesh.write("empty.ply")


def test_progress_callback_is_called_and_its_exception_stops_the_run():
    calls = []
    tessera.mesh("torus", method="front", step=0.05, progress=calls.append)
    assert calls and {"vertex_count", "triangle_count", "front_size"} <= set(calls[0])

    def stop(progress):
        raise RuntimeError("enough at %d" % progress["vertex_count"])

    with pytest.raises(RuntimeError, match="enough at"):
        tessera.mesh("torus", method="front", step=0.05, progress=stop)


def test_help_is_useful():
    assert "tolerance" in tessera.mesh.__doc__ and "ComputationFailed" in tessera.mesh.__doc__
    assert "scipy.sparse" in tessera.Problem.__doc__
