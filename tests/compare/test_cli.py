"""The DEM through the command line and the sweep machinery: ``run --model dem`` (JSON keys shared
with the four-link run, GIF), ``domain --model dem``, and a DEM sweep over a process pool."""

from __future__ import annotations

import json

import pytest

from archquake.cli.main import main
from archquake.outcome import RESULT_KEYS
from archquake.validation import paper

#: The JSON keys both models' runs print (the result vocabulary, and what the CLI adds).
SHARED_KEYS = (*RESULT_KEYS, "arch", "excitation")


def test_run_dem_json_keys_match_the_fourlink_run(capsys):
    """Figure 4(d) (t_p = 0.20 s) on the arch cut at the hinges: the same keys as the four-link
    run where they apply, and the same first impact (the 3-voussoir arch is the four-link
    mechanism: within 1 ms)."""
    args = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.20", "--t-end", "1.0", "--json"]
    assert main(["run", "--model", "fourlink", *args]) == 0
    an = json.loads(capsys.readouterr().out)
    assert main(["run", "--model", "dem", "--dem-assembly", "hinges", *args]) == 0
    dm = json.loads(capsys.readouterr().out)
    assert list(dm)[:len(RESULT_KEYS)] == list(an)[:len(RESULT_KEYS)] == list(RESULT_KEYS)
    for key in SHARED_KEYS:
        assert key in dm and key in an
    assert dm["model"] == "dem" and an["model"] == "fourlink"
    for key in ("end_time_s", "energy_error", "settings", "solver"):
        assert key in dm
    # both rock at 1.0 s: the fixed-hinge model says 'survives' with final_state 'moving'; the
    # DEM's verdict needs rest (docs/notes/mechanism.md, "An honest verdict for the block models")
    assert an["outcome"] == "survives" and an["final_state"] == "moving"
    assert dm["outcome"] == "indeterminate" and dm["final_state"] == "moving"
    assert dm["impact_times_s"][0] == pytest.approx(an["impact_times_s"][0], abs=1e-3)
    assert paper.RAYLEIGH_ALPHA.within(dm["settings"]["rayleigh_alpha_1_s"])


def test_run_dem_options_and_errors(capsys, tmp_path):
    """--damping F_MIN,XI_MIN(%) gives UDEC's alpha = xi w, beta = xi / w (Figure 10's values);
    --restitution is refused with one line and exit 2; --animate writes a GIF."""
    gif = tmp_path / "a.gif"
    assert main(["run", "--model", "dem", "--dem-assembly", "hinges", "--pulse", "step",
                 "--magnitude", "1.0", "--duration", "0.2", "--t-end", "0.4", "--damping", "0.05,0.001",
                 "--animate", str(gif), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["settings"]["rayleigh_alpha_1_s"] == pytest.approx(3.1416e-6, rel=1e-4)
    assert out["settings"]["rayleigh_beta_s"] == pytest.approx(3.1831e-5, rel=1e-4)
    assert gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert main(["run", "--model", "dem", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.2",
                 "--restitution", "0.9"]) == 2
    err = capsys.readouterr().err.strip()
    assert "restitution" in err and len(err.splitlines()) == 1


def test_domain_dem_quick(capsys):
    """A very coarse DEM domain at one duration (2 magnitudes + bisection to 0.3 g, ceiling 1.2 g):
    the JSON has both DEM boundaries beside the four-link ones. The DEM boundary reported is the
    collapsing end of a bracket <= 0.3 g wide, and the two models agree to 0.5 % (1st half cycle)
    and 10 % (governing, DEM higher: 0.672 vs 0.610 g at 0.01 g resolution), so it lies between
    the four-link boundary and that plus 0.3 g + 10 %."""
    assert main(["domain", "--model", "dem", "--durations", "0.3", "--scan", "2", "--precision", "0.3",
                 "--max-magnitude", "1.2", "--workers", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = {r["boundary"]: r for r in out["rows"]}
    assert set(rows) == {"first_half_cycle", "collapse"}
    assert rows["first_half_cycle"]["assembly"] == "hinges"
    assert rows["collapse"]["assembly"] == "voussoirs"
    for r in rows.values():
        if r["block_g"] is not None:
            a = r["fourlink_g"]
            assert 0.995 * a <= r["block_g"] <= 1.1 * a + 0.3
    assert out["block_governing"]["runs"] >= 2


#: R = 5 m, t = 0.6 m, a semicircle of 15 voussoirs: hinges at joints (3, 7, 12, 15), hinge A three
#: joints above the left springing (the DEM refused it before the hinges had one home).
SEMICIRCLE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15"]


def test_run_dem_hinges_on_a_semicircle(capsys):
    """a = 0.2 g, t_p = 0.3 s: the four-link mechanism collapses in its first half cycle; so does
    the DEM arch cut at its hinges (voussoirs 0-2 held with the support), with no impact (its
    collapse criterion, a crown drop of t, is met later than the four-link crest: 1.21 s)."""
    args = [*SEMICIRCLE, "--pulse", "step", "--magnitude", "0.2", "--duration", "0.3", "--json"]
    assert main(["run", "--model", "fourlink", *args]) == 0
    an = json.loads(capsys.readouterr().out)
    assert main(["run", "--model", "dem", "--dem-assembly", "hinges", "--t-end", "1.4", *args]) == 0
    dm = json.loads(capsys.readouterr().out)
    assert an["outcome"] == dm["outcome"] == "collapse"
    assert an["collapse_half_cycle"] == dm["collapse_half_cycle"] == 1
    assert dm["impact_times_s"] == []
    asm = dm["assembly"]
    assert asm["cut_joints"] == [0, 3, 7, 12, 15] and asm["held_voussoirs"] == [0, 1, 2]


def test_domain_dem_on_a_semicircle(capsys):
    """One duration, 2 coarse magnitudes, brackets of 0.2 g under a 0.3 g ceiling, one process:
    both DEM boundaries are found. The 1st-half-cycle boundary (arch cut at the hinges) is the
    collapsing end of a bracket <= 0.2 g wide on a model that follows the four-link first half
    cycle within 2 % (tests/dem/test_any_arch.py), so it lies in [0.98 a, 1.02 a + 0.2 g]
    (measured 0.121 g against 0.113 g)."""
    assert main(["domain", "--model", "dem", *SEMICIRCLE, "--durations", "0.3", "--scan", "2",
                 "--precision", "0.2", "--max-magnitude", "0.3", "--workers", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = {r["boundary"]: r for r in out["rows"]}
    assert set(rows) == {"first_half_cycle", "collapse"}
    first = rows["first_half_cycle"]
    assert first["assembly"] == "hinges"
    assert 0.98 * first["fourlink_g"] <= first["block_g"] <= 1.02 * first["fourlink_g"] + 0.2
    assert rows["collapse"]["assembly"] == "voussoirs" and rows["collapse"]["block_g"] is not None
    assert out["block_governing"]["runs"] >= 2


def test_dem_sweep_through_a_process_pool(tmp_path):
    """Three DEM cases through run_sweep with two worker processes: stored once each (a second
    run computes nothing), with the DEM result's summary (the shared keys, then the DEM's own)."""
    from archquake.sweeps import ResultStore, run_sweep
    from archquake.sweeps.study import parse_study

    study = parse_study({
        "study": {"name": "dem", "model": "dem"},
        "arches": {"radius": 10, "thickness_ratio": 0.15, "embrace_deg": 157.5, "voussoirs": 7},
        "excitation": {"type": "step", "magnitude_g": [0.3, 0.8, 1.0], "duration_s": 0.2},
        "options": {"t_end_s": 0.8},
    })
    with ResultStore(tmp_path / "d.sqlite") as store:
        report = run_sweep(study.cases, store, workers=2)
        again = run_sweep(study.cases, store, workers=2)
        rows = store.rows(flatten_outputs=False)
    assert report.computed == 3 and again.computed == 0 and again.already_stored == 3
    assert len(rows) == 3
    out = {r["magnitude_g"]: json.loads(r["outputs_json"]) for r in rows}
    # 0.3 g < lambda = 0.37 g: no hinging (the equivalent static analysis); 1.0 g: the first
    # impact near 0.64 s of Figure 4(d)
    assert out[0.3]["outcome"] == "no_hinging"
    assert out[1.0]["model"] == "dem"
    assert out[1.0]["impact_times_s"][0] == pytest.approx(0.635, abs=0.01)
    assert out[1.0]["settings"]["duration_s"] == pytest.approx(0.8)
