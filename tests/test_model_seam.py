"""One seam for the three models: only `archquake.models` and the models' own packages branch
on a model's name.

Oracle: the source itself, parsed with ``ast``. A *branch on a model's name* is a comparison
(``==``, ``!=``, ``is``, ``is not``, ``in``, ``not in``) one of whose sides is a model's name:
``Model.RIGID``, ``Model.FOURLINK``, ``Model.DEM``, or the words ``"rigid"``, ``"fourlink"``,
``"dem"``, ``"analytical"``, ``"rigid_chain"`` (alone or in a tuple, list or set). Every other
module asks `archquake.models` (``models.run``, ``models.takes``) instead. The modules that
still branch are listed in `ALLOWED` with how many branches and why; the count is exact, so
that a new branch fails here and a removed one shrinks the list.
"""

from __future__ import annotations

import ast
from pathlib import Path

import archquake

ROOT = Path(archquake.__file__).parent

#: The seam and the models' own packages: they may name the models.
SEAM = ("archquake.models", "archquake.mechanism", "archquake.rigid", "archquake.dem")

#: Module -> (branches on a model's name, why they are there).
ALLOWED: dict[str, tuple[int, str]] = {
    "archquake.assess.report": (1, "'dem' is the name of the DEM check's section of the report"),
    "archquake.assess.runner": (2, "'dem' is the name of the DEM check's section"),
    "archquake.compare.rigid": (1, "runs the rigid chain or the DEM with the DEM settings' "
                                   "thresholds and output interval, which RunOptions does not "
                                   "carry"),
}

_NAMES = frozenset({"rigid", "fourlink", "dem", "analytical", "rigid_chain"})
_MEMBERS = frozenset({"RIGID", "FOURLINK", "DEM"})


def _is_name(node: ast.AST) -> bool:
    if isinstance(node, ast.Constant):
        return isinstance(node.value, str) and node.value in _NAMES
    if isinstance(node, ast.Attribute):
        return (node.attr in _MEMBERS and isinstance(node.value, ast.Name)
                and node.value.id == "Model")
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return any(_is_name(e) for e in node.elts)
    return False


def _module(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def model_branches(root: Path = ROOT) -> dict[str, list[int]]:
    """Module -> the lines of its comparisons against a model's name, outside the seam."""
    out: dict[str, list[int]] = {}
    for path in sorted(root.rglob("*.py")):
        name = _module(path, root)
        if any(name == s or name.startswith(s + ".") for s in SEAM):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Compare) and any(
                    _is_name(side) for side in (node.left, *node.comparators)):
                out.setdefault(name, []).append(node.lineno)
    return out


def test_only_the_seam_branches_on_a_model_name():
    found = {name: len(lines) for name, lines in model_branches().items()}
    allowed = {name: count for name, (count, _why) in ALLOWED.items()}
    assert found == allowed, {name: lines for name, lines in model_branches().items()
                              if len(lines) != allowed.get(name)}


def test_the_check_sees_each_kind_of_branch(tmp_path):
    """The check is not blind: each spelling of a branch is found (and a string that is not
    compared is not)."""
    pkg = tmp_path / "archquake"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "models.py").write_text("ok = m == 'rigid'\n")  # the seam
    (pkg / "caller.py").write_text(
        "a = model is Model.RIGID\n"
        "b = args.model == 'dem'\n"
        "c = word in ('fourlink', 'rigid')\n"
        "d = 'analytical' != x\n"
        "e = Model.DEM\n"
        "f = {'rigid': 1}\n")
    assert model_branches(pkg) == {"archquake.caller": [1, 2, 3, 4]}


def test_a_rigid_run_does_not_load_the_four_link_model():
    """The rigid chain's window ends at the end of the excitation + 60 sqrt(R/g)
    (`archquake.ranges.default_t_end`), without the four-link model. Oracle: ``sys.modules``
    after ``archquake run`` under the default model, in a fresh interpreter."""
    import subprocess
    import sys

    code = ("import sys, contextlib, io\n"
            "from archquake.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    assert main(['run', '--pulse', 'step', '--magnitude', '1.0', '--duration',"
            " '0.27', '--json']) == 0\n"
            "print(sorted(m for m in sys.modules if m.startswith('archquake.mechanism')))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"
