"""Sets of AVIs (.smcps format version 4) from Python: read_problem_set returns AviProblem objects, write_problem_set
writes AffineVI / AviProblem objects; round trips bit for bit (the committed v4 file re-written identically), an AVI
read back solved and its KKT conditions recomputed in numpy, `smcbench library --certify` and `solve --id` on a set
made here, bench on it, and the errors."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import smcbench

BOX_H = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])  # 0 <= λ <= 1
BOX_K = np.array([0.0, -1.0, 0.0, -1.0])


def kkt_violation(avi, lam, mu, nu):
    """The largest violation of M λ + q − Hᵀμ − Eᵀν = 0, μ ≥ 0, H λ ≥ K, μ ⟂ H λ − K, E λ = f, from the data."""
    stationarity = avi.M @ lam + avi.q - avi.H.T @ mu - avi.E.T @ nu
    slack = avi.H @ lam - avi.K
    return max(np.abs(stationarity).max(initial=0.0), max(0.0, -mu.min(initial=0.0)),
               max(0.0, -slack.min(initial=0.0)), np.abs(mu * slack).max(initial=0.0),
               np.abs(avi.E @ lam - avi.f).max(initial=0.0))


def hand_made_avis():
    """The projection of (0.7, 0.1) onto the unit box ∩ {λ₁ + λ₂ = 1}: (0.8, 0.2); of (2, 3) onto the box: (1, 1)."""
    segment = smcbench.AffineVI(np.eye(2), [-0.7, -0.1], BOX_H, BOX_K, E=[[1.0, 1.0]], f=[1.0], name="hand/segment")
    corner = smcbench.AffineVI(np.eye(2), [-2.0, -3.0 - 1e-15], BOX_H, BOX_K, name="corner")
    return segment, corner, {"hand/segment": [0.8, 0.2], "hand/corner": [1.0, 1.0]}


def smcbench_cli():
    """The smcbench program of the same build: $SMCBENCH_CLI (ctest sets it), else beside the module's build."""
    beside = pathlib.Path(smcbench.__file__).resolve().parents[2] / "tools" / "smcbench"
    path = os.environ.get("SMCBENCH_CLI") or str(beside)
    if not os.path.exists(path):
        pytest.skip(f"no smcbench program at {path} (set SMCBENCH_CLI)")
    return path


def test_avis_written_from_python_read_back_bit_for_bit(tmp_path):
    segment, corner, _ = hand_made_avis()
    problems = [segment,  # a bare AffineVI: its name is its id
                smcbench.AviProblem(id="hand/corner", avi=corner, source="hand-made:corner", tags=["box"],
                                    expected="solvable", metadata={"why": "a corner"})]
    path = tmp_path / "avis.smcps"
    smcbench.write_problem_set(path, problems, name="hand-made", description="two AVIs")
    back = smcbench.read_problem_set(path)
    assert back.kind == "avi" and back.version == 4
    assert back.name == "hand-made" and back.description == "two AVIs"
    assert [p.id for p in back] == ["hand/segment", "hand/corner"]
    a, b = back
    assert isinstance(a, smcbench.AviProblem) and isinstance(a.avi, smcbench.AffineVI)
    for original, read in ((segment, a.avi), (corner, b.avi)):
        for key in ("M", "q", "H", "K", "E", "f"):
            np.testing.assert_array_equal(getattr(read, key), getattr(original, key))
    assert b.avi.q[1] == -3.0 - 1e-15  # every bit kept
    assert b.avi.name == "corner"  # named apart from its id
    assert a.source == "python" and a.expected == "solvable"  # avi.expected on a bounded P
    assert b.source == "hand-made:corner" and b.tags == ["box"] and b.metadata == {"why": "a corner"}
    assert a.reference["certificate"] == "none" and a.reference["lambda_"] is None
    # Written back as read, the file is the same bytes.
    again = tmp_path / "again.smcps"
    smcbench.write_problem_set(again, back, name=back.name, description=back.description)
    assert again.read_bytes() == path.read_bytes()


def test_the_committed_v4_set_rewrites_identically_and_its_references_solve(source_dir, tmp_path):
    committed = source_dir / "problems" / "library" / "testdata" / "avi-small-v4.smcps"
    problems = smcbench.read_problem_set(committed)
    assert problems.kind == "avi" and problems.version == 4
    out = tmp_path / "copy.smcps"
    smcbench.write_problem_set(out, problems, name=problems.name, description=problems.description)
    assert out.read_bytes() == committed.read_bytes()
    verified = [p for p in problems if p.reference["lambda_"] is not None]
    assert verified
    for p in verified:
        ref = p.reference
        assert ref["certificate"] not in ("none", "none found")
        np.testing.assert_array_equal(ref["lambda_"], ref["z"][:p.avi.n])
        # The stored λ*, μ*, ν* meet the KKT conditions recomputed from the stored data.
        assert kkt_violation(p.avi, ref["lambda_"], ref["mu"], ref["nu"]) <= 1e-12, p.id


def test_an_avi_read_back_solves_and_meets_the_kkt_conditions(tmp_path):
    segment, corner, answers = hand_made_avis()
    path = tmp_path / "avis.smcps"
    smcbench.write_problem_set(path, [segment, smcbench.AviProblem(id="hand/corner", avi=corner)])
    for p in smcbench.read_problem_set(path):
        result = p.solve("lemke")
        assert result.status == "solved" and result.verdict == "solved", p.id
        assert result.expected == "solvable"
        assert kkt_violation(p.avi, result.lambda_, result.mu, result.nu) <= 1e-12, p.id
        np.testing.assert_allclose(result.lambda_, answers[p.id], atol=1e-12)


def test_a_set_made_in_python_is_certified_solved_and_benched_by_the_command_line(tmp_path):
    cli = smcbench_cli()
    segment, corner, answers = hand_made_avis()
    path, certified = tmp_path / "avis.smcps", tmp_path / "certified.smcps"
    smcbench.write_problem_set(path, [segment, smcbench.AviProblem(id="hand/corner", avi=corner)])
    run = subprocess.run([cli, "library", str(path), "--certify", str(certified)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "certified 2 AVI(s)" in run.stdout
    for p in smcbench.read_problem_set(certified):
        ref = p.reference
        assert ref["lambda_unique"] and ref["strictly_monotone"] == "yes", p.id  # M = I
        np.testing.assert_allclose(ref["lambda_"], answers[p.id], atol=1e-15)
        assert kkt_violation(p.avi, ref["lambda_"], ref["mu"], ref["nu"]) <= 1e-14, p.id
        result = p.solve("lemke")  # judged against the reference: its forward error is defined
        assert result.verdict == "solved" and result.forward_error <= 1e-12, p.id
    run = subprocess.run([cli, "solve", str(certified), "--id", "hand/corner", "--solver", "lemke", "--json",
                          "--reference"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    entry = json.loads(run.stdout)[0]
    assert entry["problem"] == "hand/corner" and entry["results"][0]["verdict"] == "solved"
    np.testing.assert_allclose(entry["reference"]["lambda"], [1.0, 1.0], atol=1e-15)
    # bench on the objects themselves: written to a set of AVIs and run as `bench --suite FILE.smcps`.
    frame = smcbench.bench(smcbench.read_problem_set(certified), solvers="lemke", repetitions=1, warm=False)
    cold = frame[frame["mode"] == "cold"]
    assert sorted(cold["problem"]) == ["hand/corner", "hand/segment"]
    assert set(cold["verdict"]) == {"solved"}


def test_bad_avi_sets_are_refused(tmp_path):
    segment, corner, _ = hand_made_avis()
    box = smcbench.Problem(id="box", M=np.eye(1), q=np.array([1.0]), l=np.zeros(1), u=np.ones(1))
    with pytest.raises(smcbench.InvalidInputError, match="box problems or AVIs, not both"):
        smcbench.write_problem_set(tmp_path / "mixed.smcps", [segment, box])
    with pytest.raises(smcbench.InvalidInputError, match="duplicate"):
        smcbench.write_problem_set(tmp_path / "dup.smcps", [segment, segment])
    unnamed = smcbench.AffineVI(np.eye(1), [1.0])
    with pytest.raises(smcbench.InvalidInputError, match="id is empty"):
        smcbench.write_problem_set(tmp_path / "unnamed.smcps", [unnamed])
    with pytest.raises(smcbench.InvalidInputError, match="expected"):
        smcbench.write_problem_set(tmp_path / "expected.smcps",
                                   [smcbench.AviProblem(id="x", avi=corner, expected="maybe")])
    # "infeasible" on a bounded P: such an AVI has a solution (Hartman–Stampacchia).
    with pytest.raises(smcbench.InvalidInputError, match="bounded"):
        smcbench.write_problem_set(tmp_path / "wrong.smcps",
                                   [smcbench.AviProblem(id="x", avi=corner, expected="infeasible")])
    for name in ("mixed", "dup", "unnamed", "expected", "wrong"):
        assert not (tmp_path / f"{name}.smcps").exists()
