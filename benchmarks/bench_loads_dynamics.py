"""Benchmark: what the loads cost in a rigid-chain history (target: at most 20 % more).

The example bridge (R 5 m, t 0.6 m, 15 voussoirs, 1800 kg/m^3) bare and with 1 m of fill, each
under a step pulse of 1.5 times its own lambda for 0.1 s, run for a fixed 2 s (the same number
of 1e-4 s steps, so the per-step cost is compared, not two different motions' lengths):

- the assembly's build (the loaded one adds the fill columns and the loaded statics' hinges);
- the history in the library (:func:`archquake.rigid.simulate_rigid`, model built each call);
- ``archquake run --t-end 2`` as a whole process.

Run: .venv/bin/python benchmarks/bench_loads_dynamics.py
"""

from __future__ import annotations

import math

from timing import BRIDGE_ARGS as BRIDGE  # benchmarks/timing.py
from timing import best_of
from timing import best_process as _process

from archquake.blocks.assembly import build_arch_assembly
from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads
from archquake.ground import StepImpulse
from archquake.limit.loaded import loaded_collapse, seismic_case
from archquake.rigid import simulate_rigid


def main() -> dict:
    arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
    fill = Loads(fill=Fill(depth=1.0, density=1800.0))
    lam = {"bare": loaded_collapse(seismic_case(arch)).multiplier,
           "fill": loaded_collapse(seismic_case(arch, fill)).multiplier}
    loads = {"bare": None, "fill": fill}
    build = {k: best_of(lambda k=k: build_arch_assembly(arch, loads=loads[k]), 5, 1)
             for k in loads}

    def history(k: str) -> None:
        simulate_rigid(build_arch_assembly(arch, loads=loads[k]),
                       StepImpulse.from_g(1.5 * lam[k], 0.1), duration=2.0)

    history("bare"), history("fill")  # compile and warm
    run = {k: best_of(lambda k=k: history(k), 3, 1) for k in loads}
    argv = ["run", *BRIDGE, "--pulse", "step", "--duration", "0.1", "--t-end", "2", "--json"]
    cli = {"bare": _process([*argv, "--magnitude", f"{1.5 * lam['bare']:.5f}"]),
           "fill": _process([*argv, "--magnitude", f"{1.5 * lam['fill']:.5f}",
                             "--fill-depth", "1"])}
    print("rigid chain, the bridge bare and with 1 m of fill, 2 s at 1e-4 s steps")
    print(f"  assembly build        bare {build['bare'] * 1e3:7.2f} ms   fill "
          f"{build['fill'] * 1e3:7.2f} ms")
    print(f"  history (library)     bare {run['bare']:7.3f} s    fill {run['fill']:7.3f} s   "
          f"{run['fill'] / run['bare']:4.2f} x (target <= 1.2)")
    print(f"  archquake run         bare {cli['bare']:7.3f} s    fill {cli['fill']:7.3f} s   "
          f"{cli['fill'] / cli['bare']:4.2f} x (whole process)")
    return {"build_bare_s": build["bare"], "build_fill_s": build["fill"],
            "history_bare_s": run["bare"], "history_fill_s": run["fill"],
            "run_bare_s": cli["bare"], "run_fill_s": cli["fill"]}


if __name__ == "__main__":
    main()
