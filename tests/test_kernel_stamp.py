"""A cached kernel is compiled afresh when any source compiled into it changes, not only its
own file (numba checks only that one): a stale kernel would run old arithmetic silently.

Oracle: numba's own cache statistics (``cache_hits``, ``cache_misses``) of a kernel run in a
fresh interpreter on a copy of the package, before and after an edit to another file."""

from __future__ import annotations

import ast
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import archquake
from archquake._kernel_cache import KERNEL_MODULES, KERNEL_SOURCES, source_file

PACKAGE = Path(archquake.__file__).resolve().parent

#: A kernel run on a copy of the package: prints its (compiled, loaded) signature counts.
RUN = """
import json, sys
import numpy as np
from archquake.ground import _kernel as K
from archquake.ground.base import KIND_STEP
d = K.ground_acceleration
d(KIND_STEP, np.array([1.0, 0.2, 0.0, 0.0]), 0.1)
print(json.dumps([sum(d.stats.cache_misses.values()), sum(d.stats.cache_hits.values())]))
"""


def _run(root: Path, cache: Path) -> tuple[int, int]:
    env = dict(os.environ, PYTHONPATH=str(root), NUMBA_CACHE_DIR=str(cache))
    out = subprocess.run([sys.executable, "-c", RUN], capture_output=True, text=True, env=env,
                         check=True, cwd=root).stdout
    compiled, loaded = json.loads(out.strip().splitlines()[-1])
    return compiled, loaded


def test_an_edit_to_a_compiled_in_source_recompiles_the_kernel(tmp_path):
    root = tmp_path / "src"
    shutil.copytree(PACKAGE, root / "archquake",
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    cache = tmp_path / "cache"
    assert _run(root, cache) == (1, 0)  # compiled and cached
    assert _run(root, cache) == (0, 1)  # loaded
    # another file than the kernel's own: numba alone would load the old machine code
    with open(root / "archquake" / "constants.py", "a") as f:
        f.write("\n# an edit\n")
    assert _run(root, cache) == (1, 0)
    assert _run(root, cache) == (0, 1)


def _kernel_defining(path: Path) -> bool:
    tree = ast.parse(path.read_text())
    return any(isinstance(node, ast.FunctionDef) and any(
        "njit" in ast.unparse(dec) or "jit(" in ast.unparse(dec) for dec in node.decorator_list)
        for node in ast.walk(tree))


def _module(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def test_every_kernel_module_is_stamped_and_its_imports_covered():
    """`KERNEL_MODULES` is every module that defines a kernel; each calls ``stamp_kernels()``
    before its first kernel; every archquake module they import is in `KERNEL_SOURCES`."""
    files = sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)
    defining = {_module(p) for p in files if _kernel_defining(p)}
    assert defining == set(KERNEL_MODULES)
    for name in KERNEL_MODULES:
        tree = ast.parse(Path(source_file(name)).read_text())
        calls = [i for i, node in enumerate(tree.body) if isinstance(node, ast.Expr)
                 and ast.unparse(node.value) == "stamp_kernels()"]
        first = min(i for i, node in enumerate(tree.body) if isinstance(node, ast.FunctionDef)
                    and node.decorator_list)
        assert calls and calls[0] < first, name
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("archquake"):
                targets = [f"{node.module}.{a.name}" for a in node.names]
                targets = [t for t in targets if os.path.isfile(source_file(t))]  # modules
                for t in targets or [node.module]:
                    assert t in KERNEL_SOURCES, (name, t)
            elif isinstance(node, ast.Import):
                for a in node.names:
                    if a.name.startswith("archquake"):
                        assert a.name in KERNEL_SOURCES, (name, a.name)
