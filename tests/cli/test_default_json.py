"""Every command that runs a time history names its model in its JSON, and by default that
model is the chain of rigid voussoirs (``"model": "rigid"``). ``run``, ``thrust`` and
``friction`` are covered in test_model_cli.py and tests/thrust/test_cli.py; here the commands
that run many histories, on the smallest inputs that still run the rigid chain."""

from __future__ import annotations

import json

import numpy as np

from archquake.cli.main import main


def test_domain_default_json_is_the_rigid_chain(capsys):
    """One duration, two coarse magnitudes, brackets of 0.4 g: the rigid chain's boundaries
    beside the four-link ones."""
    assert main(["domain", "--durations", "0.3", "--scan", "2", "--precision", "0.4",
                 "--max-magnitude", "1.2", "--workers", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == out["block_model"] == "rigid"
    assert {r["boundary"] for r in out["rows"]} == {"first_half_cycle", "collapse"}


def test_ida_default_json_is_the_rigid_chain(capsys, tmp_path):
    """One 3 s record, a 0.3-wide bracket under a 1 g ceiling: a few rigid histories."""
    t = np.arange(0.0, 3.0, 0.01)
    acc = np.where(t < 0.6, np.sin(2 * np.pi * t / 0.6), 0.0) * 0.5  # g: one sine cycle
    np.savetxt(tmp_path / "pulse.csv", np.column_stack([t, acc]), delimiter=",")
    assert main(["ida", "--records", str(tmp_path / "pulse.csv"), "--units", "g", "--ceiling",
                 "1.0", "--precision", "0.3", "--fill", "1.0", "--workers", "1", "--bootstrap",
                 "0", "--no-progress", "--store", str(tmp_path / "s.sqlite"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "rigid" and out["computed_now"] > 0


def test_sweep_default_json_and_store_column_are_the_rigid_chain(capsys, tmp_path):
    study = tmp_path / "s.toml"
    study.write_text('[study]\nname = "s"\n[arches]\nradius = 10\nthickness_ratio = 0.15\n'
                     'embrace_deg = 157.5\nvoussoirs = 7\n[excitation]\ntype = "step"\n'
                     'magnitude_g = 0.5\nduration_s = 0.25\n')
    assert main(["sweep", str(study), "--workers", "1", "--no-progress", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "rigid" and out["computed_now"] == 1
    from archquake.sweeps import ResultStore

    with ResultStore(tmp_path / "s.sqlite") as store:
        (row,) = store.rows()
    assert row["model"] == "rigid" and row["status"] == "ok"
    assert main(["sweep", str(study), "--model", "fourlink", "--workers", "1", "--no-progress",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["model"] == "fourlink"
