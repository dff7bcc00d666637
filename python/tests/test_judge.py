"""smcbench.judge gives one box-MLCP answer the verdict `smcbench bench` gives it (Judge, docs/verdict.md) against
a certified reference: the library's when none is given, else the given z* certified; solve(..., reference=...)
reports the verdict and forward error. The answers are computed here by hand."""
import math

import numpy as np
import pytest

import smcbench

M = np.array([[2.0, 1.0], [1.0, 2.0]])
Q = np.array([-5.0, -6.0])
Z_STAR = np.linalg.solve(M, -Q)  # both rows strictly positive: the LCP's only solution (M is positive definite)


def test_the_exact_answer_is_solved_against_the_librarys_unique_reference():
    j = smcbench.judge(M, Q, None, None, Z_STAR)
    assert j["verdict"] == "solved" and not j["wrong"]
    assert j["reference"]["certificate"] == "unique"
    np.testing.assert_allclose(j["reference"]["z"], Z_STAR, rtol=0, atol=1e-15)
    assert j["reference"]["proved_unique"] and j["reference"]["proved_radius"] < 1e-12
    assert j["forward_error"] <= 1e-15 and j["forward_allowance"] > 0


def test_an_answer_off_by_1e_6_claimed_solved_is_wrongly_claimed_with_its_forward_error():
    j = smcbench.judge(M, Q, None, None, Z_STAR + [1e-6, 0.0])
    assert j["verdict"] == "WRONGLY CLAIMED" and j["wrong"]
    assert j["forward_error"] == pytest.approx(1e-6, rel=1e-6)
    # The same point at a tolerance it meets: solved (the allowance grows with tol).
    assert smcbench.judge(M, Q, None, None, Z_STAR + [1e-6, 0.0], tol=1e-5)["verdict"] == "solved"


def test_a_given_reference_is_certified_from_its_active_set():
    j = smcbench.judge(M, Q, 0, np.inf, Z_STAR, reference=Z_STAR + 1e-12)
    assert j["reference"]["certificate"] == "unique" and j["forward_error"] <= 1e-15
    # z = 0 is no solution (w = q < 0): the certifier moves on from its active set to the solution and proves it.
    moved = smcbench.judge(M, Q, 0, np.inf, Z_STAR, reference=[0.0, 0.0])
    np.testing.assert_allclose(moved["reference"]["z"], Z_STAR, rtol=0, atol=1e-15)


def test_no_forward_error_where_the_solution_is_not_unique():
    # M = [[1, 1], [1, 1]], q = (-1, -1): every z >= 0 with z1 + z2 = 1 solves it.
    ones = np.ones((2, 2))
    j = smcbench.judge(ones, [-1.0, -1.0], None, None, [0.5, 0.5])
    assert j["verdict"] == "solved" and j["reference"]["certificate"] == "non-unique"
    assert math.isnan(j["forward_error"]) and math.isnan(j["forward_allowance"])


def test_relay_bounds_and_refusals():
    # Relay -1 <= z <= 1, M z + q with q = (3, -2): z = (-1, 1), w = (2, -1) (docs/python.md's example).
    z = np.array([-1.0, 1.0])
    assert smcbench.judge(M, [3.0, -2.0], -1, 1, z)["verdict"] == "solved"
    assert smcbench.judge(M, [3.0, -2.0], -1, 1, z, status="iteration_limit")["verdict"] == "failed"
    # Claiming infeasible on a problem the certifier solves: wrongly refused.
    assert smcbench.judge(M, [3.0, -2.0], -1, 1, z, status="infeasible")["verdict"] == "WRONGLY REFUSED"


def test_solve_reports_verdict_and_forward_error_when_asked():
    plain = smcbench.solve(M, Q, solver="lemke")
    assert plain.verdict is None and plain.forward_error is None and plain.reference is None
    r = smcbench.solve(M, Q, solver="lemke", reference=True)
    assert r.verdict == "solved" and r.forward_error <= 1e-14 and r.reference["certificate"] == "unique"
    given = smcbench.solve(M, Q, solver="psor", tol=1e-6, reference=Z_STAR, polish=False)
    assert given.forward_error == pytest.approx(np.max(np.abs(given.z - Z_STAR)), abs=1e-15)


def test_bad_input_names_the_field():
    with pytest.raises(smcbench.InvalidInputError, match="judge: z has size 3"):
        smcbench.judge(M, Q, None, None, [1.0, 2.0, 3.0])
    with pytest.raises(smcbench.InvalidInputError, match="judge: status"):
        smcbench.judge(M, Q, None, None, Z_STAR, status="done")
    with pytest.raises(smcbench.InvalidInputError, match="judge: reference has size 1"):
        smcbench.judge(M, Q, None, None, Z_STAR, reference=[1.0])
    with pytest.raises(smcbench.InvalidInputError, match="judge: expected"):
        smcbench.judge(M, Q, None, None, Z_STAR, expected="maybe")
    with pytest.raises(smcbench.InvalidInputError, match="judge: tol"):
        smcbench.judge(M, Q, None, None, Z_STAR, tol=0.0)
    with pytest.raises(smcbench.InvalidInputError, match="q\\[1\\] is NaN"):
        smcbench.judge(M, [1.0, np.nan], None, None, Z_STAR)
