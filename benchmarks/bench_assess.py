"""Benchmark: the whole ``archquake assess examples/bridge.toml`` command (default model, the
chain of rigid voussoirs; DEM check included), ``--quick`` and in full (the 28 FEMA P695
near-field pulse components), each in a fresh output folder, against a plain reference
measured in the same run: a Python process that only imports numpy (``python -c "import
numpy"``), so that the ratio says how many bare interpreter starts the command costs on this
machine, whatever its load.

Printed for each: wall time, the CPU time of the command and its child processes (user +
system: on shared cores the wall time grows with the other load, the CPU time much less), the
ratios of wall and of CPU times to the reference's, and each section's wall time as the report
records it (results.json). Targets (docs/assess.md): at most 30 s with ``--quick`` and 120 s in
full on two idle cores. The kernels are compiled first (``archquake warm``: numba's cache, as a
user's second run finds them). Needs the FEMA suites (``pip install 'archquake[records]'``).
Run:

    .venv/bin/python benchmarks/bench_assess.py          # quick and full
    .venv/bin/python benchmarks/bench_assess.py --quick  # quick only
    .venv/bin/python benchmarks/bench_assess.py --full   # full only
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "bridge.toml"


def _stat(pid: str) -> tuple[int, float] | None:
    """(parent pid, CPU s: user + system) of a live process from /proc, or None."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2:].split()  # after "pid (comm) "
    return int(fields[1]), (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _timed(argv: list[str]) -> tuple[float, float]:
    """Wall and CPU time (user + system) of one command and every process under it, s.

    The CPU time of the process pools' workers does not reach ``getrusage`` (they are the
    forkserver's children, which the command does not wait for), so on Linux the process tree
    is sampled from /proc every 0.1 s and each process's last reading summed (a process's last
    0.1 s may be missed); elsewhere the reaped children's ``getrusage`` only."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            cwd=ROOT)
    seen: dict[int, float] = {}
    tree = {proc.pid}
    while proc.poll() is None:
        if Path("/proc").is_dir():
            for entry in Path("/proc").iterdir():
                if not entry.name.isdigit():
                    continue
                st = _stat(entry.name)
                pid = int(entry.name)
                if st is not None and (pid in tree or st[0] in tree):
                    tree.add(pid)
                    seen[pid] = max(seen.get(pid, 0.0), st[1])
        time.sleep(0.1)
    wall = time.perf_counter() - t0
    if proc.returncode:
        raise subprocess.CalledProcessError(proc.returncode, argv)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    reaped = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # the command itself (and what it waited for) read exactly once reaped; the rest sampled
    return wall, reaped + sum(v for pid, v in seen.items() if pid != proc.pid)


def _archquake() -> list[str]:
    exe = Path(sys.executable).with_name("archquake")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "archquake"]


def main() -> None:
    args = sys.argv[1:]
    modes = ["--quick"] if "--quick" in args else [""] if "--full" in args else ["--quick", ""]
    refs = [_timed([sys.executable, "-c", "import numpy"]) for _ in range(5)]
    ref_wall, ref_cpu = min(w for w, _ in refs), min(c for _, c in refs)
    print(f"reference: python -c 'import numpy' {ref_wall:.3f} s wall, {ref_cpu:.3f} s CPU "
          "(best of 5)")
    _timed([*_archquake(), "warm"])  # numba's cache filled, as a user's second run finds it
    for mode in modes:
        with tempfile.TemporaryDirectory() as tmp:
            argv = [*_archquake(), "assess", str(EXAMPLE), "--out", tmp, *([mode] if mode else [])]
            wall, cpu = _timed(argv)
            sections = json.loads((Path(tmp) / "results.json").read_text())["sections"]
        name = "assess bridge.toml " + (mode or "(full)")
        print(f"{name}: {wall:.1f} s wall, {cpu:.1f} s CPU ({os.cpu_count()} cores); "
              f"{wall / ref_wall:.0f}x the reference's wall, {cpu / ref_cpu:.0f}x its CPU")
        print("  sections, wall s: " + ", ".join(f"{k} {v['seconds']:.1f}"
                                                 for k, v in sections.items()))


if __name__ == "__main__":
    main()
