"""smcbench.report_tables: the tables report.md is rendered from (bench/analysis/report_tables.h), as pandas
DataFrames, on a quick run of the tiny suite: the backends, their counts and times are the run's, from a folder, its
results.json or the DataFrame bench() returned; the backends table agrees with the report's own markdown."""
import math

import pytest

import smcbench

BACKENDS = ["lemke", "enum"]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """A quick run of the tiny suite on two exact backends: (folder, DataFrame)."""
    folder = tmp_path_factory.mktemp("runs") / "tables"
    df = smcbench.bench("tiny", solvers=BACKENDS, repetitions=1, quick=True, warm=False, out=folder)
    return folder, df


def test_tables_hold_the_runs_backends_counts_and_times(run):
    folder, df = run
    tables = smcbench.report_tables(folder)
    assert list(tables) == ["summary", "failures", "backends", "statuses", "audit", "bands", "ladder", "sweep",
                            "peers", "profiles"]
    backends = tables["backends"]
    assert list(backends.columns[:4]) == ["suite", "backend", "problems", "solved"]
    assert len(backends) == 2
    assert sorted(backends["backend"]) == sorted(BACKENDS)
    assert set(backends["suite"]) == {"tiny"}
    cold = df[df["mode"] == "cold"]
    for _, row in backends.iterrows():
        mine = cold[cold["solver"] == row["backend"]]
        assert row["problems"] == len(mine) == 5
        assert row["solved"] == (mine["verdict"] == "solved").sum() == 4
        assert row["correctly refused"] == 1
        assert row["wrongly claimed"] == row["inaccurate"] == row["wrongly refused"] == 0
        assert row["success"] == 1.0
        assert 0 < row["SGM time"] < 1
        assert row["worst residual (solved)"] <= 1e-10
    assert backends["solved"].dtype.kind == "i" and backends["SGM time"].dtype.kind == "f"
    audit = tables["audit"]
    assert len(audit) == 2 and (audit["records"] == 5).all() and (audit["flag right"] == 5).all()
    assert len(tables["bands"]) >= 1 and tables["bands"]["fastest correct"].iloc[0] in BACKENDS
    ladder = tables["ladder"]
    assert set(ladder["backend"]) == set(BACKENDS) and (ladder["correct"] <= ladder["problems"]).all()
    profiles = tables["profiles"]
    assert (profiles["ratio"] >= 1.0).all()
    statuses = tables["statuses"]
    assert (statuses.groupby("backend")["records"].sum() == 5).all()
    assert statuses[statuses["status"] == "solved"]["records"].tolist() == [4, 4]
    # The summary's classes count every problem once.
    assert tables["summary"]["problems"].sum() == 5
    assert (tables["failures"]["not correct"] == 0).all()
    # The markdown prints the same SGM time for each backend.
    text = smcbench.report(folder)
    for _, row in backends.iterrows():
        assert f"| {row['backend']} | {row['solved']} | {row['correctly refused']} | " in text
    # The same tables from results.json and from the DataFrame.
    again = smcbench.report_tables(folder / "results.json")["backends"]
    assert again.equals(backends)
    from_df = smcbench.report_tables(df)["backends"]
    assert list(from_df["backend"]) == list(backends["backend"])
    assert not math.isnan(from_df["SGM time"].iloc[0])


def test_tables_refuse_what_is_not_a_results_folder(tmp_path):
    with pytest.raises(smcbench.InvalidInputError, match="report_tables: .*no results.json"):
        smcbench.report_tables(tmp_path)
