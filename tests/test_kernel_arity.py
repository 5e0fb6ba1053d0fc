"""No function of the packed models takes 15 or more parameters.

Oracle: the source itself, parsed with ``ast``: every ``def`` (methods, nested functions and
numba kernels included) of the files matched by `COVERED`, its parameters counted as Python
binds them (positional, keyword-only, ``*args`` and ``**kwargs``, ``self`` included). The limit
is exact (`LIMIT`): a model's kernels take the model packed once (the mechanism table, the
excitation, the settings, the output buffers: `archquake.mechanism._kernels`), not one
argument per array and scalar, as the DEM's do.

`COVERED` lists the source files checked, as globs under ``src/archquake``; a model whose
kernels are packed is added there. The IDA's public ``incremental_dynamic_analysis`` (16
keyword options) is why ``ida/`` is covered through its kernels only; the rigid chain is
covered through its kernels, the modules that pack for them and its driver (``rigid/run.py``).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import archquake

ROOT = Path(archquake.__file__).parent

#: The files checked, globs relative to ``src/archquake``.
COVERED: tuple[str, ...] = ("mechanism/*.py", "domains/*.py", "ida/_kernels.py",
                            "rigid/_*_kernels.py", "rigid/model.py", "rigid/steps.py",
                            "rigid/verdict.py", "rigid/events.py", "rigid/forces.py",
                            "rigid/run.py")

#: A function with this many parameters or more fails.
LIMIT = 15


def arity(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Number of parameters of a ``def``: positional-only, ordinary, keyword-only, and one
    each for ``*args`` and ``**kwargs``."""
    a = node.args
    return (len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + (a.vararg is not None)
            + (a.kwarg is not None))


def wide_functions(path: Path, limit: int = LIMIT) -> list[str]:
    """``"file:line name (n parameters)"`` for each ``def`` of ``path`` with ``limit`` or more."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    return [f"{path.relative_to(ROOT)}:{node.lineno} {node.name} ({arity(node)} parameters)"
            for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
            and arity(node) >= limit]


def covered_files() -> list[Path]:
    return sorted({p for pattern in COVERED for p in ROOT.glob(pattern)})


def test_every_covered_glob_matches_source_files():
    """A glob that matches nothing (a moved package) would check nothing."""
    for pattern in COVERED:
        assert list(ROOT.glob(pattern)), f"{pattern} matches no file under {ROOT}"


@pytest.mark.parametrize("path", covered_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_no_function_takes_fifteen_or_more_parameters(path):
    assert wide_functions(path) == []


def test_the_count_sees_every_kind_of_parameter(tmp_path):
    """The counter on a function of 15 parameters of every kind, and on one of 14."""
    source = tmp_path / "wide.py"
    source.write_text(
        "def wide(a, b, /, c, d, e, f, g, h, *args, i, j, k, l, m, **kwargs):\n    pass\n"
        "class C:\n    def narrow(self, a, b, c, d, e, f, g, h, i, j, k, l, m):\n        pass\n",
        encoding="utf-8")
    tree = ast.parse(source.read_text(encoding="utf-8"))
    counts = {n.name: arity(n) for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
    assert counts == {"wide": 15, "narrow": 14}
