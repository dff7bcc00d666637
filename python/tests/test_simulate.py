"""smcbench.simulate on the paper's scene S1 (sign): the finite-time arrival of Lemma (yahoo) of Acary &
Brogliato 2009, from the scene's name, its file and a dict."""
# The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.

import json
import math

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
