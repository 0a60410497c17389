# SPDX-License-Identifier: MIT
"""The price of problems written in Python (bench/RESULTS.md, "Python callbacks";
the history in bench/history/RESULTS-log.md section 11).

Meshes the same surface twice with the same options: once as the C++ catalogue problem, once as
a Python tessera.Problem with the same F, J, start and step (they make the same mesh, triangle
for triangle, python/tests). The difference of the runs' own wall times (summary run.wall_seconds,
without the report) divided by the evaluations of F and J is the cost of one Python callback.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_callbacks.py [repetitions]
"""
import pathlib
import sys
import time

import numpy as np

import tessera

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python" / "examples"))
from bvp_scipy import bratu_problem  # noqa: E402


def best_run(problem, repetitions, **options):
    """The fastest of `repetitions` runs: (run seconds, F evaluations, J evaluations, vertices)."""
    best = None
    for _ in range(repetitions):
        started = time.perf_counter()
        mesh = tessera.mesh(problem, allow_partial=True, report_samples=1, **options)
        total = time.perf_counter() - started
        run = mesh.summary["run"]
        measured = (run["wall_seconds"], run["function_evaluations"],
                    run["jacobian_evaluations"], mesh.vertex_count, total)
        if best is None or measured[0] < best[0]:
            best = measured
    return best


def compare(label, cpp, python, repetitions, **options):
    c = best_run(cpp, repetitions, **options)
    p = best_run(python, repetitions, **options)
    assert (c[1], c[2], c[3]) == (p[1], p[2], p[3]), "the two problems made different runs"
    per_call = (p[0] - c[0]) / (p[1] + p[2]) * 1e6
    print(f"{label:34s} {c[3]:6d} vertices {c[1]:8d} F {c[2]:6d} J   C++ {c[0]:7.3f} s   "
          f"Python {p[0]:7.3f} s   x{p[0] / c[0]:6.1f}   +{per_call:5.1f} us per call")


def main():
    repetitions = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    sphere = tessera.Problem.from_catalogue("sphere")
    python_sphere = tessera.Problem(n=3, F=lambda x: [x @ x - 1.0], J=lambda x: [2.0 * x],
                                    start=sphere.start, step=sphere.suggested_step)
    compare("sphere, front, step 0.05", sphere, python_sphere, repetitions, method="front",
            step=0.05)
    compare("sphere, atlas, tolerance 1e-4", sphere, python_sphere, repetitions,
            tolerance=1e-4)
    for N in (100, 1000):
        compare(f"bvp:points={N} (scipy.sparse J), front", tessera.Problem.from_catalogue(
            "bvp", points=N), bratu_problem(N), repetitions, method="front", max_vertices=500)


if __name__ == "__main__":
    main()
