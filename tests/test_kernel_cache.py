"""Compiled kernels are cached on disk: a second process compiles nothing.

Oracle: numba's own per-dispatcher record (``Dispatcher.stats``: cache hits and misses by
signature) in two fresh interpreters sharing a new, empty ``NUMBA_CACHE_DIR``. The first must
miss (the directory was empty, so the test can fail), the second must load every kernel it
runs. No timing is asserted; ``benchmarks/bench_startup.py`` prints the times."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "archquake"

#: Run ``WORK`` then report every numba dispatcher of the package that holds a compiled
#: signature: {qualified name: [cache hits, cache misses]}.
PROBE = """
import json, sys
from numba.core.dispatcher import Dispatcher
{work}
seen = {{}}
for name, module in list(sys.modules.items()):
    if not name.startswith("archquake"):
        continue
    for attr, obj in list(vars(module).items()):
        if isinstance(obj, Dispatcher) and obj.signatures:
            s = obj.stats
            seen[f"{{obj.py_func.__module__}}.{{obj.py_func.__name__}}"] = [
                sum(s.cache_hits.values()), sum(s.cache_misses.values())]
print(json.dumps(seen))
"""

GROUND = """
import numpy as np
from archquake.ground import SinePulse, StepImpulse
from archquake.ground._kernel import ground_acceleration, ground_duration
for motion in (StepImpulse.from_g(0.5, 0.3), SinePulse.from_g(0.5, 0.3)):
    kind, params = motion.kernel_spec()
    ground_acceleration(kind, params, 0.1)
    ground_duration(kind, params)
"""

ANALYTICAL_AND_DOMAIN = """
import math
from archquake import Arch, StepImpulse, failure_domain, simulate
from archquake.domains import DomainSettings
arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
simulate(arch, StepImpulse.from_g(1.0, 0.27))
failure_domain(arch, "step", [0.2, 0.4], model="fourlink",
               settings=DomainSettings(coarse_points=6, fine_points=4, precision_g=0.05))
"""

DEM = """
import math
from archquake import Arch, StepImpulse, simulate_dem
from archquake.dem import DemSettings
arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
simulate_dem(arch, StepImpulse.from_g(1.0, 0.27), DemSettings(duration=0.01))
"""


def _run(work: str, cache_dir: Path) -> dict[str, list[int]]:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir),
               PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    done = subprocess.run([sys.executable, "-c", PROBE.format(work=work)], env=env,
                          capture_output=True, text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def _second_process_compiles_nothing(work: str, cache_dir: Path, packages: tuple[str, ...]) -> None:
    first = _run(work, cache_dir)
    assert first, "the work compiled no kernel of the package"
    assert sum(misses for _, misses in first.values()) > 0, "the new cache directory was not empty"
    second = _run(work, cache_dir)
    # a kernel called only from other kernels compiles with them in the first process, and in
    # the second is part of their cached code: the second sees a subset
    assert second and set(second) <= set(first)
    compiled_again = {name: misses for name, (_, misses) in second.items() if misses}
    assert compiled_again == {}
    assert all(hits > 0 for hits, _ in second.values())
    for package in packages:  # the kernels meant are among those loaded
        assert any(name.startswith(f"archquake.{package}.") for name in second), package


def test_every_njit_kernel_is_cached():
    """A source check: each ``njit``/``jit`` decorator in the package passes ``cache=True``."""
    missing = []
    for path in SRC.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call):
                continue
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
            if name in ("njit", "jit"):
                cache = {k.arg: k.value for k in node.keywords}.get("cache")
                if not (isinstance(cache, ast.Constant) and cache.value is True):
                    missing.append(f"{path.relative_to(SRC)}:{node.lineno}")
    assert missing == []


def test_ground_kernels_load_from_cache(tmp_path):
    _second_process_compiles_nothing(GROUND, tmp_path / "numba", ("ground",))


@pytest.mark.slow
def test_fourlink_and_domain_kernels_load_from_cache(tmp_path):
    """Includes the parallel (prange) batch kernel of the domain search, the four-link
    model's (the default model's domain search runs the rigid chain's verdicts instead)."""
    _second_process_compiles_nothing(ANALYTICAL_AND_DOMAIN, tmp_path / "numba",
                                     ("mechanism", "domains"))


@pytest.mark.slow
def test_dem_kernels_load_from_cache(tmp_path):
    _second_process_compiles_nothing(DEM, tmp_path / "numba", ("dem",))


class TestCacheDirFallback:
    """``archquake._kernel_cache.ensure_cache_dir``: oracle is numba's own locator order
    (user-set directory, beside the sources, the user's cache directory), with writability
    injected so the read-only cases run as any user."""

    def test_a_writable_package_keeps_numbas_choice(self):
        from archquake._kernel_cache import ensure_cache_dir

        env = {"HOME": "/home/u"}
        assert ensure_cache_dir(env, "/pkg", writable=lambda p: p == "/pkg") is None
        assert "NUMBA_CACHE_DIR" not in env

    def test_a_read_only_package_falls_back_to_the_user_cache(self):
        from archquake._kernel_cache import ensure_cache_dir, user_cache_dir

        env = {"HOME": "/home/u"}
        asked = []

        def writable(p):
            asked.append(p)
            return p == "/home/u/.cache/numba"

        assert ensure_cache_dir(env, "/pkg", writable=writable) is None
        assert asked == ["/pkg", "/home/u/.cache/numba"]
        assert user_cache_dir({"HOME": "/h", "XDG_CACHE_HOME": "/x"}) == "/x/numba"

    def test_nowhere_writable_sets_a_temporary_directory(self):
        from archquake._kernel_cache import ensure_cache_dir

        env = {"HOME": "/nonexistent"}
        chosen = ensure_cache_dir(env, "/pkg", writable=lambda p: False)
        assert chosen is not None and env["NUMBA_CACHE_DIR"] == chosen
        assert "archquake-numba-cache" in chosen

    def test_an_empty_xdg_cache_home_is_ignored(self):
        """numba would read an empty XDG_CACHE_HOME as the working directory (a relative
        ``numba``); the XDG specification says to use ``$HOME/.cache``."""
        from archquake._kernel_cache import ensure_cache_dir, user_cache_dir

        env = {"HOME": "/home/u", "XDG_CACHE_HOME": ""}
        assert user_cache_dir(env) == "numba"
        chosen = ensure_cache_dir(env, "/pkg", writable=lambda p: p != "/pkg")
        assert chosen == env["NUMBA_CACHE_DIR"] == "/home/u/.cache/numba"
        env = {"HOME": "/home/u", "XDG_CACHE_HOME": ""}
        chosen = ensure_cache_dir(env, "/pkg", writable=lambda p: p == "numba")
        assert chosen is not None and "archquake-numba-cache" in chosen

    def test_a_user_setting_is_never_changed(self):
        from archquake._kernel_cache import ensure_cache_dir

        env = {"NUMBA_CACHE_DIR": "/mine"}
        assert ensure_cache_dir(env, "/pkg", writable=lambda p: False) is None
        assert env["NUMBA_CACHE_DIR"] == "/mine"
