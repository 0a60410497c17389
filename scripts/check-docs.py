#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Runs the shell and Python examples of README.md and docs/ as written, so that the docs
cannot go stale (issue 34).

Every ```sh, ```bash and ```python block of a document runs, in the document's order, in one
scratch directory per document that links the repository's build/, examples/, python/,
scripts/, docs/ and bench/ (so `build/tessera mesh examples/problems/cstr.tsr` works as
written, and the files one example writes are there for the next). Shell blocks run under
`bash -e -o pipefail`; Python blocks under Debian's /usr/bin/python3 with build/python on
PYTHONPATH, and `python3` in a shell block is that interpreter too (a Debian machine's).

An HTML comment on the line before a block's fence says how to treat it:

    <!-- docs-check: skip WHY -->      not run (WHY is required: a set-up command CI runs
                                       itself, a command that needs MPI ranks, ...)
    <!-- docs-check: slow -->          run only with --slow (over about 30 s on 2 cores)
    <!-- docs-check: output -->        the block is the printed output of the block before:
                                       its numbers are compared (see compare_output)
    <!-- docs-check: continues -->     a Python block that goes on from the Python block before
                                       (its names): runs after that block's code, in one process

Run as root (a container, CI), Open MPI's mpiexec refuses to start unless told otherwise; the
check then sets OMPI_ALLOW_RUN_AS_ROOT as docs/cluster.md tells a root user to.

Usage: scripts/check-docs.py [--slow] [--list] [--timeout S] [DOCUMENT ...]
Exit status 0 when every block that ran succeeded and every output matched, 1 otherwise.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional

REPOSITORY = Path(__file__).resolve().parent.parent
LINKED = ["build", "examples", "python", "scripts", "docs", "bench", "tests"]
RUNNABLE = {"sh": "shell", "bash": "shell", "python": "python"}
MARKER = re.compile(r"<!--\s*docs-check:\s*(skip|slow|output|continues)\b\s*(.*?)\s*-->")


@dataclass
class Block:
    document: str
    line: int           # of the opening fence, 1-based
    language: str       # the fence's info string
    text: str
    marker: Optional[str] = None  # skip, slow, output or continues
    reason: str = ""

    @property
    def kind(self) -> Optional[str]:
        return RUNNABLE.get(self.language)

    def where(self) -> str:
        return f"{self.document}:{self.line}"


def blocks_of(document: Path) -> List[Block]:
    lines = document.read_text().splitlines()
    found: List[Block] = []
    i = 0
    while i < len(lines):
        fence = re.match(r"^(`{3,})(\S*)\s*$", lines[i])
        if not fence:
            i += 1
            continue
        start = i
        end = i + 1
        while end < len(lines) and not lines[end].startswith(fence.group(1)):
            end += 1
        block = Block(str(document.relative_to(REPOSITORY)), start + 1, fence.group(2),
                      "\n".join(lines[start + 1:end]) + "\n")
        previous = lines[start - 1] if start > 0 else ""
        marker = MARKER.search(previous)
        if marker:
            block.marker, block.reason = marker.group(1), marker.group(2)
        found.append(block)
        i = end + 1
    return found


NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
# Numbers followed by these are measurements of the machine, not of the mesh.
VOLATILE_UNIT = re.compile(r"\s*(?:s\b|ms\b|min\b|MB\b|MiB\b|GB\b|GiB\b)")


def deterministic_numbers(line: str) -> List[str]:
    """The numbers of a line up to an elision (…), without times and memory sizes."""
    line = line.split("…")[0] if "…" in line and not re.search(r"\d\s*…\s*\d", line) else line
    numbers = []
    for match in NUMBER.finditer(line):
        if VOLATILE_UNIT.match(line, match.end()):
            continue
        numbers.append(match.group(0))
    return numbers


def line_key(line: str) -> str:
    words = line.split()
    return " ".join(words[:2]) if line.startswith("  ") else (words[0] if words else "")


def compare_output(expected: str, actual: str) -> List[str]:
    """Each line of the documented output whose key (its first word, or first two when indented)
    starts a line of the actual output must have the same numbers, times and sizes aside and up
    to an elision (…). Lines of the documented output that the run does not print are reported;
    the run may print more."""
    problems = []
    actual_lines = {}
    for line in actual.splitlines():
        actual_lines.setdefault(line_key(line), line)
    for line in expected.splitlines():
        key = line_key(line)
        if not key:
            continue
        if key not in actual_lines:
            problems.append(f"documented line not printed: {line.strip()}")
            continue
        want = deterministic_numbers(line)
        got = deterministic_numbers(actual_lines[key])[:len(want)]
        if want != got:
            problems.append(f"documented: {line.strip()}\n        printed:    "
                            f"{actual_lines[key].strip()}")
    return problems


def scratch_directory(base: Path, document: str) -> Path:
    directory = base / re.sub(r"[^A-Za-z0-9_.-]", "_", document)
    directory.mkdir(parents=True)
    for name in LINKED:
        if (REPOSITORY / name).exists():
            (directory / name).symlink_to(REPOSITORY / name)
    return directory


def environment(shims: Path) -> dict:
    env = dict(os.environ)
    env["PATH"] = f"{shims}:{env.get('PATH', '/usr/bin:/bin')}"
    python_path = str(REPOSITORY / "build" / "python")
    env["PYTHONPATH"] = python_path + (":" + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    return env


def run_block(block: Block, directory: Path, env: dict, timeout: float) -> subprocess.CompletedProcess:
    if block.kind == "shell":
        command = ["bash", "-e", "-o", "pipefail", "-c", block.text]
    else:
        command = ["/usr/bin/python3", "-c", block.text]
    # Its own process group, so that a block over the time limit (or Ctrl-C here) ends with
    # everything it started (mpiexec's ranks, a tessera run in a pipeline), not only its shell.
    with subprocess.Popen(command, cwd=directory, env=env, text=True, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, start_new_session=True) as process:
        try:
            output, _ = process.communicate(timeout=timeout)
        except BaseException:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            raise
        return subprocess.CompletedProcess(command, process.returncode, output)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("documents", nargs="*", help="README.md and docs/**/*.md by default")
    parser.add_argument("--slow", action="store_true", help="run the blocks marked slow too")
    parser.add_argument("--list", action="store_true", help="list the blocks, run nothing")
    parser.add_argument("--timeout", type=float, default=300.0,
                        help="seconds per block (default 300); a block over it fails")
    parser.add_argument("--keep", action="store_true", help="keep the scratch directories")
    options = parser.parse_args()
    documents = ([REPOSITORY / d for d in options.documents] if options.documents else
                 [REPOSITORY / "README.md"] + sorted((REPOSITORY / "docs").rglob("*.md")))
    if not (REPOSITORY / "build" / "tessera").exists():
        print("check-docs: build/tessera is missing: run scripts/build.sh first", file=sys.stderr)
        return 1
    base = Path(tempfile.mkdtemp(prefix="tessera-docs-"))
    shims = base / "shims"
    shims.mkdir()
    (shims / "python3").symlink_to("/usr/bin/python3")
    env = environment(shims)
    failures = []
    counts = {"ran": 0, "skipped": 0, "slow": 0, "outputs": 0}
    started = time.monotonic()
    try:
        for document in documents:
            blocks = blocks_of(document)
            directory = None
            last_output = None
            python_so_far = ""  # the code a 'continues' block goes on from
            for block in blocks:
                if block.marker == "output":
                    if options.list:
                        print(f"{block.where():32} output of the block before")
                        continue
                    if last_output is None:
                        continue  # its command did not run here (skipped or slow)
                    counts["outputs"] += 1
                    for problem in compare_output(block.text, last_output):
                        failures.append(f"{block.where()}: {problem}")
                    continue
                last_output = None
                if block.kind is None:
                    continue
                if block.marker == "skip":
                    if not block.reason:
                        failures.append(f"{block.where()}: 'docs-check: skip' needs a reason")
                    counts["skipped"] += 1
                    if options.list:
                        print(f"{block.where():32} skip: {block.reason}")
                    continue
                if block.marker == "slow" and not options.slow:
                    counts["slow"] += 1
                    if options.list:
                        print(f"{block.where():32} slow")
                    continue
                if options.list:
                    print(f"{block.where():32} {block.kind}")
                    continue
                if block.kind == "python":
                    if block.marker == "continues":
                        block.text = python_so_far + block.text
                    python_so_far = block.text
                if directory is None:
                    directory = scratch_directory(base, block.document)
                began = time.monotonic()
                try:
                    result = run_block(block, directory, env, options.timeout)
                except subprocess.TimeoutExpired:
                    failures.append(f"{block.where()}: over {options.timeout:.0f} s "
                                    "(mark it '<!-- docs-check: slow -->' if it must be slow)")
                    continue
                counts["ran"] += 1
                seconds = time.monotonic() - began
                print(f"check-docs: {block.where():32} {block.kind:6} {seconds:6.1f} s "
                      f"{'ok' if result.returncode == 0 else 'FAILED'}", flush=True)
                if result.returncode != 0:
                    tail = "\n".join(result.stdout.splitlines()[-15:])
                    failures.append(f"{block.where()}: exit {result.returncode}\n{tail}")
                    print(tail, flush=True)
                else:
                    last_output = result.stdout
    finally:
        if options.keep:
            print(f"check-docs: scratch directories kept in {base}")
        else:
            shutil.rmtree(base, ignore_errors=True)
    if options.list:
        return 0
    print(f"check-docs: {counts['ran']} blocks ran, {counts['outputs']} outputs compared, "
          f"{counts['slow']} slow ones left out{'' if options.slow else ' (--slow runs them)'}, "
          f"{counts['skipped']} skipped by their marker, in {time.monotonic() - started:.0f} s")
    for failure in failures:
        print(f"check-docs: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
