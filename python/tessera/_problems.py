# SPDX-License-Identifier: MIT
"""tessera.Problem and tessera.Dynamics: the surfaces to mesh, written in Python, from the
catalogue or from problem files (docs/python.md, "Problems written in Python")."""
from __future__ import annotations

import math
import numbers
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _tessera

ArrayLike = Union[np.ndarray, Sequence[float]]
ProblemLike = Union["Problem", str, "os.PathLike[str]"]


def _finite_difference_jacobian(F: Callable[[np.ndarray], Any], n: int) -> Callable:
    # Central differences, h ~ eps^(1/3) relative: about 1e-10 accurate for smooth F.
    def J(x: np.ndarray) -> np.ndarray:
        columns = []
        for i in range(n):
            h = 6e-6 * (1.0 + abs(x[i]))
            forward = x.copy()
            backward = x.copy()
            forward[i] += h
            backward[i] -= h
            columns.append((np.atleast_1d(F(forward)) - np.atleast_1d(F(backward))) / (2 * h))
        return np.stack(columns, axis=1)

    return J


class Dynamics:
    """What a problem's equations are the right-hand side of: B·u' = sign·F(u, p).

    M is then the surface of steady states, and ``mesh(..., stability=True)`` says which are
    stable (every eigenvalue μ of sign·D_uF·v = μ·B·v with Re μ < 0)::

        tessera.Dynamics(parameters=("lambda", "mu"), sign=-1)

    parameters: the two coordinates p, by name or by index (0 … n-1); the state u is the other
        n-2 coordinates in their order, and equation i of F is row i of B.
    sign: 1 (B·u' = F as written) or -1 (B·u' = -F, e.g. F = ∇V of a potential V that the
        dynamics descend, as for Whitney's pleat).
    mass: B. None: the identity; n-2 numbers: its diagonal (each >= 0; 0 marks an algebraic
        equation); an (n-2, n-2) array or a scipy.sparse matrix: all of it.

    `Problem` takes one as ``dynamics=``, or a dict with the same keys; the shapes and names are
    checked against the problem there. ``Problem.dynamics`` is the problem's, for any problem
    (parameters as names).
    """

    def __init__(self, parameters: Sequence[Union[str, int]], sign: float = 1,
                 mass: Optional[Any] = None):
        if isinstance(parameters, str) or not hasattr(parameters, "__len__") or \
                len(parameters) != 2:
            raise ValueError(f"dynamics.parameters must be two coordinates (names or indices), "
                             f"got {parameters!r}")
        for parameter in parameters:
            if not isinstance(parameter, (str, numbers.Integral)) or isinstance(parameter, bool):
                raise ValueError(f"dynamics.parameters: {parameter!r} is neither a coordinate "
                                 f"name nor an index")
        if sign not in (1, -1):
            raise ValueError(f"dynamics.sign must be 1 or -1, got {sign!r}")
        self.parameters = tuple(parameters)
        self.sign = int(sign)
        self.mass = None if mass is None else (mass if _is_scipy_sparse(mass)
                                               else np.asarray(mass, dtype=float))

    @classmethod
    def _from(cls, value: Union["Dynamics", Mapping[str, Any]]) -> "Dynamics":
        if isinstance(value, Dynamics):
            return value
        if not isinstance(value, Mapping):
            raise TypeError(f"dynamics must be a tessera.Dynamics or a dict with the keys "
                            f"parameters, sign, mass; not {type(value).__name__}")
        unknown = [key for key in value if key not in ("parameters", "sign", "mass")]
        if unknown:
            raise ValueError(f"dynamics: unknown key {unknown[0]!r} (keys: parameters, sign, "
                             f"mass)")
        if "parameters" not in value:
            raise ValueError("dynamics: 'parameters' is required: the two coordinates that are "
                             "the dynamics' parameters")
        return cls(**value)

    def _core(self, n: int, names: Sequence[str]) -> Any:
        """The C++ dynamics of a problem in R^n with these coordinate names."""
        indices = []
        for parameter in self.parameters:
            if isinstance(parameter, str):
                if parameter not in names:
                    raise ValueError(f"dynamics.parameters: {parameter!r} is not a coordinate "
                                     f"(coordinates: {', '.join(names)})")
                index = list(names).index(parameter)
            else:
                index = int(parameter)
                if not 0 <= index < n:
                    raise ValueError(f"dynamics.parameters: index {index} is not a coordinate "
                                     f"index (0 … {n - 1})")
            if index in indices:
                raise ValueError(f"dynamics.parameters: coordinate {names[index]!r} is given "
                                 f"twice; the two parameters must differ")
            indices.append(index)
        core = _tessera.Dynamics()
        core.parameters = indices
        core.sign = float(self.sign)
        m = n - 2
        if self.mass is None:
            return core
        shape = tuple(self.mass.shape)
        if shape == (m,):
            diagonal = self.mass
            bad = [i for i in range(m) if not (math.isfinite(diagonal[i]) and diagonal[i] >= 0)]
            if bad:
                raise ValueError(f"dynamics.mass[{bad[0]}] = {diagonal[bad[0]]!r} must be a "
                                 f"finite number >= 0 (0: an algebraic equation)")
            core.mass_diagonal = diagonal
        elif shape == (m, m):
            import scipy.sparse

            matrix = scipy.sparse.csc_matrix(self.mass, dtype=float)
            if not np.isfinite(matrix.data).all():
                raise ValueError("dynamics.mass has entries that are not finite")
            core.mass_matrix = matrix
        else:
            raise ValueError(f"dynamics.mass has shape {shape}, expected ({m},) (the diagonal of "
                             f"B, one entry per equation) or ({m}, {m}) for n = {n}")
        return core

    @classmethod
    def _wrap(cls, core: Any, names: Sequence[str]) -> "Dynamics":
        mass = None
        if core.mass_diagonal.size:
            mass = core.mass_diagonal
        elif core.mass_matrix.shape[0]:
            mass = core.mass_matrix
        return cls((names[core.parameters[0]], names[core.parameters[1]]), int(core.sign), mass)

    def __repr__(self) -> str:
        if self.mass is None:
            mass = ""
        elif _is_scipy_sparse(self.mass) or self.mass.size > 8:  # large B: its shape only
            mass = f", mass=<{'sparse' if _is_scipy_sparse(self.mass) else 'array'} of shape " \
                   f"{self.mass.shape}>"
        else:
            mass = f", mass={self.mass!r}"
        return f"tessera.Dynamics(parameters={self.parameters!r}, sign={self.sign}{mass})"


class Problem:
    """An implicitly defined surface M = {x in R^n : F(x) = 0}, F: R^n -> R^(n-2).

    Written in Python::

        p = tessera.Problem(n=3, F=lambda x: [x @ x - 1], J=lambda x: [2 * x], start=[0, 0, 1])

    F(x) returns n-2 numbers (a number is fine for n = 3). J(x) returns DF(x) as an (n-2, n)
    array, or as a scipy.sparse matrix for large n: the solvers then use sparse LU and never
    form a dense matrix (``sparse`` says which form the solvers ask for; by default the form
    that J returns at ``start``). Without J, central finite differences (dense, n + 1 calls).
    x is a fresh float64 array on every call. F and J run with the GIL held, one call at a time;
    an exception they raise ends the run and is raised by `mesh`.

    ``step`` is the suggested edge length (the CLI's problem-file ``step``), ``box`` a list of
    lower, upper for each coordinate, ``blocks`` named coordinate ranges as (name, first, size[,
    weight]) tuples (docs/problem-files.md), ``euler_characteristic`` and ``area`` what is known
    of the component of M through ``start`` (used by `check`). ``dynamics`` says what F is the
    right-hand side of (a `Dynamics`, or a dict {"parameters": ("a", "b"), "sign": 1, "mass":
    ...}), which ``mesh(..., stability=True)`` needs.

    Catalogue entries and problem files: `Problem.from_catalogue`, `Problem.from_file`,
    `Problem.from_text`, `Problem.from_equations`.
    """

    def __init__(
        self,
        n: int,
        F: Callable[[np.ndarray], Any],
        J: Optional[Callable[[np.ndarray], Any]] = None,
        start: Optional[ArrayLike] = None,
        *,
        sparse: Optional[bool] = None,
        name: str = "python",
        coordinate_names: Optional[Sequence[str]] = None,
        blocks: Optional[Sequence[tuple]] = None,
        box: Optional[ArrayLike] = None,
        step: float = 0.1,
        euler_characteristic: Optional[int] = None,
        area: Optional[float] = None,
        dynamics: Optional[Union[Dynamics, Mapping[str, Any]]] = None,
    ):
        if start is None:
            raise ValueError("Problem: start is required (a point near M, n values)")
        start_array = np.asarray(start, dtype=float).ravel()
        if J is None:
            J = _finite_difference_jacobian(F, int(n))
            sparse = False
        names = list(coordinate_names or [])
        core_dynamics = None
        if dynamics is not None:
            core_dynamics = Dynamics._from(dynamics)._core(
                int(n), names or _tessera.default_coordinate_names(int(n)))
        if sparse is None:
            sparse = _is_scipy_sparse(J(start_array.copy()))
        self._core = _tessera.Problem.from_python(
            int(n), F, J, bool(sparse), name, names, list(blocks or []), start_array,
            _numbers(box), float(step), euler_characteristic, area, core_dynamics)

    @classmethod
    def _wrap(cls, core: Any) -> "Problem":
        problem = cls.__new__(cls)
        problem._core = core
        return problem

    @classmethod
    def from_catalogue(cls, name: str, **parameters: float) -> "Problem":
        """A catalogue entry (`problems()`), e.g. ``Problem.from_catalogue("torus", R=2)``;
        ``"torus:R=2"`` is the same."""
        specification = name
        if parameters:
            specification += ":" + ",".join(f"{key}={value!r}" for key, value in parameters.items())
        return cls._wrap(_tessera.Problem.resolve(specification))

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"], **parameters: float) -> "Problem":
        """A problem file (.tsr, docs/problem-files.md); keyword arguments replace the file's
        parameters by name."""
        return cls._wrap(_tessera.Problem.from_file(os.fspath(path), _parameters(parameters)))

    @classmethod
    def from_text(cls, text: str, source_name: str = "<text>", **parameters: float) -> "Problem":
        """Problem-file text (docs/problem-files.md); messages name ``source_name``."""
        return cls._wrap(_tessera.Problem.from_text(text, source_name, _parameters(parameters)))

    @classmethod
    def from_equations(
        cls,
        variables: Sequence[str],
        equations: Sequence[str],
        start: ArrayLike,
        *,
        parameters: Optional[Mapping[str, float]] = None,
        box: Optional[ArrayLike] = None,
        step: Optional[float] = None,
        name: str = "equations",
    ) -> "Problem":
        """Expression strings, compiled and differentiated exactly by tessera (no Python runs
        during the computation), e.g.
        ``Problem.from_equations("x y z", ["x^2 + y^2 + z^2 - 1"], [0, 0, 1])``."""
        if isinstance(variables, str):
            variables = variables.split()
        lines = [f"name {name}", "variables " + " ".join(variables)]
        lines += [f"parameter {key} = {value!r}" for key, value in (parameters or {}).items()]
        lines += [f"equation {equation}" for equation in equations]
        lines.append("start " + " ".join(repr(float(v)) for v in np.asarray(start).ravel()))
        if step is not None:
            lines.append(f"step {float(step)!r}")
        box_values = _numbers(box)
        for i in range(len(box_values) // 2):
            name_i = variables[i] if i < len(variables) else f"x{i}"
            lines.append(f"box {name_i} {box_values[2 * i]!r} {box_values[2 * i + 1]!r}")
        if len(box_values) % 2 or (box_values and len(box_values) != 2 * len(variables)):
            raise ValueError(f"box has {len(box_values)} values, expected {2 * len(variables)} "
                             f"(lower,upper for each of the {len(variables)} coordinates)")
        return cls.from_text("\n".join(lines) + "\n", f"<{name}>")

    @property
    def n(self) -> int:
        """The dimension of the ambient space."""
        return self._core.n

    @property
    def name(self) -> str:
        return self._core.name

    @property
    def coordinate_names(self) -> List[str]:
        return self._core.coordinate_names

    @property
    def start(self) -> np.ndarray:
        """The start point (n,) near M; `mesh` projects it onto M first."""
        return self._core.start

    @property
    def suggested_step(self) -> float:
        return self._core.suggested_step

    @property
    def description(self) -> str:
        return self._core.description

    @property
    def expected_euler_characteristic(self) -> Optional[int]:
        return self._core.expected_euler_characteristic

    @property
    def exact_area(self) -> Optional[float]:
        return self._core.exact_area

    @property
    def has_sparse_jacobian(self) -> bool:
        return self._core.has_sparse_jacobian

    @property
    def dynamics(self) -> Optional[Dynamics]:
        """The dynamics F is the right-hand side of (parameters by name), None if it declares
        none: a Python problem's ``dynamics=``, a problem file's ``dynamics`` line, a catalogue
        problem's own."""
        core = self._core.dynamics
        return None if core is None else Dynamics._wrap(core, self.coordinate_names)

    def F(self, x: ArrayLike) -> np.ndarray:
        """F(x), (n-2,), evaluated by tessera (for any problem, catalogue ones too)."""
        return self._core.F(np.asarray(x, dtype=float))

    def J(self, x: ArrayLike) -> np.ndarray:
        """DF(x) as a dense (n-2, n) array."""
        return self._core.J(np.asarray(x, dtype=float))

    def __repr__(self) -> str:
        return f"tessera.Problem({self._core.argument!r}, n={self.n})"


def _is_scipy_sparse(value: Any) -> bool:
    return hasattr(value, "tocsc") and hasattr(value, "nnz")


def _numbers(values: Optional[ArrayLike]) -> List[float]:
    if values is None:
        return []
    if isinstance(values, str):
        raise ValueError(f"expected numbers, got the string {values!r}")
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def _parameters(parameters: Mapping[str, float]) -> Dict[str, float]:
    return {str(key): float(value) for key, value in parameters.items()}


def _problem(problem: ProblemLike) -> Problem:
    if isinstance(problem, Problem):
        return problem
    if isinstance(problem, (str, os.PathLike)):
        return Problem._wrap(_tessera.Problem.resolve(os.fspath(problem)))
    raise TypeError(f"problem must be a tessera.Problem, a catalogue name or a problem file, "
                    f"not {type(problem).__name__}")
