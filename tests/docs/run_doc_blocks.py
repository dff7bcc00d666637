#!/usr/bin/python3
"""Runs the code blocks that README.md and docs/*.md mark runnable, so every printed command is known to work.

Convention (docs/documentation.md): a fenced block whose info string carries `runnable=quick` or `runnable=long` is
run with bash (`set -euo pipefail`) from a scratch copy of the repository root, as a reader would run it there:
    ```sh runnable=quick writes=sign.smcps,out/index.csv needs=gnuplot exit=1 timeout=120
- writes=PATH[,PATH]: files the block says it writes; each must exist and be non-empty afterwards (and must not be
  in the repository itself: a test never dirties the checkout);
- needs=TOOL[,TOOL]: programs (looked up on PATH) or files relative to the root; when one is missing the block is
  skipped, not failed, and the summary says why;
- exit=N: the exit status the block must end with (default 0); timeout=S: seconds (default 60 quick, 3600 long);
- id=NAME: the block's output is kept under NAME, for the numbers the page quotes from it (tools/docs_numbers.py:
  a span defined by output('NAME', REGEX) is checked against this run's output after the blocks ran).
A ```python block runs with /usr/bin/python3 (PYTHONPATH=build/release/python), every other one with bash.
Every command block (bash, sh, shell, console, python or no language) must carry a mark: `runnable=quick`,
`runnable=long`, or `runnable=no reason="..."` (not a command to run here: root, a cluster, changes the checkout);
`--list-unmarked` prints the ones that do not and fails, so a page cannot gain an unmarked command.

The scratch root holds a symlink to every top-level entry of the repository, a copy of results/ (blocks may
rewrite it) and build/release pointing at the build under test, so commands run exactly as printed
(`build/release/tools/smcbench ...`); build/release/tools is first on PATH, so a bare `smcbench` works too.
Usage: run_doc_blocks.py --source-dir ROOT --build-dir BUILD --class quick|long [--budget S] [FILE ...]
Exit 0 when every selected block passed or was skipped, 1 otherwise; the last line is the summary.
"""
import argparse
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
DEFAULT_TIMEOUT = {"quick": 60, "long": 3600}
# Languages whose blocks are commands a reader would run, so each must say whether the tests run it.
COMMAND_LANGUAGES = ("bash", "sh", "shell", "console", "python", "py", "")
# Tools a CI machine cannot have, with the reason the summary prints instead of "not found".
CANNOT_HAVE = {
    "sbatch": "Slurm is not installed on the CI image (no cluster there)",
    "srun": "Slurm is not installed on the CI image (no cluster there)",
    "squeue": "Slurm is not installed on the CI image (no cluster there)",
    "nvidia-smi": "no GPU on the CI machine",
}


class Block:
    def __init__(self, path, line, info, body):
        self.path, self.line, self.body = path, line, body
        try:
            words = shlex.split(info)  # reason="needs root" is one word
        except ValueError:
            words = info.split()
        self.lang = words[0] if words else ""
        self.attrs = {}
        for word in words[1:]:
            key, _, value = word.partition("=")
            self.attrs[key] = value

    def mark_problem(self):
        """Why this block's mark is not acceptable, or None."""
        runnable = self.attrs.get("runnable")
        if runnable is None:
            if self.lang in COMMAND_LANGUAGES and self.body.strip():
                return "a command block without a mark (runnable=quick, runnable=long or runnable=no reason=...)"
            return None
        if runnable == "no":
            return None if self.attrs.get("reason") else 'runnable=no needs reason="why it is not run here"'
        if runnable not in DEFAULT_TIMEOUT:
            return f"runnable={runnable} (expected quick, long or no)"
        return None

    def is_python(self):
        return self.lang in ("python", "py")

    def name(self, root):
        return f"{os.path.relpath(self.path, root)}:{self.line}"

    def list_attr(self, key):
        return [v for v in self.attrs.get(key, "").split(",") if v]


def parse_blocks(path):
    """Every fenced block of a markdown file, with its info string; indented fences (in list items) are dedented."""
    blocks, lines = [], path.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, start = len(m["indent"]), m["fence"], i
        body = []
        i += 1
        while i < len(lines) and not (lines[i].strip().startswith(fence) and lines[i].strip().strip(fence[0]) == ""):
            body.append(lines[i][indent:] if lines[i][:indent].strip() == "" else lines[i])
            i += 1
        blocks.append(Block(path, start + 1, m["info"].strip(), "\n".join(body) + "\n"))
        i += 1
    return blocks


def make_scratch_root(source, build):
    """A folder that looks like the repository root to the blocks but keeps their writes out of the checkout."""
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="smcbench-docs-"))
    for entry in source.iterdir():
        if entry.name in ("build", "results", ".git"):
            continue
        (scratch / entry.name).symlink_to(entry)
    if (source / "results").is_dir():
        shutil.copytree(source / "results", scratch / "results", symlinks=True)
    (scratch / "build").mkdir()
    (scratch / "build" / "release").symlink_to(build)
    return scratch


def missing_need(need, scratch):
    """Why a block's requirement is not met here, or None."""
    if "/" in need:
        return None if (scratch / need).exists() else f"{need} is not built in this build"
    if shutil.which(need):
        return None
    return CANNOT_HAVE.get(need, f"'{need}' is not installed")


def inside(path, folder):
    try:
        path.relative_to(folder)
        return True
    except ValueError:
        return False


def run_block(block, scratch, source, klass, outputs):
    """(outcome, detail, seconds) for one block: outcome is passed, failed or skipped; its output goes to
    outputs[id] when the block has an id."""
    for need in block.list_attr("needs"):
        reason = missing_need(need, scratch)
        if reason:
            return "skipped", reason, 0.0
    writes = [scratch / w for w in block.list_attr("writes")]
    for w in writes:
        resolved = w.parent.resolve() / w.name
        if inside(resolved, source.resolve()) or not inside(resolved, scratch.resolve()):
            return "failed", f"writes={w.relative_to(scratch)} would land in the repository, not the scratch root", 0.0
        if resolved.is_dir():
            shutil.rmtree(resolved)
        elif resolved.exists():
            resolved.unlink()
    env = dict(os.environ)
    env["PATH"] = f"{scratch / 'build' / 'release' / 'tools'}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = str(scratch / "build" / "release" / "python")
    timeout = float(block.attrs.get("timeout") or DEFAULT_TIMEOUT[klass])
    expected = int(block.attrs.get("exit") or 0)
    command = (["/usr/bin/python3", "-c", block.body] if block.is_python()
               else ["bash", "-c", "set -euo pipefail\n" + block.body])
    start = time.monotonic()
    try:
        proc = subprocess.run(command, cwd=scratch, env=env,
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return "failed", f"did not finish within {timeout:g} s", time.monotonic() - start
    seconds = time.monotonic() - start
    output = proc.stdout.decode(errors="replace")
    if block.attrs.get("id"):
        outputs[block.attrs["id"]] = output
    tail = "\n".join(output.splitlines()[-15:])
    if proc.returncode != expected:
        return "failed", f"exit status {proc.returncode}, expected {expected}; output ends:\n{tail}", seconds
    for w in writes:
        if not w.exists() or (w.is_file() and w.stat().st_size == 0):
            return "failed", f"exit status {expected} but it did not write {w.relative_to(scratch)}", seconds
    return "passed", "", seconds


def check_quoted_output(files, source, outputs):
    """The numbers the pages quote from the output of the blocks just run (tools/docs_numbers.py), one line each."""
    if not outputs:
        return []
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))  # this checkout's checker
    import docs_numbers  # pylint: disable=import-outside-toplevel
    stale, summary = docs_numbers.check(files, source, outputs, only_outputs=True)
    for line in stale:
        print(f"FAILED {line}")
    print(summary.replace("docs numbers:", "docs numbers from block output:"))
    return stale


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source-dir", required=True, type=pathlib.Path)
    parser.add_argument("--build-dir", required=True, type=pathlib.Path)
    parser.add_argument("--class", dest="klass", choices=["quick", "long"], default="quick")
    parser.add_argument("--budget", type=float, default=0,
                        help="fail when the blocks together use more CPU time (s, user + system of the commands they "
                             "run: a measure of their work that a loaded machine does not inflate, as it does wall time)")
    parser.add_argument("--list-unmarked", action="store_true",
                        help="print the command blocks without an acceptable mark; exit 1 if there is one")
    parser.add_argument("--save-outputs", type=pathlib.Path,
                        help="write each run block's output with an id to DIR/ID.out (for docs_numbers.py --write)")
    parser.add_argument("files", nargs="*", type=pathlib.Path, help="default: README.md and docs/*.md")
    args = parser.parse_args()
    source, build = args.source_dir.resolve(), args.build_dir.resolve()
    files = args.files or [source / "README.md", *sorted((source / "docs").glob("*.md"))]
    blocks = [b for f in files for b in parse_blocks(f)]
    if args.list_unmarked:
        unmarked = [(b, b.mark_problem()) for b in blocks if b.mark_problem()]
        for b, problem in unmarked:
            print(f"unmarked: {b.name(source)}: {problem}")
        print(f"docs marks: {len(blocks)} blocks in {len(files)} files, {len(unmarked)} without an acceptable mark")
        return 1 if unmarked else 0
    bad = [b for b in blocks if "runnable" in b.attrs and b.mark_problem()]
    for b in bad:
        print(f"FAILED {b.name(source)}: {b.mark_problem()}")
    selected = [b for b in blocks if b.attrs.get("runnable") == args.klass]
    scratch = make_scratch_root(source, build)
    counts, total, skips, outputs = {"passed": 0, "failed": len(bad), "skipped": 0}, 0.0, [], {}
    cpu_start = os.times()
    try:
        for b in selected:
            outcome, detail, seconds = run_block(b, scratch, source, args.klass, outputs)
            counts[outcome] += 1
            total += seconds
            print(f"{outcome.upper():7} {b.name(source)} ({seconds:.1f} s){': ' + detail if detail else ''}",
                  flush=True)
            if outcome == "skipped":
                skips.append(detail)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    if args.save_outputs:
        args.save_outputs.mkdir(parents=True, exist_ok=True)
        for block_id, output in outputs.items():
            (args.save_outputs / f"{block_id}.out").write_text(output, encoding="utf-8")
    stale = check_quoted_output(files, source, outputs)
    cpu_end = os.times()
    cpu = (cpu_end.children_user - cpu_start.children_user) + (cpu_end.children_system - cpu_start.children_system)
    over = args.budget and cpu > args.budget
    if over:
        print(f"FAILED budget: the {args.klass} blocks used {cpu:.1f} s of CPU time, more than {args.budget:g} s")
    print(f"docs ({args.klass}): {len(selected)} blocks in {len(files)} files: {counts['passed']} passed, "
          f"{counts['skipped']} skipped, {counts['failed']} failed, "
          + (f"{len(stale)} stale quoted numbers, " if stale else "") + f"{total:.1f} s ({cpu:.1f} s CPU)"
          + (f" (skipped: {'; '.join(sorted(set(skips)))})" if skips else ""))
    return 1 if counts["failed"] or stale or over else 0


if __name__ == "__main__":
    sys.exit(main())
