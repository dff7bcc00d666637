"""smcbench.judge_mcp (the MCP verdict, JudgeMCP) and smcbench.bench_mcp (a user's MCP suite on every MCP backend)."""

import threading

import numpy as np
import pandas as pd
import pytest
import scipy.sparse

import smcbench
from mcp_problems import (CARDANO_L, CARDANO_SOLUTION, CARDANO_U, PLANTED_L, PLANTED_SOLUTION, PLANTED_U, cardano_F,
                          cardano_J, mcp_backends, planted_F, planted_J)

# A linear F(z) = B (z - z_star) on two free rows with B nearly singular (det B = 1e-8): moving z by t along the
# null direction (1, -1) of the first row changes F by (0, -1e-8 t) only. The answer is unique, but ill-conditioned:
# μ = ‖(D⁻¹B)⁻¹‖∞ ≈ 2e8 (D the row scales, here 1 and 1 + 1e-8).
ILL_B = np.array([[1.0, 1.0], [1.0, 1.0 + 1e-8]])
ILL_SOLUTION = np.array([1.0, 2.0])
ILL_L = np.full(2, -np.inf)
ILL_U = np.full(2, np.inf)
ILL_CONDITION = np.abs(np.linalg.inv(np.diag(1.0 / np.array([1.0, 1.0 + 1e-8])) @ ILL_B)).sum(axis=1).max()


def ill_F(z):
    return ILL_B @ (z - ILL_SOLUTION)


def ill_J(z):
    return ILL_B.copy()


# --- judge_mcp -----------------------------------------------------------------------------------------------


def test_the_solution_is_solved_with_zero_forward_error():
    unique = [{"z": PLANTED_SOLUTION, "certificate": "unique"}]
    j = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, PLANTED_SOLUTION, "solved", references=unique,
                           expected="solvable")
    assert j["verdict"] == "solved" and not j["wrong"]
    assert j["residual_scaled"] == 0.0 and j["residual_abs"] == 0.0
    assert j["forward_error"] == 0.0
    # The allowance of docs/verdict.md: 10 · max(1, μ) · tol · (1 + ‖z*‖∞) with μ = 0 stated.
    assert j["forward_allowance"] == pytest.approx(10.0 * 1e-10 * 2.0, rel=1e-15)


def test_a_perturbed_answer_claimed_solved_is_wrongly_claimed():
    z = PLANTED_SOLUTION + np.array([1e-6, 0.0, 0.0])  # row 1 is interior: F_1 moves by about 4e-6
    j = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, z, "solved")
    assert j["verdict"] == "WRONGLY CLAIMED" and j["wrong"]
    # The scale-free residual by hand: row 1's scale d_1 = max_j |J_1j| at z, |F_1|/d_1 over 1 + ‖z‖∞.
    d1 = np.abs(planted_J(z)[0]).max()
    assert j["residual_scaled"] == pytest.approx(abs(planted_F(z)[0]) / d1 / (1.0 + np.abs(z).max()), rel=1e-9)
    # The same answer reported as not solved is an honest failure, not a wrong answer.
    j = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, z, "iteration_limit")
    assert j["verdict"] == "failed" and not j["wrong"]


def test_the_verdict_does_not_see_a_scaling_of_the_rows_of_F():
    z = PLANTED_SOLUTION + np.array([1e-6, -1e-7, 0.0])
    D = np.array([1e8, 1.0, 1e-8])
    plain = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, z, "solved")
    scaled = smcbench.judge_mcp(lambda x: D * planted_F(x), lambda x: D[:, None] * planted_J(x), PLANTED_L,
                                PLANTED_U, z, "solved")
    assert scaled["residual_scaled"] == pytest.approx(plain["residual_scaled"], rel=1e-12)
    assert scaled["verdict"] == plain["verdict"] == "WRONGLY CLAIMED"


def test_the_verdict_does_not_see_a_change_of_units_stated_through_variable_scale():
    # y = z / S: G(y) = F(S y), dG/dy = J(S y) S, bounds l / S, u / S, units c = 1 / S.
    S = np.array([1e-4, 1.0, 1e4])
    z = PLANTED_SOLUTION + np.array([1e-6, -1e-7, 0.0])
    plain = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, z, "solved")
    units = smcbench.judge_mcp(lambda y: planted_F(S * y), lambda y: planted_J(S * y) * S, PLANTED_L / S,
                               PLANTED_U / S, z / S, "solved", variable_scale=1.0 / S)
    assert units["residual_scaled"] == pytest.approx(plain["residual_scaled"], rel=1e-9)


def test_a_small_residual_far_from_a_unique_reference_is_inaccurate():
    # t = 1e-4 along the null direction: the scale-free residual is 1e-12 / (1 + 2) < tol, but z is 1e-4 away from
    # the unique solution. With the stated condition μ = 0 the allowance is 10 · tol · 3 = 3e-9: inaccurate.
    z = ILL_SOLUTION + 1e-4 * np.array([1.0, -1.0])
    j = smcbench.judge_mcp(ill_F, ill_J, ILL_L, ILL_U, z, "solved", references=[{"z": ILL_SOLUTION,
                                                                                   "certificate": "unique"}])
    assert j["residual_scaled"] <= 1e-10
    assert j["forward_error"] == pytest.approx(1e-4, rel=1e-9)
    assert j["verdict"] == "INACCURATE" and j["wrong"]
    # Stated with its true condition (μ ≈ 2e8) the allowance is 10 · μ · tol · 3 ≈ 0.6: the same z is solved.
    j = smcbench.judge_mcp(ill_F, ill_J, ILL_L, ILL_U, z, "solved",
                           references=[{"z": ILL_SOLUTION, "certificate": "unique", "condition": ILL_CONDITION}])
    assert 1e8 < ILL_CONDITION < 1e9
    assert j["verdict"] == "solved"


def test_an_isolated_reference_alone_defines_no_forward_error():
    z = ILL_SOLUTION + 1e-4 * np.array([1.0, -1.0])
    j = smcbench.judge_mcp(ill_F, ill_J, ILL_L, ILL_U, z, "solved", references=[ILL_SOLUTION])
    assert np.isnan(j["forward_error"])
    assert j["verdict"] == "solved"


def test_a_refusal_of_a_problem_known_solvable_is_wrongly_refused():
    j = smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "infeasible", expected="solvable")
    assert j["verdict"] == "WRONGLY REFUSED" and j["wrong"]


def test_judge_mcp_errors_name_the_field():
    with pytest.raises(smcbench.InvalidInputError, match="judge_mcp: z has size 2 but the problem has 3 unknowns"):
        smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(2), "solved")
    with pytest.raises(smcbench.InvalidInputError, match="judge_mcp: status: unknown status 'done'"):
        smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "done")
    with pytest.raises(smcbench.InvalidInputError, match="judge_mcp: expected: expected 'unknown'"):
        smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "solved", expected="maybe")
    with pytest.raises(smcbench.InvalidInputError, match=r"references\[0\].certificate: unknown certificate 'sure'"):
        smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "solved",
                           references=[{"z": PLANTED_SOLUTION, "certificate": "sure"}])
    with pytest.raises(smcbench.InvalidInputError, match=r"references\[0\].z has size 2"):
        smcbench.judge_mcp(planted_F, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "solved", references=[[1.0, 2.0]])
    with pytest.raises(smcbench.InvalidInputError, match="judge_mcp: F must be callable"):
        smcbench.judge_mcp(None, planted_J, PLANTED_L, PLANTED_U, np.zeros(3), "solved")


# --- bench_mcp -----------------------------------------------------------------------------------------------


def two_problem_suite():
    return [
        smcbench.McpProblem("cardano", cardano_F, cardano_J, CARDANO_L, CARDANO_U,
                            starts=[[0.0, 0.0, 0.0], [2.0, 1.0, -1.0]], solution=CARDANO_SOLUTION, tags=["classic"]),
        smcbench.McpProblem("planted", planted_F, lambda z: scipy.sparse.csc_matrix(planted_J(z)), PLANTED_L,
                            PLANTED_U, starts=[np.zeros(3), [1.0, -1.0, 1.0]], start_labels=["origin", "far corner"],
                            references=[{"z": PLANTED_SOLUTION, "certificate": "unique"}]),
    ]


def test_bench_mcp_has_one_row_per_problem_start_and_backend():
    backends = mcp_backends()
    frame = smcbench.bench_mcp(two_problem_suite(), repetitions=2)
    assert isinstance(frame, pd.DataFrame)
    assert len(frame) == 2 * 2 * len(backends)
    for column in ("problem", "start", "solver", "status", "verdict", "residual_scaled", "forward_error",
                   "time_median", "iterations"):
        assert column in frame.columns
    assert list(frame["problem"][:2 * len(backends)]) == ["cardano"] * (2 * len(backends))
    assert sorted(set(frame["start"])) == ["far corner", "origin", "start1", "start2"]
    assert set(frame["solver"]) == set(backends)
    # No backend may call a wrong answer solved; every solved answer is within its allowance of the solution.
    assert not frame["wrong"].any(), frame[["problem", "start", "solver", "verdict", "message"]]
    solved = frame[frame["verdict"] == "solved"]
    assert (solved["residual_scaled"] <= 1e-10).all()
    assert (solved["forward_error"] <= solved["forward_allowance"]).all()
    assert (frame["time_median"] > 0).all() and (frame["samples"] >= 1).all()
    assert (frame["time_min"] <= frame["time_median"]).all() and (frame["time_median"] <= frame["time_max"]).all()
    # newton, the reference MCP backend, solves both from every start.
    newton = frame[frame["solver"] == "newton"]
    assert (newton["verdict"] == "solved").all(), newton[["problem", "start", "status", "message"]]
    assert (newton["iterations"] >= 1).all()


def test_bench_mcp_judges_like_judge_mcp():
    # A "solution" stated wrong by 1e-3 makes every solved answer inaccurate: the same rule as judge_mcp's.
    wrong_solution = PLANTED_SOLUTION + np.array([1e-3, 0.0, 0.0])
    suite = [smcbench.McpProblem("planted", planted_F, planted_J, PLANTED_L, PLANTED_U, starts=[np.zeros(3)],
                                 solution=wrong_solution)]
    frame = smcbench.bench_mcp(suite, solvers=["newton"], repetitions=1)
    assert list(frame["verdict"]) == ["INACCURATE"]
    assert frame["forward_error"][0] == pytest.approx(1e-3, rel=1e-6)


def test_bench_mcp_without_starts_uses_the_projection_of_zero():
    suite = [smcbench.McpProblem("planted", planted_F, planted_J, PLANTED_L, PLANTED_U)]
    frame = smcbench.bench_mcp(suite, solvers="newton", repetitions=1)
    assert list(frame["start"]) == ["cold"] and list(frame["verdict"]) == ["solved"]
    assert list(frame["solver"]) == ["newton"]


def test_a_suite_problem_solves_from_each_of_its_starts():
    cardano, planted = two_problem_suite()
    for start in range(2):
        result = planted.solve(start=start, solver="newton")
        assert result.solved, result.message
        # To the solve's default tolerance, 1e-10 (newton's globalized path stops 1.4e-12 off from start 1).
        np.testing.assert_allclose(result.z, PLANTED_SOLUTION, rtol=0, atol=1e-10)
    np.testing.assert_allclose(cardano.solve(start=1).z, CARDANO_SOLUTION, rtol=0, atol=1e-12)


def test_bench_mcp_runs_beside_other_python_threads():
    # The timing loop releases the GIL and each callback takes it back: two benchmarks in two threads finish.
    frames = []

    def run():
        frames.append(smcbench.bench_mcp(two_problem_suite(), solvers=["newton"], repetitions=1))

    threads = [threading.Thread(target=run) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert len(frames) == 2
    for frame in frames:
        assert (frame["verdict"] == "solved").all()


def test_an_exception_in_F_ends_the_benchmark():
    def broken(z):
        raise RuntimeError("model undefined here")

    suite = [smcbench.McpProblem("broken", broken, planted_J, PLANTED_L, PLANTED_U, starts=[np.zeros(3)])]
    with pytest.raises(RuntimeError, match="model undefined here"):
        smcbench.bench_mcp(suite, solvers=["newton"], repetitions=1)


def test_bench_mcp_errors_name_the_problem_and_the_field():
    def problem(**changes):
        fields = dict(id="p", F=planted_F, J=planted_J, l=PLANTED_L, u=PLANTED_U, starts=[np.zeros(3)])
        fields.update(changes)
        return smcbench.McpProblem(**fields)

    cases = [
        ([problem(starts=[np.zeros(2)])], r"problems\[0\] \('p'\): starts\[0\] has size 2 but the problem has 3"),
        ([problem(l=[-1.0, np.nan, -1.0])], r"problems\[0\] \('p'\): MCP: l\[1\] is NaN"),
        ([problem(u=[1.0, 1.0])], r"problems\[0\] \('p'\): MCP: l has size 3 but u has size 2"),
        ([problem(F="planted_F")], r"problems\[0\] \('p'\): F must be callable"),
        ([problem(), problem()], r"problems\[1\] \('p'\): id 'p' is used twice"),
        ([problem(starts=[])], r"problems\[0\] \('p'\): starts is empty"),
        ([problem(start_labels=["a", "b"])], r"start_labels has 2 entries for 1 starts"),
        ([problem(starts=[[0.0, np.nan, 0.0]])], r"problems\[0\] \('p'\): starts\[0\]\[1\] is NaN"),
        ([problem(expected="probably")], r"problems\[0\] \('p'\): expected: expected 'unknown'"),
        ([problem(F=lambda z: np.zeros(4))], r"problems\[0\] \('p'\): F\(z\) returned 4 entries, expected 3"),
    ]
    for suite, message in cases:
        with pytest.raises(smcbench.InvalidInputError, match=message):
            smcbench.bench_mcp(suite, solvers=["newton"], repetitions=1)
    with pytest.raises(smcbench.InvalidInputError, match="unknown solver 'nope'"):
        smcbench.bench_mcp([problem()], solvers=["nope"])
    with pytest.raises(smcbench.InvalidInputError, match="backend 'lemke' does not solve nonlinear MCPs"):
        smcbench.bench_mcp([problem()], solvers=["lemke"])
    with pytest.raises(smcbench.InvalidInputError, match="repetitions must be >= 1"):
        smcbench.bench_mcp([problem()], repetitions=0)
    with pytest.raises(smcbench.InvalidInputError, match=r"problems\[0\] is a dict, expected McpProblem"):
        smcbench.bench_mcp([{"id": "p"}])


def test_bench_mcp_writes_a_results_folder_the_report_reads(tmp_path):
    frame = smcbench.bench_mcp(two_problem_suite(), solvers=["newton"], repetitions=1, out=tmp_path / "run")
    assert (tmp_path / "run" / "results.json").is_file() and (tmp_path / "run" / "results.csv").is_file()
    loaded = smcbench.load_bench_results(tmp_path / "run")
    assert list(loaded.suite.unique()) == ["python"] and set(loaded["mode"]) == {"cold"}
    key = ["problem", "start", "solver", "verdict", "status", "certificate", "tags"]
    pd.testing.assert_frame_equal(loaded[key].fillna(""), frame[key].fillna(""), check_dtype=False)
    # The known solutions are unique references: every record has its forward error, far inside the allowance.
    assert set(frame["certificate"]) == {"unique"}
    assert frame["forward_error"].notna().all() and (frame["forward_error"] <= frame["forward_allowance"]).all()
    assert list(frame["tags"][:2]) == ["classic", "classic"]
    text = smcbench.report(tmp_path / "run")
    assert "python" in text and "newton" in text
    assert smcbench.report(frame) == text, "the DataFrame knows its results"
