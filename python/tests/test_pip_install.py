"""pip install of the checkout as a Python user runs it (docs/python.md, "Build, import, install"): a fresh virtual
environment seeing Debian's packages, `pip install --no-build-isolation --no-deps --no-index <checkout>` (offline),
then, from an unrelated folder with no PYTHONPATH, `import smcbench` must come from the environment, solve an LCP
whose answer is computed here independently, and simulate a registered scene read from the environment's own
share/smcbench/scenes; the console command `smcbench` and `python -m smcbench` must run the packaged command-line
program, which finds the environment's data folders too.

Run by ctest as python_pip_install (SMCBENCH_BUILD_DIR: package the module the build tree built) and
python_pip_install_standalone (label slow: setup.py configures and builds its own tree). Not collected by
python_tests (--ignore), since it builds."""

import json
import os
import pathlib
import subprocess
import sys
import sysconfig

import numpy as np

SOURCE_DIR = pathlib.Path(os.environ.get("SMCBENCH_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))

# What the installed module is asked; it prints JSON for the checks below.
PROBE = r"""
import json, sys
import numpy as np
import smcbench
M = np.array([[2.0, 1.0], [1.0, 2.0]])
r = smcbench.solve(M, [-5.0, -6.0], solver="lemke")
run = smcbench.simulate("sign", h=0.01, x0=[0.505])
json.dump({"file": smcbench.__file__, "status": r.status, "z": r.z.tolist(), "w": r.w.tolist(),
           "scenes": smcbench.scenes_directory(), "reaching_step": run.summary["reaching_step"]}, sys.stdout)
"""


def run(command, **kwargs):
    done = subprocess.run(command, capture_output=True, text=True, **kwargs)
    assert done.returncode == 0, f"{command} failed ({done.returncode}):\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done.stdout


def test_pip_install_into_a_venv_then_import_and_solve_elsewhere(tmp_path):
    venv = tmp_path / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)])
    python = venv / "bin" / "python"

    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SMCBENCH_SCENES_DIR", "SMCBENCH_SICONOS_DIR")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index", str(SOURCE_DIR)],
        env=env, cwd=tmp_path)

    # The installed distribution: the compiled module, every python/smcbench/*.py, and the data folders.
    files = run([str(python), "-m", "pip", "show", "--files", "smcbench"], env=env, cwd=tmp_path)
    listed = {line.strip() for line in files.splitlines()}
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    expected = {"smcbench/_smcbench" + suffix, "smcbench/bin/smcbench"}
    expected |= {"smcbench/" + p.name for p in (SOURCE_DIR / "python" / "smcbench").glob("*.py")}
    assert expected <= listed, f"missing from the installed files: {sorted(expected - listed)}"
    data = venv / "share" / "smcbench"
    assert (data / "scenes" / "sign.json").is_file()
    assert (data / "siconos" / "LICENSE").is_file() and (data / "siconos" / "lcp" / "lcp_CPS_3.dat").is_file()

    # From an unrelated folder: nothing of the checkout on the path, the scenes found beside the installed module.
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    probe = json.loads(run([str(python), "-c", PROBE], env=env, cwd=elsewhere))
    assert pathlib.Path(probe["file"]).resolve().is_relative_to(venv.resolve()), probe["file"]
    assert pathlib.Path(probe["scenes"]).resolve() == (data / "scenes").resolve()

    # 2 z1 + z2 = 5, z1 + 2 z2 = 6 with z > 0: both rows active, z = M^-1 (-q), w = 0 (computed here, not by smcbench).
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    z_star = np.linalg.solve(M, [5.0, 6.0])
    assert probe["status"] == "solved"
    np.testing.assert_allclose(probe["z"], z_star, rtol=0, atol=1e-12)
    np.testing.assert_allclose(probe["w"], [0.0, 0.0], rtol=0, atol=1e-12)
    # S1 x' in -sgn(x) from 0.505 with h = 0.01: x loses h per step and is exactly 0 from step 51 on (docs/python.md).
    assert probe["reaching_step"] == 51

    # The command-line program: the console command and python -m run it with their arguments, from elsewhere.
    command = venv / "bin" / "smcbench"
    for program in ([str(command)], [str(python), "-m", "smcbench"]):
        help_text = run(program + ["--help"], env=env, cwd=elsewhere)
        assert "simulate" in help_text and "bench" in help_text and "report" in help_text, help_text
    # A registered scene by name: the program finds the environment's share/smcbench/scenes.
    summary = elsewhere / "summary.json"
    run([str(command), "simulate", "sign", "--h", "0.01", "--x0", "0.505", "--summary", str(summary)], env=env,
        cwd=elsewhere)
    assert json.loads(summary.read_text(encoding="utf-8"))["reaching_step"] == 51
    failed = subprocess.run([str(python), "-m", "smcbench", "solve", "--solver", "nope"], env=env, cwd=elsewhere,
                            capture_output=True, text=True)
    assert failed.returncode != 0, "the program's exit status comes back through python -m"
