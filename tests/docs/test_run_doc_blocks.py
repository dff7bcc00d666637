#!/usr/bin/python3
"""The docs runner itself: on a made-up repository it passes, fails and skips the blocks it should, and says why."""
import os
import pathlib
import subprocess
import sys
import tempfile

RUNNER = pathlib.Path(__file__).resolve().parent / "run_doc_blocks.py"

README = """# demo
```sh runnable=quick writes=out.txt
smcbench > out.txt   # the fake build's program, found on PATH
```

- in a list item:

  ```sh runnable=quick exit=3
  build/release/tools/smcbench; exit 3
  ```

```sh runnable=quick writes=never.txt
true   # claims to write never.txt and does not
```

```sh runnable=quick
false
```

```sh runnable=quick needs=sbatch-not-here,sbatch
sbatch job.sh
```

```sh runnable=quick writes=docs/escaped.txt
echo x > docs/escaped.txt
```

```sh runnable=long
sleep 100
```

```sh
echo unmarked, never run > unmarked.txt
```

```bash runnable=no reason="needs root (apt-get)"
apt-get install something
```

```python runnable=no
print("no reason given")
```

```text
output, not a command
```
"""

PYTHON_PAGE = """```python runnable=quick writes=py.txt
import os, sys
open("py.txt", "w").write(sys.executable + " " + os.environ["PYTHONPATH"])
```
"""


def run(args):
    proc = subprocess.run([sys.executable, str(RUNNER), *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, check=False)
    return proc.returncode, proc.stdout


def check(condition, message, output):
    if not condition:
        print(output)
        raise SystemExit(f"FAIL: {message}")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        root, build = pathlib.Path(tmp) / "repo", pathlib.Path(tmp) / "build"
        (root / "docs").mkdir(parents=True)
        (build / "tools").mkdir(parents=True)
        (root / "README.md").write_text(README, encoding="utf-8")
        program = build / "tools" / "smcbench"
        program.write_text("#!/bin/sh\necho hello from the build under test\n")
        program.chmod(0o755)

        status, out = run(["--source-dir", str(root), "--build-dir", str(build), "--class", "quick"])
        lines = [" ".join(l.split(None, 1)) for l in out.splitlines()]  # "PASSED  x" -> "PASSED x"
        check(status == 1, f"exit status {status}, expected 1 (three blocks fail)", out)
        check(any(l.startswith("PASSED README.md:2 ") for l in lines), "the block writing out.txt passes", out)
        check(any(l.startswith("PASSED README.md:8 ") for l in lines), "the indented block with exit=3 passes", out)
        check(any(l.startswith("FAILED README.md:12 ") and "did not write never.txt" in l for l in lines),
              "a missing written file fails", out)
        check(any(l.startswith("FAILED README.md:16 ") and "exit status 1, expected 0" in l for l in lines),
              "a failing command fails", out)
        check(any(l.startswith("SKIPPED README.md:20 ") and "'sbatch-not-here' is not installed" in l
                  for l in lines), "a missing tool skips with its reason", out)
        check(any(l.startswith("FAILED README.md:24 ") and "would land in the repository" in l for l in lines),
              "a write into the checkout is refused", out)
        check(not (root / "docs" / "escaped.txt").exists(), "the refused block was not run", out)
        check(any(l.startswith("FAILED README.md:40: runnable=no needs reason=") for l in lines),
              "runnable=no without a reason fails", out)
        check(lines[-1].startswith("docs (quick): 6 blocks in 1 files: 2 passed, 1 skipped, 4 failed"),
              "the summary counts", out)
        check(not (root / "out.txt").exists() and not (root / "unmarked.txt").exists(),
              "nothing is written into the repository", out)

        status, out = run(["--source-dir", str(root), "--build-dir", str(build), "--list-unmarked"])
        listed = [":".join(l.split(":")[:3]) for l in out.splitlines() if l.startswith("unmarked:")]
        check(status == 1 and listed == ["unmarked: README.md:32", "unmarked: README.md:40"],
              "the unmarked shell block and the reasonless runnable=no are listed (text and reasoned ones are not), "
              "and the listing fails", out)

        (root / "README.md").write_text(PYTHON_PAGE, encoding="utf-8")
        status, out = run(["--source-dir", str(root), "--build-dir", str(build)])
        check(status == 0 and "PASSED README.md:1 " in " ".join(out.split()), "a python block runs with python3", out)

        # The budget counts CPU time, not wall time: a block that waits is within it, one that works is not.
        (root / "README.md").write_text("```sh runnable=quick\nsleep 0.3\n```\n", encoding="utf-8")
        status, out = run(["--source-dir", str(root), "--build-dir", str(build), "--budget", "0.1"])
        check(status == 0 and "FAILED budget" not in out, "waiting is not CPU time", out)
        busy = "```sh runnable=quick\npython3 -c 'import time\nt = time.process_time()\nwhile time.process_time() - t < 0.3: pass'\n```\n"
        (root / "README.md").write_text(busy, encoding="utf-8")
        status, out = run(["--source-dir", str(root), "--build-dir", str(build), "--budget", "0.1"])
        check(status == 1 and "FAILED budget" in out and "of CPU time" in out, "the CPU-time budget is enforced", out)
    print("docs runner self-test: all checks passed")
    return 0


if __name__ == "__main__":
    os.environ.pop("CDPATH", None)
    sys.exit(main())
