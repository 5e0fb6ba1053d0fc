"""``archquake warm`` compiles every kernel the commands use, so that no later command compiles.

Oracles: numba's own record of each dispatcher (``Dispatcher.stats``: cache hits and misses by
signature), numba's on-disk cache index (the signatures saved for each kernel) and numba's
debug trace (``NUMBA_DEBUG_CACHE`` prints ``data saved`` for every signature it compiles and
writes, in any process, worker processes included), all in fresh interpreters on a new, empty
``NUMBA_CACHE_DIR``, so that each check can fail. The kernel modules are found in the source
(the ``njit`` decorators), independently of :data:`archquake.warm.KERNEL_MODULES`. No timing is
asserted; ``benchmarks/bench_startup.py`` prints the times.
"""

from __future__ import annotations

import ast
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from archquake import warm as warm_module
from archquake.errors import InvalidParameterError

SRC = Path(__file__).resolve().parents[1] / "src" / "archquake"


def _env(cache_dir: Path, **extra: str) -> dict[str, str]:
    return dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir),
                PYTHONPATH=os.pathsep.join(p for p in sys.path if p), **extra)


def _python(code: str, cache_dir: Path) -> dict:
    done = subprocess.run([sys.executable, "-c", code], env=_env(cache_dir), capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def _decorated_kernels() -> dict[str, set[str]]:
    """{module: names of the functions it compiles with numba's ``njit``/``jit``}, from the AST."""
    found: dict[str, set[str]] = {}
    for path in SRC.rglob("*.py"):
        module = ".".join(("archquake", *path.relative_to(SRC).with_suffix("").parts))
        for node in ast.walk(ast.parse(path.read_text())):
            calls = []
            if isinstance(node, ast.FunctionDef):
                calls = [(d, node.name) for d in node.decorator_list]
            elif (isinstance(node, ast.Assign) and isinstance(node.value, ast.Call)
                  and isinstance(node.targets[0], ast.Name)):
                calls = [(node.value.func, node.targets[0].id)]  # name = nb.njit(...)(function)
            for decorator, name in calls:
                call = decorator.func if isinstance(decorator, ast.Call) else decorator
                attr = call.attr if isinstance(call, ast.Attribute) else getattr(call, "id", "")
                if attr in ("njit", "jit"):
                    found.setdefault(module, set()).add(name)
    return found


def test_the_kernel_modules_are_every_module_that_compiles_with_numba():
    assert set(warm_module.KERNEL_MODULES) == set(_decorated_kernels())


def test_dispatchers_finds_every_decorated_kernel():
    names = {(k.py_func.__module__, k.py_func.__name__) for k in warm_module.dispatchers()}
    for module, kernels in _decorated_kernels().items():
        for name in kernels:
            kernel = getattr(sys.modules[module], name)
            assert (kernel.py_func.__module__, kernel.py_func.__name__) in names, (module, name)


def test_an_unknown_workload_is_refused_in_one_line(capsys):
    with pytest.raises(InvalidParameterError, match="unknown warm-up 'nope'"):
        warm_module.warm(["nope"])
    from archquake.cli.main import main

    assert main(["warm", "--only", "nope"]) == 2
    err = capsys.readouterr().err
    assert "--only" in err and "four-link" in err and err.count("\n") == 1


WARM_MEASURES = """
import json
from archquake.warm import warm
print(json.dumps(warm(["measures"]).to_dict()))
"""


def test_a_workload_compiles_once_then_loads(tmp_path):
    """The cheapest workload (one kernel, ~1 s), twice on one new cache directory: the first
    process compiles (the directory was empty), the second only loads."""
    cache = tmp_path / "numba"
    first = _python(WARM_MEASURES, cache)
    second = _python(WARM_MEASURES, cache)
    assert [s["name"] for s in first["steps"]] == ["measures"]
    assert first["compiled"] >= 1 and first["steps"][0]["loaded"] == 0
    assert second["compiled"] == 0 and second["steps"][0]["loaded"] == first["compiled"]
    assert all(str(cache) in path for path in first["cache_dirs"])
    # each step's CPU time (this process's) is reported beside its wall time, and summed
    assert all(s["cpu_s"] > 0.0 for s in first["steps"])
    assert first["cpu_s"] == pytest.approx(sum(s["cpu_s"] for s in first["steps"]), rel=1e-12)


#: Commands a user runs first, each on a short problem: after ``archquake warm`` none may compile.
COMMANDS = [
    ["run", "--model", "fourlink", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27"],
    ["run", "--model", "fourlink", "--pulse", "sine", "--magnitude", "1.0", "--period", "0.5",
     "--json"],
    ["run", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27",
     "--t-end", "0.3", "--json"],
    ["run", "--integrator", "events", "--pulse", "step", "--magnitude",
     "1.0", "--duration", "0.27", "--t-end", "0.3"],
    ["run", "--friction", "0.6", "--pulse", "step", "--magnitude", "1.0",
     "--duration", "0.27", "--t-end", "0.1"],
    ["run", "--model", "dem", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27",
     "--t-end", "0.05", "--json"],
    ["domain", "--model", "fourlink", "--durations", "0.3", "--scan", "4", "--json"],
    ["domain", "--model", "rigid", "--durations", "0.3", "--scan", "4", "--json"],
    ["friction", "--model", "fourlink", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27"],
    ["records", "fema-p695-far-field", "--json"],
]


def _unused(kernel: str) -> bool:
    """Whether the kernel's name appears in the package's source only where it is defined."""
    word = re.compile(rf"\b{re.escape(kernel)}\b")
    return sum(len(word.findall(p.read_text())) for p in SRC.rglob("*.py")) <= 1


INDEX = """
import json
from archquake.warm import dispatchers
print(json.dumps({f"{k.py_func.__module__}.{k.py_func.__name__}":
                  [len(k._cache._cache_file._load_index()), k.targetoptions.get("inline", "never")]
                  for k in dispatchers()}))
"""


@pytest.mark.slow
def test_after_warm_every_kernel_is_cached_and_no_command_compiles(tmp_path):
    cache = tmp_path / "numba"
    cli = [sys.executable, "-m", "archquake.cli.main"]
    done = subprocess.run([*cli, "warm", "--json"], env=_env(cache), capture_output=True,
                          text=True, check=True)
    report = json.loads(done.stdout)
    assert report["compiled"] > 0 and set(s["name"] for s in report["steps"]) == set(
        warm_module.WORKLOADS)
    # every kernel has a signature in the cache, but those numba inlines into their callers
    # (no code of their own) and those nothing calls
    index = _python(INDEX, cache)
    missing = [name for name, (saved, inline) in index.items()
               if saved == 0 and inline != "always" and not _unused(name.rsplit(".", 1)[1])]
    assert missing == []
    for argv in COMMANDS:
        done = subprocess.run([*cli, *argv], env=_env(cache, NUMBA_DEBUG_CACHE="1"),
                              capture_output=True, text=True)
        assert done.returncode == 0, (argv, done.stderr[-400:])
        trace = done.stdout + done.stderr
        assert "[cache] index loaded" in trace, argv  # the command ran a kernel
        compiled = [line for line in trace.splitlines() if "data saved" in line]
        assert compiled == [], (argv, compiled)


def test_make_demo_and_make_test_warm_every_workload_once():
    """``make demo`` and ``make test`` warm numba's cache in two processes, one a core
    (``WARM_A`` and ``WARM_B`` in the Makefile): together the halves name every workload of
    :data:`archquake.warm.WORKLOADS`, each once, so a new workload cannot be left out, and
    both targets' recipes warm both halves."""
    text = (Path(__file__).resolve().parents[1] / "Makefile").read_text()
    halves = [re.search(rf"^{name}\s*:=\s*(.*)$", text, re.M) for name in ("WARM_A", "WARM_B")]
    assert all(halves), "WARM_A and WARM_B are defined in the Makefile"
    names = [n for m in halves if m for n in m.group(1).split()]
    assert sorted(names) == sorted(warm_module.WORKLOADS)
    for target in ("demo", "test"):
        recipe = re.search(rf"^{target}:.*\n((?:\t.*\n)+)", text, re.M)
        assert recipe, f"make {target} has a recipe"
        body = recipe.group(1)
        assert "warm --only $(WARM_A) &" in body and "warm --only $(WARM_B)" in body, target


ONE_SIGNATURE = """
import json
from archquake.warm import dispatchers, warm
warm(["rigid", "verdicts", "events"])
print(json.dumps({f"{d.py_func.__module__}.{d.py_func.__name__}": [str(s) for s in d.signatures]
                  for d in dispatchers()}))
"""


def test_the_rigid_workloads_compile_each_rigid_and_ground_kernel_once():
    """After the rigid chain's warm-up workloads (time stepper, verdicts, event integrator) each
    kernel of ``archquake.rigid`` and ``archquake.ground`` holds one signature: no caller passes
    a literal constant where the kernel is otherwise called with a run-time integer (numba
    would compile a copy specialised to the constant), and no caller of the contact solves
    passes None where the time step passes arrays (the event integrator's and the joint
    forces' solves pass empty ones). Run in a fresh interpreter on the usual
    cache (loads if warm, compiles otherwise)."""
    done = subprocess.run([sys.executable, "-c", ONE_SIGNATURE], capture_output=True, text=True,
                          check=True, env=dict(os.environ, PYTHONPATH=os.pathsep.join(
                              p for p in sys.path if p)))
    held = json.loads(done.stdout.strip().splitlines()[-1])
    assert held["archquake.rigid._event_kernels.run"]  # the workloads ran
    modules = ("archquake.rigid.", "archquake.ground.")
    several = {name: sigs for name, sigs in held.items()
               if name.startswith(modules) and len(sigs) > 1}
    assert several == {}
