"""MCPs without a hand-written Jacobian (J=None: complex step or central differences), the derivative test that
flags a wrong J, and McpProblem starts with None entries. The reference answer is Josephy's NCP (MCPLIB `josephy`),
whose unique solution (√6/2, 0, 0, 1/2) is known in closed form, and the same solve with the analytic J."""

import warnings

import numpy as np
import pytest

import smcbench

JOSEPHY_SOLUTION = np.array([np.sqrt(6.0) / 2.0, 0.0, 0.0, 0.5])
L = np.zeros(4)
U = np.full(4, np.inf)


def josephy_F(x):
    return np.array([3 * x[0] ** 2 + 2 * x[0] * x[1] + 2 * x[1] ** 2 + x[2] + 3 * x[3] - 6,
                     2 * x[0] ** 2 + x[0] + x[1] ** 2 + 3 * x[2] + 2 * x[3] - 2,
                     3 * x[0] ** 2 + x[0] * x[1] + 2 * x[1] ** 2 + 2 * x[2] + 3 * x[3] - 1,
                     x[0] ** 2 + 3 * x[1] ** 2 + 2 * x[2] + 3 * x[3] - 3])


def josephy_J(x):
    return np.array([[6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3],
                     [4 * x[0] + 1, 2 * x[1], 3, 2],
                     [6 * x[0] + x[1], x[0] + 4 * x[1], 2, 3],
                     [2 * x[0], 6 * x[1], 2, 3]], dtype=float)


def josephy_F_real_only(x):
    """The same F, but forcing float64: complex input loses its imaginary part (auto must fall back to central)."""
    return josephy_F(np.asarray(x, dtype=np.float64))


@pytest.mark.parametrize("derivatives,F,method", [("auto", josephy_F, "complex-step"),
                                                  ("auto", josephy_F_real_only, "central"),
                                                  ("complex-step", josephy_F, "complex-step"),
                                                  ("central", josephy_F, "central")])
def test_no_jacobian_solves_josephy_as_the_analytic_one(derivatives, F, method):
    start = np.ones(4)
    by_hand = smcbench.solve_mcp(josephy_F, josephy_J, L, U, z0=start, solver="newton")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy's ComplexWarning while auto probes josephy_F_real_only
        result = smcbench.solve_mcp(F, None, L, U, z0=start, solver="newton", derivatives=derivatives)
    assert by_hand.solved and result.solved, result.message
    assert result.details["jacobian"] == method
    np.testing.assert_allclose(result.z, JOSEPHY_SOLUTION, rtol=0, atol=1e-9)
    np.testing.assert_allclose(result.z, by_hand.z, rtol=0, atol=1e-9)


def test_default_backend_without_jacobian():
    result = smcbench.solve_mcp(josephy_F, None, 0.0, U, z0=np.ones(4))
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, JOSEPHY_SOLUTION, rtol=0, atol=1e-9)


def test_central_differences_stay_in_the_box():
    # F is undefined below 0 (sqrt): at z = 0 on the bound, the difference must be taken forward.
    def F(z):
        if np.any(z < 0):
            raise ValueError(f"F called outside the box at {z}")
        return np.sqrt(z + 1.0) - 2.0

    result = smcbench.solve_mcp(F, None, 0.0, np.full(2, np.inf), z0=np.zeros(2), solver="newton",
                                derivatives="central")
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, [3.0, 3.0], rtol=0, atol=1e-9)


def test_derivative_test_flags_a_wrong_jacobian():
    def wrong_J(x):
        J = josephy_J(x)
        J[1, 2] = 30.0  # a slip: 3 written as 30
        return J

    with pytest.warns(RuntimeWarning, match=r"derivative check: J\[1, 2\] = 30"):
        result = smcbench.solve_mcp(josephy_F, wrong_J, L, U, z0=np.ones(4), solver="newton", derivative_test=True)
    assert result.message.startswith("derivative check: J[1, 2] = 30 but central differences give 3")
    assert result.details["derivative_check_error"] > 1.0


def test_derivative_test_passes_a_right_jacobian():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = smcbench.solve_mcp(josephy_F, josephy_J, L, U, z0=np.ones(4), solver="newton", derivative_test=True)
    assert result.solved
    assert not result.message.startswith("derivative check")
    assert result.details["derivative_check_error"] < 1e-6


def test_derivative_options_are_checked():
    with pytest.raises(smcbench.InvalidInputError, match="derivatives must be one of"):
        smcbench.solve_mcp(josephy_F, None, L, U, derivatives="forward")
    with pytest.raises(smcbench.InvalidInputError, match="applies when J is None"):
        smcbench.solve_mcp(josephy_F, josephy_J, L, U, derivatives="central")
    with pytest.raises(smcbench.InvalidInputError, match="F must be callable"):
        smcbench.solve_mcp(None, None, L, U)


def test_mcp_problem_starts_may_hold_none():
    problem = smcbench.McpProblem("josephy", josephy_F, None, L, U, starts=[None, np.ones(4)],
                                  solution=JOSEPHY_SOLUTION)
    df = smcbench.bench_mcp([problem], solvers="newton", repetitions=1)
    assert list(df["start"]) == ["start1", "start2"]
    assert list(df["verdict"]) == ["solved", "solved"], list(df["message"])
    assert problem.solve(start=0, solver="newton").solved
    judged = smcbench.judge_mcp(josephy_F, None, L, U, JOSEPHY_SOLUTION, references=[JOSEPHY_SOLUTION])
    assert judged["verdict"] == "solved"
