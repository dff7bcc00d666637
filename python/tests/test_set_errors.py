"""A bad problem inside a Python-built set: the error names the problem by its index and id, whether the set is
written (write_problem_set) or benchmarked (bench with a list of Problem)."""

import numpy as np
import pytest

import smcbench


def problems():
    good = smcbench.Problem("good", np.eye(2), np.array([1.0, -1.0]), np.array([-1.0, -1.0]), np.array([1.0, 1.0]))
    bad = smcbench.Problem("bad", np.eye(2), np.array([1.0, -1.0]), np.array([0.0, 2.0]), np.array([1.0, 1.0]))
    return [good, bad]


def test_write_problem_set_names_the_bad_problem(tmp_path):
    with pytest.raises(smcbench.InvalidInputError,
                       match=r"^problems\[1\] \('bad'\): BoxMLCP: l\[1\] = 2 > u\[1\] = 1"):
        smcbench.write_problem_set(str(tmp_path / "set.smcps"), problems())
    assert not (tmp_path / "set.smcps").exists()


def test_bench_names_the_bad_problem():
    with pytest.raises(smcbench.InvalidInputError, match=r"problems\[1\] \('bad'\): BoxMLCP: l\[1\] = 2 > u\[1\] = 1"):
        smcbench.bench(problems(), solvers="enum", repetitions=1, quick=True, warm=False)
