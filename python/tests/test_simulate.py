"""smcbench.simulate on the paper's scene S1 (sign): the finite-time arrival of Lemma (yahoo) of Acary &
Brogliato 2009, from the scene's name, its file and a dict."""
# The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.

import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import smcbench


def check_sign_run(run, x0, h):
    steps = int(round(2.0 / h))  # the scene's T = 2
    assert run.t.shape == (steps + 1,)
    assert run.x.shape == (steps + 1, 1) and run.s.shape == (steps + 1, 1) and run.y.shape == (steps + 1, 1)
    np.testing.assert_allclose(run.t, h * np.arange(steps + 1), atol=1e-12)
    x, s = run.x[:, 0], run.s[:, 0]
    # Implicit Euler on x' in -sgn(x): x_{k+1} = x_k - h s_{k+1}, s in Sgn(x_{k+1}). Before arrival s = 1 and x drops
    # by h per step; at k0 + 1 (k0 = ceil(x0/h) - 1) x is 0 and stays exactly 0, with |s| <= 1 (here s = x_k0 / h).
    # When x0/h is an integer the rounding of x_k0 - h can leave a residue of order 1e-16 at k0 + 1, zeroed the step
    # after (the C++ test scenes_test.cc SignSceneExactSolutionAndFiniteArrival allows k0 + 1 or k0 + 2 alike).
    k0 = math.ceil(x0 / h) - 1
    arrival = int(np.argmax(x == 0.0))
    assert arrival in (k0 + 1, k0 + 2)
    assert np.all(x[arrival:] == 0.0)
    assert np.all(x[: k0 + 1] > 0.0)
    assert np.all(np.abs(x[k0 + 1 : arrival]) <= 1e-14)
    np.testing.assert_allclose(s[1 : k0 + 1], 1.0, atol=1e-12)
    assert np.all(np.abs(s) <= 1.0 + 1e-12)
    np.testing.assert_allclose(np.diff(x[: k0 + 1]), -h, atol=1e-12)
    # y = C x = x for S1.
    np.testing.assert_array_equal(run.y[:, 0], x)
    return arrival


def test_registered_scene_reaches_the_surface_in_finite_time():
    run = smcbench.simulate("sign", x0=[0.505], h=0.01)
    arrival = check_sign_run(run, 0.505, 0.01)
    assert run.s[arrival, 0] == pytest.approx(0.5, abs=1e-9)  # the last step ends exactly on x = 0
    assert run.solver == "auto"
    assert run.summary["steps"] == 200
    assert run.summary["reaching_step"] == arrival
    assert run.summary["s_error_max"] <= 1e-12  # against the certified reference run
    assert all(st == "solved" for st in run.status[1:])


def test_scene_file_and_dict_give_the_same_trajectory(source_dir):
    path = source_dir / "problems" / "scenes" / "sign.json"
    from_file = smcbench.simulate(str(path), solver="lemke", reference=False)
    document = json.loads(path.read_text())
    document["simulation"]["x0"] = [0.3]
    document["name"] = "sign-from-dict"
    from_dict = smcbench.simulate(document, solver="lemke", reference=False)
    check_sign_run(from_file, 1.01, 0.01)
    check_sign_run(from_dict, 0.3, 0.01)
    assert from_dict.scene == "sign-from-dict"
    by_name = smcbench.simulate("sign", x0=[0.3], solver="lemke", reference=False)
    np.testing.assert_array_equal(by_name.x, from_dict.x)


def test_explicit_euler_chatters_where_implicit_rests():
    explicit = smcbench.simulate("sign", method="explicit", x0=[0.505])
    assert explicit.solver is None
    assert np.max(np.abs(explicit.x[-20:, 0])) > 1e-3  # oscillates around 0 with amplitude of order h


def test_bad_overrides_raise():
    with pytest.raises(ValueError, match="unknown scene 'nope'"):
        smcbench.simulate("nope")
    with pytest.raises(ValueError, match="unknown method 'sideways'"):
        smcbench.simulate("sign", method="sideways")
    with pytest.raises(ValueError, match="no parameter 'tau'"):
        smcbench.simulate("sign", parameters={"tau": 1.0})
    with pytest.raises(ValueError, match="h"):
        smcbench.simulate("sign", h=-1.0)
    with pytest.raises(TypeError, match="unknown override"):
        smcbench.simulate("sign", step=0.1)


def test_scene_list():
    names = smcbench.scenes()
    assert names[0] == "sign" and "observer" in names and "parasitic" in names


def cli_binary():
    """The smcbench program of the same build: $SMCBENCH_CLI (ctest sets it), else beside the module's build."""
    beside = pathlib.Path(smcbench.__file__).resolve().parents[2] / "tools" / "smcbench"
    path = os.environ.get("SMCBENCH_CLI") or str(beside)
    if not os.access(path, os.X_OK):
        pytest.skip(f"no smcbench program at {path} (set SMCBENCH_CLI)")
    return path


def cli_trajectory(tmp_path, *args):
    """`smcbench simulate ... --out CSV` read back: its header and its rows as floats (nan included)."""
    csv = tmp_path / "trajectory.csv"
    subprocess.run([cli_binary(), "simulate", *args, "--out", str(csv)], check=True, capture_output=True)
    lines = csv.read_text().splitlines()
    return lines[0].split(","), np.array([[float(v) for v in line.split(",")] for line in lines[1:]])


def columns(header, rows, prefix):
    return rows[:, [i for i, name in enumerate(header) if name.startswith(prefix) and name[len(prefix):].isdigit()]]


@pytest.mark.parametrize("scene", ["sign", "zoh-mimo"])
def test_u_is_the_input_the_cli_writes(tmp_path, scene):
    header, rows = cli_trajectory(tmp_path, scene, "--solver", "lemke")
    run = smcbench.simulate(scene, solver="lemke", reference=False)
    assert run.u is not None and run.u.shape == run.s.shape
    # The CSV's numbers are shortest round-trip text: the same doubles, bit for bit (NaN in the last row: no step
    # applies it).
    np.testing.assert_array_equal(run.t, rows[:, 0])
    np.testing.assert_array_equal(run.x, columns(header, rows, "x"))
    np.testing.assert_array_equal(run.u, columns(header, rows, "u"))
    assert np.all(np.isnan(run.u[-1])) and not np.any(np.isnan(run.u[:-1]))


def test_u_of_implicit_sign_is_minus_the_multiplier():
    # S1 is x' = u with u = -s, s in Sgn(x): implicit Euler's x_{k+1} = x_k + h u_k, u_k = -s_{k+1}.
    run = smcbench.simulate("sign", x0=[0.505], h=0.01, reference=False)
    np.testing.assert_array_equal(run.u[:-1, 0], -run.s[1:, 0])
    np.testing.assert_allclose(np.diff(run.x[:, 0]), 0.01 * run.u[:-1, 0], atol=1e-15)


def test_super_twisting_scene_returns_u_and_its_summary(tmp_path):
    # sigma' = u (no disturbance): sigma_{k+1} = sigma_k + h u_k; the implicit run reaches sigma = v = 0 exactly.
    run = smcbench.simulate("super-twisting", reference=False)
    assert run.solver is None and run.u is not None and run.x.shape == (run.t.shape[0], 2)
    np.testing.assert_allclose(np.diff(run.x[:, 0]), 0.01 * run.u[:-1, 0], atol=1e-15)
    st = run.summary["super_twisting"]
    assert st["convergence_step"] is not None and st["max_abs_sigma_tail"] == 0.0
    assert np.all(run.x[st["convergence_step"] + 1 :] == 0.0)
    # The same scene as a dict, and the MCP route on newton: the same trajectory.
    document = json.loads((pathlib.Path(smcbench.scenes_directory()) / "super-twisting.json").read_text())
    via_mcp = smcbench.simulate(document, algorithm="mcp", reference=False)
    assert via_mcp.solver == "newton"
    np.testing.assert_allclose(via_mcp.x, run.x, atol=1e-8)
    # The CLI writes the same u.
    header, rows = cli_trajectory(tmp_path, "super-twisting")
    np.testing.assert_array_equal(run.u, columns(header, rows, "u"))


def test_plant_rows_between_samples_are_the_cli_rows(tmp_path, source_dir):
    scene = str(source_dir / "problems" / "scenes" / "smc-disturbed.json")
    header, rows = cli_trajectory(tmp_path, scene, "--T", "0.1", "--plant-substeps", "10")
    run = smcbench.simulate(scene, T=0.1, plant_substeps=10, reference=False)
    plant = run.plant
    assert plant is not None and plant.t.shape == (10 * 10 + 1,)
    np.testing.assert_array_equal(plant.t, rows[:, 0])
    for name in ("x", "s", "y", "u"):
        np.testing.assert_array_equal(getattr(plant, name), columns(header, rows, name), err_msg=name)
    # Every 10th row is a sample of the run itself.
    np.testing.assert_array_equal(plant.x[::10], run.x)
    np.testing.assert_array_equal(plant.u[::10], run.u)
    assert smcbench.simulate(scene, T=0.1, reference=False).plant is None


def test_plant_substeps_follow_the_cli_rules():
    with pytest.raises(ValueError, match="plant_substeps 3 needs method zoh or zoh-explicit"):
        smcbench.simulate("zoh-siso", method="implicit", plant_substeps=3)
    with pytest.raises(ValueError, match="plant_substeps must be an integer >= 1, got 0"):
        smcbench.simulate("zoh-siso", plant_substeps=0)
    with pytest.raises(ValueError, match="max_iterations must be an integer >= 0"):
        smcbench.simulate("sign", max_iterations=-1)
    run = smcbench.simulate("sign", gamma=0.5, reference=False)
    assert run.notes == ["gamma has no effect on a linear scene (g(x) = B is constant)"]
