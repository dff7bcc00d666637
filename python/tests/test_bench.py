"""smcbench.bench runs a benchmark through the engine `smcbench bench` runs: the same columns and verdicts as the
command's results.csv for the same suite, Python-made problems judged against their known solution, and bad input
refused naming it."""
import os
import pathlib
import subprocess

import numpy as np
import pandas as pd
import pytest

import smcbench

BACKENDS = ["lemke", "enum", "psor"]  # two exact backends and an iterative one (it gets the tolerance sweep)
KEY = ["suite", "problem", "solver", "mode", "tolerance"]


def cli_path() -> pathlib.Path:
    """The smcbench command of the build the module comes from (ctest names it in SMCBENCH_CLI)."""
    if os.environ.get("SMCBENCH_CLI"):
        return pathlib.Path(os.environ["SMCBENCH_CLI"])
    return pathlib.Path(smcbench.__file__).resolve().parents[2] / "tools" / "smcbench"


def test_tiny_suite_has_the_columns_and_verdicts_of_the_commands_results_csv(tmp_path):
    cli = cli_path()
    if not cli.is_file():
        pytest.skip(f"no smcbench command at {cli}")
    args = [str(cli), "bench", "--suite", "tiny", "--quick", "--repetitions", "1", "--out", str(tmp_path / "cli")]
    for name in BACKENDS:
        args += ["--solver", name]
    subprocess.run(args, check=True, capture_output=True, text=True)
    expected = pd.read_csv(tmp_path / "cli" / "results.csv")

    df = smcbench.bench("tiny", solvers=BACKENDS, repetitions=1, quick=True, out=tmp_path / "py")
    assert list(df.columns) == list(expected.columns) + ["tags", "message"]
    assert (tmp_path / "py" / "results.json").is_file()
    assert len(df) == len(expected)
    assert (df["mode"] == "sweep").any(), "psor's tolerance sweep"
    joined = df.merge(expected, on=KEY, suffixes=("_py", "_cli"), validate="one_to_one")
    assert len(joined) == len(df)
    for column in ["status", "verdict", "iterations", "expected", "certificate"]:
        assert (joined[f"{column}_py"] == joined[f"{column}_cli"]).all(), column
    # The known answers: both exact backends solve the four planted problems and refuse the infeasible LCP.
    cold = df[(df["mode"] == "cold") & df.solver.isin(["lemke", "enum"])]
    assert set(cold[cold.problem == "tiny/infeasible-lcp"].verdict) == {"correctly refused"}
    solved = cold[cold.problem != "tiny/infeasible-lcp"]
    assert len(solved) == 8 and (solved.verdict == "solved").all()
    assert (solved.forward_error <= 1e-8).all()


def test_a_list_of_problems_is_run_as_one_suite():
    # M = [[2, 1], [1, 2]], q = (-1, -1): both rows free, z* = (1/3, 1/3), the only solution (M is a P-matrix).
    problem = smcbench.Problem(id="mine/2x2", M=np.array([[2.0, 1.0], [1.0, 2.0]]), q=np.array([-1.0, -1.0]),
                               l=np.zeros(2), u=np.full(2, np.inf), expected="solvable")
    df = smcbench.bench([problem], solvers="lemke", repetitions=1, quick=True)
    cold = df[df["mode"] == "cold"].reset_index(drop=True)
    assert list(cold.suite) == ["python"] and list(cold.problem) == ["mine/2x2"]
    assert cold.verdict[0] == "solved"
    assert cold.forward_error[0] <= 1e-14
    # The tolerance ladder: the same problem at each rung, solved at every one (lemke is exact).
    ladder = df[df["mode"] == "sweep"]
    assert sorted(ladder.tolerance) == [1e-12, 1e-9, 1e-6, 1e-3]
    assert (ladder.verdict == "solved").all()


def test_problems_sharing_m_l_u_are_also_replayed_in_order_as_a_warm_sequence():
    # Three steps of one time-stepper: M, l, u fixed, q moving; z*_k = M^-1 (-q_k) stays inside the box (l = -inf).
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    steps = [smcbench.Problem(id=f"run/step{k}", M=M, q=np.array([-1.0 - 0.1 * k, -1.0]), l=np.full(2, -np.inf),
                              u=np.full(2, np.inf), expected="solvable") for k in range(3)]
    df = smcbench.bench(steps, solvers="lemke", repetitions=1, quick=True)
    warm = df[df["mode"] == "warm"]
    assert len(warm) == 1 and warm.verdict.iloc[0] == "solved", "one sequence of three steps, every step solved"
    no_warm = smcbench.bench(steps, solvers="lemke", repetitions=1, quick=True, warm=False)
    assert not (no_warm["mode"] == "warm").any()
    cold = ["problem", "status", "verdict", "iterations", "residual_abs"]
    pd.testing.assert_frame_equal(df[df["mode"] == "cold"][cold].reset_index(drop=True),
                                  no_warm[no_warm["mode"] == "cold"][cold].reset_index(drop=True))


def test_the_budgets_are_those_of_the_flags():
    # A sequence budget of 1e-12 s cuts the warm sequence in or after its first step: a record of mode "cut" (no
    # verdict) saying which budget; budgets of 0 (bench --full) let it run to its end.
    M = np.array([[2.0, 1.0], [1.0, 2.0]])
    steps = [smcbench.Problem(id=f"run/step{k}", M=M, q=np.array([-1.0 - 0.1 * k, -1.0]), l=np.full(2, -np.inf),
                              u=np.full(2, np.inf), expected="solvable") for k in range(3)]
    cut = smcbench.bench(steps, solvers="lemke", repetitions=1, quick=True, sequence_budget=1e-12)
    assert list(cut[cut["mode"] == "cut"].message.str.contains("sequence budget of 1e-12 s")) == [True]
    assert not (cut["mode"] == "warm").any()
    full = smcbench.bench(steps, solvers="lemke", repetitions=1, quick=True, job_budget=0, sequence_budget=0,
                          backend_budget=0)
    assert list(full[full["mode"] == "warm"].verdict) == ["solved"]
    with pytest.raises(ValueError, match="sequence budget must be a finite number of seconds >= 0, got -1"):
        smcbench.bench(steps, solvers="lemke", sequence_budget=-1)


def test_bad_input_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="unknown suite 'tinny'"):
        smcbench.bench(["tiny", "tinny"], solvers=["lemke"])
    with pytest.raises(smcbench.InvalidInputError, match="'lemkee'"):
        smcbench.bench("tiny", solvers=["lemkee"])
    with pytest.raises(ValueError, match="repetitions must be a whole number >= 1, got 0"):
        smcbench.bench("tiny", solvers=["lemke"], repetitions=0)
    with pytest.raises(ValueError, match="time limit"):
        smcbench.bench("tiny", solvers=["lemke"], time_limit=float("nan"))


def test_problems_keeps_only_the_matching_ids_and_refuses_a_glob_that_matches_none(tmp_path):
    df = smcbench.bench("tiny", solvers="lemke", repetitions=1, quick=True, problems=["tiny/infeasible*"],
                        out=tmp_path)
    assert set(df.problem) == {"tiny/infeasible-lcp"}
    assert len(df[df["mode"] == "cold"]) == 1
    with pytest.raises(smcbench.InvalidInputError, match=r"--problem 'tiny/nope\*' matches no problem"):
        smcbench.bench("tiny", solvers="lemke", problems="tiny/nope*")


def test_docs_example_prints_what_its_comments_say():
    """docs/python.md's benchmark example (docs_quick only checks that it runs)."""
    import contextlib
    import io
    import re

    from conftest import SOURCE_DIR

    text = (SOURCE_DIR / "docs" / "python.md").read_text(encoding="utf-8")
    section = text[text.index("### Benchmarks from Python"):]
    match = re.search(r"<<'PY'\n(.*?)\nPY\n", section, re.S)
    assert match, "docs/python.md: the benchmark example's heredoc (<<'PY' ... PY) is missing"
    code = match.group(1)
    expected = [line.split("  # ", 1)[1].strip() for line in code.splitlines() if line.startswith("print(")]
    assert len(expected) == 2
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/python.md", "exec"), {})
    assert out.getvalue().splitlines() == expected


def test_the_dataframe_has_every_column_of_results_csv_then_tags_and_message(tmp_path):
    df = smcbench.bench("tiny", solvers=["lemke"], repetitions=1, quick=True, out=tmp_path)
    header = (tmp_path / "results.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    assert list(df.columns) == header + ["tags", "message"], "results.csv has no tags or message: from results.json"
    assert {"certificate", "reference_radius", "start"} <= set(df.columns)
    # The same values as results.json: the refusal of the infeasible LCP says why, and the tags are kept.
    loaded = smcbench.load_bench_results(tmp_path)
    joined = df.merge(loaded, on=KEY, suffixes=("_csv", "_json"), validate="one_to_one")
    for column in ("message", "tags"):
        assert (joined[f"{column}_csv"].fillna("") == joined[f"{column}_json"].fillna("")).all(), column
    refusal = df[(df.problem == "tiny/infeasible-lcp") & (df["mode"] == "cold")]
    assert refusal.message.iloc[0] and isinstance(refusal.message.iloc[0], str)
    assert df.attrs["results_dir"] == str(tmp_path) and df.attrs["results_json"].startswith("{")
