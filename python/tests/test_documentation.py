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
