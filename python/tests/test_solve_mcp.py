"""smcbench.solve_mcp with Python callables: every MCP backend on MCPs with closed-form solutions, dense and sparse
Jacobians, the variables' units, errors."""

import numpy as np
import pytest
import scipy.sparse

import smcbench
from mcp_problems import (CARDANO_L, CARDANO_SOLUTION, CARDANO_U, PLANTED_L, PLANTED_SOLUTION, PLANTED_U, ROOT,
                          cardano_F, cardano_J, mcp_backends, planted_F, planted_J)

# The MCP backends the library means to have, and whatever else the registry says solves MCPs: each is tested; one
# not registered in this build is skipped (asked of smcbench.solvers()).
PLANNED_MCP_BACKENDS = ["newton", "auto", "newton-min", "ipopt", "siconos-mcp-newton-fb", "siconos-mcp-newton-min"]
MCP_BACKENDS = PLANNED_MCP_BACKENDS + [name for name in mcp_backends() if name not in PLANNED_MCP_BACKENDS]


def registered(name):
    if name not in mcp_backends():
        pytest.skip(f"{name} does not solve MCPs in this build (smcbench.solvers())")


def test_cardano_root_is_a_root():
    assert abs(ROOT ** 3 + ROOT - 1.0) < 1e-15
    assert abs(ROOT - 0.6823278038280193) < 1e-15


@pytest.mark.parametrize("solver", MCP_BACKENDS)
def test_each_mcp_backend_finds_the_cardano_solution(solver):
    registered(solver)
    result = smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, z0=[0.5, 0.5, 0.0], solver=solver)
    assert result.solved, f"{solver}: {result.status} {result.message}"
    np.testing.assert_allclose(result.z, CARDANO_SOLUTION, rtol=0, atol=1e-8)
    np.testing.assert_allclose(result.w, cardano_F(result.z), rtol=0, atol=1e-12)
    assert result.residual_scaled <= 1e-10


@pytest.mark.parametrize("solver", MCP_BACKENDS)
def test_each_mcp_backend_finds_the_planted_solution(solver):
    registered(solver)
    result = smcbench.solve_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, z0=np.zeros(3), solver=solver)
    assert result.solved, f"{solver}: {result.status} {result.message}"
    np.testing.assert_allclose(result.z, PLANTED_SOLUTION, rtol=0, atol=1e-8)


def test_default_backend_is_auto_exactly_when_auto_solves_mcps():
    result = smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U)
    assert result.solver == ("auto" if "auto" in mcp_backends() else "newton")
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, CARDANO_SOLUTION, rtol=0, atol=1e-12)


def test_residual_scaled_is_the_verdicts_scale_free_residual():
    result = smcbench.solve_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, solver="newton")
    judged = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, result.z, result.status)
    assert result.residual_scaled == pytest.approx(judged["residual_scaled"], rel=1e-9, abs=1e-300)
    assert judged["verdict"] == "solved"


def test_nonlinear_mcp_dense_jacobian():
    result = smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, solver="newton")
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, CARDANO_SOLUTION, atol=1e-12)
    np.testing.assert_allclose(result.w, [0.0, ROOT + 1.0, 1.0 - 2.0 * ROOT], atol=1e-12)
    assert result.iterations >= 1


def test_nonlinear_mcp_sparse_jacobian_and_start_point():
    calls = []

    def sparse_J(z):
        calls.append(1)
        return scipy.sparse.csr_matrix(cardano_J(z))

    result = smcbench.solve_mcp(cardano_F, sparse_J, CARDANO_L, CARDANO_U, z0=[2.0, 1.0, 0.0], solver="newton")
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, CARDANO_SOLUTION, atol=1e-12)
    assert len(calls) >= 2  # the probe at z0 and at least one Newton iteration


def test_units_of_the_variables_reach_the_verdict():
    # z = S y with S = diag(1e-3, 1, 1e3): the MCP in y has G(y) = F(S y), dG/dy = J(S y) S and bounds l/S, u/S;
    # its answer is the one in z divided by S. The units c = 1/S reach the solve's scale-free residual: it is the
    # verdict's with the same units.
    S = np.array([1e-3, 1.0, 1e3])
    G = lambda y: planted_F(S * y)  # noqa: E731
    JG = lambda y: planted_J(S * y) * S  # noqa: E731
    result = smcbench.solve_mcp(G, JG, PLANTED_L / S, PLANTED_U / S, solver="newton", variable_scale=1.0 / S)
    assert result.solved, result.message
    np.testing.assert_allclose(result.z * S, PLANTED_SOLUTION, rtol=0, atol=1e-8)
    judged = smcbench.judge_mcp(G, JG, PLANTED_L / S, PLANTED_U / S, result.z, result.status, variable_scale=1.0 / S)
    assert result.residual_scaled == pytest.approx(judged["residual_scaled"], rel=1e-9, abs=1e-300)


def test_exception_in_the_callback_reaches_the_caller():
    def broken(z):
        raise RuntimeError("user model failed at this z")

    with pytest.raises(RuntimeError, match="user model failed"):
        smcbench.solve_mcp(broken, cardano_J, CARDANO_L, CARDANO_U)


def test_wrong_shapes_are_clear_errors():
    with pytest.raises(ValueError, match=r"F\(z\) returned 2 entries, expected 3"):
        smcbench.solve_mcp(lambda z: np.zeros(2), cardano_J, CARDANO_L, CARDANO_U)
    with pytest.raises(ValueError, match=r"J\(z\) returned a 2x2 matrix, expected 3x3"):
        smcbench.solve_mcp(cardano_F, lambda z: np.eye(2), CARDANO_L, CARDANO_U)
    with pytest.raises(smcbench.InvalidInputError, match="l has size 3 but u has size 2"):
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, [1.0, 1.0])
    with pytest.raises(smcbench.InvalidInputError, match="z0 has size 2 but the problem has 3 unknowns"):
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, z0=[0.0, 0.0])
    with pytest.raises(smcbench.InvalidInputError, match=r"variable_scale\[1\] = -1 must be finite and > 0"):
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, variable_scale=[1.0, -1.0, 1.0])


def test_nan_bound_names_the_bound():
    with pytest.raises(smcbench.InvalidInputError, match=r"u\[2\] is NaN"):
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, [np.inf, np.inf, np.nan])


def test_non_callable_F_or_J_is_named():
    with pytest.raises(smcbench.InvalidInputError, match="solve_mcp: F must be callable"):
        smcbench.solve_mcp(np.zeros(3), cardano_J, CARDANO_L, CARDANO_U)
    with pytest.raises(smcbench.InvalidInputError, match="solve_mcp: J must be callable"):
        smcbench.solve_mcp(cardano_F, "J", CARDANO_L, CARDANO_U)


def test_unknown_backend_lists_the_known_ones():
    with pytest.raises(smcbench.InvalidInputError, match="unknown solver 'nope'"):
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, solver="nope")


def test_backend_that_solves_no_mcp_is_refused_with_the_mcp_backends_named():
    with pytest.raises(smcbench.InvalidInputError, match="does not solve nonlinear MCPs") as error:
        smcbench.solve_mcp(cardano_F, cardano_J, CARDANO_L, CARDANO_U, solver="lemke")
    for name in mcp_backends():
        assert name in str(error.value)


@pytest.mark.parametrize("solver", MCP_BACKENDS)
def test_a_start_outside_the_box_is_projected_and_reported(solver):
    # F is NaN below z = -1 (log), so no backend could start from z0 = (-3, 20) itself; the box is [0, 10]^2 and the
    # unique solution (e^0.5 - 1, 0): F2 = z2 + 1 > 0 on the box puts z2 at its lower bound.
    registered(solver)
    F = lambda z: np.array([np.log(1 + z[0]) - 0.5, z[1] + 1])
    J = lambda z: np.diag([1 / (1 + z[0]), 1.0])
    result = smcbench.solve_mcp(F, J, [0, 0], [10, 10], z0=[-3.0, 20.0], solver=solver)
    assert result.solved, f"{solver}: {result.status} {result.message}"
    np.testing.assert_allclose(result.z, [np.exp(0.5) - 1, 0.0], rtol=0, atol=1e-8)
    assert result.details["start_projected"] == 2
    assert result.details["start_projection_distance"] == 10.0
