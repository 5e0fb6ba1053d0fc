"""The package's imports point one way: down the layers, with no cycle.

Oracle: the source itself, parsed with ``ast`` (every ``import`` statement of every module,
those inside functions and under ``if TYPE_CHECKING`` included), against the layer order
written below. Three checks, each exact (a count that must be zero):

* no cycle between subpackages (``archquake.X``, a package or a top-level module);
* no cycle between modules;
* no import up the layers.

How an import is read. ``import a.b.c`` and ``from a.b import c`` where ``a.b.c`` is a module
are edges to the module ``a.b.c``; ``from a.b import name`` (a function, a class) is an edge to
``a.b`` (its module, or its package's ``__init__``). The parent packages that Python runs on
the way (``a/__init__``) are not counted as imported: a package's ``__init__`` re-exports its
modules, and counting it would make every module that imports a sibling part of a cycle.
``from archquake import name`` resolves the root package's lazy public names (its ``_LAZY``
table) to the modules that define them; its other names (``__version__``, ``errors``) need
only the root's own top (errors, constants, the kernel cache). The root ``__init__`` itself,
the public facade over everything, is not checked.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import archquake

ROOT = Path(archquake.__file__).parent

#: The layers, bottom first. A unit may import units of its own layer or below, never above.
#: Why this order:
#: - foundation: constants, errors and the helpers every layer uses (units, ranges, argument
#:   validation, JSON, the kernel cache, the outcome vocabulary, the result interface, the
#:   Dormand-Prince tableau, process pools, the lazy loader of names); they import nothing
#:   above them;
#: - geometry (the arch) -> ground (motions) -> codes (design codes' elastic spectra, numbers
#:   only) -> limit (statics of the arch) -> validation (closed
#:   forms and the paper's numbers, read by the DEM's post-processing);
#: - blocks: what the two block models stand on (assemblies, the thresholds of their verdict,
#:   their result and its post-processing);
#: - the three models, each on what is below: mechanism (the paper's four-link model), dem, and
#:   rigid (on the blocks; it imports nothing from dem: `test_rigid_imports_nothing_from_dem`),
#:   each with its own run to a verdict;
#: - models: the one way to run any of the three (their names and ``run``), above them and
#:   below everything that runs a model by its name;
#: - thrust (the line of thrust in motion, from the four-link model), domains (failure domains
#:   of the four-link model);
#: - compare (the models against each other) -> codecheck (the code check of the arch's
#:   mechanism: its kinematics, the site's spectra, the rigid chain's run to a verdict) ->
#:   sweeps (grids of cases of any model, run through models) -> ida (incremental dynamic
#:   analysis through sweeps) -> warm (compiles every
#:   model's kernels, the batched ones of domains and ida included);
#: - plotting (figures of results) -> reproduce (the paper's studies, which draw figures) ->
#:   assess (a bridge's assessment, reusing the reproduction's report) -> cli (the shell).
LAYERS: tuple[tuple[str, ...], ...] = (
    ("constants", "errors", "units", "ranges", "_validate", "_json", "_kernel_cache", "outcome",
     "result", "_dopri", "parallel", "_lazy", "_deprecated"),
    ("geometry",),
    ("ground",),
    ("codes",),
    ("limit",),
    ("validation",),
    ("blocks",),
    ("mechanism",),
    ("dem",),
    ("rigid",),
    ("models",),
    ("thrust",),
    ("domains",),
    ("compare",),
    ("codecheck",),
    ("sweeps",),
    ("ida",),
    ("warm",),
    ("plotting",),
    ("reproduce",),
    ("assess",),
    ("cli",),
)
#: Units of the root package's own top-level code (what ``from archquake import __version__``
#: runs): they sit in the foundation.
ROOT_TOP = "errors"


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _modules(root: Path) -> dict[str, Path]:
    return {_module_name(p, root): p for p in sorted(root.rglob("*.py"))}


def _lazy_names(root: Path) -> dict[str, str]:
    """The root package's ``_LAZY`` table: public name -> defining module."""
    tree = ast.parse((root / "__init__.py").read_text(encoding="utf-8"))
    for node in tree.body:
        target = getattr(node, "target", None) or (node.targets[0] if isinstance(node, ast.Assign)
                                                   else None)
        if isinstance(target, ast.Name) and target.id == "_LAZY":
            value = ast.literal_eval(node.value)
            assert isinstance(value, dict)
            return value
    return {}


def module_edges(root: Path = ROOT) -> set[tuple[str, str]]:
    """(importer, imported) between the package's modules, as the module docstring reads them."""
    modules = _modules(root)
    pkg = root.name
    lazy = _lazy_names(root)
    edges: set[tuple[str, str]] = set()
    for name, path in modules.items():
        if name == pkg:
            continue  # the facade
        is_pkg = path.name == "__init__.py"
        here = name.split(".") if is_pkg else name.split(".")[:-1]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    base = ".".join(here[: len(here) - node.level + 1] + ([base] if base else []))
                for alias in node.names:
                    sub = f"{base}.{alias.name}"
                    if sub in modules:
                        targets.append(sub)
                    elif base == pkg:
                        targets.append(lazy.get(alias.name, f"{pkg}.{ROOT_TOP}"))
                    else:
                        targets.append(base)
            for t in targets:
                while t and t not in modules:  # a name inside a module: the module
                    t = t.rpartition(".")[0]
                if t and t != name and t != pkg and t.split(".")[0] == pkg:
                    edges.add((name, t))
    return edges


def unit_of(module: str) -> str:
    """``archquake.X...`` -> ``X``."""
    return module.split(".")[1]


def unit_edges(root: Path = ROOT) -> set[tuple[str, str]]:
    return {(unit_of(a), unit_of(b)) for a, b in module_edges(root) if unit_of(a) != unit_of(b)}


def cycles(edges: set[tuple[str, str]]) -> list[list[str]]:
    """The strongly connected components of more than one node (Tarjan, iterative)."""
    adj: dict[str, list[str]] = {}
    for a, b in sorted(edges):
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, [])
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for start in adj:
        if start in index:
            continue
        work = [(start, 0)]
        while work:
            v, i = work.pop()
            if i == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on.add(v)
            if i < len(adj[v]):
                work.append((v, i + 1))
                w = adj[v][i]
                if w not in index:
                    work.append((w, 0))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            for w in adj[v]:
                if w in on:
                    low[v] = min(low[v], low[w])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def layer_of() -> dict[str, int]:
    return {unit: k for k, layer in enumerate(LAYERS) for unit in layer}


def imports_up(root: Path = ROOT) -> list[str]:
    """Module imports whose target's unit sits on a higher layer than the importer's."""
    layer = layer_of()
    return sorted(f"{a} -> {b}" for a, b in module_edges(root)
                  if layer[unit_of(a)] < layer[unit_of(b)])


def test_every_unit_has_a_layer():
    units = {unit_of(m) for m in _modules(ROOT) if m != ROOT.name}
    assert units - set(layer_of()) == set()
    assert set(layer_of()) - units == set()


def test_no_cycle_between_subpackages():
    assert cycles(unit_edges()) == []


def test_no_cycle_between_modules():
    assert cycles(module_edges()) == []


def test_no_import_up_the_layers():
    assert imports_up() == []


@pytest.mark.parametrize("edges, want", [
    ({("a", "b"), ("b", "c")}, []),
    ({("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")}, [["a", "b", "c"]]),
    ({("a", "b"), ("b", "a"), ("c", "d"), ("d", "c")}, [["a", "b"], ["c", "d"]]),
])
def test_cycles_finds_them(edges, want):
    """The checker can fail: hand-made graphs with and without cycles."""
    assert sorted(cycles(edges)) == want


def test_the_reader_sees_function_level_imports(tmp_path):
    """An import inside a function, and one up the layers, are seen (a package written here)."""
    pkg = tmp_path / "archquake"
    (pkg / "geometry").mkdir(parents=True)
    (pkg / "cli").mkdir()
    (pkg / "__init__.py").write_text("_LAZY = {}\n")
    (pkg / "errors.py").write_text("")
    (pkg / "geometry" / "__init__.py").write_text("")
    (pkg / "geometry" / "arch.py").write_text("def f():\n    from archquake.cli import main\n")
    (pkg / "cli" / "__init__.py").write_text("")
    (pkg / "cli" / "main.py").write_text("from archquake.geometry.arch import f\n")
    edges = module_edges(pkg)
    assert ("archquake.geometry.arch", "archquake.cli.main") in edges
    assert cycles(edges) == [["archquake.cli.main", "archquake.geometry.arch"]]
    assert imports_up(pkg) == ["archquake.geometry.arch -> archquake.cli.main"]


def imports_between(source: str, target: str, root: Path = ROOT) -> list[str]:
    """Module imports from the unit ``source`` into the unit ``target`` (as `module_edges`
    reads them: function-level imports and ``TYPE_CHECKING`` blocks included)."""
    return sorted(f"{a} -> {b}" for a, b in module_edges(root)
                  if unit_of(a) == source and unit_of(b) == target)


def test_rigid_imports_nothing_from_dem():
    """The rigid chain stands on the blocks, not on the distinct-element model: no module of
    ``rigid`` imports a module of ``dem`` (exact: the count is zero). Oracle: the source parsed
    with ``ast``."""
    assert imports_between("rigid", "dem") == []


def test_the_rigid_dem_check_can_fail(tmp_path):
    """An import of the DEM from a rigid module, at module level or inside a function, is seen
    (a package written here)."""
    pkg = tmp_path / "archquake"
    for unit in ("rigid", "dem"):
        (pkg / unit).mkdir(parents=True)
        (pkg / unit / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("_LAZY = {}\n")
    (pkg / "errors.py").write_text("")
    (pkg / "dem" / "settings.py").write_text("class DemSettings: ...\n")
    (pkg / "rigid" / "run.py").write_text("def f():\n    from archquake.dem.settings import "
                                          "DemSettings\n")
    (pkg / "rigid" / "steps.py").write_text("import archquake.dem.settings as S\n")
    assert imports_between("rigid", "dem", pkg) == [
        "archquake.rigid.run -> archquake.dem.settings",
        "archquake.rigid.steps -> archquake.dem.settings"]
