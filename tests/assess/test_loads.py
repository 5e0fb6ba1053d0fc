"""An assessment of an arch that carries loads: the study file's [loads] table, checked before
anything is computed (each problem one line naming the key), carried by every section (each
section's numbers set beside the library's call with the same loads, the oracle), listed in the
report, and the traffic check's adequacy factor. The examples' loads are read as their comments
say. One whole quick assessment with loads is marked slow."""

from __future__ import annotations

import json

import numpy as np
import pytest

from archquake.assess import load_config
from archquake.assess.config import parse_config
from archquake.assess.sections import Context, Mode
from archquake.errors import StudyFileError

from .conftest import EXAMPLES

#: A small bridge: the example's semicircle (R 5 m, t 0.6 m) in 9 voussoirs, 0.8 m of fill,
#: 1 m of backing, a moving point load and an axle.
ARCH = {"radius": 5.0, "thickness_ratio": 0.12, "embrace_deg": 180, "voussoirs": 9,
        "density": 1800, "friction": 0.6}
LOADS = {"fill_depth": 0.8, "fill_density": 1900, "backing": 1.0,
         "point_loads": [{"position": 3.0, "load_kN": 20.0}],
         "traffic": {"axle_kN": 100.0, "position": 2.35, "dispersion_deg": 26.57}}


def config(loads=None, **seismic):
    data = {"arch": dict(ARCH), "seismic": seismic or {"site_pga_g": 0.15},
            "loads": dict(LOADS if loads is None else loads)}
    return parse_config(data, source="b.toml")


def context(tmp_path, cfg=None, prior=None):
    cfg = config() if cfg is None else cfg
    return Context(cfg, cfg.build_arch(), Mode(True), tmp_path, tmp_path, prior or {})


# ----------------------------------------------------------------------------- the table
def test_table_is_read_in_the_cli_units():
    cfg = config()
    loads = cfg.loads
    assert loads.fill.depth == 0.8 and loads.fill.density == 1900.0
    assert loads.backing.left == loads.backing.right == 1.0
    assert loads.point_loads[0].load == 20e3 and loads.point_loads[0].moves_with_arch
    assert loads.traffic.load == 100e3 and loads.traffic.dispersion == 26.57
    assert cfg.dead_loads.traffic is None and cfg.dead_loads.fill == loads.fill
    assert cfg.canonical()["loads"]["traffic"]["load_N_m"] == 100e3


def test_a_file_without_loads_keeps_its_digest():
    """The cache key of a bare study is what it was before [loads] existed."""
    bare = parse_config({"arch": dict(ARCH), "seismic": {"site_pga_g": 0.15}})
    assert "loads" not in bare.canonical() and bare.loads is None and bare.dead_loads is None
    assert bare.digest != config().digest


@pytest.mark.parametrize("loads, key", [
    ({"fill_dept": 1.0}, "[loads] fill_dept"),
    ({"fill_depth": -1.0}, "[loads] fill depth"),
    ({"point_loads": [{"position": 12.0, "load_kN": 5.0}]}, "[loads] point_loads[0] position"),
    ({"point_loads": [{"position": 2.0, "load_kN": 5.0, "moves_with_arch": False}]},
     "[loads] point_loads[0] moves_with_arch"),
    ({"distributed_loads": [{"start": 1.0, "end": 9.9, "load_kN_m": 5.0}]},
     "[loads] distributed_loads[0] end"),
    ({"distributed_loads": [{"start": 1.0, "end": 2.0, "load_kN_m": 5.0,
                             "moves_with_arch": False}]},
     "[loads] distributed_loads[0] moves_with_arch"),
    ({"traffic": {"axle_kN": 100.0, "position": 11.0}}, "[loads] traffic position"),
    ({"fill_depth": 0.5, "passive": 0.3}, "[loads] passive"),
])
def test_errors_name_the_toml_key(loads, key):
    with pytest.raises(StudyFileError) as exc:
        config(loads)
    text = str(exc.value)
    assert text.startswith(f"b.toml: {key}"), text
    assert "\n" not in text


def test_loads_on_piers_are_refused_before_any_computation():
    data = {"arch": {"shape": "pointed", "span": 8.0, "rise": 6.0, "thickness": 0.6,
                     "voussoirs": 13, "pier_height": 6.0, "pier_width": 1.2, "pier_courses": 4,
                     "friction": 0.7},
            "seismic": {"site_pga_g": 0.1}, "loads": {"fill_depth": 0.3}}
    with pytest.raises(StudyFileError, match=r"^n.toml: \[loads\] cannot be carried: .*piers"):
        parse_config(data, source="n.toml")


def test_the_examples_loads_are_read():
    bridge = load_config(EXAMPLES / "bridge.toml")
    assert bridge.loads.fill.depth == 0.8 and bridge.loads.fill.density == 1900.0
    assert bridge.loads.backing.left == 1.0
    assert bridge.loads.traffic.load == 100e3 and bridge.loads.traffic.length == 0.0
    nave = load_config(EXAMPLES / "nave_wall.toml")
    (wall,) = nave.loads.distributed_loads
    assert wall.pressure == pytest.approx(3 * 2200 * 9.81, rel=1e-3)  # 3 m of limestone
    assert wall.moves_with_arch and nave.loads.point_loads[0].moves_with_arch
    assert nave.loads.traffic is None


# ----------------------------------------------------------------------------- the sections
def test_arch_section_lists_the_masses_and_draws_the_loads(tmp_path):
    """Oracle: the masses of block_extras (the column model) and the voussoirs'; masonry and
    carried kept apart, the fill and the point load's mass (load / g) adding up to the carried."""
    from archquake.assess.sections import section_arch
    from archquake.constants import STANDARD_GRAVITY
    from archquake.geometry.loads import block_extras

    ctx = context(tmp_path)
    data = section_arch(ctx).data
    m = data["masses"]
    assert m["masonry_mass_kg"] == pytest.approx(float(np.sum(ctx.arch.voussoir_masses)))
    carried = float(block_extras(ctx.arch, ctx.config.dead_loads).mass.sum())
    assert m["carried_mass_kg"] == pytest.approx(carried, rel=1e-12)
    assert m["superimposed_mass_kg"] == pytest.approx(20e3 / STANDARD_GRAVITY, rel=1e-9)
    assert m["fill_mass_kg"] + m["superimposed_mass_kg"] == pytest.approx(carried, rel=1e-12)
    # 1 m of backing holds the springing joints only (joints 1 and 8 end 1.81 m up): no block
    assert m["held_joints"] == [0, 9] and m["held_blocks"] == [] and m["held_mass_kg"] == 0.0
    assert data["loads"]["traffic"]["load_N_m"] == 100e3
    assert (tmp_path / "arch.png").stat().st_size > 10_000


def test_static_section_is_the_loaded_limit_analysis(tmp_path):
    """Oracle: limit_analysis with the dead loads (the traffic left out), to 1e-12; the bare
    arch's lambda is another (the fill and backing change it by far more than 10 %)."""
    from archquake.assess.sections import section_static
    from archquake.limit import limit_analysis

    ctx = context(tmp_path)
    data = section_static(ctx).data
    ref = limit_analysis(ctx.arch, loads=ctx.config.dead_loads)
    assert data["collapse_acceleration_g"] == pytest.approx(ref.collapse_acceleration_g,
                                                            rel=1e-12)
    assert [h["joint"] for h in data["hinges"]] == [h.joint for h in ref.mechanism.hinges]
    assert ctx.collapse_acceleration_g() == pytest.approx(ref.collapse_acceleration_g, rel=1e-9)
    bare = limit_analysis(ctx.arch).collapse_acceleration_g
    assert data["collapse_acceleration_g"] > 1.1 * bare
    assert data["min_thickness_m"] < float(ctx.arch.thickness)
    assert data["loads"]["traffic"] is None  # the statics of every section: dead loads only


def test_traffic_section_is_the_capacity_scan(tmp_path):
    """Oracle: capacity_scan at the same positions; the critical multiplier is the least of the
    scan, both bounds agree at it (the kinematic and static methods, 9 voussoirs)."""
    from archquake.assess.sections import TRAFFIC_POSITIONS, section_traffic
    from archquake.limit.capacity import capacity_scan

    ctx = context(tmp_path)
    data = section_traffic(ctx).data
    loads = ctx.config.loads
    ref = capacity_scan(ctx.arch, loads, loads.traffic, TRAFFIC_POSITIONS[True])
    assert data["adequacy_factor"] == pytest.approx(ref.adequacy_factor, rel=1e-12)
    assert data["critical_position_m"] == ref.critical.traffic.position
    finite = [m for m in data["scan"]["multiplier"] if m is not None]
    assert data["adequacy_factor"] == pytest.approx(min(finite), rel=1e-9)
    crit = data["critical"]
    assert crit["static_multiplier"] == pytest.approx(crit["kinematic_multiplier"], rel=1e-6)
    assert (tmp_path / "traffic.png").is_file()


class Stop(Exception):
    pass


def test_pulses_search_the_loaded_blocks(tmp_path, monkeypatch):
    """The rigid chain's domains get the loads, and their scan starts from the loaded lambda."""
    import archquake.compare as compare
    from archquake.assess.sections import pulse_domains, rigid_scan_ceiling

    asked = {}

    def fake(arch, family, durations, **kwargs):
        asked.update(kwargs)
        raise Stop

    monkeypatch.setattr(compare, "dem_failure_domain", fake)
    ctx = context(tmp_path)
    with pytest.raises(Stop):
        pulse_domains(ctx, None)
    assert asked["loads"] == ctx.config.dead_loads
    lam = ctx.collapse_acceleration_g()
    assert asked["settings"].max_magnitude_g == rigid_scan_ceiling(lam, 0.15)


def test_records_ida_carries_the_loads(tmp_path, monkeypatch):
    import archquake.ida as ida
    from archquake.assess.sections import run_ida

    asked = {}

    def fake(*args, **kwargs):
        asked.update(kwargs)
        raise Stop

    monkeypatch.setattr(ida, "incremental_dynamic_analysis", fake)
    ctx = context(tmp_path, config(suite="near-field-pulse", site_pga_g=0.15))
    with pytest.raises(Stop):
        run_ida(ctx, None)
    assert asked["loads"] == ctx.config.dead_loads


def test_dem_check_runs_the_loaded_assembly(tmp_path, monkeypatch):
    """The DEM and the rigid chain's verdicts beside it both run the blocks that carry the
    fill: the assembly's masses are the voussoirs' plus the carried ones."""
    from archquake.assess import sections
    from archquake.assess.sections import section_dem
    from archquake.blocks.assembly import Assembly

    bodies = []
    monkeypatch.setattr(sections, "_dem_outcome",
                        lambda body, motion, duration: bodies.append(body) or "survives")
    import archquake.rigid as rigid

    seen = []

    def verdicts(body, motions, **kwargs):
        seen.append((body, kwargs["duration"]))
        return [type("V", (), {"outcome": type("O", (), {"value": "survives"})})()
                for _ in motions]

    monkeypatch.setattr(rigid, "rigid_verdicts", verdicts)
    ctx = context(tmp_path, prior={"static": {"collapse_acceleration_g": 0.2},
                                   "pulses": {"step": {"durations_s": [0.3],
                                                       "collapse_g": [0.5]}}})
    data = section_dem(ctx).data
    (body,) = bodies
    assert isinstance(body, Assembly) and seen[0][0] is not ctx.arch
    moving = float(np.sum(np.asarray(body.masses)[~np.asarray(body.base, dtype=bool)]))
    assert moving > float(np.sum(ctx.arch.voussoir_masses))  # 0.8 m of fill: more than the ring
    assert all(w is not None for w in seen[0][1])
    assert data["cases"][0]["runs"][0]["dem_outcome"] == "survives"


def test_report_lists_the_loads_and_the_traffic_check(tmp_path):
    from types import SimpleNamespace

    from archquake.assess import report
    from archquake.assess.sections import section_arch, section_traffic

    ctx = context(tmp_path)
    arch = section_arch(ctx)
    traffic = section_traffic(ctx)
    el: list = []
    report._loads(el, arch.data)
    report._traffic(el, SimpleNamespace(sections={"traffic": traffic}), traffic.data)
    tables = [e for e in el if e[0] == "table"]
    loads_rows = {r[0]: r[1] for r in tables[0][2]}
    assert "0.8 m over the crown" in loads_rows["fill"]
    assert "1 m (left)" in loads_rows["backing"]
    assert "no hinge at joints 0, 9" in loads_rows["backing"]
    assert "20 kN/m at 3 m" in loads_rows["point load"]
    assert "100 kN/m axle" in loads_rows["traffic"]
    assert loads_rows["passive fill pressure"].startswith("off")
    masses = {r[0]: r[1] for r in tables[1][2]}
    assert masses["masonry (the voussoirs)"] == f"{arch.data['masses']['masonry_mass_kg']:.0f}"
    assert masses["carried in all"] == f"{arch.data['masses']['carried_mass_kg']:.0f}"
    rows = {r[0]: r[1] for r in tables[2][2]}
    assert rows["adequacy factor (least multiplier)"] == f"{traffic.data['adequacy_factor']:.3f}"
    assert ("fig", "traffic.png", traffic.figures[0].caption) in el


def test_verdict_names_the_adequacy_factor_and_the_fill_model():
    from archquake.assess.sections import LOADS_ASSUMPTION, verdict

    prior = {"static": {"collapse_acceleration_g": 0.3, "geometric_safety_factor": 2.0},
             "traffic": {"load_kN_m": 100.0, "kind": "axle", "adequacy_factor": 1.467,
                         "critical_position_m": 3.01}}
    v = verdict(config(), prior)
    assert v["level"] == "stands" and v["numbers"]["traffic_adequacy_factor"] == 1.467
    assert "100 kN/m axle collapses the arch at 1.47 times itself, at 3.01 m" in v["text"]
    assert LOADS_ASSUMPTION in v["text"] and "no backfill" not in v["text"]


# ----------------------------------------------------------------------------- the whole run
@pytest.mark.slow
def test_quick_assessment_with_loads_runs_every_section(tmp_path):
    """A whole quick assessment of the small bridge (9 voussoirs, no records): every section
    present, each carrying the loads; the report lists them."""
    from archquake.assess import run_assessment

    cfg = config()
    rep = run_assessment(cfg, tmp_path / "out", quick=True)
    res = json.loads((tmp_path / "out" / "results.json").read_text())
    assert list(res["sections"]) == ["arch", "static", "traffic", "pulses", "dem", "validity"]
    assert res["input"]["loads"]["fill"]["depth_m"] == 0.8
    lam = res["sections"]["static"]["collapse_acceleration_g"]
    assert lam == pytest.approx(context(tmp_path, cfg).collapse_acceleration_g(), rel=1e-9)
    assert rep.verdict["numbers"]["traffic_adequacy_factor"] == pytest.approx(
        res["sections"]["traffic"]["adequacy_factor"])
    text = (tmp_path / "out" / "report.md").read_text()
    assert "What the arch carries" in text and "Traffic check" in text
    carried = res["sections"]["arch"]["masses"]["carried_mass_kg"]
    assert f"Mass of the masonry {res['sections']['arch']['total_mass_kg']:.0f} kg (depth 1 m), " \
           f"carrying {carried:.0f} kg" in text


def test_fourlink_model_carries_the_loads_on_its_links():
    """Under model = "fourlink" the pulses, records and restitution use the mechanism whose
    links carry the fill: its lambda is the loaded static analysis's (to 1e-9), not the bare
    ring's."""
    from archquake.assess.sections import prepared_mechanism, used_restitution
    from archquake.limit import limit_analysis

    data = {"arch": dict(ARCH), "seismic": {"site_pga_g": 0.15},
            "options": {"model": "fourlink", "restitution": 0.8},
            "loads": {"fill_depth": 0.8, "fill_density": 1900, "backing": 1.0}}
    cfg = parse_config(data)
    arch = cfg.build_arch()
    prep = prepared_mechanism(arch, cfg.impact, cfg.dead_loads)
    loaded = limit_analysis(arch, loads=cfg.dead_loads).collapse_acceleration_g
    assert prep.collapse_acceleration_g == pytest.approx(loaded, rel=1e-9)
    assert prep.collapse_acceleration_g > 1.1 * limit_analysis(arch).collapse_acceleration_g
    assert used_restitution(cfg, arch)[0] == 0.8
