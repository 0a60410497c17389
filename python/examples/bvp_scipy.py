# SPDX-License-Identifier: MIT
"""The catalogue's `bvp` (Arrhenius-Bratu boundary value problem) written in NumPy/SciPy:
u'' + λ exp(u/(1 + εu)) = 0 on (0, 1), u(0) = u(1) = 0, on N interior grid points; the
unknowns are x = (u_1 … u_N, λ, ε), n = N + 2, and the Jacobian is a scipy.sparse matrix.

Run as a script (PYTHONPATH=build/python /usr/bin/python3 python/examples/bvp_scipy.py) it
covers N = 50 with the front method: about 12600 vertices in 20-30 s on a 2-core machine, a
quarter of it the covering and the rest the report, which measures the distance to M of every
triangle's centroid and edge midpoints with the Python F and J (mesh(report_samples=300) makes
that a second). Progress goes to stderr once the run has lasted 5 s (mesh(progress=...))."""
import numpy as np
import scipy.sparse as sp

import tessera


def bratu_problem(N: int) -> tessera.Problem:
    h = 1.0 / (N + 1)
    laplacian = sp.diags([np.ones(N - 1), -2 * np.ones(N), np.ones(N - 1)], [-1, 0, 1],
                         format="csc")

    def F(x):
        u, lam, eps = x[:N], x[N], x[N + 1]
        return laplacian @ u + h * h * lam * np.exp(u / (1 + eps * u))

    # DF's pattern never changes (the tridiagonal u-block and the full columns of λ and ε): it is
    # built once, and each J(x) fills its values. Assembling with sp.hstack took 0.7 ms a call,
    # which at 3 Jacobians per vertex was most of a run's time.
    pattern = sp.hstack([laplacian + sp.eye(N), np.ones((N, 2))], format="csc")
    pattern.sort_indices()
    indices, indptr = pattern.indices, pattern.indptr
    diagonal = np.array([indptr[j] + np.flatnonzero(indices[indptr[j]:indptr[j + 1]] == j)[0]
                         for j in range(N)])
    off_diagonal = pattern.data.copy()
    off_diagonal[diagonal] = 0.0

    def J(x):
        u, lam, eps = x[:N], x[N], x[N + 1]
        e = np.exp(u / (1 + eps * u))
        d_u = e / (1 + eps * u) ** 2
        d_eps = -e * u * u / (1 + eps * u) ** 2
        data = off_diagonal.copy()
        data[diagonal] = -2.0 + h * h * lam * d_u
        data[indptr[N]:indptr[N + 1]] = h * h * e
        data[indptr[N + 1]:] = h * h * lam * d_eps
        return sp.csc_matrix((data, indices, indptr), shape=(N, N + 2))

    catalogue = tessera.Problem.from_catalogue("bvp", points=N)  # for its start point
    box = [-np.inf, 20.0] * N + [0.5, 10.0, 0.0, 0.3]
    return tessera.Problem(n=N + 2, F=F, J=J, start=catalogue.start, box=box, step=0.1,
                           name="bvp_scipy", coordinate_names=catalogue.coordinate_names,
                           blocks=[("u", 0, N, np.sqrt(h))], euler_characteristic=1)


if __name__ == "__main__":
    problem = bratu_problem(50)
    mesh = tessera.mesh(problem, method="front", view="lambda,epsilon,max:u")
    print(mesh, "max |F| at the vertices:",
          max(np.abs(problem.F(x)).max() for x in mesh.vertices))
