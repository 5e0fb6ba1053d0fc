"""``archquake sweep``: summary with --json, resume on rerun, export, Ctrl-C exits 130 and
says how to resume, bad options are one line and exit 2."""

from __future__ import annotations

import csv
import json

import pytest
import sweep_fake_model

from archquake.cli import cmd_sweep


def test_sweep_json_summary_and_rerun(small_study_file, capsys, sweep_cli):
    store = small_study_file.parent / "small.sqlite"  # default: <name>.sqlite beside the study
    assert sweep_cli(["sweep", str(small_study_file), "--workers", "1", "--json"]) == 0
    first = json.loads(capsys.readouterr().out)
    expected = {}
    for case in sweep_fake_model_cases(small_study_file):
        outcome = sweep_fake_model.fake_evaluate(case)["outcome"]
        expected[outcome] = expected.get(outcome, 0) + 1
    assert first == {"model": "fourlink", "cases_total": 24, "computed_now": 24, "already_stored": 0,
                     "outcomes": dict(sorted(expected.items())), "store": str(store),
                     "study": "small"}
    assert sweep_cli(["sweep", str(small_study_file), "--workers", "2", "--json"]) == 0
    second = json.loads(capsys.readouterr().out)
    assert (second["computed_now"], second["already_stored"]) == (0, 24)
    assert second["outcomes"] == first["outcomes"]


def test_sweep_text_output_store_and_export(small_study_file, tmp_path, capsys, sweep_cli):
    out_csv = tmp_path / "results.csv"
    store = tmp_path / "elsewhere" / "r.sqlite"
    code = sweep_cli(["sweep", str(small_study_file), "--store", str(store), "--workers", "2",
                      "--chunk-size", "4", "--export", str(out_csv)])
    assert code == 0
    out = capsys.readouterr().out
    assert "24 cases, 24 computed now, 0 already stored" in out
    assert store.exists()
    with out_csv.open() as fh:
        assert len(list(csv.DictReader(fh))) == 24


def test_ctrl_c_stores_what_finished_and_exits_130(small_study_file, capsys, monkeypatch,
                                                   sweep_cli):
    counter = sweep_fake_model.CountingEvaluate(stop_at=8)
    monkeypatch.setattr(cmd_sweep, "case_function", lambda model: counter)
    assert sweep_cli(["sweep", str(small_study_file), "--workers", "1", "--chunk-size", "1"]) == 130
    err = capsys.readouterr().err
    assert "interrupted: 7 of 24 cases are stored" in err
    assert "again to resume" in err
    resumed = sweep_fake_model.CountingEvaluate()
    monkeypatch.setattr(cmd_sweep, "case_function", lambda model: resumed)
    assert sweep_cli(["sweep", str(small_study_file), "--workers", "1", "--json"]) == 0
    assert resumed.calls == 17
    assert json.loads(capsys.readouterr().out)["already_stored"] == 7


@pytest.mark.parametrize("extra, needle", [
    (["--workers", "0"], "--workers"),
    (["--chunk-size", "0"], "--chunk-size"),
    (["--scheduler", "127.0.0.1:8786"], "--scheduler"),
    (["--export", "out.xlsx"], "--export"),
    (["--scheduler", "tcp://127.0.0.1:1"], "cannot reach the Dask scheduler"),
])
def test_bad_options_are_one_line(small_study_file, capsys, sweep_cli, extra, needle,
                                  monkeypatch):
    monkeypatch.setattr("archquake.parallel.CONNECT_TIMEOUT", 1.0)  # nothing listens there
    assert sweep_cli(["sweep", str(small_study_file), *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


def sweep_fake_model_cases(path):
    from archquake.sweeps import load_study

    return load_study(path).cases
