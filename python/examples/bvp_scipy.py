# SPDX-License-Identifier: MIT
"""The catalogue's `bvp` (Arrhenius-Bratu boundary value problem) written in NumPy/SciPy:
u'' + λ exp(u/(1 + εu)) = 0 on (0, 1), u(0) = u(1) = 0, on N interior grid points; the
unknowns are x = (u_1 … u_N, λ, ε), n = N + 2, and the Jacobian is a scipy.sparse matrix."""
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

    def J(x):
        u, lam, eps = x[:N], x[N], x[N + 1]
        e = np.exp(u / (1 + eps * u))
        d_u = e / (1 + eps * u) ** 2
        d_eps = -e * u * u / (1 + eps * u) ** 2
        return sp.hstack([laplacian + sp.diags(h * h * lam * d_u),
                          sp.csc_matrix((h * h * e)[:, None]),
                          sp.csc_matrix((h * h * lam * d_eps)[:, None])], format="csc")

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
