#!/usr/bin/python3
"""tools/docs_numbers.py on a made-up repository: it names every stale or broken quoted number, --write regenerates
them from the results files, and the docs runner checks the numbers quoted from a block's output after running it."""
import os
import pathlib
import subprocess
import sys
import tempfile

TOOLS = pathlib.Path(__file__).resolve().parents[2] / "tools"
NUMBERS = TOOLS / "docs_numbers.py"
RUNNER = pathlib.Path(__file__).resolve().parent / "run_doc_blocks.py"
sys.path.insert(0, str(TOOLS))
import docs_numbers  # noqa: E402  pylint: disable=wrong-import-position

REPORT = """# report

## Suite `paper`: one-step problems

12 problems; certified references: 3 non-unique, 9 unique.

| backend | solved | SGM time |
|---|---|---|
| lemke | 12 | 312 ns |
| `psor` | 11 | 1.25 µs |

Fastest against the sparse path: speed-up median 126.4×, min 2.82×.

| scene | backend | cold/warm |
|---|---|---|
| sign | lemke | 1.01 |
| sign | ipopt | 3.23 |

## Suite `hard`: hard ones

| backend | solved | SGM time |
|---|---|---|
| lemke | 5 | 9 µs |
"""

CSV = "suite,solver,time_median\npaper,lemke,3e-07\npaper,psor,1e-06\nhard,lemke,9e-06\n"

PAGE = """# page

<!-- numbers
R = 'results/report.md'
paper.problems = match(R, r'^(\\d+) problems;', 'Suite `paper`')
paper.unique = match(R, r'(\\d+) unique', 'Suite `paper`')
paper.lemke.sgm = cell(R, 'Suite `paper`', 'lemke', 'SGM time')
paper.psor.solved = cell(R, 'Suite `paper`',
    'psor', 'solved')
hard.lemke.solved = cell(R, 'Suite `hard`', 'lemke', 'solved')
paper.speedup = sig(match(R, r'median ([\\d.]+)×'), 3)
csv.rows = str(len(csv('results/data.csv')))
csv.paper-mean = g(csv('results/data.csv').query("suite == 'paper'").time_median.mean() * 1e9, 3)
broken.column = cell(R, 'Suite `paper`', 'lemke', 'no such column')
run.ratio = fields('ratios', 'ratio')[1]
warm.ipopt = sig(cell(R, 'Suite `paper`', ('sign', 'ipopt'), 'cold/warm'))
run.sweeps = cell('output:ratios', None, '16', 'sweeps')
hard.table = table(R, 'Suite `hard`', 'SGM time')
-->

The paper suite has <!--n paper.problems-->12<!--/n--> problems (<!--n paper.unique-->9<!--/n--> unique);
| lemke | <!--n paper.lemke.sgm-->300 ns<!--/n--> | psor <!--n paper.psor.solved-->11<!--/n--> |
hard: <!--n hard.lemke.solved-->5<!--/n-->, speed-up <!--n paper.speedup-->126<!--/n-->×,
<!--n csv.rows-->3<!--/n--> rows, mean <!--n csv.paper-mean-->600<!--/n--> ns, <!--n broken.column-->?<!--/n-->,
<!--n undefined.name-->1<!--/n-->, warm <!--n warm.ipopt-->3.2<!--/n-->×.

```sh runnable=quick id=ratios
echo "ratio 0.40"
printf '| m | sweeps |\n|---|---|\n| 16 | 45 |\n'
```

The block prints ratio <!--n run.ratio-->0.42<!--/n--> and <!--n run.sweeps-->45<!--/n--> sweeps.

<!--n hard.table-->

| backend | solved | SGM time |
|---|---|---|
| lemke | 4 | 9 µs |

<!--/n-->

````text
An example, not a live number: <!--n example.only-->1<!--/n-->
````
"""


def run(args):
    proc = subprocess.run([sys.executable, *map(str, args)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, check=False)
    return proc.returncode, proc.stdout


def line_of(text, snippet):
    return text[:text.index(snippet)].count("\n") + 1


def check(condition, message, output=""):
    if not condition:
        print(output)
        raise SystemExit(f"FAIL: {message}")


def test_formats():
    """The formatters write numbers as the pages do (known answers)."""
    cases = [(docs_numbers.sig(2.82), "2.8"), (docs_numbers.sig("2.65×"), "2.7"),
             (docs_numbers.sig(9.99), "10"), (docs_numbers.sig(0.0999), "0.10"),  # rounded up a decade
             (docs_numbers.sig(1675.7, 3), "1680"), (docs_numbers.sig(316, 3), "316"),
             (docs_numbers.sig(1.67e-16), "1.7e-16"), (docs_numbers.sig(0.0019401, 3), "0.00194"),
             (docs_numbers.sig("4.15× slower"), "4.2"), (docs_numbers.sig(0), "0"),
             (docs_numbers.sci(0.019165, 3), "1.917e-2"), (docs_numbers.sci(148.0, 1), "1.5e2"),
             (docs_numbers.g(0.4596, 3), "0.46"), (docs_numbers.g(1680.0, 4), "1680"),
             (docs_numbers.fixed("2.625 µs", 2), "2.62"), (docs_numbers.num("1.67e-16 (468 with z*)"), 1.67e-16)]
    for got, expected in cases:
        check(got == expected, f"format: got {got!r}, expected {expected!r}")


def main():
    test_formats()
    with tempfile.TemporaryDirectory() as tmp:
        root, build = pathlib.Path(tmp) / "repo", pathlib.Path(tmp) / "build"
        (root / "docs").mkdir(parents=True)
        (root / "results").mkdir()
        (build / "tools").mkdir(parents=True)
        (root / "results" / "report.md").write_text(REPORT, encoding="utf-8")
        (root / "results" / "data.csv").write_text(CSV, encoding="utf-8")
        page = root / "docs" / "page.md"
        page.write_text(PAGE, encoding="utf-8")
        (root / "README.md").write_text("# demo\n", encoding="utf-8")

        status, out = run([NUMBERS, "--source-dir", root])
        lines = out.splitlines()
        check(status == 1, f"exit status {status}, expected 1 (stale numbers)", out)
        sgm_line, mean_line = line_of(PAGE, "paper.lemke.sgm-->"), line_of(PAGE, "csv.paper-mean-->")
        check(any(l.startswith(f"docs/page.md:{sgm_line}: paper.lemke.sgm: the page says '300 ns'") and "'312 ns'" in l
                  for l in lines), "a stale cell is named with its line, the page's value and the source's", out)
        check(any(l.startswith(f"docs/page.md:{mean_line}: csv.paper-mean: the page says '600'") and "'650'" in l
                  for l in lines),
              "a stale number computed from a CSV is named", out)
        check(any("broken.column" in l and "no table has a column 'no such column'" in l for l in lines),
              "a definition whose column is missing says which", out)
        check(any("undefined.name: no definition" in l for l in lines), "a span with no definition is named", out)
        check(any(l.startswith(f"docs/page.md:{line_of(PAGE, '| lemke | 4 |')}: hard.table: the page says "
                               "'| lemke | 4 | 9 µs |'") and "'| lemke | 5 | 9 µs |'" in l for l in lines),
              "a stale row of a copied table is named with its own line", out)
        check("example.only" not in out, "a span shown inside a code block is not checked", out)
        check(not any(n in out for n in ("paper.problems", "paper.unique", "paper.psor.solved", "hard.lemke.solved",
                                          "paper.speedup", "csv.rows", "warm.ipopt")),
              "numbers that match are not named", out)
        check(lines[-1].startswith("docs numbers: 10 checked in 2 files, 5 stale or broken, 2 from block output"),
              "the summary counts checked, stale and deferred numbers", out)

        status, out = run([NUMBERS, "--source-dir", root, "--write"])
        text = page.read_text(encoding="utf-8")
        check("| lemke | 5 | 9 µs |" in text and "| lemke | 4 |" not in text, "--write rewrites a copied table", out)
        check("<!--n paper.lemke.sgm-->312 ns<!--/n-->" in text and "<!--n csv.paper-mean-->650<!--/n-->" in text,
              "--write rewrites the stale spans", out)
        check(f"rewrote docs/page.md:{sgm_line}: paper.lemke.sgm: '300 ns' -> '312 ns'" in out,
              "--write says what it changed", out)
        check("<!--n run.ratio-->0.42<!--/n-->" in text, "--write without outputs leaves output spans alone", out)
        status, out = run([NUMBERS, "--source-dir", root, page])
        check(status == 1 and "broken.column" in out and "paper.lemke.sgm" not in out,
              "after --write only the broken definitions remain", out)

        # The numbers quoted from a block's output: the runner checks them once it ran the block.
        page.write_text(text.replace(", <!--n broken.column-->?<!--/n-->", "").replace(
            "broken.column = cell(R, 'Suite `paper`', 'lemke', 'no such column')\n", "").replace(
            "<!--n undefined.name-->1<!--/n-->", "1"), encoding="utf-8")
        status, out = run([NUMBERS, "--source-dir", root])
        check(status == 0, "with the broken spans gone the results-based numbers all match", out)
        outputs = pathlib.Path(tmp) / "outputs"
        status, out = run([RUNNER, "--source-dir", root, "--build-dir", build, "--class", "quick",
                           "--save-outputs", outputs])
        ratio_line = line_of(page.read_text(encoding="utf-8"), "run.ratio-->")
        check(status == 1 and any(l.startswith(f"FAILED docs/page.md:{ratio_line}: run.ratio: the page says '0.42'")
                                  for l in out.splitlines()), "the runner names a number its block no longer prints",
              out)
        check((outputs / "ratios.out").read_text(encoding="utf-8").startswith("ratio 0.40\n| m |"),
              "the output is saved by id", out)
        check("run.sweeps" not in out, "a table in a block's output is read with cell('output:ID', ...)", out)
        status, out = run([NUMBERS, "--source-dir", root, "--outputs", outputs, "--write"])
        check("<!--n run.ratio-->0.40<!--/n-->" in page.read_text(encoding="utf-8"),
              "--write --outputs regenerates the numbers quoted from a saved output", out)
        status, out = run([RUNNER, "--source-dir", root, "--build-dir", build, "--class", "quick"])
        check(status == 0 and "docs numbers from block output: 2 checked" in out, "then the runner passes", out)
    print("docs numbers self-test: all checks passed")
    return 0


if __name__ == "__main__":
    os.environ.pop("CDPATH", None)
    sys.exit(main())
