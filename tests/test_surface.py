"""The public surface: the names the package and its subpackages export, held in one list, and
no private name crossing a package line.

Oracles:

* ``tests/data/public_api.json``, the committed list of the public names: the flat API
  (``archquake.__all__``) and each subpackage's ``__all__``. A name added to or removed from
  the surface fails here until the list is rewritten, on purpose::

      .venv/bin/python tests/test_surface.py --write

* the source, parsed with ``ast`` (every import, those inside functions included): a name
  ``_x`` is private to its package, so ``from archquake.<other package>... import _x`` is an
  error; a private module of another package (``archquake.blocks._kernels``) may be imported only
  by a private module (a compiled kernel calling another package's kernel: numba needs the
  function itself), except for the few listed in :data:`PRIVATE_MODULE_USES` with their
  reason. The root package's own private modules (``archquake._validate``, ``_json``,
  ``_dopri``, ``_kernel_cache``) are the foundation's helpers, shared by every layer by design.
"""

from __future__ import annotations

import ast
import importlib
import json
import pkgutil
import sys
from pathlib import Path

import archquake

ROOT = Path(archquake.__file__).parent
DATA = Path(__file__).parent / "data" / "public_api.json"

#: (importing module, imported private module) -> why it is allowed.
PRIVATE_MODULE_USES: dict[tuple[str, str], str] = {
    ("archquake.rigid.events", "archquake.blocks._kernels"):
        "the rigid chain checks the block models' compiled collapse criteria between its runs",
    ("archquake.rigid.steps", "archquake.blocks._kernels"):
        "the rigid chain checks the block models' compiled collapse criteria between its runs",
    ("archquake.ida.batch", "archquake.domains._kernels"):
        "the IDA batch decodes the domains' batch kernel's outcome codes",
    ("archquake.ida.batch", "archquake.mechanism._kernels"):
        "the IDA batch packs excitations for the four-link kernel",
}


def public_surface() -> dict[str, list[str]]:
    """``__all__`` of the root package and of every subpackage that has one, sorted."""
    out = {"archquake": sorted(archquake.__all__)}
    for info in pkgutil.iter_modules(archquake.__path__):
        if not info.ispkg:
            continue
        module = importlib.import_module(f"archquake.{info.name}")
        names = getattr(module, "__all__", None)
        if names is not None:
            out[module.__name__] = sorted(names)
    return out


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _package(module: str) -> str:
    """``archquake.dem`` for ``archquake.dem.result``; ``archquake`` for top-level modules."""
    parts = module.split(".")
    if len(parts) >= 2 and (ROOT / parts[1]).is_dir():
        return ".".join(parts[:2])
    return "archquake"


def _is_module(package: str, name: str) -> bool:
    folder = ROOT.joinpath(*package.split(".")[1:])
    return (folder / f"{name}.py").is_file() or (folder / name / "__init__.py").is_file()


def _private_module(module: str) -> bool:
    return any(p.startswith("_") and not p.startswith("__") for p in module.split(".")[1:])


def crossings() -> list[str]:
    """Every private name, and every private module not allowed, crossing a package line."""
    bad = []
    for path in sorted(ROOT.rglob("*.py")):
        importer = _module_name(path)
        home = _package(importer)
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                # ``from archquake.dem import _kernels`` imports a module, not a name
                targets = [(f"{node.module}.{alias.name}", "") if _is_module(node.module, alias.name)
                           else (node.module, alias.name) for alias in node.names]
            elif isinstance(node, ast.Import):
                targets = [(alias.name, "") for alias in node.names]
            else:
                continue
            for module, name in targets:
                if not module.startswith("archquake.") or _package(module) in (home, "archquake"):
                    continue
                if name.startswith("_") and not name.startswith("__"):
                    bad.append(f"{importer}: from {module} import {name}")
                elif (_private_module(module) and not _private_module(importer)
                      and (importer, module) not in PRIVATE_MODULE_USES):
                    bad.append(f"{importer}: imports {module}")
    return bad


def test_public_surface_is_the_committed_list():
    assert public_surface() == json.loads(DATA.read_text())


def test_public_names_are_public_and_resolve():
    for package, names in public_surface().items():
        module = importlib.import_module(package)
        for name in names:
            assert not name.startswith("_") or name == "__version__", (package, name)
            getattr(module, name)


def test_no_private_name_crosses_a_package():
    assert crossings() == []


def test_the_crossing_check_can_fail(tmp_path, monkeypatch):
    """A private name taken from another package is seen (the check is not vacuous)."""
    fake = tmp_path / "archquake"
    (fake / "assess").mkdir(parents=True)
    (fake / "reproduce").mkdir()
    (fake / "assess" / "report.py").write_text("from archquake.reproduce.report import _CSS\n")
    (fake / "reproduce" / "report.py").write_text("_CSS = ''\n")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", fake)
    assert crossings() == ["archquake.assess.report: from archquake.reproduce.report import _CSS"]


def test_listed_exceptions_are_still_needed():
    """Each allowed private-module use still exists (the list does not outlive its reason)."""
    used = set()
    for path in sorted(ROOT.rglob("*.py")):
        importer = _module_name(path)
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module:
                used.add((importer, node.module))
            elif isinstance(node, ast.Import):
                used.update((importer, alias.name) for alias in node.names)
    assert set(PRIVATE_MODULE_USES) <= used


if __name__ == "__main__":  # pragma: no cover - rewrites the committed list
    if sys.argv[1:] != ["--write"]:
        sys.exit("usage: python tests/test_surface.py --write")
    DATA.write_text(json.dumps(public_surface(), indent=1) + "\n")
