""".smcps problem sets: write from Python, read back bit for bit; read the committed version-1 test file."""

import numpy as np
import pytest
import scipy.sparse

import smcbench


def test_write_read_round_trip(tmp_path):
    dense = smcbench.Problem(id="py/dense/1", M=np.array([[2.0, 1.0], [1.0, 2.0]]), q=np.array([-5.0, -6.0]),
                             l=np.array([0.0, -np.inf]), u=np.array([np.inf, 1.5]), tags=["hand", "lcp"], seed=7,
                             expected="solvable", solution=np.array([1.75, 1.5]),
                             metadata={"note": "hand-computed"}, matrix={"symmetric": "yes"})
    sparse_M = scipy.sparse.csc_matrix(np.array([[4.0, 0.0, -1.0], [0.0, 3.0, 0.0], [-1.0, 0.0, 5.0]]))
    sparse = {"id": "py/sparse/1", "M": sparse_M, "q": [1.0, -3.0, 0.1 + 0.2], "l": -1.0, "u": 1.0}
    path = tmp_path / "set.smcps"
    smcbench.write_problem_set(path, [dense, sparse], name="roundtrip", description="two problems")
    problems = smcbench.read_problem_set(path)
    assert problems.name == "roundtrip" and problems.description == "two problems"
    assert [p.id for p in problems] == ["py/dense/1", "py/sparse/1"]
    a, b = problems
    np.testing.assert_array_equal(a.M, dense.M)
    np.testing.assert_array_equal(a.q, dense.q)
    np.testing.assert_array_equal(a.l, dense.l)
    np.testing.assert_array_equal(a.u, dense.u)
    np.testing.assert_array_equal(a.solution, dense.solution)
    assert a.tags == ["hand", "lcp"] and a.seed == 7 and a.expected == "solvable"
    assert a.metadata == {"note": "hand-computed"} and a.matrix["symmetric"] == "yes"
    assert scipy.sparse.issparse(b.M)
    np.testing.assert_array_equal(b.M.toarray(), sparse_M.toarray())
    assert b.q[2] == 0.1 + 0.2  # every bit kept
    np.testing.assert_array_equal(b.l, [-1.0] * 3)
    assert b.seed is None and b.solution is None
    # The problem read back solves to its hand-computed solution: with z2 <= 1.5 the LCP's (4/3, 7/3) is cut off;
    # z2 = u2 = 1.5 gives 2 z1 + 1.5 - 5 = 0, z1 = 1.75 > 0 (w1 = 0), and w2 = 1.75 + 3 - 6 = -1.25 <= 0 at u2.
    result = a.solve("lemke")
    np.testing.assert_allclose(result.z, a.solution, atol=1e-14)
    np.testing.assert_allclose(result.w, [0.0, -1.25], atol=1e-14)


def test_duplicate_ids_are_refused(tmp_path):
    p = {"id": "same", "M": np.eye(1), "q": [1.0]}
    with pytest.raises(ValueError, match="same"):
        smcbench.write_problem_set(tmp_path / "dup.smcps", [p, dict(p)])
    assert not (tmp_path / "dup.smcps").exists()


def test_read_committed_version_1_file(source_dir):
    problems = smcbench.read_problem_set(source_dir / "problems" / "library" / "testdata" / "format-v1-sign.smcps")
    assert problems.version == 1
    assert len(problems) >= 1
    for p in problems:
        assert p.M.shape == (p.q.shape[0], p.q.shape[0])
        assert p.l.shape == p.q.shape == p.u.shape


def test_unreadable_file_raises(tmp_path):
    bad = tmp_path / "bad.smcps"
    bad.write_bytes(b"not a problem set")
    with pytest.raises(ValueError, match="bad.smcps"):
        smcbench.read_problem_set(bad)
