"""The sections side by side import nothing of the package that is not imported before they
start (`archquake.assess.runner.SECTION_MODULES`): two threads importing one package at once
can be handed it half initialised. Oracle: every module of the package the assessment's code
can reach, read from the code itself (its imports, at module level and inside functions,
followed from module to module), found imported in a fresh process after
`import_section_modules`."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from test_layers import module_edges  # noqa: E402  (the package's imports, read from the code)


def _reachable(start: list[str]) -> set[str]:
    """The package's modules ``start`` import, at module level or inside functions, followed
    from module to module, with the packages they sit in (imported on the way)."""
    edges: dict[str, set[str]] = {}
    for a, b in module_edges():
        edges.setdefault(a, set()).add(b)
    seen: set[str] = set()
    todo = list(start)
    while todo:
        module = todo.pop()
        if module not in seen:
            seen.add(module)
            todo += sorted(edges.get(module, set()) - seen)
    return {".".join(m.split(".")[:i]) for m in seen for i in range(2, m.count(".") + 2)}


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
