# SPDX-License-Identifier: MIT
# Shared fixtures: the problems the tests mesh, and the paths of the repository and the CLI.
import pathlib
import shutil

import numpy as np
import pytest

import tessera

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def sphere() -> tessera.Problem:
    """The unit sphere written in NumPy: F = |x|² − 1, J = 2xᵀ."""
    return tessera.Problem(n=3, F=lambda x: [x @ x - 1.0], J=lambda x: [2.0 * x],
                           start=[0.1, 0.2, 1.1], step=0.3, name="python_sphere",
                           euler_characteristic=2, area=4 * np.pi)


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The tessera CLI of the build whose module is imported (build/python/tessera/..)."""
    candidate = pathlib.Path(tessera.__file__).resolve().parents[2] / "tessera"
    if not candidate.exists():
        found = shutil.which("tessera")
        if found is None:
            pytest.skip("no tessera CLI beside the module or on PATH")
        candidate = pathlib.Path(found)
    return candidate
