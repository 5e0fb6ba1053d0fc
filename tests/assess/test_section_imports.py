"""The sections side by side import nothing of the package that is not imported before they
start (`archquake.assess.runner.SECTION_MODULES`): two threads importing one package at once
can be handed it half initialised. Oracle: every module of the package the assessment's code
can reach, read from the code itself (its imports, at module level and inside functions,
followed from module to module), found imported in a fresh process after
`import_section_modules`."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import archquake

SRC = Path(archquake.__file__).resolve().parent.parent


def _path(module: str) -> Path | None:
    p = SRC.joinpath(*module.split("."))
    if (p / "__init__.py").exists():
        return p / "__init__.py"
    return p.with_suffix(".py") if p.with_suffix(".py").exists() else None


def _imports(module: str) -> set[str]:
    """The package's modules ``module`` imports anywhere in its code, with their parents."""
    path = _path(module)
    if path is None:
        return set()
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("archquake")}
        elif (isinstance(node, ast.ImportFrom) and node.level == 0 and node.module
              and node.module.startswith("archquake")):
            found.add(node.module)
            found |= {f"{node.module}.{a.name}" for a in node.names
                      if _path(f"{node.module}.{a.name}") is not None}
    parents = {".".join(m.split(".")[:i]) for m in found for i in range(1, m.count(".") + 2)}
    return {m for m in parents if _path(m) is not None}


def _reachable(start: list[str]) -> set[str]:
    seen: set[str] = set()
    todo = list(start)
    while todo:
        module = todo.pop()
        if module not in seen:
            seen.add(module)
            todo += sorted(_imports(module) - seen)
    return seen


def test_every_module_the_sections_reach_is_imported_before_they_start():
    reach = _reachable(["archquake.assess.runner", "archquake.assess.sections",
                        "archquake.assess.site", "archquake.assess.report"])
    assert "archquake.rigid.verdict" in reach and "archquake.dem.run" in reach  # the walk works
    code = ("import json, sys\n"
            "from archquake.assess.runner import import_section_modules\n"
            "import_section_modules()\n"
            "print(json.dumps(sorted(m for m in sys.modules if m.startswith('archquake'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    missing = sorted(reach - set(json.loads(out.stdout)))
    assert not missing, f"add to SECTION_MODULES: {missing}"
