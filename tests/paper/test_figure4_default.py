"""Figure 4 of the paper (Oppenheim's arch, step impulse a = 1.0 g, t_p = 0.44, 0.27, 0.20 s:
Figure 4(b)-(d)) under the default model of ``archquake run``, the chain of rigid voussoirs.

Oracles: the paper's outcomes (p. 2126: collapse in the first half cycle with no impact; one
impact then collapse; survival with shrinking half cycles) and the distinct-element model's
histories at the paper's stiffness (docs/notes/mechanism.md, "The rigid limit": collapse at 1.508 s;
first impact 0.916 s then collapse in half cycle 2; survival with first impact 0.635 s). The
rigid chain is the DEM's rigid limit; the DEM's contact compliance moves its impacts by
milliseconds, so the first impacts are held to the DEM's within the paper's own 0.02 s (one
line width of Figure 4(c)), and the collapse time to the DEM's within 0.03 s (the crown falling
by t, reached a few steps apart). The four-link model's first impacts, 0.861 and 0.601 s, are
0.06 and 0.03 s earlier than both block models (its hinges never move; tests/paper/
test_figure4.py holds it to the paper)."""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main
from archquake.validation import paper

T44, T27, T20 = paper.FIGURE4_DURATIONS
A = paper.FIGURE4_MAGNITUDE_G
#: (outcome, collapse half cycle, first impact s or None, collapse time s or None): the DEM.
DEM = {T44: ("collapse", 1, None, 1.508), T27: ("collapse", 2, 0.916, None),
       T20: ("survives", None, 0.635, None)}


@pytest.mark.parametrize("tp", paper.FIGURE4_DURATIONS)
def test_figure4_under_the_default_model(capsys, tp):
    assert main(["run", "--pulse", "step", "--magnitude", str(A), "--duration", str(tp),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    outcome, half, first, t_collapse = DEM[tp]
    assert out["model"] == "rigid"
    assert (out["outcome"], out["collapse_half_cycle"]) == (outcome, half)
    if first is None:
        assert out["impact_times_s"] == []
    else:
        assert out["impact_times_s"][0] == pytest.approx(first, abs=0.02)
    if t_collapse is not None:
        assert out["collapse_time_s"] == pytest.approx(t_collapse, abs=0.03)
    if tp == T27:  # the paper: one impact, then collapse
        assert len(out["impact_times_s"]) == 1
