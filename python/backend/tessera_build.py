# SPDX-License-Identifier: MIT
"""The PEP 517 build backend of `pip install .` (pyproject.toml): CMake builds the module, this
packs it into a wheel.

Standard library only: pip runs a backend in an isolated environment that sees no installed
package, so a backend that needed setuptools or scikit-build would have to be downloaded, and
`pip install .` would fail offline. CMake finds Debian's pybind11 (python3-pybind11) as
scripts/build.sh does, and the module is built for the interpreter that runs pip
(-DPython3_EXECUTABLE=sys.executable), e.g. a virtual environment's. The build folder is
build-pip/ in the repository (one for every interpreter: each configure names the one that runs
pip, and the wheel takes only that one's module); the environment variable TESSERA_PIP_BUILD_DIR
replaces it and CMAKE_ARGS adds configure options (e.g. CMAKE_ARGS="-DTESSERA_USE_METIS=OFF").
"""
from __future__ import annotations

import base64
import hashlib
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
import time
import zipfile
from typing import Any, Dict, List, Mapping, Optional

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]


def _project() -> Dict[str, Any]:
    """pyproject.toml's [project] table, with the version of CMakeLists.txt's project()."""
    text = (SOURCE_DIR / "pyproject.toml").read_text(encoding="utf-8")
    try:
        import tomllib  # Python 3.11

        project = dict(tomllib.loads(text)["project"])
    except ImportError:  # older Pythons: the table's one-line `key = value` entries suffice
        table = text.split("[project]", 1)[1].split("\n[", 1)[0]
        project = {}
        for key, value in re.findall(r"^([\w-]+)\s*=\s*(.+)$", table, re.M):
            strings = re.findall(r'"([^"]*)"', value)
            project[key] = strings if value.lstrip().startswith("[") else strings[0]
    cmake_lists = (SOURCE_DIR / "CMakeLists.txt").read_text(encoding="utf-8")
    project["version"] = re.search(r"project\(tessera VERSION ([\d.]+)", cmake_lists).group(1)
    return project


def _tag() -> str:
    """The wheel's tag for this interpreter and platform, e.g. cp311-cp311-linux_x86_64."""
    implementation = {"cpython": "cp", "pypy": "pp"}.get(sys.implementation.name,
                                                         sys.implementation.name)
    interpreter = f"{implementation}{sys.version_info[0]}{sys.version_info[1]}"
    debug = "d" if sysconfig.get_config_var("Py_DEBUG") else ""
    platform = re.sub(r"[-.]", "_", sysconfig.get_platform())
    return f"{interpreter}-{interpreter}{debug}-{platform}"


def _metadata_files() -> Dict[str, bytes]:
    """The .dist-info files other than RECORD: METADATA and WHEEL."""
    project = _project()
    lines = ["Metadata-Version: 2.1", f"Name: {project['name']}", f"Version: {project['version']}"]
    if "description" in project:
        lines.append(f"Summary: {project['description']}")
    if "requires-python" in project:
        lines.append(f"Requires-Python: {project['requires-python']}")
    license_ = project.get("license")
    if isinstance(license_, Mapping) and "text" in license_:
        lines.append(f"License: {license_['text']}")
    lines += [f"Requires-Dist: {dependency}" for dependency in project.get("dependencies", [])]
    wheel = ["Wheel-Version: 1.0", "Generator: tessera_build (python/backend)",
             "Root-Is-Purelib: false", f"Tag: {_tag()}"]
    return {"METADATA": ("\n".join(lines) + "\n").encode(),
            "WHEEL": ("\n".join(wheel) + "\n").encode()}


def _dist_info_name() -> str:
    project = _project()
    return f"{project['name']}-{project['version']}.dist-info"


def _build_module() -> pathlib.Path:
    """Configures and builds the target _tessera; returns the package folder it fills."""
    build_dir = pathlib.Path(os.environ.get("TESSERA_PIP_BUILD_DIR") or SOURCE_DIR / "build-pip")
    configure = ["cmake", "-S", str(SOURCE_DIR), "-B", str(build_dir),
                 "-DCMAKE_BUILD_TYPE=Release", "-DTESSERA_BUILD_TESTS=OFF",
                 "-DTESSERA_BUILD_PYTHON=ON", "-DTESSERA_USE_PETSC=OFF",
                 f"-DPython3_EXECUTABLE={sys.executable}"]
    if not (build_dir / "CMakeCache.txt").exists() and shutil.which("ninja"):
        configure += ["-G", "Ninja"]
    configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    build = ["cmake", "--build", str(build_dir), "--target", "_tessera", "--parallel", jobs]
    if shutil.which("cmake") is None:
        raise RuntimeError("tessera: `pip install .` needs cmake and Debian's python3-pybind11, "
                           "python3-dev and libraries: run scripts/install-dependencies.sh first")
    print(f"tessera: building the Python module for {sys.executable} in {build_dir} "
          f"(the first time about as long as the command-line tool)", flush=True)
    started = time.monotonic()
    for command in (configure, build):
        print("tessera: " + " ".join(shlex.quote(part) for part in command), flush=True)
        subprocess.run(command, check=True)
    print(f"tessera: built in {time.monotonic() - started:.0f} s", flush=True)
    return build_dir / "python" / "tessera"


def _record_line(path: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{path},sha256={digest},{len(data)}"


# The PEP 517 hooks. Nothing is needed to build beyond the standard library.

def get_requires_for_build_wheel(config_settings: Optional[Mapping[str, Any]] = None) -> List[str]:
    return []


def prepare_metadata_for_build_wheel(metadata_directory: str,
                                     config_settings: Optional[Mapping[str, Any]] = None) -> str:
    dist_info = pathlib.Path(metadata_directory) / _dist_info_name()
    dist_info.mkdir(parents=True, exist_ok=True)
    for name, data in _metadata_files().items():
        (dist_info / name).write_bytes(data)
    return dist_info.name


def build_wheel(wheel_directory: str, config_settings: Optional[Mapping[str, Any]] = None,
                metadata_directory: Optional[str] = None) -> str:
    package_dir = _build_module()
    project = _project()
    wheel_name = f"{project['name']}-{project['version']}-{_tag()}.whl"
    # The Python files and this interpreter's module, not one left by another interpreter.
    module = "_tessera" + sysconfig.get_config_var("EXT_SUFFIX")
    files: Dict[str, bytes] = {}
    for path in sorted(package_dir.iterdir()):
        if path.name in (module, "py.typed") or path.suffix == ".py":
            files[f"tessera/{path.name}"] = path.read_bytes()
    if f"tessera/{module}" not in files:
        raise RuntimeError(f"tessera: the build made no {package_dir / module}")
    dist_info = _dist_info_name()
    for name, data in _metadata_files().items():
        files[f"{dist_info}/{name}"] = data
    record = [_record_line(path, data) for path, data in files.items()]
    record.append(f"{dist_info}/RECORD,,")
    files[f"{dist_info}/RECORD"] = ("\n".join(record) + "\n").encode()
    wheel_path = pathlib.Path(wheel_directory) / wheel_name
    with zipfile.ZipFile(wheel_path, "w", compression=zipfile.ZIP_DEFLATED) as wheel:
        for path, data in files.items():
            info = zipfile.ZipInfo(path, date_time=(1980, 1, 1, 0, 0, 0))
            executable = path.endswith(".so") or path.endswith(".pyd")
            info.external_attr = (0o755 if executable else 0o644) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(info, data)
    return wheel_name
