# SPDX-License-Identifier: MIT
"""Says which interpreter tessera's compiled module was built for when it cannot be imported.

The module `_tessera` is compiled for one interpreter (Debian's /usr/bin/python3 by
scripts/build.sh, the one that ran pip for `pip install .`). Another `python3` first on PATH
(pyenv, conda) fails with "No module named 'numpy'" or "cannot import name '_tessera'", which
names neither interpreter; this turns that into a message that names both. tessera/__init__.py
imports this module first, and importing it runs the check.
"""
from __future__ import annotations

import os
import sys
import sysconfig
from typing import Mapping, Optional


def _describe(executable: str, version: str) -> str:
    return f"{executable} (Python {version})"


def _is_same_interpreter(built_for: Mapping[str, str]) -> bool:
    # A virtual environment's python is a link to the interpreter it was made from, so the real
    # paths of /usr/bin/python3 and venv/bin/python agree; the suffix tells versions apart.
    this_suffix = sysconfig.get_config_var("EXT_SUFFIX") or ""
    if built_for.get("extension_suffix") and built_for["extension_suffix"] != this_suffix:
        return False
    built = built_for.get("executable", "")
    return bool(built) and os.path.realpath(built) == os.path.realpath(sys.executable)


def explain(error: ImportError, built_for: Optional[Mapping[str, str]]) -> Optional[str]:
    """The message for `error`, raised while importing numpy or `_tessera`; None keeps it.

    ``built_for`` holds ``executable``, ``version`` and ``extension_suffix`` of the interpreter
    the module was built for (tessera/_build_info.py), or is None where that is unknown.
    """
    this = _describe(sys.executable, "{}.{}.{}".format(*sys.version_info[:3]))
    if built_for is None or _is_same_interpreter(built_for):
        if getattr(error, "name", None) == "numpy" and sys.prefix != sys.base_prefix:
            return (f"tessera needs NumPy, which this virtual environment ({sys.prefix}) does not "
                    f"have ({error}): install numpy into it, or make it with `/usr/bin/python3 -m "
                    f"venv --system-site-packages` to see Debian's python3-numpy")
        return None
    built = _describe(built_for.get("executable", "?"), built_for.get("version", "?"))
    return (f"tessera's compiled module was built for {built}; this is {this}, which cannot "
            f"import it ({error}). Run it with {built_for.get('executable', 'that interpreter')}, "
            f"or build tessera for this interpreter: `{sys.executable} -m pip install .` in the "
            f"repository (docs/python.md)")


def check_imports() -> None:
    """Imports numpy and the compiled module; explains a failure that another interpreter causes.

    Raises ImportError naming the interpreter the module was built for and this one, chained to
    the original error; the original error itself where the interpreters are the same.
    """
    try:
        import numpy  # noqa: F401

        from . import _tessera  # noqa: F401
    except ImportError as error:
        try:
            from . import _build_info

            built_for: Optional[Mapping[str, str]] = {
                "executable": _build_info.executable,
                "version": _build_info.version,
                "extension_suffix": _build_info.extension_suffix,
            }
        except ImportError:  # the source tree, or a package built before _build_info.py existed
            built_for = None
        message = explain(error, built_for)
        if message is None:
            raise
        raise ImportError(message, name=__package__) from error


check_imports()
