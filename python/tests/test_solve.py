"""smcbench.solve against hand-computed solutions, across backends, dense and sparse, and its errors."""

import numpy as np
import pytest
import scipy.sparse

import smcbench


def test_solvers_lists_backends_with_capabilities():
    backends = {b["name"]: b for b in smcbench.solvers()}
    for name in ("lemke", "psor", "newton", "enum", "ipopt", "auto"):
        assert name in backends
    assert backends["newton"]["sparse"] and backends["newton"]["mcp"]
    assert backends["lemke"]["exact"] and not backends["psor"]["exact"]
    assert "omega" in backends["psor"]["options"]


@pytest.mark.parametrize("solver", ["auto", "lemke", "enum", "newton", "psor"])
def test_two_by_two_lcp_interior_solution(solver):
    # M z + q = 0 with z > 0: 2 z1 + z2 = 5, z1 + 2 z2 = 6  ->  z = (4/3, 7/3), w = 0.
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    result = smcbench.solve(M, [-5.0, -6.0], solver=solver)
    assert result.solved and result.status == "solved"
    np.testing.assert_allclose(result.z, [4 / 3, 7 / 3], rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.w, [0.0, 0.0], atol=1e-12)
    assert result.residual_rel <= 1e-10
    assert result.time_seconds > 0


def test_two_by_two_lcp_one_row_at_its_bound():
    # Guess z2 = 0: 2 z1 - 1 = 0 -> z1 = 1/2, and w2 = z1 + 3 = 3.5 >= 0: complementary, so z = (1/2, 0).
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    result = smcbench.solve(M, np.array([-1.0, 3.0]), solver="lemke")
    assert result.solved
    np.testing.assert_allclose(result.z, [0.5, 0.0], atol=1e-14)
    np.testing.assert_allclose(result.w, [0.0, 3.5], atol=1e-14)


def test_auto_reports_the_backend_it_chose():
    result = smcbench.solve(np.array([[2.0, 1.0], [1.0, 2.0]]), [-5.0, -6.0])
    assert result.solver == "auto"
    assert result.chosen in ("enum", "psor", "lemke", "newton")
    # The detail is the backend's name, not a number standing for it.
    assert result.details["chosen"] == result.chosen
    assert result.details["fallbacks"] == 0.0


def test_code_details_are_names_and_measurements_numbers():
    # One free row (l = -inf, u = +inf) with M_FF = 2 well conditioned: lemke eliminates it by a Schur complement.
    # z1 free: 2 z1 + z2 = 5; z2 >= 0: z1 + 2 z2 - 6 >= 0 complementary -> z = (4/3, 7/3) with w2 = 0.
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    result = smcbench.solve(M, [-5.0, -6.0], l=[-np.inf, 0.0], u=[np.inf, np.inf], solver="lemke")
    assert result.solved
    np.testing.assert_allclose(result.z, [4 / 3, 7 / 3], atol=1e-12)
    assert result.details["free_row_mode"] == "schur"
    assert isinstance(result.details["lcp_size"], float) and result.details["lcp_size"] == 1.0
    # Without free rows the detail is absent, and a backend other than auto has no choice.
    plain = smcbench.solve(M, [-5.0, -6.0], solver="lemke")
    assert "free_row_mode" not in plain.details
    assert plain.chosen is None


def test_fortran_order_and_integer_matrix_are_copied_correctly():
    # A nonsymmetric M: a transposed read would give another solution.
    M = np.asfortranarray(np.array([[3, 1], [0, 2]]))  # int dtype, column-major
    result = smcbench.solve(M, [-4.0, -2.0], solver="lemke")
    # 3 z1 + z2 = 4, 2 z2 = 2 -> z = (1, 1).
    np.testing.assert_allclose(result.z, [1.0, 1.0], atol=1e-14)


def relay_problem():
    # Planted: z* = (0.5, -1, 0.25) with M SPD (so a P-matrix: unique solution). M z* = (1, -2.25, -0.5);
    # rows 1 and 3 interior need w = 0, row 2 at l = -1 needs w >= 0: take w* = (0, 1.5, 0), q = w* - M z*.
    M = np.array([[4.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 2.0]])
    z_star = np.array([0.5, -1.0, 0.25])
    q = np.array([0.0, 1.5, 0.0]) - M @ z_star
    return M, q, z_star


def test_lemke_enum_psor_agree_on_a_relay_problem():
    M, q, z_star = relay_problem()
    answers = {}
    for solver in ("lemke", "enum", "psor"):
        result = smcbench.solve(M, q, -1.0, 1.0, solver=solver)
        assert result.solved, (solver, result.status, result.message)
        answers[solver] = result.z
        np.testing.assert_allclose(result.z, z_star, atol=1e-10)
    np.testing.assert_allclose(answers["lemke"], answers["enum"], atol=1e-12)
    np.testing.assert_allclose(answers["psor"], answers["enum"], atol=1e-10)


def test_backend_options_are_passed_through():
    M, q, z_star = relay_problem()
    # Over-relaxation changes the sweeps PSOR takes on this problem (omega = 1: Gauss-Seidel, 2 sweeps here).
    gauss_seidel = smcbench.solve(M, q, -1.0, 1.0, solver="psor", omega=1.0)
    relaxed = smcbench.solve(M, q, -1.0, 1.0, solver="psor", omega=1.2)
    assert gauss_seidel.solved and relaxed.solved
    assert relaxed.iterations > gauss_seidel.iterations
    np.testing.assert_allclose(relaxed.z, z_star, atol=1e-10)
    # The same backend with a too small iteration budget and no polish stops short.
    short = smcbench.solve(M, q, -1.0, 1.0, solver="psor", polish=False, max_iterations=1)
    assert not short.solved and short.status == "iteration_limit"


def test_sparse_matrix_through_newton():
    # Tridiagonal SPD M (m = 200), planted LCP solution: even rows interior (w = 0), odd rows at 0 with w > 0.
    m = 200
    M = scipy.sparse.diags([-np.ones(m - 1), 4.0 * np.ones(m), -np.ones(m - 1)], [-1, 0, 1], format="csr")
    k = np.arange(m)
    z_star = np.where(k % 2 == 0, 1.0 + 0.01 * k, 0.0)
    w_star = np.where(k % 2 == 0, 0.0, 0.5 + 0.001 * k)
    q = w_star - M @ z_star
    result = smcbench.solve(M, q, solver="newton")
    assert result.solved, result.message
    np.testing.assert_allclose(result.z, z_star, atol=1e-10)
    np.testing.assert_allclose(result.w, w_star, atol=1e-9)
    # auto sends a sparse M to newton.
    assert smcbench.solve(M.tocoo(), q).chosen == "newton"


def test_free_rows_with_infinite_bounds():
    # l = -inf, u = inf on every row: the linear system M z + q = 0.
    M = np.array([[2.0, 1.0], [1.0, 3.0]])
    result = smcbench.solve(M, [1.0, 2.0], -np.inf, np.inf, solver="lemke")
    assert result.solved
    np.testing.assert_allclose(result.z, np.linalg.solve(M, [-1.0, -2.0]), atol=1e-14)


@pytest.mark.parametrize("kwargs, message", [
    (dict(M=np.eye(2), q=[1.0, np.nan]), "BoxMLCP: q[1] is NaN"),
    (dict(M=np.array([[1.0, np.nan], [0.0, 1.0]]), q=[1.0, 1.0]), "NaN"),
    (dict(M=np.eye(2), q=[1.0, 1.0, 1.0]), "3"),
    (dict(M=np.eye(2), q=[1.0, 1.0], l=[0.0, 0.0, 0.0]), "BoxMLCP: l has size 3 but M is 2x2"),
    (dict(M=np.eye(2), q=[1.0, 1.0], l=[0.0, 2.0], u=[1.0, 1.0]), "l[1] = 2 > u[1] = 1"),
    (dict(M=np.eye(2), q=[1.0, 1.0], solver="nope"), "unknown solver 'nope' (known: lemke"),
    (dict(M=np.eye(2), q=[1.0, 1.0], solver="psor", bogus=1), "psor: unknown option 'bogus'"),
    (dict(M=np.eye(2), q=[1.0, 1.0], solver="psor", omega="fast"), "omega"),
    (dict(M=np.eye(2), q=[1.0, 1.0], tol=-1.0), "tolerance"),
    (dict(M=np.ones(3), q=[1.0, 1.0]), "M: expected a 2-D array"),
])
def test_invalid_input_raises_value_error_with_the_library_message(kwargs, message):
    with pytest.raises(ValueError) as error:
        smcbench.solve(**kwargs)
    assert message in str(error.value)
    assert isinstance(error.value, smcbench.InvalidInputError)
