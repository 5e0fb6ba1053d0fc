"""``archquake domain --model fourlink`` and the domain figures: JSON is the model and the
domain's summary with its to_dict rows, bad input is one line with exit status 2, and the plots
write their files."""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main
from archquake.limit import limit_analysis
from archquake.validation import paper


def test_domain_json(capsys):
    code = main(["domain", "--model", "fourlink", "--durations", "0.27:0.44:2", "--scan", "20",
                 "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "fourlink" and out["impact_law"] == "paper"
    rows = out["rows"]
    assert [round(r["duration_s"], 2) for r in rows] == [0.27, 0.44]
    # paper Figure 4: at 1.0 g, t_p = 0.27 s lies between the boundaries, 0.44 s above both
    assert rows[0]["collapse_g"] < 1.0 < rows[0]["first_half_cycle_g"]
    assert rows[1]["first_half_cycle_g"] < 1.0
    lam = limit_analysis(paper.oppenheim_arch()).collapse_acceleration_g  # the default arch's
    assert rows[0]["no_hinging_g"] == pytest.approx(lam, abs=5e-4)


def test_domain_csv_and_plot(tmp_path, capsys):
    csv, png = tmp_path / "d.csv", tmp_path / "d.png"
    code = main(["domain", "--model", "fourlink", "--pulse", "sine", "--durations", "1.0:2.0:2",
                 "--scan", "16",
                 "--csv", str(csv), "--plot", str(png)])
    assert code == 0
    assert "failure domain, sine pulse" in capsys.readouterr().out
    assert csv.read_text().count("\n") == 3 and png.stat().st_size > 10_000


@pytest.mark.parametrize("argv, message", [
    (["--durations", "0.2:x:3"], "expected START:STOP:COUNT"),
    (["--durations", "0.5:0.1:3"], "STOP must exceed START"),
    (["--durations", "0:1:3"], "durations must be finite and > 0 s"),
    (["--max-magnitude", "0.2", "--durations", "0.3"],
     "--max-magnitude must exceed the arch's no-hinging limit"),
    (["--pulse", "ramp"], "invalid choice"),
])
def test_domain_bad_input_exit_2(capsys, argv, message):
    assert main(["domain", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
