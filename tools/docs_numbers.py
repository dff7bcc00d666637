#!/usr/bin/python3
"""Checks or regenerates the numbers README.md and docs/*.md quote from results/ files and from command output.

Convention (docs/documentation.md): a quoted number is a span `<!--n NAME-->TEXT<!--/n-->` (invisible when the page is
rendered) and the same page defines NAME in a comment block
    <!-- numbers
    R = 'results/bench/report.md'
    paper.auto.sgm = cell(R, 'Suite `paper`', 'auto', 'SGM time')
    -->
Each line is `NAME = EXPRESSION`, a Python expression over the helpers below (and names defined above it in the
same block); its value, as text, must equal the span's TEXT. A line starting with whitespace continues the one
before. `output('BLOCK_ID', REGEX)` reads what the runnable block with `id=BLOCK_ID` printed: those spans are checked
by the docs runner after it ran the block (tests/docs/run_doc_blocks.py), the others here, from the files alone.

Usage: docs_numbers.py [--source-dir ROOT] [--write] [--outputs DIR] [FILE ...]
  default: check README.md and docs/*.md, print one line per stale number, exit 1 if any;
  --write: rewrite every stale span in place (the command to run after `bash tools/bench.sh` re-made results/);
  --outputs DIR: block outputs saved by `run_doc_blocks.py --save-outputs DIR`, so output() spans are checked too.
"""
import argparse
import builtins
import decimal
import functools
import json as jsonlib
import math
import pathlib
import re
import sys

SPAN = re.compile(r"<!--n (?P<name>[\w.\-/+]+)-->(?P<text>.*?)<!--/n-->", re.S)
DEFINITIONS = re.compile(r"<!-- numbers\n(?P<body>.*?)-->", re.S)
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


class SourceError(Exception):
    """A definition that cannot be evaluated: a missing file, table, row, column or match."""


class OutputMissing(Exception):
    """A definition reads a block's output that this run does not have (the block was not run)."""


class Sources:
    """The helpers a definition may call, reading files relative to the repository root (each file read once)."""

    def __init__(self, root, outputs=None):
        self.root, self.outputs = pathlib.Path(root), outputs
        self.read_output = False  # set by output(): the definition being evaluated quotes a block's output

    def text(self, path):
        """The file's text; `output:ID` is what the block with id=ID printed, so cell() and match() read it too."""
        if path.startswith("output:"):
            return self.output(path[len("output:"):], r"\A((?:.|\n)*)\Z")
        return self.file_text(path)

    @functools.lru_cache(maxsize=None)
    def file_text(self, path):
        try:
            return (self.root / path).read_text(encoding="utf-8")
        except OSError as error:
            raise SourceError(f"cannot read {path}: {error.strerror}") from None

    def section(self, path, under):
        """The lines of PATH from the first line containing UNDER to the next heading of the same level or above."""
        lines = self.text(path).splitlines()
        if under is None:
            return lines
        for i, line in enumerate(lines):
            if under in line:
                level = len(line) - len(line.lstrip("#")) if line.startswith("#") else 7
                end = next((j for j in range(i + 1, len(lines)) if lines[j].startswith("#")
                            and len(lines[j]) - len(lines[j].lstrip("#")) <= level), len(lines))
                return lines[i:end]
        raise SourceError(f"{path} has no line containing {under!r}")

    def tables(self, path, under):
        """Every markdown table in the section, as (header cells, rows of cells)."""
        found, current = [], []
        for line in self.section(path, under) + [""]:
            if line.startswith("|"):
                current.append([c.strip() for c in line.strip().strip("|").split("|")])
            elif current:
                if len(current) >= 2:
                    found.append((current[0], current[2:]))
                current = []
        return found

    def table_with(self, path, under, column):
        for header, rows in self.tables(path, under):
            if column in header:
                return header, rows
        raise SourceError(f"{path}{' under ' + repr(under) if under else ''}: no table has a column {column!r}")

    # --- the helpers definitions call ---
    def cell(self, path, under, row, column):
        """The cell in COLUMN of the row whose first cell is ROW (backticks ignored; a tuple ROW matches the first
        cells in turn), in the first table of the section UNDER that has both COLUMN and that row (a section may
        hold several tables with a column of that name, e.g. "problems" per backend and per size)."""
        self.table_with(path, under, column)  # names the missing column when no table has it
        keys = [str(k) for k in (row if isinstance(row, tuple) else (row,))]
        for header, rows in self.tables(path, under):
            if column not in header:
                continue
            for cells in rows:
                if [c.strip("`") for c in cells[:len(keys)]] == keys:
                    return cells[header.index(column)]
        raise SourceError(f"{path} under {under!r}: no table with column {column!r} has a row {row!r}")

    def column(self, path, under, column):
        """Every cell of COLUMN in the first table of the section that has it."""
        header, rows = self.table_with(path, under, column)
        return [cells[header.index(column)] for cells in rows]

    def table(self, path, under, column):
        """The whole first table of the section that has COLUMN, between blank lines: for a span whose tags stand on
        lines of their own around a table copied from a results file (the blank line keeps the closing tag from
        being read as one more table row)."""
        lines, inside_table = [], False
        for line in self.section(path, under) + [""]:
            if line.startswith("|"):
                lines.append(line)
                inside_table = True
            elif inside_table:
                header = [c.strip() for c in lines[0].strip().strip("|").split("|")]
                if column in header:
                    return "\n\n" + "\n".join(lines) + "\n\n"
                lines, inside_table = [], False
        raise SourceError(f"{path}{' under ' + repr(under) if under else ''}: no table has a column {column!r}")

    def match(self, path, regex, under=None, group=1):
        """Group GROUP of the first match of REGEX (multiline) in the section UNDER of PATH."""
        found = re.search(regex, "\n".join(self.section(path, under)), re.M)
        if not found:
            raise SourceError(f"{path}{' under ' + repr(under) if under else ''}: nothing matches {regex!r}")
        return found.group(group)

    def json(self, path):
        return jsonlib.loads(self.text(path))

    @functools.lru_cache(maxsize=None)
    def csv(self, path):
        import pandas  # only definitions that read a CSV pay for pandas
        try:
            return pandas.read_csv(self.root / path, keep_default_na=False)
        except OSError as error:
            raise SourceError(f"cannot read {path}: {error.strerror}") from None

    def output(self, block_id, regex, group=1):
        """Group GROUP of the first match of REGEX in what the block with id=BLOCK_ID printed."""
        self.read_output = True
        if self.outputs is None or block_id not in self.outputs:
            raise OutputMissing(block_id)
        found = re.search(regex, self.outputs[block_id], re.M)
        if not found:
            raise SourceError(f"the output of block id={block_id} has nothing matching {regex!r}")
        return found.group(group)

    def fields(self, block_id, prefix):
        """The whitespace-separated fields of the first line the block with id=BLOCK_ID printed that starts with
        PREFIX and a space (the prefix's own fields included)."""
        escaped = r"\s+".join(re.escape(word) for word in prefix.split())
        return self.output(block_id, rf"^({escaped}\s.*)$").split()

    def namespace(self):
        return {"cell": self.cell, "column": self.column, "table": self.table, "match": self.match,
                "json": self.json, "csv": self.csv, "output": self.output, "fields": self.fields, "findall": findall,
                "num": num, "sig": sig, "sci": sci, "g": g, "fixed": fixed}


def num(text):
    """The first number in TEXT ("88 ns" → 88.0, "1.67e-16 (468 with z*)" → 1.67e-16)."""
    found = NUMBER.search(str(text))
    if not found:
        raise SourceError(f"no number in {text!r}")
    return float(found.group())


def findall(regex, text):
    """Every match of REGEX in TEXT (the groups, as re.findall gives them)."""
    return re.findall(regex, str(text))


def sig(value, digits=2):
    """VALUE with DIGITS significant digits, as a page writes it: 2.82 → '2.8', 1675.7 → '1680',
    1.67e-16 → '1.7e-16' (e notation below 1e-4 and from 1e6 on)."""
    value = num(value) if isinstance(value, str) else float(value)
    if value == 0 or not math.isfinite(value):
        return f"{value:g}"
    exponent = math.floor(math.log10(abs(value)))
    if -4 <= exponent < 6:
        # Half up on the shortest decimal text (2.65 → 2.7, as a reader rounds the report's 2.65), not on the binary.
        decimals = digits - 1 - exponent
        rounded = decimal.Decimal(repr(value)).quantize(decimal.Decimal(1).scaleb(-decimals), decimal.ROUND_HALF_UP)
        if abs(rounded) >= decimal.Decimal(10) ** (exponent + 1):  # rounded up a decade (9.99 → 10): one digit less
            decimals -= 1
            rounded = rounded.quantize(decimal.Decimal(1).scaleb(-decimals), decimal.ROUND_HALF_UP)
        return f"{rounded:.{max(decimals, 0)}f}"
    return sci(value, digits - 1)


def sci(value, decimals):
    """VALUE in e notation, DECIMALS digits after the point, a short exponent: sci(0.019165, 3) → '1.917e-2'."""
    value = num(value) if isinstance(value, str) else float(value)
    mantissa, _, exponent = f"{value:.{decimals}e}".partition("e")
    return f"{mantissa}e{int(exponent)}"


def g(value, digits):
    """VALUE in Python's general format, DIGITS significant digits, no trailing zeros: g(0.4596, 3) → '0.46'."""
    value = num(value) if isinstance(value, str) else float(value)
    return f"{value:.{digits}g}"


def fixed(value, decimals):
    """VALUE with DECIMALS digits after the point: fixed(1.345, 2) → '1.35'."""
    value = num(value) if isinstance(value, str) else float(value)
    return f"{value:.{decimals}f}"


FENCE = re.compile(r"^[ \t]*(`{3,}|~{3,})", re.M)


def code_ranges(text):
    """(start, end) offsets of the fenced code blocks: spans and definitions shown as examples there are not live."""
    ranges, opened = [], None
    for fence in FENCE.finditer(text):
        if opened is None:
            opened = fence
        elif fence.group(1)[0] == opened.group(1)[0] and len(fence.group(1)) >= len(opened.group(1)):
            ranges.append((opened.start(), fence.end()))
            opened = None
    return ranges


def live(matches, text):
    ranges = code_ranges(text)
    return [m for m in matches if not any(start <= m.start() < end for start, end in ranges)]


class Span:
    def __init__(self, page, name, text, start, end, line):
        self.page, self.name, self.text, self.start, self.end, self.line = page, name, text, start, end, line


def definitions(page, text):
    """NAME → expression text, from the page's `<!-- numbers` blocks, in order (continuation lines joined)."""
    defs = {}
    for block in live(DEFINITIONS.finditer(text), text):
        lines = []
        for line in block["body"].splitlines():
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            if line[0].isspace() and lines:
                lines[-1] += " " + line.strip()
            else:
                lines.append(line.strip())
        for line in lines:
            name, sep, expression = line.partition("=")
            if not sep or not re.fullmatch(r"[\w.\-/+]+", name.strip()):
                raise SourceError(f"{page}: a numbers line must be NAME = EXPRESSION, not {line!r}")
            if name.strip() in defs:
                raise SourceError(f"{page}: {name.strip()} is defined twice")
            defs[name.strip()] = expression.strip()
    return defs


def spans(page, text):
    return [Span(page, m["name"], m["text"], m.start("text"), m.end("text"), text.count("\n", 0, m.start()) + 1)
            for m in live(SPAN.finditer(text), text)]


def evaluate(defs, sources, page):
    """(NAME → value or the exception its definition raised, the names that quote a block's output). Dotted names
    are not Python names: a definition reads an earlier one with v('paper.auto.sgm'); plain identifiers (R = ...)
    are variables for the lines below."""
    values, from_output, scope = {}, set(), sources.namespace()
    scope["v"] = lambda name: _value(values, name, page)
    scope["__builtins__"] = SAFE_BUILTINS  # one globals dict, so generator expressions see the helpers too
    for name, expression in defs.items():
        sources.read_output = False
        try:
            value = eval(expression, scope)  # pylint: disable=eval-used
            values[name] = value
            if name.isidentifier():
                scope[name] = value
        except (SourceError, OutputMissing) as error:
            values[name] = error
        except NameError as error:  # an earlier plain variable that failed: pass its reason on
            failed = values.get(getattr(error, "name", None))
            values[name] = failed if isinstance(failed, Exception) else SourceError(
                f"{page}: definition {name} = {expression} failed: NameError: {error}")
        except Exception as error:  # a definition with a bug: report it like a stale number, with the page line
            values[name] = SourceError(f"{page}: definition {name} = {expression} failed: "
                                       f"{type(error).__name__}: {error}")
        if sources.read_output or isinstance(values[name], OutputMissing):
            from_output.add(name)
    return values, from_output


def _value(values, name, page):
    if name not in values:
        raise SourceError(f"{page}: {name} is used before it is defined")
    if isinstance(values[name], Exception):
        raise values[name]
    return values[name]


# What a definition may call besides the helpers: arithmetic and containers, no I/O or imports.
SAFE_BUILTINS = {name: getattr(builtins, name)
                 for name in ("abs", "all", "any", "float", "int", "len", "max", "min", "round", "sorted", "str", "sum",
                              "list", "set", "dict", "tuple", "zip", "range", "enumerate", "isinstance")}


def short(text):
    """TEXT quoted for a message, cut after 80 characters."""
    text = str(text)
    return repr(text) if len(text) <= 80 else repr(text[:77]) + "…"


def first_difference(page_text, value):
    """(line offset, page's line, source's line) of the first line where a copied table differs."""
    ours, theirs = page_text.split("\n"), value.split("\n")
    k = next((i for i, (a, b) in enumerate(zip(ours, theirs)) if a != b), min(len(ours), len(theirs)))
    return k, ours[k] if k < len(ours) else "(nothing)", theirs[k] if k < len(theirs) else "(nothing)"


def check_page(path, root, sources, write=False, only_outputs=False):
    """(problems, checked, deferred) for one page; with write, stale spans are rewritten in the file."""
    text = path.read_text(encoding="utf-8")
    page = str(path.relative_to(root)) if path.is_absolute() and path.is_relative_to(root) else str(path)
    problems, checked, deferred, replacements = [], 0, 0, []
    try:
        defs = definitions(page, text)
    except SourceError as error:
        return [str(error)], 0, 0
    found = spans(page, text)
    if not found and not defs:
        return [], 0, 0
    values, from_output = evaluate(defs, sources, page)
    used = set()
    for span in found:
        used.add(span.name)
        where = f"{page}:{span.line}: {span.name}"
        if span.name not in values:
            problems.append(f"{where}: no definition (add `{span.name} = ...` to a `<!-- numbers` block of the page)")
            continue
        value = values[span.name]
        if isinstance(value, OutputMissing):
            deferred += 1
            continue
        if only_outputs and span.name not in from_output:
            continue
        if isinstance(value, SourceError):
            problems.append(f"{where}: {value}")
            continue
        checked += 1
        if str(value) != span.text:
            if write:
                replacements.append((span, str(value)))
            else:
                if "\n" in span.text + str(value):  # a copied table: name its first differing line
                    k, ours, theirs = first_difference(span.text, str(value))
                    problems.append(f"{page}:{span.line + k}: {span.name}: the page says {short(ours)}, "
                                    f"{defs[span.name]} gives {short(theirs)}")
                else:
                    problems.append(f"{where}: the page says {short(span.text)}, "
                                    f"{defs[span.name]} gives {short(value)}")
    for name in defs if not only_outputs else ():  # the docs runner leaves this to the file check
        if name not in used and "." in name:
            problems.append(f"{page}: {name} is defined but no span quotes it")
    if replacements:
        for span, value in sorted(replacements, key=lambda r: -r[0].start):
            text = text[:span.start] + value + text[span.end:]
        path.write_text(text, encoding="utf-8")
        for span, value in replacements:
            print(f"rewrote {page}:{span.line}: {span.name}: {short(span.text)} -> {short(value)}")
    return problems, checked, deferred


def check(files, root, outputs=None, write=False, only_outputs=False):
    """Every problem on the pages, one line each, and the summary line."""
    sources = Sources(root, outputs)
    problems, checked, deferred = [], 0, 0
    for path in files:
        p, c, d = check_page(path, root, sources, write, only_outputs)
        problems += p
        checked += c
        deferred += d
    summary = (f"docs numbers: {checked} checked in {len(files)} files, {len(problems)} stale or broken"
               + (f", {deferred} from block output not checked here (the docs runner checks them)"
                  if deferred else ""))
    return problems, summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source-dir", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent)
    parser.add_argument("--write", action="store_true", help="rewrite stale numbers in place")
    parser.add_argument("--outputs", type=pathlib.Path, help="block outputs saved by run_doc_blocks --save-outputs")
    parser.add_argument("files", nargs="*", type=pathlib.Path, help="default: README.md and docs/*.md")
    args = parser.parse_args()
    root = args.source_dir.resolve()
    files = [f.resolve() for f in args.files] or [root / "README.md", *sorted((root / "docs").glob("*.md"))]
    outputs = None
    if args.outputs:
        outputs = {p.stem: p.read_text(encoding="utf-8", errors="replace") for p in args.outputs.glob("*.out")}
    problems, summary = check(files, root, outputs, args.write)
    for problem in problems:
        print(problem)
    print(summary)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
