"""`python -m smcbench ARGS` and the console command `smcbench ARGS` (pip's entry point, pyproject.toml): the C++
command-line program shipped inside this package (smcbench/bin/smcbench, see program()), run with ARGS in this
process's place, so both take every command and flag of the program and return its exit status. See
docs/python.md."""

import os
import sys
from typing import List, Optional


def program() -> str:
    """The path of the packaged command-line program: a copy (wheel), or a link to tools/smcbench (build tree) or
    to <prefix>/bin/smcbench (cmake --install)."""
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "smcbench")


def _environment() -> dict:
    """This environment, with the data folders the Python module finds (problems/io/data_dirs.h) passed on to the
    program: installed in a package, it sits one folder deeper than its own lookup searches for share/smcbench, so
    it is told SMCBENCH_SCENES_DIR and SMCBENCH_SICONOS_DIR (unless they are set already)."""
    from . import _smcbench

    env = dict(os.environ)
    for name in ("scenes", "siconos"):
        variable = f"SMCBENCH_{name.upper()}_DIR"
        if not env.get(variable):
            env[variable] = _smcbench._data_directory(name)
    return env


def main(argv: Optional[List[str]] = None) -> None:
    """Replace this process by the program with argv (default: this process's arguments); never returns."""
    path = program()
    if not os.access(path, os.X_OK):
        sys.exit(f"smcbench: the command-line program is not in this package ({path}): build it (cmake --build "
                 "build/release --target smcbench_python_cli), or install the package with pip or cmake --install")
    args = sys.argv[1:] if argv is None else list(argv)
    sys.stdout.flush()
    os.execve(path, [path] + args, _environment())


if __name__ == "__main__":
    main()
