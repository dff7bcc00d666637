"""smcbench.AffineVI, solve_avi, read_avi and write_avi: a planted AVI's λ and the KKT conditions recomputed here in
numpy, the twisting parallelogram worked by hand, the AVI file's round trip, and the errors."""

import numpy as np
import pytest

import smcbench

# Implicit twisting's parallelogram |λ₁| ≤ 1, |λ₂ − (h/2)λ₁| ≤ 1 with h = 0.1, as rows of H λ ≥ K.
PARALLELOGRAM_H = np.array([[1.0, 0.0], [-1.0, 0.0], [-0.05, 1.0], [0.05, -1.0]])
PARALLELOGRAM_K = -np.ones(4)


def kkt_violation(avi, lam, mu, nu):
    """The largest violation of M λ + q − Hᵀμ − Eᵀν = 0, μ ≥ 0, H λ ≥ K, μ ⟂ H λ − K, E λ = f, from the data."""
    stationarity = avi.M @ lam + avi.q - avi.H.T @ mu - avi.E.T @ nu
    slack = avi.H @ lam - avi.K
    parts = [np.abs(stationarity).max(initial=0.0), max(0.0, -mu.min(initial=0.0)),
             max(0.0, -slack.min(initial=0.0)), np.abs(mu * slack).max(initial=0.0),
             np.abs(avi.E @ lam - avi.f).max(initial=0.0)]
    return max(parts)


def planted_avi(seed, n=4, m=3, active=2, p=1):
    """λ* and μ* ≥ 0 on `active` rows chosen first, then q := −M λ* + Hᵀμ* + Eᵀν*; M + Mᵀ positive definite, so
    λ* is the only solution. The box λ* ± 2 keeps P bounded."""
    rng = np.random.default_rng(seed)
    lam = rng.uniform(-1, 1, n)
    H = np.vstack([rng.uniform(-1, 1, (m, n)), np.eye(n), -np.eye(n)])
    K = np.concatenate([H[:m] @ lam - np.r_[np.zeros(active), rng.uniform(0.2, 1.0, m - active)],
                        lam - 2.0, -lam - 2.0])
    mu = np.r_[rng.uniform(0.5, 2.0, active), np.zeros(m - active + 2 * n)]
    E = rng.uniform(-1, 1, (p, n))
    f = E @ lam
    nu = rng.uniform(-1, 1, p)
    A, S = rng.uniform(-1, 1, (n, n)), rng.uniform(-1, 1, (n, n))
    M = A.T @ A / n + 0.5 * np.eye(n) + (S - S.T)
    q = -M @ lam + H.T @ mu + E.T @ nu
    return smcbench.AffineVI(M, q, H, K, E, f, name=f"planted-{seed}"), lam, mu, nu


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_planted_avi_lambda_and_kkt(seed):
    avi, lam_star, mu_star, nu_star = planted_avi(seed)
    assert kkt_violation(avi, lam_star, mu_star, nu_star) < 1e-12  # the plant itself
    r = smcbench.solve_avi(avi, solver="lemke", tol=1e-10)
    assert r.solved and r.verdict == "solved", r.message
    assert r.expected == "solvable"
    assert r.lambda_.shape == (4,) and r.mu.shape == (3 + 8,) and r.nu.shape == (1,)
    np.testing.assert_allclose(r.lambda_, lam_star, atol=1e-10)
    assert kkt_violation(avi, r.lambda_, r.mu, r.nu) < 1e-10
    # Strictly complementary and with independent active rows, so the multipliers are unique too.
    np.testing.assert_allclose(r.mu, mu_star, atol=1e-9)
    np.testing.assert_allclose(r.nu, nu_star, atol=1e-9)
    assert r.reduced.z.shape == (4 + 11 + 1,)
    # With the plant as reference: its forward error is judged and within the tolerance's reach.
    judged = smcbench.solve_avi(avi, reference=lam_star)
    assert judged.reference_certificate not in (None, "none")
    assert judged.forward_error is not None and judged.forward_error < 1e-9


def test_twisting_parallelogram_projection_by_hand():
    # The projection of c onto the parallelogram (M = I, q = −c). c = (2, 3): λ = (1, 1.05) on rows 1 and 3, and
    # λ − c = (−1, −1.95) = Hᵀμ gives μ₃ = 1.95, μ₁ = 1 + 0.05·1.95 = 1.0975.
    avi = smcbench.AffineVI(np.eye(2), -np.array([2.0, 3.0]), PARALLELOGRAM_H, PARALLELOGRAM_K,
                            name="twisting-projection")
    for solver in ("lemke", "enum"):
        r = smcbench.solve_avi(avi, solver=solver)
        assert r.verdict == "solved", (solver, r.message)
        np.testing.assert_allclose(r.lambda_, [1.0, 1.05], atol=1e-12)
        np.testing.assert_allclose(r.mu, [0.0, 1.0975, 0.0, 1.95], atol=1e-12)
        assert r.nu.shape == (0,)
    # A point inside P is its own projection, with no active row.
    inside = smcbench.AffineVI(np.eye(2), -np.array([0.5, -0.2]), PARALLELOGRAM_H, PARALLELOGRAM_K)
    r = smcbench.solve_avi(inside)
    np.testing.assert_allclose(r.lambda_, [0.5, -0.2], atol=1e-14)
    np.testing.assert_allclose(r.mu, np.zeros(4), atol=1e-14)


def test_properties_are_the_data():
    M = np.array([[2.0, 1.0], [0.0, 3.0]], dtype=np.float32)  # any float dtype, copied as float64
    avi = smcbench.AffineVI(M, [1.0, -1.0], PARALLELOGRAM_H, PARALLELOGRAM_K, name="props")
    np.testing.assert_array_equal(avi.M, M.astype(np.float64))
    np.testing.assert_array_equal(avi.H, PARALLELOGRAM_H)
    assert avi.E.shape == (0, 2) and avi.f.shape == (0,)
    assert (avi.n, avi.m, avi.p, avi.name) == (2, 4, 0, "props")
    assert avi.boundedness == "bounded" and avi.expected == "solvable"
    assert np.all(avi.H @ avi.feasible_point - avi.K >= -1e-9)
    assert repr(avi) == "AffineVI(name='props', n=2, m=4, p=0)"
    free = smcbench.AffineVI(np.eye(2), [1.0, 2.0])  # no rows at all: P = R², the linear system λ = −q
    assert free.boundedness == "unbounded" and free.expected == "unknown"
    np.testing.assert_allclose(smcbench.solve_avi(free).lambda_, [-1.0, -2.0], atol=1e-14)
    assert "feasible_point" in smcbench.AffineVI.__doc__ and "lambda_" in smcbench.AviResult.__doc__


def test_no_solution_is_never_claimed(tmp_path):
    # λ ≥ 0, M = 0, q = −1: (x − λ)ᵀ(−1) ≥ 0 for every x ≥ 0 is impossible; P is unbounded, expected unknown.
    avi = smcbench.AffineVI(np.zeros((1, 1)), [-1.0], np.eye(1), [0.0])
    r = smcbench.solve_avi(avi)
    assert not r.solved
    assert r.expected == "unknown" and r.verdict == "failed"  # not known to have no solution: a plain failure
    # Stated as infeasible (in the call, or in its file), the same refusal is correct.
    assert smcbench.solve_avi(avi, expected="infeasible").verdict == "correctly refused"
    path = tmp_path / "none.avi.json"
    smcbench.write_avi(avi, path, expected="infeasible")
    f = smcbench.read_avi(path)
    assert f.expected == "infeasible"
    assert smcbench.solve_avi(f.avi, expected=f.expected).verdict == "correctly refused"
    with pytest.raises(ValueError, match="expected: 'solvable', 'infeasible' or 'unknown', got 'maybe'"):
        smcbench.solve_avi(avi, expected="maybe")


def test_file_round_trip_bit_for_bit(tmp_path):
    avi, lam_star, _, _ = planted_avi(7)
    path = tmp_path / "planted.avi.json"
    smcbench.write_avi(avi, path, solution=lam_star)
    back, solution, expected = smcbench.read_avi(path)
    assert expected == "solvable"
    for name in ("M", "q", "H", "K", "E", "f"):
        a, b = getattr(avi, name), getattr(back, name)
        assert a.tobytes() == b.tobytes(), name  # every bit, signed zeros included
    assert solution.tobytes() == lam_star.tobytes()
    assert back.name == "planted-7"
    smcbench.write_avi(avi, tmp_path / "bare.avi.json")
    assert smcbench.read_avi(tmp_path / "bare.avi.json").solution is None


def test_the_docs_example_file(source_dir):
    avi, solution, _ = smcbench.read_avi(source_dir / "problems" / "io" / "testdata" / "twisting-projection.avi.json")
    assert avi.name == "twisting-projection" and (avi.n, avi.m, avi.p) == (2, 4, 0)
    np.testing.assert_array_equal(solution, [1.0, 1.05])
    np.testing.assert_allclose(smcbench.solve_avi(avi).lambda_, solution, atol=1e-12)


def test_errors_carry_the_cpp_message(tmp_path):
    with pytest.raises(ValueError, match=r"q\[1\] is NaN|q.*NaN"):
        smcbench.AffineVI(np.eye(2), [1.0, np.nan], PARALLELOGRAM_H, PARALLELOGRAM_K)
    with pytest.raises(smcbench.InvalidInputError, match="H"):
        smcbench.AffineVI(np.eye(2), [1.0, 2.0], np.ones((2, 3)), [0.0, 0.0])
    with pytest.raises(ValueError, match="is empty"):
        smcbench.AffineVI(np.eye(1), [0.0], [[1.0], [-1.0]], [1.0, 0.0])  # λ ≥ 1 and λ ≤ 0
    with pytest.raises(ValueError, match="E and f come together"):
        smcbench.AffineVI(np.eye(2), [1.0, 2.0], E=[[1.0, 1.0]])
    avi = smcbench.AffineVI(np.eye(2), [1.0, 2.0], PARALLELOGRAM_H, PARALLELOGRAM_K)
    with pytest.raises(ValueError, match="unknown"):
        smcbench.solve_avi(avi, solver="no-such-backend")
    with pytest.raises(ValueError, match=r"start has size 3, expected n = 2 \(λ\) or n \+ m \+ p = 6"):
        smcbench.solve_avi(avi, start=[0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="reference has size 1"):
        smcbench.solve_avi(avi, reference=[0.0])
    bad = tmp_path / "bad.avi.json"
    bad.write_text('{"format": "smcbench-avi", "version": 1, "M": [[1]], "q": ["nan"], "H": [], "K": []}')
    with pytest.raises(ValueError, match=r"AVI file '.*bad.avi.json': \"q\[0\]\": expected a number, got string"):
        smcbench.read_avi(bad)
    with pytest.raises(ValueError, match="solution has 3 entries"):
        smcbench.write_avi(avi, tmp_path / "x.avi.json", solution=[1.0, 2.0, 3.0])
