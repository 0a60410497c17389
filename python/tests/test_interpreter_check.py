# SPDX-License-Identifier: MIT
# `import tessera` under an interpreter the compiled module was not built for names both
# interpreters (tessera/_interpreter_check.py) instead of "No module named 'numpy'".
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig

import pytest

import tessera
from tessera import _build_info, _interpreter_check

PACKAGE_DIR = pathlib.Path(tessera.__file__).resolve().parent


def _import_tessera(python: str, python_path: pathlib.Path,
                    before: str = "") -> subprocess.CompletedProcess:
    environment = dict(os.environ, PYTHONPATH=str(python_path))
    return subprocess.run([python, "-c", before + "import tessera"], env=environment,
                          capture_output=True, text=True, timeout=120)


def test_build_info_names_this_interpreter():
    # The tests run under the interpreter the module was built for (scripts/run-tests.sh).
    assert os.path.realpath(_build_info.executable) == os.path.realpath(sys.executable)
    assert _build_info.version.startswith("{}.{}.".format(*sys.version_info[:2]))
    assert _build_info.extension_suffix == sysconfig.get_config_var("EXT_SUFFIX")


def test_same_interpreter_keeps_the_original_error():
    built_for = {"executable": sys.executable, "version": _build_info.version,
                 "extension_suffix": sysconfig.get_config_var("EXT_SUFFIX")}
    error = ImportError("No module named 'scipy'", name="scipy")
    assert _interpreter_check.explain(error, built_for) is None
    assert _interpreter_check.explain(error, None) is None


def test_another_interpreter_is_named():
    built_for = {"executable": "/opt/python3.9/bin/python3", "version": "3.9.18",
                 "extension_suffix": ".cpython-39-x86_64-linux-gnu.so"}
    message = _interpreter_check.explain(ImportError("No module named 'numpy'", name="numpy"),
                                         built_for)
    assert message is not None
    assert "built for /opt/python3.9/bin/python3 (Python 3.9.18)" in message
    assert f"this is {sys.executable}" in message
    assert "No module named 'numpy'" in message
    assert "Run it with /opt/python3.9/bin/python3" in message


def test_import_under_a_mismatched_recorded_interpreter(tmp_path):
    # A copy of the package whose _build_info.py records another interpreter, imported where
    # numpy cannot be imported: what pyenv's python3 without numpy sees.
    package = tmp_path / "tessera"
    package.mkdir()
    for path in PACKAGE_DIR.iterdir():
        if path.is_file() and path.name != "_build_info.py":
            (package / path.name).symlink_to(path)
    (package / "_build_info.py").write_text(
        'executable = "/opt/python3.9/bin/python3"\nversion = "3.9.18"\n'
        'extension_suffix = ".cpython-39-x86_64-linux-gnu.so"\n')
    result = _import_tessera(sys.executable, tmp_path,
                             before="import sys; sys.modules['numpy'] = None; ")
    assert result.returncode != 0
    last_line = result.stderr.strip().splitlines()[-1]
    assert last_line.startswith("ImportError: tessera's compiled module was built for "
                                "/opt/python3.9/bin/python3 (Python 3.9.18); this is "
                                f"{sys.executable}"), result.stderr


def _other_interpreters():
    this = os.path.realpath(sys.executable)
    candidates = [shutil.which("python3"), os.path.expanduser("~/.pyenv/shims/python3")]
    found = []
    for candidate in candidates:
        if candidate and os.access(candidate, os.X_OK):
            resolved = subprocess.run([candidate, "-c", "import os, sys; "
                                       "print(os.path.realpath(sys.executable))"],
                                      capture_output=True, text=True).stdout.strip()
            if resolved and resolved != this and resolved not in found:
                found.append(resolved)
    return found


@pytest.mark.parametrize("python", _other_interpreters() or [None])
def test_import_under_another_interpreter(python):
    # The real case where one exists (pyenv's python3 first on PATH): either it imports tessera
    # (same ABI, with numpy) or it says which interpreter to use.
    if python is None:
        pytest.skip("no other python3 on this machine")
    result = _import_tessera(python, PACKAGE_DIR.parent)
    if result.returncode != 0:
        assert f"tessera's compiled module was built for {_build_info.executable}" in \
            result.stderr, result.stderr
