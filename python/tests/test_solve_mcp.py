"""smcbench.solve_mcp with Python callables: a hand-checked nonlinear MCP, dense and sparse Jacobians, errors."""

import numpy as np
import pytest
import scipy.sparse

import smcbench

# The real root of r^3 + r - 1 = 0 by Cardano's formula (one real root since the discriminant is positive).
_D = np.sqrt(0.25 + 1.0 / 27.0)
ROOT = np.cbrt(0.5 + _D) + np.cbrt(0.5 - _D)


def F(z):
    # Row 1 free (F_1 = 0): z1^3 + z1 - 1 = 0 -> z1 = ROOT. Row 2 with l = 0: F_2 = z2^3 + z1 + 1 > 0 at z2 = 0
    # (z1 = ROOT > 0), so z2 = 0 and F_2 = ROOT + 1. Row 3 in [-1, 1]: F_3 = z3 - 2 z1 vanishes at z3 = 2 ROOT
    # = 1.36 > 1, so z3 = u = 1 with F_3 = 1 - 2 ROOT < 0 (the upper-bound sign).
    return np.array([z[0] ** 3 + z[0] - 1.0, z[1] ** 3 + z[0] + 1.0, z[2] - 2.0 * z[0]])


def J(z):
    return np.array([[3.0 * z[0] ** 2 + 1.0, 0.0, 0.0], [1.0, 3.0 * z[1] ** 2, 0.0], [-2.0, 0.0, 1.0]])


L = [-np.inf, 0.0, -1.0]
U = [np.inf, np.inf, 1.0]
EXPECTED = [ROOT, 0.0, 1.0]


def test_cardano_root_is_a_root():
    assert abs(ROOT ** 3 + ROOT - 1.0) < 1e-15
    assert abs(ROOT - 0.6823278038280193) < 1e-15


def test_nonlinear_mcp_dense_jacobian():
    result = smcbench.solve_mcp(F, J, L, U)
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, EXPECTED, atol=1e-12)
    np.testing.assert_allclose(result.w, [0.0, ROOT + 1.0, 1.0 - 2.0 * ROOT], atol=1e-12)
    assert result.iterations >= 1


def test_nonlinear_mcp_sparse_jacobian_and_start_point():
    calls = []

    def sparse_J(z):
        calls.append(1)
        return scipy.sparse.csr_matrix(J(z))

    result = smcbench.solve_mcp(F, sparse_J, L, U, z0=[2.0, 1.0, 0.0])
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, EXPECTED, atol=1e-12)
    assert len(calls) >= 2  # the probe at z0 and at least one Newton iteration


def test_exception_in_the_callback_reaches_the_caller():
    def broken(z):
        raise RuntimeError("user model failed at this z")

    with pytest.raises(RuntimeError, match="user model failed"):
        smcbench.solve_mcp(broken, J, L, U)


def test_wrong_shapes_are_clear_errors():
    with pytest.raises(ValueError, match=r"F\(z\) returned 2 entries, expected 3"):
        smcbench.solve_mcp(lambda z: np.zeros(2), J, L, U)
    with pytest.raises(ValueError, match=r"J\(z\) returned a 2x2 matrix, expected 3x3"):
        smcbench.solve_mcp(F, lambda z: np.eye(2), L, U)


def test_backend_that_solves_no_mcp_is_refused():
    with pytest.raises(ValueError, match="does not solve nonlinear MCPs"):
        smcbench.solve_mcp(F, J, L, U, solver="lemke")
