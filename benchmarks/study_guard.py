"""Study: does the rigid chain's verdict on an earthquake record move with the step, and which
rule flags it? (docs/notes/mechanism.md, "The rigid chain's step, its guard and its verdict
path": the records' part).

For an arch under the 28 FEMA P695 near-field pulse components scaled in PGA over a grid of
levels, the raw verdicts (guard off) at the default step h, at h/2 and at h/4 (the reference),
batched and threaded through :func:`archquake.rigid.rigid_verdicts`. Each batch is stored as it
ends (``--out``, JSON lines), so an interrupted run resumes. Then ``--table`` prints, for each
candidate rule that would rerun a verdict at h/2: how many verdicts it reruns (its cost), and of
the verdicts where h and h/4 differ, how many it would flag ``indeterminate`` (h and h/2 differ
there) and how many it misses. Also each record's first collapsing level on the grid at each
step, and the CPU time of each batch. Needs the FEMA suites (``archquake[records]``). Run:

    .venv/bin/python benchmarks/study_guard.py --arch bridge --out guard-bridge.jsonl
    .venv/bin/python benchmarks/study_guard.py --arch bridge --out guard-bridge.jsonl --table

CPU time is the process's (``time.process_time``, both threads), so it holds on a loaded machine.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from collections.abc import Callable
from pathlib import Path

from archquake.geometry import Arch
from archquake.ground.measures import im_value
from archquake.ground.suites import load_suite
from archquake.rigid import rigid_verdicts
from archquake.rigid.verdict import GUARD_LENGTHENING, verdict_time_step

ARCHES = {
    # examples/bridge.toml's arch (density does not change a rigid chain's verdict)
    "bridge": (Arch(5.0, 0.6, math.pi, 15),
               [0.06, 0.07, 0.08, 0.09, 0.10, 0.11, 0.12, 0.14, 0.16, 0.20]),
    # Oppenheim's arch (lambda = 0.370 g)
    "oppenheim": (Arch(10.0, 1.5, math.radians(157.5), 7),
                  [0.40, 0.45, 0.50, 0.60, 0.70, 0.80, 1.00, 1.20]),
}
DIVISORS = (1, 2, 4)
KEYS = ("outcome", "collapse_half_cycle", "collapse_time_s", "onset_time_s", "end_time_s",
        "peak_crown_drop", "max_rotation_rad", "lengthening", "impacts", "steps", "final_state")


def run(arch_name: str, out: Path, threads: int, levels: list[float] | None) -> None:
    arch, grid = ARCHES[arch_name]
    levels = grid if levels is None else levels
    records = load_suite("near-field-pulse").records
    pga = [im_value(r, "pga") for r in records]
    h = verdict_time_step(arch)
    done = {(e["level_g"], e["divisor"]) for e in _load(out)}
    for divisor in DIVISORS:
        for level in levels:
            if (level, divisor) in done:
                continue
            motions = [r.scaled(level / p) for r, p in zip(records, pga, strict=True)]
            c0 = time.process_time()
            vs = rigid_verdicts(arch, motions, guard=False, time_step=h / divisor,
                                threads=threads)
            cpu = time.process_time() - c0
            entry = {"arch": arch_name, "level_g": level, "divisor": divisor,
                     "time_step_s": h / divisor, "cpu_s": cpu,
                     "verdicts": [{"record": r.name, **{k: v.to_dict()[k] for k in KEYS}}
                                  for r, v in zip(records, vs, strict=True)]}
            with out.open("a") as f:
                f.write(json.dumps(entry) + "\n")
            print(f"{arch_name} {level:.3f} g h/{divisor}: {cpu:.1f} s CPU", flush=True)


def _load(out: Path) -> list[dict]:
    if not out.exists():
        return []
    return [json.loads(line) for line in out.read_text().splitlines() if line.strip()]


def _decided(outcome: str) -> str:
    """Survival or collapse as the IDA counts them (an unfinished run counts as collapse)."""
    return "survives" if outcome in ("survives", "no_hinging") else "collapse"


#: Candidate triggers of a rerun at h/2, on the verdict at h (a dict of KEYS).
RULES: dict[str, Callable[[dict], bool]] = {
    "current: any later half cycle > 2.0 x the first":
        lambda d: d["impacts"] >= 1 and d["outcome"] in ("survives", "collapse")
        and d["lengthening"] > GUARD_LENGTHENING,
    "every verdict after an impact": lambda d: d["impacts"] >= 1,
    "every collapse": lambda d: d["outcome"] == "collapse",
    "collapse after an impact": lambda d: d["outcome"] == "collapse" and d["impacts"] >= 1,
    "survival with crown drop > 0.3": lambda d: d["outcome"] == "survives"
        and d["peak_crown_drop"] > 0.3,
    "everything that hinged": lambda d: d["outcome"] != "no_hinging",
}


def table(out: Path) -> None:
    entries = _load(out)
    by = {(e["level_g"], e["divisor"]): e for e in entries}
    levels = sorted({e["level_g"] for e in entries if all((e["level_g"], d) in by
                                                           for d in DIVISORS)})
    rows = []
    for level in levels:
        vs = [by[(level, d)]["verdicts"] for d in DIVISORS]
        for a, b, c in zip(*vs, strict=True):
            rows.append((level, a, b, c))
    n = len(rows)
    print(f"{n} verdicts ({len(levels)} levels x {n // max(1, len(levels))} records)")
    cpu = {d: sum(by[(lv, d)]["cpu_s"] for lv in levels) for d in DIVISORS}
    print("CPU s by step: " + ", ".join(f"h/{d} {cpu[d]:.0f}" for d in DIVISORS))
    d14 = [r for r in rows if _decided(r[1]["outcome"]) != _decided(r[3]["outcome"])]
    d24 = [r for r in rows if _decided(r[2]["outcome"]) != _decided(r[3]["outcome"])]
    d12 = [r for r in rows if _decided(r[1]["outcome"]) != _decided(r[2]["outcome"])]
    print(f"h vs h/4 differ: {len(d14)}; h/2 vs h/4: {len(d24)}; h vs h/2: {len(d12)}")
    for level in levels:
        sub = [r for r in rows if r[0] == level]
        print(f"  {level:.3f} g: collapses h {sum(_decided(r[1]['outcome']) == 'collapse' for r in sub)}"
              f" h/2 {sum(_decided(r[2]['outcome']) == 'collapse' for r in sub)}"
              f" h/4 {sum(_decided(r[3]['outcome']) == 'collapse' for r in sub)};"
              f" h!=h/4 {sum(r in d14 for r in sub)}, h/2!=h/4 {sum(r in d24 for r in sub)},"
              f" current rule reruns {sum(RULES[next(iter(RULES))](r[1]) for r in sub)}")
    print("| rule | reruns | of h != h/4: flagged | missed | flagged where h = h/4 |")
    for name, rule in RULES.items():
        rerun = [r for r in rows if rule(r[1])]
        flagged = [r for r in rerun if _decided(r[1]["outcome"]) != _decided(r[2]["outcome"])]
        caught = [r for r in flagged if r in d14]
        print(f"| {name} | {len(rerun)} | {len(caught)} | {len(d14) - len(caught)} |"
              f" {len(flagged) - len(caught)} |")
    print("h != h/4 in detail (level, record, h, h/2, h/4 outcome; impacts, lengthening, "
          "drop at h):")
    for level, a, b, c in d14:
        print(f"  {level:.3f} {a['record']:22s} {a['outcome']:9s} {b['outcome']:9s} "
              f"{c['outcome']:9s} imp {a['impacts']:3d} len {a['lengthening']:5.2f} "
              f"drop {a['peak_crown_drop']:.3f} half {a['collapse_half_cycle']}")
    print("first collapsing level on the grid, by record (h, h/2, h/4):")
    names = [v["record"] for v in by[(levels[0], 1)]["verdicts"]] if levels else []
    moved = 0
    for i, name in enumerate(names):
        firsts = []
        for d in DIVISORS:
            first = next((lv for lv in levels
                          if _decided(by[(lv, d)]["verdicts"][i]["outcome"]) == "collapse"),
                         None)
            firsts.append(first)
        moved += len(set(firsts)) > 1
        print(f"  {name:22s} " + " ".join("-" if f is None else f"{f:.3f}" for f in firsts))
    print(f"first collapse moves with the step on {moved} of {len(names)} records")
    print("first collapsing level on the grid with each guard, against h/4's "
          "(indeterminate counted as collapse, as the IDA counts it):")
    print("| guard | reruns | equal | lower (conservative) | higher (missed) |")
    for name, rule in (("none", lambda d: False), ("current rule", RULES[next(iter(RULES))]),
                       ("deciding levels", None)):
        reruns = 0
        tally = [0, 0, 0]
        for i in range(len(names)):
            at_h = [by[(lv, 1)]["verdicts"][i] for lv in levels]
            at_h2 = [by[(lv, 2)]["verdicts"][i] for lv in levels]
            ref = [_decided(by[(lv, 4)]["verdicts"][i]["outcome"]) == "collapse"
                   for lv in levels]
            counted = [_decided(a["outcome"]) == "collapse" for a in at_h]
            if rule is not None:
                for k, (a, b) in enumerate(zip(at_h, at_h2, strict=True)):
                    if rule(a):
                        reruns += 1
                        counted[k] |= _decided(a["outcome"]) != _decided(b["outcome"])
            else:
                checked: set[int] = set()
                while True:
                    pending = [k for k in _deciding(counted) if k not in checked]
                    if not pending:
                        break
                    for k in pending:
                        checked.add(k)
                        reruns += 1
                        counted[k] |= (_decided(at_h[k]["outcome"])
                                       != _decided(at_h2[k]["outcome"]))
            first = next((k for k, c in enumerate(counted) if c), len(levels))
            first_ref = next((k for k, c in enumerate(ref) if c), len(levels))
            tally[0 if first == first_ref else 1 if first < first_ref else 2] += 1
        print(f"| {name} | {reruns} | {tally[0]} | {tally[1]} | {tally[2]} |")


def _deciding(counted: list[bool]) -> list[int]:
    """:func:`archquake.ida.analysis.deciding_levels` on a grid's collapse flags."""
    out = set()
    if counted and counted[0]:
        out.add(0)
    if counted and not counted[-1]:
        out.add(len(counted) - 1)
    for k in range(len(counted) - 1):
        if counted[k] != counted[k + 1]:
            out.update((k, k + 1))
    return sorted(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--arch", choices=sorted(ARCHES), default="bridge")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--levels", type=float, nargs="*")
    ap.add_argument("--table", action="store_true")
    args = ap.parse_args()
    if args.table:
        table(args.out)
    else:
        run(args.arch, args.out, args.threads, args.levels)


if __name__ == "__main__":
    main()
