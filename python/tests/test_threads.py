# SPDX-License-Identifier: MIT
# threads= (docs/threads.md): the mesh and the summary do not depend on it, and a problem
# written in Python is evaluated on one thread (each call takes the GIL) whatever it says.
import threading

import numpy as np
import pytest

import tessera
from summary_compare import without_times


def without_threads(summary):
    summary = without_times(summary)
    del summary["run"]["threads"]
    return summary


def test_the_mesh_and_summary_are_the_same_on_one_and_two_threads():
    one = tessera.mesh("torus", tolerance=3e-3, threads=1)
    two = tessera.mesh("torus", tolerance=3e-3, threads=2)
    assert one.summary["run"]["threads"] == 1
    assert two.summary["run"]["threads"] == 2
    np.testing.assert_array_equal(one.vertices, two.vertices)
    np.testing.assert_array_equal(one.triangles, two.triangles)
    assert without_threads(one.summary) == without_threads(two.summary)


def test_a_python_problem_is_evaluated_on_one_thread():
    callers = set()

    def F(x):
        callers.add(threading.get_ident())
        return [x @ x - 1.0]

    def J(x):
        callers.add(threading.get_ident())
        return [2.0 * x]

    problem = tessera.Problem(n=3, F=F, J=J, start=[0, 0, 1], step=0.3)
    mesh = tessera.mesh(problem, tolerance=0.02, threads=4)
    assert mesh.summary["run"]["threads"] == 1
    assert len(callers) == 1


def test_threads_must_be_positive():
    with pytest.raises(ValueError):
        tessera.mesh("sphere", threads=0)
