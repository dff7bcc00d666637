"""`python -m smcbench ARGS` runs the command-line program packaged with the module (smcbench/bin/smcbench; in a build
tree a link to tools/smcbench) with ARGS: its help, its output, its exit status, and the data folders the module
finds (a scene by name, from a folder that is not the checkout)."""
import json
import os
import subprocess
import sys

import pytest

import smcbench
from smcbench import __main__ as entry


def python_m(*args, cwd):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.dirname(os.path.dirname(smcbench.__file__))
    for variable in ("SMCBENCH_SCENES_DIR", "SMCBENCH_SICONOS_DIR"):
        env.pop(variable, None)
    return subprocess.run([sys.executable, "-m", "smcbench", *args], cwd=cwd, env=env, capture_output=True, text=True)


@pytest.fixture
def packaged_program():
    if not os.access(entry.program(), os.X_OK):
        pytest.skip(f"no packaged program at {entry.program()} (target smcbench_python_cli)")


def test_help_and_exit_status_are_the_programs(packaged_program, tmp_path):
    done = python_m("--help", cwd=tmp_path)
    assert done.returncode == 0
    assert "Usage:" in done.stdout and "simulate" in done.stdout and "compare" in done.stdout
    refused = python_m("solve", "--solver", "nope", cwd=tmp_path)
    assert refused.returncode != 0 and refused.stdout + refused.stderr


def test_a_scene_by_name_is_found_from_any_folder(packaged_program, tmp_path):
    summary = tmp_path / "summary.json"
    done = python_m("simulate", "sign", "--h", "0.01", "--x0", "0.505", "--summary", str(summary), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    # S1 from 0.505 with h = 0.01: x = 0 exactly from step 51 on (docs/python.md's example).
    assert json.loads(summary.read_text(encoding="utf-8"))["reaching_step"] == 51


def test_the_data_folders_passed_on_are_the_modules(monkeypatch):
    monkeypatch.delenv("SMCBENCH_SCENES_DIR", raising=False)
    monkeypatch.setenv("SMCBENCH_SICONOS_DIR", "/elsewhere")
    env = entry._environment()
    assert env["SMCBENCH_SCENES_DIR"] == smcbench.scenes_directory()
    assert env["SMCBENCH_SICONOS_DIR"] == "/elsewhere", "a folder already set wins"
