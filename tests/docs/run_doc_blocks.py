#!/usr/bin/python3
"""Runs the code blocks that README.md and docs/*.md mark runnable, so every printed command is known to work.

Convention (docs/documentation.md): a fenced block whose info string carries `runnable=quick` or `runnable=long` is
run with bash (`set -euo pipefail`) from a scratch copy of the repository root, as a reader would run it there:
    ```sh runnable=quick writes=sign.smcps,out/index.csv needs=gnuplot exit=1 timeout=120
- writes=PATH[,PATH]: files the block says it writes; each must exist and be non-empty afterwards (and must not be
  in the repository itself: a test never dirties the checkout);
- needs=TOOL[,TOOL]: programs (looked up on PATH) or files relative to the root; when one is missing the block is
  skipped, not failed, and the summary says why;
- exit=N: the exit status the block must end with (default 0); timeout=S: seconds (default 60 quick, 3600 long).
Blocks without `runnable=` are not run; `--list-unmarked` prints the shell blocks that carry no mark.

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
import shutil
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
DEFAULT_TIMEOUT = {"quick": 60, "long": 3600}
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
        self.lang = info.split()[0] if info.split() else ""
        self.attrs = {}
        for word in info.split()[1:]:
            key, _, value = word.partition("=")
            self.attrs[key] = value

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


def run_block(block, scratch, source, klass):
    """(outcome, detail, seconds) for one block: outcome is passed, failed or skipped."""
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
    timeout = float(block.attrs.get("timeout") or DEFAULT_TIMEOUT[klass])
    expected = int(block.attrs.get("exit") or 0)
    start = time.monotonic()
    try:
        proc = subprocess.run(["bash", "-c", "set -euo pipefail\n" + block.body], cwd=scratch, env=env,
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return "failed", f"did not finish within {timeout:g} s", time.monotonic() - start
    seconds = time.monotonic() - start
    tail = "\n".join(proc.stdout.decode(errors="replace").splitlines()[-15:])
    if proc.returncode != expected:
        return "failed", f"exit status {proc.returncode}, expected {expected}; output ends:\n{tail}", seconds
    for w in writes:
        if not w.exists() or (w.is_file() and w.stat().st_size == 0):
            return "failed", f"exit status {expected} but it did not write {w.relative_to(scratch)}", seconds
    return "passed", "", seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source-dir", required=True, type=pathlib.Path)
    parser.add_argument("--build-dir", required=True, type=pathlib.Path)
    parser.add_argument("--class", dest="klass", choices=["quick", "long"], default="quick")
    parser.add_argument("--budget", type=float, default=0, help="fail when the blocks together take longer (s)")
    parser.add_argument("--list-unmarked", action="store_true", help="print the shell blocks carrying no mark")
    parser.add_argument("files", nargs="*", type=pathlib.Path, help="default: README.md and docs/*.md")
    args = parser.parse_args()
    source, build = args.source_dir.resolve(), args.build_dir.resolve()
    files = args.files or [source / "README.md", *sorted((source / "docs").glob("*.md"))]
    blocks = [b for f in files for b in parse_blocks(f)]
    if args.list_unmarked:
        for b in blocks:
            if b.lang in ("sh", "bash", "") and "runnable" not in b.attrs and b.body.strip():
                print(f"unmarked: {b.name(source)}")
        return 0
    bad = [b for b in blocks if "runnable" in b.attrs and b.attrs["runnable"] not in DEFAULT_TIMEOUT]
    for b in bad:
        print(f"FAILED {b.name(source)}: runnable={b.attrs['runnable']} (expected quick or long)")
    selected = [b for b in blocks if b.attrs.get("runnable") == args.klass]
    scratch = make_scratch_root(source, build)
    counts, total, skips = {"passed": 0, "failed": len(bad), "skipped": 0}, 0.0, []
    try:
        for b in selected:
            outcome, detail, seconds = run_block(b, scratch, source, args.klass)
            counts[outcome] += 1
            total += seconds
            print(f"{outcome.upper():7} {b.name(source)} ({seconds:.1f} s){': ' + detail if detail else ''}",
                  flush=True)
            if outcome == "skipped":
                skips.append(detail)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    over = args.budget and total > args.budget
    if over:
        print(f"FAILED budget: the {args.klass} blocks took {total:.1f} s, more than {args.budget:g} s")
    print(f"docs ({args.klass}): {len(selected)} blocks in {len(files)} files: {counts['passed']} passed, "
          f"{counts['skipped']} skipped, {counts['failed']} failed, {total:.1f} s"
          + (f" (skipped: {'; '.join(sorted(set(skips)))})" if skips else ""))
    return 1 if counts["failed"] or over else 0


if __name__ == "__main__":
    sys.exit(main())
