"""load_bench_results on the committed main-job results (results/bench/results.json): the columns of results.csv and
the counts the README's table states for the paper suite (468 problems, enum solves all 468)."""

import json

import pandas as pd
import pytest

import smcbench

CSV_COLUMNS = ["suite", "problem", "solver", "mode", "size", "sparse", "expected", "status", "verdict", "iterations",
               "residual_abs", "residual_rel", "tolerance", "time_median", "time_min", "time_max", "time_mad",
               "samples", "solves_per_sample", "residual_scaled", "forward_error", "forward_error_rel",
               "forward_allowance", "certificate"]


@pytest.fixture(scope="module")
def frame(request):
    from conftest import SOURCE_DIR
    return smcbench.load_bench_results(SOURCE_DIR / "results" / "bench" / "results.json")


def test_columns_and_metadata(frame):
    assert isinstance(frame, pd.DataFrame)
    for column in CSV_COLUMNS:
        assert column in frame.columns
    assert frame.attrs["format"] == "smcbench-bench/1"
    assert "git_sha" in frame.attrs["environment"]


def test_paper_suite_counts_match_the_readme(frame):
    paper = frame[(frame.suite == "paper") & (frame["mode"] == "cold")]
    assert paper.problem.nunique() == 468
    enum = paper[paper.solver == "enum"]
    assert len(enum) == 468 and (enum.verdict == "solved").all()
    # Nothing wrongly claimed, inaccurate or wrongly refused on any suite by any backend (README).
    wrong = frame[frame["mode"] == "cold"].verdict.str.lower().isin(["wrongly claimed", "inaccurate", "wrongly refused"])
    assert not wrong.any()


def test_sweep_records_can_be_left_out(frame):
    from conftest import SOURCE_DIR
    without = smcbench.load_bench_results(SOURCE_DIR / "results" / "bench", include_sweep=False)
    assert "sweep" not in set(without["mode"]) and "sweep" in set(frame["mode"])
    # Exactly the suites' sweep records are left out: the rungs run (mode "sweep") and those a time budget cut
    # (mode "cut", kept in the sweep list).
    document = json.loads((SOURCE_DIR / "results" / "bench" / "results.json").read_text(encoding="utf-8"))
    sweep_records = sum(len(suite.get("sweep", [])) for suite in document["suites"])
    assert len(frame) - len(without) == sweep_records >= (frame["mode"] == "sweep").sum()
