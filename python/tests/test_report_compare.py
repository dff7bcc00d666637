"""smcbench.report and smcbench.compare make what `smcbench report DIR` and `smcbench compare A B` make, through the
same C++ code: the same report.md and compare.md as the command on the same results, from a folder or from the
DataFrame bench() returned; a verdict that got worse is a regression; bad input names the argument."""
import json
import shutil
import subprocess

import pytest

import smcbench
from test_bench import cli_path

BACKENDS = ["lemke", "enum"]


@pytest.fixture(scope="module")
def run_a(tmp_path_factory):
    """A quick run of the tiny suite on two exact backends, kept in a folder: (folder, DataFrame)."""
    folder = tmp_path_factory.mktemp("runs") / "a"
    df = smcbench.bench("tiny", solvers=BACKENDS, repetitions=1, quick=True, warm=False, out=folder)
    return folder, df


def cli(*args, check=True):
    program = cli_path()
    if not program.is_file():
        pytest.skip(f"no smcbench command at {program}")
    return subprocess.run([str(program), *map(str, args)], check=check, capture_output=True, text=True)


def test_report_is_the_commands_report_md(run_a, tmp_path):
    folder, df = run_a
    text = smcbench.report(folder)
    assert not (folder / "report.md").exists(), "out=None writes nothing, not even into the results folder"
    copy = tmp_path / "cli"
    shutil.copytree(folder, copy)
    cli("report", copy, "--no-plots")
    # Word for word, the folder's name apart (the report says which folder it was made from).
    assert f"`smcbench report {folder}` from `{folder}/results.json`" in text
    assert text.replace(str(folder), str(copy)) == (copy / "report.md").read_text(encoding="utf-8")
    assert "tiny" in text and "lemke" in text
    # From the DataFrame bench() returned, and from its results.json: the same report; out= writes it.
    assert smcbench.report(df, out=tmp_path / "r") == text
    assert (tmp_path / "r" / "report.md").read_text(encoding="utf-8") == text
    assert smcbench.report(folder / "results.json") == text


def test_report_of_a_run_without_an_out_folder(run_a):
    df = smcbench.bench("tiny", solvers="lemke", repetitions=1, quick=True, warm=False)
    assert df.attrs["results_dir"] is None
    assert "lemke" in smcbench.report(df)


def test_report_refuses_what_is_not_a_results_folder(tmp_path):
    with pytest.raises(smcbench.InvalidInputError, match="report: .*no results.json"):
        smcbench.report(tmp_path)
    with pytest.raises(smcbench.InvalidInputError, match="report: expected a results folder.*got int"):
        smcbench.report(42)


def test_compare_of_a_run_with_itself_finds_nothing_and_matches_the_command(run_a, tmp_path):
    folder, df = run_a
    c = smcbench.compare(folder, folder, out=tmp_path / "py")
    assert not c.regressed and c.regressions == 0 and c.verdict_changes == []
    assert c.matched_records == len(df)
    assert all(0.0 < g["ratio"] < float("inf") for g in c.groups)
    done = cli("compare", folder, folder, "--out", tmp_path / "cli", "--no-plots")
    assert (tmp_path / "cli" / "compare.md").read_text(encoding="utf-8") == c.markdown
    assert (tmp_path / "py" / "compare.md").read_text(encoding="utf-8") == c.markdown
    assert done.stdout.startswith(c.summary)
    # compare.json as the command writes it: the runs side by side (identical here: nothing differs), the method.
    assert json.loads((tmp_path / "py" / "compare.json").read_text(encoding="utf-8")) == c.data
    assert json.loads((tmp_path / "cli" / "compare.json").read_text(encoding="utf-8")) == c.data
    assert c.data["format"] == "smcbench-compare/1" and not c.data["regressed"]


def test_compare_draws_the_commands_figure(run_a, tmp_path):
    folder, _ = run_a
    if shutil.which("gnuplot") is None:
        with pytest.raises(smcbench.InvalidInputError, match="compare: no figure: .*gnuplot"):
            smcbench.compare(folder, folder, out=tmp_path / "py", plots=True)
        assert (tmp_path / "py" / "compare.md").is_file(), "the comparison is written without its figure"
        return
    c = smcbench.compare(folder, folder, out=tmp_path / "py", plots=True)
    cli("compare", folder, folder, "--out", tmp_path / "cli")
    # The same files as the command's --out, the figure linked from compare.md and its data identical.
    for name in ("compare.md", "compare-ratios.dat", "compare-ratios.gp"):
        assert (tmp_path / "py" / name).read_text(encoding="utf-8") == (tmp_path / "cli" / name).read_text(
            encoding="utf-8"), name
    assert "](compare-ratios.png)" in c.markdown
    assert c.markdown == (tmp_path / "py" / "compare.md").read_text(encoding="utf-8")
    for name in ("compare-ratios.png", "compare-ratios.svg"):
        assert (tmp_path / "py" / name).stat().st_size > 1000, name
    rows = [line for line in (tmp_path / "py" / "compare-ratios.dat").read_text().splitlines()
            if not line.startswith("#")]
    assert len(rows) == len(c.groups) and len(rows) > 0, "one row per group"


def test_compare_plots_needs_an_out_folder(run_a):
    folder, _ = run_a
    with pytest.raises(smcbench.InvalidInputError, match="plots=True needs out="):
        smcbench.compare(folder, folder, plots=True)


def test_a_verdict_that_got_worse_is_a_regression(run_a, tmp_path):
    folder, _ = run_a
    document = json.loads((folder / "results.json").read_text(encoding="utf-8"))
    record = next(r for r in document["suites"][0]["records"] if r["verdict"] == "solved")
    record["verdict"], record["status"] = "failed", "iteration_limit"
    worse = tmp_path / "b"
    worse.mkdir()
    (worse / "results.json").write_text(json.dumps(document), encoding="utf-8")
    c = smcbench.compare(folder, worse)
    assert c.regressed and c.regressions == 1
    change = c.verdict_changes[0]
    assert (change["kind"], change["problem"], change["solver"]) == ("regression", record["problem"], record["solver"])
    assert (change["verdict_a"], change["verdict_b"], change["status_b"]) == ("solved", "failed", "iteration_limit")
    assert cli("compare", folder, worse, check=False).returncode == 1, "the command agrees: exit status 1"


def test_compare_refuses_runs_of_other_suites_and_bad_options(run_a, tmp_path):
    folder, _ = run_a
    other = tmp_path / "other"
    smcbench.bench("tiny", solvers="lemke", repetitions=1, quick=True, warm=False, out=other)
    document = json.loads((other / "results.json").read_text(encoding="utf-8"))
    document["suites"][0]["suite"] = "renamed"
    (other / "results.json").write_text(json.dumps(document), encoding="utf-8")
    with pytest.raises(smcbench.InvalidInputError, match="compare: "):
        smcbench.compare(folder, other)
    with pytest.raises(smcbench.InvalidInputError, match="resamples"):
        smcbench.compare(folder, folder, resamples=3)
    with pytest.raises(smcbench.InvalidInputError, match="compare: .*no results.json"):
        smcbench.compare(folder, tmp_path / "missing")
