# SPDX-License-Identifier: MIT
"""tessera.Mesh: a triangle mesh in R^n with its summary, views of its arrays and its files
(docs/python.md, "Meshes")."""
from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _tessera
from ._problems import ArrayLike, Problem


class Mesh:
    """A triangle mesh with vertices in R^n, and what was learnt making it.

    ``vertices`` (N, n) float64 and ``triangles`` (T, 3) int32 are read-only NumPy views of the
    C++ storage (no copy; they keep the mesh alive); ``np.array(m.vertices)`` copies. A Mesh
    never changes: `improve` returns a new one.
    """

    def __init__(self, vertices: ArrayLike, triangles: ArrayLike):
        """A mesh from arrays (copied once): vertices (N, n), triangles (T, 3) indices."""
        self._core = _tessera.Mesh.from_arrays(np.asarray(vertices), np.asarray(triangles))
        self._summary: Optional[Dict[str, Any]] = None

    @classmethod
    def _wrap(cls, core: Any) -> "Mesh":
        mesh = cls.__new__(cls)
        mesh._core = core
        mesh._summary = None
        return mesh

    @property
    def vertices(self) -> np.ndarray:
        """(N, n) float64, row j is vertex j; a read-only view of the C++ storage."""
        return self._core.vertices

    @property
    def triangles(self) -> np.ndarray:
        """(T, 3) int32 vertex indices, oriented; a read-only view of the C++ storage."""
        return self._core.triangles

    @property
    def summary(self) -> Dict[str, Any]:
        """The summary as a dict: for `mesh`, the JSON of ``tessera mesh --summary``
        (docs/summary-json.md); for `improve` and `ddt`, their CLI summaries; {} otherwise."""
        if self._summary is None:
            self._summary = json.loads(self._core.summary_json)
        return self._summary

    @property
    def fold_curves(self) -> List[np.ndarray]:
        """The fold curves of ``mesh(..., folds="P,Q")``: one (m, k) array per curve, its points
        in order in the mesh's view (``summary["folds"]["columns"]``); cusps and counts are in
        ``summary["folds"]``. Empty without ``folds``."""
        folds = self.summary.get("folds")
        if folds is None:
            return []
        return [np.asarray(curve["points"], dtype=float) for curve in folds["curves"]]

    @property
    def unstable_count(self) -> Optional[np.ndarray]:
        """mesh(..., stability=True): (N,) int32, the unstable eigenvalues at each vertex (0:
        stable, -1: the eigenvalues failed there, see ``summary["stability"]["failures"]``);
        None without stability."""
        return self._core.unstable_count if self._core.has_stability else None

    @property
    def leading_real_part(self) -> Optional[np.ndarray]:
        """mesh(..., stability=True): (N,) float64, the largest real part among each vertex's
        computed eigenvalues (NaN where they failed); None without stability."""
        return self._core.leading_real_part if self._core.has_stability else None

    @property
    def stability_certain(self) -> Optional[np.ndarray]:
        """mesh(..., stability=True): (N,) bool, whether ``unstable_count`` counts every
        eigenvalue (dense problems, symmetric sparse ones) or only the computed ones; None
        without stability."""
        return self._core.stability_certain if self._core.has_stability else None

    @property
    def eigenvalues(self) -> Optional[List[np.ndarray]]:
        """mesh(..., stability=True): per vertex, its computed eigenvalues (complex128, by
        decreasing real part; all of them for dense problems, ``eigenvalues`` nearest 0 for
        sparse ones); None without stability."""
        return self._core.eigenvalues if self._core.has_stability else None

    @property
    def hopf_curves(self) -> List[np.ndarray]:
        """mesh(..., hopf=True): one (m, k) array per Hopf curve, its points in order, in the
        columns ``summary["hopf"]["columns"]``: the mesh's view, the dynamics' parameters not in
        it, then omega (the imaginary part of the crossing pair ±iω) and l1 (the first Lyapunov
        coefficient: < 0 supercritical, > 0 subcritical; NaN for sparse problems). Empty without
        hopf."""
        return self._curves("hopf", "curves")

    @property
    def neutral_saddle_curves(self) -> List[np.ndarray]:
        """mesh(..., hopf=True): the neutral saddle curves (a real pair ±κ), as `hopf_curves`,
        with κ in the omega column."""
        return self._curves("hopf", "neutral_saddle_curves")

    @property
    def special_points(self) -> List[Dict[str, Any]]:
        """mesh(..., hopf=True): the Bogdanov-Takens, fold-Hopf and Bautin points, as dicts
        {"kind": "bogdanov_takens" | "zero_hopf" | "bautin", "point": {column: value},
        "plane": {p1: value, p2: value}}."""
        hopf = self.summary.get("hopf")
        return [] if hopf is None else hopf["special_points"]

    @property
    def level_curves(self) -> List[np.ndarray]:
        """mesh(..., level="F=V"): one (m, k) array per level curve, in the mesh's view
        (``summary["level"]["columns"]``). Empty without level."""
        return self._curves("level", "curves")

    def _curves(self, section: str, key: str) -> List[np.ndarray]:
        found = self.summary.get(section)
        if found is None:
            return []
        return [np.asarray(curve["points"], dtype=float) for curve in found[key]]

    @property
    def termination(self) -> str:
        """"completed", or why the run stopped early ("interrupted", "vertex limit reached"...)."""
        return self._core.termination

    @property
    def is_complete(self) -> bool:
        return not self._core.failure and not self._core.interrupted

    @property
    def problem(self) -> Optional[Problem]:
        core = self._core.problem
        return None if core is None else Problem._wrap(core)

    @property
    def vertex_count(self) -> int:
        return self.vertices.shape[0]

    @property
    def triangle_count(self) -> int:
        return self.triangles.shape[0]

    def write(self, path: Union[str, "os.PathLike[str]"], *, ascii: bool = False,
              view: Optional[str] = None) -> None:
        """Writes the mesh as ``tessera mesh -o`` does: .ply (binary unless ``ascii``), .obj,
        .vtk, .vtu, or .npy (the states of ``--states``: every coordinate, with the triangles
        in FILE.triangles.npy). ``view`` as ``--view`` (e.g. "lambda,epsilon,max:u"); default
        the problem file's view, else every coordinate (a summary for n > 50)."""
        self._core.write(os.fspath(path), ascii, view or "")

    def write_patches(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """The Bézier control points of method "bezier" (``--patches``, docs/bezier-patches.md)."""
        self._core.write_patches(os.fspath(path))

    def to_meshio(self) -> Any:
        """A meshio.Mesh with the vertices and a "triangle" cell block (copies)."""
        import meshio

        return meshio.Mesh(np.array(self.vertices), [("triangle", np.array(self.triangles))])

    def __repr__(self) -> str:
        n = self.vertices.shape[1]
        return (f"<tessera.Mesh {self.vertex_count} vertices in R^{n}, {self.triangle_count} "
                f"triangles, {self.termination}>")


def from_meshio(mesh: Any) -> Mesh:
    """A Mesh of the points and the triangle cells of a meshio.Mesh."""
    blocks = [block.data for block in mesh.cells if block.type == "triangle"]
    if not blocks:
        raise ValueError("the meshio mesh has no triangle cells")
    return Mesh(mesh.points, np.concatenate(blocks))


def read(path: Union[str, "os.PathLike[str]"]) -> Mesh:
    """Reads a mesh file tessera writes (.ply, .obj, .vtk, .vtu, or the .npy states)."""
    return Mesh._wrap(_tessera.Mesh.read(os.fspath(path)))
