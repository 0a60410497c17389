# SPDX-License-Identifier: MIT
"""tessera: triangulations of implicitly defined surfaces M = {x in R^n : F(x) = 0}.

The Python face of the tessera library and CLI (docs/python.md). Every command of the CLI is a
function here with the same options (``--max-vertices`` is ``max_vertices=``) and defaults:

>>> import tessera
>>> m = tessera.mesh("torus", tolerance=1e-3)          # catalogue name or .tsr problem file
>>> m.vertices.shape[1], m.triangles.shape[1]          # (N, n) float64 and (T, 3) int32 views
(3, 3)
>>> m.summary["run"]["termination"]                    # the JSON summary of `tessera mesh`
'completed'

Problems may be written in Python, with dense NumPy or scipy.sparse Jacobians (`Problem`).
Errors: ValueError for bad input (the CLI's message), `ComputationFailed` for a run that did not
succeed, `Interrupted` (a KeyboardInterrupt) for Ctrl-C; both carry the valid partial mesh.
"""
from __future__ import annotations

import json
import math
import os
import warnings
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

# First: under another interpreter, says which one the compiled module was built for.
from . import _interpreter_check  # noqa: F401
import numpy as np

from . import _tessera
from . import _checkpoints
from ._checkpoints import extend, resume  # noqa: F401
from ._meshes import Mesh, from_meshio, read  # noqa: F401 (the package's)
from ._problems import ArrayLike, Dynamics, Problem, ProblemLike, _numbers, _problem

# The classes are the package's: their repr and help say tessera.Problem, not the submodule.
for _class in (Dynamics, Problem, Mesh):
    _class.__module__ = __name__

__all__ = [
    "ComputationFailed",
    "Dynamics",
    "Interrupted",
    "Mesh",
    "Problem",
    "check",
    "compare",
    "ddt",
    "improve",
    "mesh",
    "methods",
    "problems",
    "read",
    "from_meshio",
    "resume",
    "extend",
]
__version__ = "0.1.0"


class ComputationFailed(RuntimeError):
    """A computation could not do what was asked (exit status 1 of the CLI).

    ``mesh`` is the valid partial mesh (possibly empty) that the CLI would have written, and
    ``termination`` the method's reason ("vertex limit reached", "front collision", ...).
    """

    def __init__(self, message: str, mesh: Optional["Mesh"] = None):
        super().__init__(message)
        self.mesh = mesh
        self.termination = mesh.termination if mesh is not None else None


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) stopped a run. A KeyboardInterrupt, so that an unhandled one ends a
    script as usual; ``mesh`` is the valid partial mesh made until then."""

    def __init__(self, message: str, mesh: Optional["Mesh"] = None):
        super().__init__(message)
        self.mesh = mesh


def _raise_interrupted(error: Interrupted, count: int) -> None:
    # A second Ctrl-C during the run (which after the first only finishes what keeps the partial
    # mesh valid) is not dropped: it follows `error` as a KeyboardInterrupt, raised where Python
    # next checks for signals, i.e. in the code handling `error`.
    if count > 1:
        _tessera.raise_with_pending_interrupt(error)
    raise error


# ---------------------------------------------------------------------------------------------
# Commands


def _finite_positive(name: str, value: Optional[float]) -> float:
    if value is None:
        return 0.0
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name}: '{value}' is not a finite number > 0")
    return value


def _in_range(name: str, value: Optional[float], low: float, high: float, cast: type = float):
    if value is None:
        return cast(0)
    if not (low <= value <= high):
        raise ValueError(f"{name}: value {value} not in range {low} to {high}")
    return cast(value)


def _member(name: str, value: str, allowed: Sequence[str]) -> str:
    if value not in allowed:
        raise ValueError(f"{name}: {value!r} not in {{{', '.join(allowed)}}}")
    return value


def _set_box(request, box) -> None:
    """A list sets lower, upper for every coordinate; a dict {name: (lower, upper)} bounds the
    named coordinates only (``--box name=lower:upper,...``; None leaves a side unbounded)."""
    if isinstance(box, dict):
        def side(value):
            return "" if value is None else repr(float(value))
        items = []
        for name, bounds in box.items():
            if not isinstance(bounds, (tuple, list)) or len(bounds) != 2:
                raise ValueError(f"box[{name!r}] must be (lower, upper), got {bounds!r}")
            items.append(f"{name}={side(bounds[0])}:{side(bounds[1])}")
        request.named_box = ",".join(items)
    else:
        request.box = _numbers(box)


def _progress(progress: Any) -> Any:
    """mesh(progress=...) as the compiled module takes it: a callable, "auto", "always" or None."""
    if progress is None:
        return "auto"
    if isinstance(progress, bool):
        return "always" if progress else None
    if not callable(progress):
        raise TypeError(f"progress must be a callable, True, False or None, not "
                        f"{type(progress).__name__}")
    return progress


def mesh(
    problem: ProblemLike,
    *,
    method: Optional[str] = None,
    step: Optional[float] = None,
    tolerance: Optional[float] = None,
    placement: str = "auto",
    start: Optional[ArrayLike] = None,
    box: Optional[Union[ArrayLike, Dict[str, Any]]] = None,
    components: str = "start",
    component_seeds: Optional[int] = None,
    improve: bool = False,
    view: Optional[str] = None,
    folds: Optional[str] = None,
    stability: bool = False,
    eigenvalues: int = 6,
    hopf: bool = False,
    level: Optional[str] = None,
    diagram: Optional[Union[str, "os.PathLike[str]"]] = None,
    report_samples: Optional[int] = None,
    max_vertices: int = 2_000_000,
    max_start_distance: Optional[float] = None,
    min_gap_angle: Optional[float] = None,
    max_valence: Optional[int] = None,
    order: str = "gap",
    max_step: Optional[float] = None,
    edge_length_factor: Optional[float] = None,
    min_tangent_cosine: Optional[float] = None,
    refine: Optional[int] = None,
    progress: Union[None, bool, Callable[[Dict[str, Any]], None]] = None,
    allow_partial: bool = False,
    handle_interrupt: bool = True,
    threads: Optional[int] = None,
    chart_tolerance: Optional[float] = None,
    checkpoint: Optional[Union[str, "os.PathLike[str]"]] = None,
    checkpoint_every: float = 300.0,
    _continue: Optional[tuple] = None,
) -> Mesh:
    """Covers a problem's surface with a triangle mesh: ``tessera mesh``.

    problem: a `Problem`, a catalogue name (``"torus"``, ``"torus:R=2"``) or a .tsr file.
    method: "atlas" (default), "front" or "bezier" (`methods()`).
    step: front: edge length h (default: the problem's suggestion); atlas: largest chart radius
        (default 2h); bezier: initial step.
    tolerance: bound on the distance of every point of every triangle to M, enforced by
        bisection on M (atlas: also sizes the charts, default step/50; bezier: also limits
        the steps; front and bezier: no bound by default).
    placement: atlas: "auto" (default: "hexagonal" where DF is dense and the domain unbounded,
        "disk" otherwise), "disk" (Henderson's) or "hexagonal" (about 30 % fewer vertices).
    start: start point (n values); box: lower, upper for each coordinate, or a dict of bounds
        on named coordinates, e.g. {"lambda": (5, 20), "epsilon": (0.15, None)}. Several start
        points, one per row (a list of lists or a 2-D array), cover the component of each
        (``--start`` given more than once); ``summary["run"]["starts"]`` says which component
        each reached.
    components: "start" (default): the components of the start points; "all": also search
        the bounded region (box or the problem's domain) for every other component with
        seeds projected onto M (``--components all``, docs/components.md). The components
        are in ``summary["run"]["components"]``.
    component_seeds: the number of seeds of that search (default 512).
    improve: edge swaps and tangential smoothing on M afterwards (``--improve``).
    view: the view written by `Mesh.write` and reported (``--view``).
    folds: the parameter plane of the fold curves, e.g. "lambda,epsilon" (``--folds``,
        docs/algorithms/folds.md): `Mesh.fold_curves` holds them, ``summary["folds"]`` the rest.
    stability: the eigenvalues of the problem's dynamics (`Problem.dynamics`) at every vertex
        (``--stability``): `Mesh.unstable_count`, `Mesh.leading_real_part`,
        `Mesh.stability_certain`, `Mesh.eigenvalues`, ``summary["stability"]``; `Mesh.write`
        writes the first three as point data.
    eigenvalues: sparse problems: how many eigenvalues nearest 0 per vertex (``--eigenvalues``).
    hopf: the Hopf curves, Bogdanov-Takens points and neutral saddle curves (``--hopf``; implies
        stability): `Mesh.hopf_curves`, `Mesh.special_points`, `Mesh.neutral_saddle_curves`,
        ``summary["hopf"]``.
    level: the level curves of one functional, e.g. "x1=0.5" (``--level``): `Mesh.level_curves`,
        ``summary["level"]``.
    diagram: draw the two-parameter bifurcation diagram to this .png or .svg (``--diagram``;
        implies hopf, and folds over the dynamics' parameters unless folds is given).
    report_samples: distances in the summary measured at this many points of each kind (0: all;
        default all for n < 500, else 300 within a tenth of the run's time or 10 s if longer).
    max_vertices, max_start_distance: stop after this many vertices; how far the start may be
        from M (default 10 steps).
    min_gap_angle, max_valence, order: front method's α_min (default 45.8), most triangles per
        vertex (default 7), "gap" or "fifo".
    max_step, edge_length_factor, min_tangent_cosine, refine: bezier method's options (refine K:
        the cubic surface on a K×K subdivision of every triangle; `Mesh.write_patches`).
    progress: None (default): progress on sys.stderr as ``tessera mesh`` shows it, a status
        line when stderr is a terminal; elsewhere (a notebook, a log) a line per stage and one
        every 10 s once the run has lasted 5 s, so short runs print nothing. True: the same
        from the start; False: nothing. A callable instead receives each record, a dict
        {"stage": "build" | "clip" | "refine" | "validate" | "patches" | "report" | "analyses",
        "vertex_count", "triangle_count", "front_size", "seconds"}: during the build every
        1000 vertices (atlas: charts) or every second, whichever comes first, then once as each
        later stage begins (docs/python.md, "Progress"); an exception it raises stops the run
        and is raised.
    allow_partial: return the mesh of a run that stopped early instead of raising.
    threads: threads of the data-parallel steps (``--threads``; default: TESSERA_THREADS,
        OMP_NUM_THREADS or every core). A Python problem runs on one thread whatever this says
        (each evaluation takes the GIL); the mesh does not depend on it (docs/threads.md).
    handle_interrupt: Ctrl-C stops the run (from the main thread, while Python's SIGINT handler
        is the default one) and raises `Interrupted` carrying the valid partial mesh.
    chart_tolerance: atlas: size the charts for this tolerance (>= tolerance) and reach
        ``tolerance`` by refinement alone (``--chart-tolerance``; what `extend` does).
    checkpoint, checkpoint_every: atlas: save the build's state to this .tsc file every
        ``checkpoint_every`` seconds (default 300), at a stop (Ctrl-C) and when the build ends;
        `resume` continues it to the same mesh, `extend` grows it (docs/checkpoints.md).

    Returns a `Mesh` whose ``summary`` is the JSON summary of ``tessera mesh --summary``.
    Raises ValueError for bad input (before any computation), `ComputationFailed` (with
    ``.mesh``, the valid partial mesh) when the method stops early or the mesh is not valid,
    `Interrupted` on Ctrl-C; an exception raised by a Python problem's F or J as it is.
    The GIL is released while C++ works (Python problems take it for each evaluation).
    """
    arguments = dict(locals())  # (first: the call's arguments, for the checkpoint's record)
    chosen = _problem(problem)
    request = _tessera.MeshRequest()
    if method is not None:
        request.method = _member("method", method, _tessera.method_names())
    request.step = _finite_positive("step", step)
    request.tolerance = _finite_positive("tolerance", tolerance)
    request.placement = _member("placement", placement, ["auto", "disk", "hexagonal"])
    if start is not None and not isinstance(start, str) and np.ndim(start) == 2:
        # Several start points, one per row (``--start`` given more than once).
        rows = [_numbers(row) for row in np.asarray(start, dtype=float)]
        if not rows:
            raise ValueError("start: no start point in the list")
        request.start = rows[0]
        request.more_starts = rows[1:]
    else:
        request.start = _numbers(start)
    request.components = _member("components", components, ["start", "all"])
    if component_seeds is not None:
        request.component_seeds = _in_range("component_seeds", component_seeds, 1, 10_000_000, int)
    _set_box(request, box)
    request.improve = bool(improve)
    request.view = view or ""
    request.folds = folds or ""
    request.stability = bool(stability)
    request.eigenvalues = _in_range("eigenvalues", eigenvalues, 1, 10_000, int)
    request.hopf = bool(hopf)
    request.level = level or ""
    request.diagram = os.fspath(diagram) if diagram is not None else ""
    request.report_samples = (-1 if report_samples is None else
                              _in_range("report_samples", report_samples, 0, 100_000_000, int))
    request.max_vertices = _in_range("max_vertices", max_vertices, 7, 100_000_000, int)
    request.max_start_distance = _finite_positive("max_start_distance", max_start_distance)
    request.min_gap_angle = _in_range("min_gap_angle", min_gap_angle, 1.0, 89.0)
    request.max_valence = _in_range("max_valence", max_valence, 6, 12, int)
    request.order = _member("order", order, ["gap", "fifo"])
    request.max_step = _finite_positive("max_step", max_step)
    request.edge_length_factor = _in_range("edge_length_factor", edge_length_factor, 0.1, 3.0)
    request.min_tangent_cosine = _in_range("min_tangent_cosine", min_tangent_cosine, 0.01, 0.999)
    request.refine = _in_range("refine", refine, 1, 64, int)
    request.threads = _in_range("threads", threads, 1, 100_000, int)
    request.chart_tolerance = _finite_positive("chart_tolerance", chart_tolerance)
    if checkpoint is not None:
        request.checkpoint = os.fspath(checkpoint)
        request.checkpoint_every = _finite_positive("checkpoint_every", checkpoint_every)
        request.checkpoint_record = _checkpoints.record(problem, chosen, arguments)
    if _continue is not None:
        request.resume_state, request.extend = _continue
    core = _tessera.mesh(chosen._core, request, _progress(progress), bool(handle_interrupt))
    result = Mesh._wrap(core)
    if core.interrupted:
        _raise_interrupted(
            Interrupted(f"interrupted; the partial mesh has {result.vertex_count} vertices and "
                        f"{result.triangle_count} triangles (.mesh)", result),
            core.interrupt_count)
    if core.failure and not allow_partial:
        raise ComputationFailed(core.failure, result)
    if core.note:
        warnings.warn(core.note, stacklevel=2)
    return result


def check(mesh: Mesh, problem: Optional[ProblemLike] = None, *,
          report_samples: Optional[int] = None) -> Dict[str, Any]:
    """Validates a mesh against M and measures it: ``tessera check --json``.

    Returns the report (docs/summary-json.md) with two more keys: "passes" (valid, the known
    Euler characteristic if any, vertices within 1e-6 of M) and "failures" (the CLI's reasons).
    The problem defaults to the one the mesh was made for.
    """
    if problem is None:
        problem = mesh.problem
        if problem is None:
            raise ValueError("check: this mesh was not made by tessera.mesh; give the problem")
    chosen = _problem(problem)
    samples = -1 if report_samples is None else _in_range("report_samples", report_samples, 0,
                                                          100_000_000, int)
    report_json, failures = _tessera.check(mesh._core, chosen._core, samples)
    report = json.loads(report_json)
    report["passes"] = not failures
    report["failures"] = failures
    return report


def improve(mesh: Mesh, problem: Optional[ProblemLike] = None, *, criterion: str = "angle",
            max_sweeps: int = 50, smooth: int = 0) -> Mesh:
    """Improves a mesh of M by edge swaps judged in M's tangent planes: ``tessera improve``.

    criterion: "angle" (max-min angle, default), "normal" or "distance"; max_sweeps: most
    sweeps over the edges; smooth: passes of tangential smoothing (0: vertices do not move).
    Returns a new Mesh whose summary is the CLI's --summary JSON (swaps, before, after).
    Raises `ComputationFailed` (with ``.mesh``) if the improved mesh is not valid.
    """
    if problem is None:
        problem = mesh.problem
        if problem is None:
            raise ValueError("improve: this mesh was not made by tessera.mesh; give the problem")
    chosen = _problem(problem)
    _member("criterion", criterion, ["angle", "normal", "distance"])
    max_sweeps = _in_range("max_sweeps", max_sweeps, 1, 100_000, int)
    smooth = _in_range("smooth", smooth, 0, 1000, int)
    core = _tessera.improve(mesh._core, chosen._core, criterion, max_sweeps, smooth)
    result = Mesh._wrap(core)
    if core.failure:
        raise ComputationFailed(core.failure, result)
    return result


def ddt(points: ArrayLike, values: Optional[ArrayLike] = None, *, function: Optional[str] = None,
        criterion: str = "abn", norm: str = "l2", test: str = "global", grid: int = 33,
        sweep_order_seed: int = 0, all_criteria: bool = False, orders: int = 1,
        compare_report: Optional[int] = None) -> Union[Mesh, Dict[str, Mesh]]:
    """Data-dependent triangulation of scattered data in the plane (Malcolm): ``tessera ddt``.

    points (N, 2); values (N,) or function "F1", "F2", "F7", "F8", "F9" (Franke's, sampled at
    the points; the summary then has the interpolation error on a grid×grid grid of [0,1]²).
    criterion: delaunay, mwt, maxmin3d, mwt3d, abn (default), jnd, pf, pd or equid; norm: l1,
    l2 (default) or lex; test: local or global (default).
    Returns a Mesh in R^3 (x, y, value), as the CLI writes it, with the summary.

    all_criteria (``--all-criteria``): instead one triangulation per row of the CLI's table
    (delaunay, mwt3d, abn, jnd, pf and pd with l1 and l2, and equid when a function is given),
    returned as a dict from the row's label (``summary["criterion"]``, e.g. "ABN-1 global") to
    its Mesh, in the table's order; criterion, norm and sweep_order_seed do not apply then.
    With a function: orders (``--orders K``, default 1) also triangulates each row in K sweep
    orders (index order, then random permutations) and puts the spread of the mean error into
    summary["orders"] ({"count", "lowest_mean", "highest_mean"}); compare_report
    (``--compare-report 33|100``) puts Malcolm's Table 1 (33 points) or 2 (100 points) value
    into summary["report"] ({"table", "mean"}, and "in_spread" when orders > 1).
    """
    xy = np.asarray(points, dtype=float)
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise ValueError(f"ddt: points must be an (N, 2) array, got shape {xy.shape}")
    _member("norm", norm, ["l1", "l2", "lex"])
    _member("test", test, ["local", "global"])
    grid = _in_range("grid", grid, 2, 10000, int)
    orders = _in_range("orders", orders, 1, 1000, int)
    report = 0
    if compare_report is not None:
        if compare_report not in (33, 100):
            raise ValueError(f"compare_report: {compare_report!r} not in {{33, 100}}")
        report = int(compare_report)
    # Options the CLI would ignore are refused, as `mesh` refuses another method's options.
    if not all_criteria and (orders != 1 or report):
        raise ValueError("orders and compare_report: only with all_criteria=True")
    if all_criteria and (orders != 1 or report) and not function:
        raise ValueError("orders and compare_report compare interpolation errors: they need "
                         "function (F1, F2, F7, F8 or F9)")
    if all_criteria and (criterion != "abn" or norm != "l2" or sweep_order_seed != 0):
        raise ValueError("criterion, norm and sweep_order_seed: not with all_criteria=True "
                         "(every criterion of the table is run)")
    data = None if values is None else np.asarray(values, dtype=float).ravel()
    if all_criteria:
        cores = _tessera.ddt_all_criteria(xy.T, data, function or "", test, grid, orders, report)
        meshes = [Mesh._wrap(core) for core in cores]
        return {mesh.summary["criterion"]: mesh for mesh in meshes}
    core = _tessera.ddt(xy.T, data, function or "", criterion, norm, test, grid,
                        int(sweep_order_seed))
    return Mesh._wrap(core)


def compare(
    problem: ProblemLike,
    *,
    step: Optional[float] = None,
    tolerance: Optional[float] = None,
    placement: str = "auto",
    start: Optional[ArrayLike] = None,
    box: Optional[Union[ArrayLike, Dict[str, Any]]] = None,
    max_vertices: int = 2_000_000,
    handle_interrupt: bool = True,
) -> Dict[str, Any]:
    """Every covering method on one problem, side by side: ``tessera compare``.

    The options are compare's (and mean what they mean for `mesh`): step, tolerance (one for
    every method, so that the rows compare; default the atlas's step/50), placement (atlas: "auto", "disk" or "hexagonal"), start,
    box, max_vertices. Returns the CLI's table as a dict::

        {"problem": "torus", "expected_euler_characteristic": 0, "passes": True,
         "methods": [{"method": "atlas", "vertex_count": ..., "triangle_count": ...,
                      "wall_seconds": ..., "max_distance": ..., "tolerance": ...,
                      "min_angle_degrees": ..., "euler_characteristic": ..., "valid": ...,
                      "termination": "completed", "completed": True, "message": "",
                      "passes": True}, ...]}

    one entry per method in `methods()`'s order. "max_distance" is the larger of the centroid
    and edge-midpoint distances to M, measured independently of the method; "tolerance" (also
    at the top level) is the bound every method was run to; "passes" is False where the CLI's exit status would be 1 (a
    method stopped early or its mesh is not valid): a failing method is a row, not an
    exception. Raises ValueError for bad input and `Interrupted` (``.report`` holds the table,
    the rows after Ctrl-C say "interrupted") on Ctrl-C.
    """
    chosen = _problem(problem)
    request = _tessera.MeshRequest()
    request.step = _finite_positive("step", step)
    request.tolerance = _finite_positive("tolerance", tolerance)
    request.placement = _member("placement", placement, ["auto", "disk", "hexagonal"])
    request.start = _numbers(start)
    _set_box(request, box)
    request.max_vertices = _in_range("max_vertices", max_vertices, 7, 100_000_000, int)
    report_json, interrupt_count = _tessera.compare(chosen._core, request,
                                                    bool(handle_interrupt))
    report = json.loads(report_json)
    if interrupt_count:
        error = Interrupted("interrupted; the comparison is in .report (the rows of the "
                            "methods stopped say \"interrupted\")")
        error.report = report
        _raise_interrupted(error, interrupt_count)
    return report


def problems() -> List[Dict[str, Any]]:
    """The catalogue (``tessera problems``): name, summary and parameters with defaults."""
    return _tessera.catalogue()


def methods() -> List[str]:
    """The covering methods, the default first."""
    return _tessera.method_names()
