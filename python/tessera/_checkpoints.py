# SPDX-License-Identifier: MIT
"""Checkpoints from Python: the record of a ``mesh(checkpoint=...)`` call, and `resume` and
`extend`, which continue it (docs/checkpoints.md, "From Python").

A checkpoint written by `mesh` holds, besides the atlas's state, a JSON record of the call:
the problem as it was named (a catalogue name or a problem file; a `Problem` written in Python
is recorded by its name only and must be given again) and every argument that decides the
run. `resume` and `extend` call `mesh` again with them; the atlas's state carries a
fingerprint of the problem (F at two points, bit for bit), its start, domain and options, so a
different problem is refused, naming what differs.
"""
from __future__ import annotations

import json
import os
from typing import Any, Dict, Optional, Union

import numpy as np

from . import _tessera

_RECORD_VERSION = 1
# mesh()'s arguments that do not decide the run (each call gives its own) or are the record's.
_NOT_RECORDED = ("problem", "progress", "allow_partial", "handle_interrupt", "threads",
                 "checkpoint", "checkpoint_every", "_continue")


def _plain(value: Any) -> Any:
    """A JSON value for an argument: arrays and tuples as lists, paths as strings."""
    if isinstance(value, dict):
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(item) for item in value]
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, np.generic):
        return value.item()
    return value


def record(problem: Any, chosen: Any, arguments: Dict[str, Any]) -> str:
    """The "python" section of a checkpoint for ``mesh(problem, **arguments)``."""
    if isinstance(problem, (str, os.PathLike)):
        specification = os.fspath(problem)
        file = specification.split(":", 1)[0]
        for candidate in (specification, file):
            if os.path.isfile(candidate):
                # Absolute, so that resume() from another folder finds the same file.
                specification = os.path.abspath(candidate) + specification[len(candidate):]
                break
        named = {"specification": specification}
    else:
        named = {"python_problem": str(getattr(chosen, "name", "python"))}
    recorded = {key: _plain(value) for key, value in arguments.items()
                if key not in _NOT_RECORDED}
    return json.dumps({"version": _RECORD_VERSION, "problem": named, "arguments": recorded,
                       "checkpoint_every": float(arguments["checkpoint_every"])})


def _load(path: Union[str, "os.PathLike[str]"], problem: Any):
    """The checkpoint's path, its method's state, its record and the problem to continue it
    with."""
    path = os.fspath(path)
    sections = _tessera.read_checkpoint(path)
    if "python" not in sections:
        raise ValueError(f"checkpoint file '{path}' was written by `tessera mesh --checkpoint`: "
                         f"continue it with `tessera resume {path}` (or `tessera extend`) on "
                         f"the command line")
    saved = json.loads(sections["python"].decode())
    if saved.get("version") != _RECORD_VERSION:
        raise ValueError(f"checkpoint file '{path}': its Python record has version "
                         f"{saved.get('version')}; this tessera reads {_RECORD_VERSION}")
    named = saved["problem"]
    if problem is None:
        if "specification" not in named:
            raise ValueError(f"checkpoint file '{path}' was made with a Problem written in "
                             f"Python ('{named.get('python_problem')}'): give it again, "
                             f"resume('{path}', problem=...)")
        problem = named["specification"]
    method = sections["method"].decode()
    return path, sections[method], saved, problem


def resume(path: Union[str, "os.PathLike[str]"], problem: Optional[Any] = None, *,
           progress: Any = None, allow_partial: bool = False, handle_interrupt: bool = True,
           threads: Optional[int] = None):
    """Continues the run of ``mesh(..., checkpoint=path)`` (method atlas or front) from its
    checkpoint: the same problem and arguments, and the same mesh, bit for bit, as the run that
    was never stopped.

    problem: needed only if the run's problem was a `Problem` written in Python (a catalogue
        name or problem file is recorded); it must be the same problem (F is compared at two
        points, bit for bit), else ValueError names what differs.
    progress, allow_partial, handle_interrupt, threads: as for `mesh`.
    Later checkpoints go to the same file. Raises ValueError for a damaged file, one written by
    the command line (``tessera resume`` continues those) or another problem.
    """
    import tessera

    path, state, saved, problem = _load(path, problem)
    return tessera.mesh(problem, **saved["arguments"], progress=progress,
                        allow_partial=allow_partial, handle_interrupt=handle_interrupt,
                        threads=threads, checkpoint=path,
                        checkpoint_every=saved["checkpoint_every"], _continue=(state, False))


def extend(path: Union[str, "os.PathLike[str]"], *, box: Any = None,
           tolerance: Optional[float] = None, problem: Optional[Any] = None,
           checkpoint: Optional[Union[str, "os.PathLike[str]"]] = None, progress: Any = None,
           allow_partial: bool = False, handle_interrupt: bool = True,
           threads: Optional[int] = None):
    """Continues the atlas of ``mesh(..., checkpoint=path)`` into a larger ``box`` or to a finer
    ``tolerance`` (or both), keeping what it computed: ``tessera extend``.

    box: as `mesh`'s; it must contain the run's box (each face parallel to one of the old box's
        and no nearer), else ValueError. The charts left open at the old box grow into it.
    tolerance: finer than the run's: the charts are kept and every triangle is bisected on M
        until it meets it (``chart_tolerance`` is set to the atlas's tolerance).
    checkpoint: where the extended run's checkpoints go (default: ``path``, replaced).
    problem, progress, allow_partial, handle_interrupt, threads: as for `resume`.
    """
    import tessera

    if box is None and tolerance is None:
        raise ValueError(f"extend('{os.fspath(path)}'): give a larger box, a finer tolerance, "
                         f"or both")
    path, state, saved, problem = _load(path, problem)
    arguments = dict(saved["arguments"])
    if arguments.get("method") not in (None, "atlas"):
        raise ValueError(f"extend continues an atlas; checkpoint file '{path}' is of method "
                         f"'{arguments['method']}': continue it with resume")
    if box is not None:
        arguments["box"] = _plain(box)  # its containment is checked where the state is read
    if tolerance is not None:
        header = _tessera.atlas_state_header(state)
        before = arguments.get("tolerance") or header["tolerance"]
        if not float(tolerance) < before:
            raise ValueError(f"extend: tolerance {tolerance} is not finer than the run's "
                             f"{before}: its mesh meets that already (a coarser mesh needs a "
                             f"new run)")
        arguments["tolerance"] = float(tolerance)
        arguments["chart_tolerance"] = header["tolerance"]
    return tessera.mesh(problem, **arguments, progress=progress, allow_partial=allow_partial,
                        handle_interrupt=handle_interrupt, threads=threads,
                        checkpoint=os.fspath(checkpoint) if checkpoint is not None else path,
                        checkpoint_every=saved["checkpoint_every"], _continue=(state, True))
