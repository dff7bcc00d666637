"""The README's Python example runs as printed, and prints what its comments say (docs are tested)."""
import contextlib
import io
import pathlib
import re

import numpy as np

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def readme_python_block():
    text = README.read_text(encoding="utf-8")
    match = re.search(r"```python[^\n]*\n(.*?)```", text, re.S)  # the fence may carry a docs-test mark
    assert match, "README.md has no ```python block"
    return match.group(1)


def test_readme_example_prints_what_its_comments_say():
    code = readme_python_block()
    printed_lines = [line for line in code.splitlines() if line.startswith("print(")]
    expected = [line.split("#", 1)[1].strip() for line in printed_lines]
    assert len(expected) >= 3
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, str(README), "exec"), {"np": np})
    got = out.getvalue().splitlines()
    assert len(got) == len(expected), out.getvalue()
    for line, comment in zip(got, expected):
        # The comment is the printed text, possibly followed by ": explanation".
        assert comment.startswith(line.strip()) or line.strip() == comment.split(":")[0].strip(), (line, comment)
