"""docs/python.md's MCP example prints what its comments say (docs_quick only checks that it runs)."""
import contextlib
import io
import re

from conftest import SOURCE_DIR


def mcp_example_code():
    text = (SOURCE_DIR / "docs" / "python.md").read_text(encoding="utf-8")
    section = text[text.index("### MCP example"):]
    match = re.search(r"<<'PY'\n(.*?)\nPY\n", section, re.S)
    assert match, "docs/python.md: the MCP example's heredoc (<<'PY' ... PY) is missing"
    return match.group(1)


def test_mcp_example_prints_what_its_comments_say():
    code = mcp_example_code()
    expected = [line.split("  # ", 1)[1].strip() for line in code.splitlines() if line.startswith("print(")]
    assert len(expected) == 3
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/python.md", "exec"), {})
    assert out.getvalue().splitlines() == expected
