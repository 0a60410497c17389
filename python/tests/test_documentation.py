# SPDX-License-Identifier: MIT
# The Python examples of README.md and docs/python.md run as written.
import os
import re

import pytest

from conftest import REPOSITORY

DOCUMENTS = ["README.md", "docs/python.md"]


def python_blocks(document: str):
    text = (REPOSITORY / document).read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


EXAMPLES = [(document, i, block) for document in DOCUMENTS
            for i, block in enumerate(python_blocks(document))]


def test_the_documents_have_examples():
    assert {document for document, _, _ in EXAMPLES} == set(DOCUMENTS)


@pytest.mark.parametrize("document, index, block", EXAMPLES,
                         ids=[f"{d}:{i}" for d, i, _ in EXAMPLES])
def test_example_runs(document, index, block, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the examples write files
    exec(compile(block, f"{document} example {index}", "exec"), {"__name__": "example"})


# Issue 34: `bvp.json` named a summary in one place and fold curves in another, `torus.json` a
# summary and Bézier patches, so that following the docs in order ended in KeyError: 'states'.
# Every file name that the commands of the docs write or read means one kind of file.
OUTPUT_KINDS = {
    "--summary": {"mesh": "mesh summary", "improve": "improve summary"},
    "--patches": "Bezier patches",
    "--folds-output": "curves", "--hopf-output": "curves", "--level-output": "curves",
    "--curves": "curves",
    "--states": "states",
    "--picture": "picture", "--diagram": "picture",
}


def documented_commands():
    """(document, command line) of every `tessera` command in the docs' sh blocks."""
    documents = [REPOSITORY / "README.md", *sorted((REPOSITORY / "docs").rglob("*.md"))]
    for document in documents:
        for block in re.findall(r"```sh\n(.*?)```", document.read_text(), flags=re.S):
            block = re.sub(r"\\\n\s*", " ", block)  # continued lines
            for line in block.splitlines():
                for command in line.split("#")[0].split("&&"):
                    words = command.split()
                    for i, word in enumerate(words):
                        if word.endswith("tessera") and i + 1 < len(words):
                            yield document.relative_to(REPOSITORY), words[i + 1:]
                            break


def test_each_file_name_in_the_docs_means_one_kind_of_file():
    kinds = {}  # file name -> {kind: where}
    for document, words in documented_commands():
        command = words[0]
        for option, value in zip(words, words[1:]):
            kind = OUTPUT_KINDS.get(option)
            if option == "-o":
                kind = "picture" if command == "render" else "mesh"
            if isinstance(kind, dict):
                kind = kind.get(command)
            if kind is None or "{" in value or value.isupper():
                continue
            kinds.setdefault(value, {}).setdefault(kind, f"{document}: tessera {' '.join(words)}")
        if command in ("render", "check", "improve") and len(words) > 1 and not words[1].startswith("-"):
            mesh = words[1]
            kind = "states" if mesh.endswith(".npy") else "mesh"
            kinds.setdefault(mesh, {}).setdefault(kind, f"{document}: tessera {' '.join(words)}")
    collisions = {name: where for name, where in kinds.items() if len(where) > 1}
    assert not collisions, "\n".join(
        f"{name} is {len(where)} kinds of file:\n  " + "\n  ".join(f"{k}: {w}" for k, w in where.items())
        for name, where in collisions.items())
