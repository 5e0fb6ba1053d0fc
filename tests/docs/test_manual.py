"""The manual builds, and its pages run as written.

Oracles: MkDocs itself (``mkdocs build --strict`` turns every broken link, missing anchor, page
left out of the navigation and docstring the API reference cannot parse into a failure), and the
command line and library (every ``$ archquake ...`` line of a page in ``RUN_PAGES`` is run, and
the output printed under it must be what the command prints; every Python block is executed).

How a page is read:

- a ```` ```console ```` block holds commands, each on a line starting with ``$ ``; the lines after
  a command, up to the next command, are its output, compared with doctest's ELLIPSIS rule (a
  ``...`` stands for any text, so a page may elide timings or long tables but shows nothing the
  command does not print). A command followed by no output lines is only required to succeed;
  one whose output starts with ``archquake: error:`` must fail with exit status 2 and that line.
- a ```` ```python ```` block is executed, a ```` ```pycon ```` block (``>>>`` prompts) is run as a
  doctest (ELLIPSIS), so the values it shows are checked; the blocks of one page share one
  namespace.
- a block right after a paragraph starting with ``*Not run by the tests`` is skipped; the page
  says why in that paragraph (a visible marker, kept for what cannot run in a test: a Dask
  cluster, an interrupted run, a run of minutes).
- a block in any other language (``toml``, ``text``, none) is shown, not run.

Each page runs in its own temporary folder holding a copy of ``examples/``, so the commands'
relative paths are those of a clone.

Regenerating the pages when a command's output changes::

    .venv/bin/python tests/docs/test_manual.py            # every page: list what differs
    .venv/bin/python tests/docs/test_manual.py --write    # ... and rewrite it in place
    .venv/bin/python tests/docs/test_manual.py --write docs/assess.md   # one page

Without ``--write`` each difference is printed as a diff of the page's lines. ``--write`` runs
each page as the test does and, for every command or ``>>>`` example whose output no longer
matches, writes what it prints now in place of what the page showed. What a page chose to show
is kept where it still holds: an output that still matches is not touched; a line holding
``...`` is kept if it still matches the new line in its place; a whole line ``...`` stays, with
as many lines before the first such line and after the last as before (a stretch between two is
found again by its first line). Wall times are written ``(... wall)`` and the temporary folder
``...``. A command that exits with another status than the page expects, or a Python block that
raises, is reported and its block left as it was; the exit status is 1 if anything was
reported or (without ``--write``) differs. Blocks marked ``*Not run by the tests`` are not
touched: their output is updated by hand. Read ``git diff docs`` before committing: a changed
number is a changed result.
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import doctest
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import traceback
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"

#: The pages whose commands and code are run: the README's tour, getting started, the guide by
#: task, the pages on the models and the reference pages. The API, validation and the research
#: notes are built, not run; so is the spectra reference, whose record selections take some 20 s
#: of CPU (the guide's site page runs the same kinds of command on smaller sets).
RUN_PAGES = (
    "README.md",
    "docs/getting-started.md",
    "docs/guide/arch.md",
    "docs/guide/site.md",
    "docs/guide/records.md",
    "docs/guide/report.md",
    "docs/guide/reading.md",
    "docs/models/choosing.md",
    "docs/models/rigid.md",
    "docs/models/fourlink.md",
    "docs/models/dem.md",
    "docs/geometry.md",
    "docs/ground-motions.md",
    "docs/thrust-and-friction.md",
    "docs/loads.md",
    "docs/domains.md",
    "docs/earthquakes.md",
    "docs/sweeps.md",
    "docs/assess.md",
    "docs/code-check.md",
)

SKIP_MARK = "*Not run by the tests"
FENCE = re.compile(r"^```(\w*)\s*$")
#: A wall time as the commands print it, and as a page shows it.
WALL = re.compile(r"\(\d+(?:\.\d+)? s wall\)")
WALL_SHOWN = "(... wall)"


@dataclass(frozen=True)
class Block:
    """One fenced block of a page: its language, first line number and lines."""

    language: str
    line: int
    lines: tuple[str, ...]
    skipped: bool


def blocks_of(text: str) -> list[Block]:
    """The fenced blocks of a Markdown page, in order, each marked skipped or not.

    ``Block.line`` is the 1-based number of the opening fence, so ``lines[k]`` is the page's line
    ``line + k`` counted from 0."""
    found: list[Block] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if m is None:
            i += 1
            continue
        start = i
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        # the paragraph before the fence, if any, decides whether the block is skipped
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        paragraph: list[str] = []
        while k >= 0 and lines[k].strip():
            paragraph.insert(0, lines[k])
            k -= 1
        skipped = bool(paragraph) and paragraph[0].lstrip().startswith(SKIP_MARK)
        found.append(Block(m.group(1), start + 1, tuple(lines[start + 1 : j]), skipped))
        i = j + 1
    return found


@dataclass(frozen=True)
class Command:
    """One command of a console block, its expected output, and where that output sits in the
    block: ``block.lines[first:end]`` (blank lines at its end excluded)."""

    command: str
    want: str
    first: int
    end: int


def command_spans(block: Block) -> list[Command]:
    """The commands of a console block with the span of each one's output."""
    starts = [k for k, line in enumerate(block.lines) if line.startswith("$ ")]
    for k, line in enumerate(block.lines[: starts[0] if starts else len(block.lines)]):
        if line.strip():
            raise AssertionError(f"line {block.line + k + 1}: output before any command: {line!r}")
    found = []
    for n, k in enumerate(starts):
        stop = starts[n + 1] if n + 1 < len(starts) else len(block.lines)
        end = stop
        while end > k + 1 and not block.lines[end - 1].strip():
            end -= 1
        want = "\n".join(block.lines[k + 1 : end]).strip("\n")
        found.append(Command(block.lines[k][2:], want, k + 1, end))
    return found


def commands_of(block: Block) -> list[tuple[str, str]]:
    """The ``(command, expected output)`` pairs of a console block."""
    return [(c.command, c.want) for c in command_spans(block)]


def run_command(command: str, cwd: Path) -> tuple[int, str]:
    """Run one command of a page in ``cwd``; ``archquake`` runs in this process (compiled kernels
    are shared between the commands), anything else in a shell. Returns (status, stdout), with
    stderr appended when the status is not 0."""
    argv = shlex.split(command)
    if argv[0] != "archquake":
        done = subprocess.run(command, shell=True, cwd=cwd, capture_output=True, text=True, timeout=600)
        return done.returncode, done.stdout + (done.stderr if done.returncode else "")
    from archquake.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    old = Path.cwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = main(argv[1:])
    finally:
        os.chdir(old)
    return status, out.getvalue() + (err.getvalue() if status else "")


def same_output(want: str, got: str) -> bool:
    """doctest's comparison with ELLIPSIS, trailing blanks ignored."""
    want = "\n".join(line.rstrip() for line in want.splitlines()) + "\n"
    got = "\n".join(line.rstrip() for line in got.strip("\n").splitlines()) + "\n"
    return doctest.OutputChecker().check_output(want, got, doctest.ELLIPSIS)


def shown(got: str, workdir: Path | None = None) -> str:
    """An output as a page shows it: wall times as ``(... wall)``, the temporary folder the page
    ran in as ``...``, trailing blanks and blank lines at the ends removed."""
    if workdir is not None:
        for folder in {str(workdir.resolve()), str(workdir)}:
            got = got.replace(folder + os.sep, "...").replace(folder, "...")
    got = WALL.sub(WALL_SHOWN, got)
    return "\n".join(line.rstrip() for line in got.strip("\n").splitlines())


def _elided_pairs(old: list[str], new: list[str]) -> tuple[list[str], list[tuple[int, int]]] | None:
    """``new`` cut where ``old`` has whole ``...`` lines, and the (old, new) line pairs kept.

    The segment before the first cut keeps its length from the top, the one after the last cut
    from the bottom; a segment between two cuts is found again in ``new`` by its first line (equal,
    or matching it with ELLIPSIS) after the previous segment. ``None`` where ``new`` has no room
    for the segments or a middle segment's first line is not found."""
    cuts = [k for k, line in enumerate(old) if line.strip() == "..."]
    bounds = [-1, *cuts, len(old)]
    segments = [(bounds[n] + 1, bounds[n + 1]) for n in range(len(bounds) - 1)]
    out: list[str] = []
    pairs: list[tuple[int, int]] = []
    pos = 0
    for n, (first, end) in enumerate(segments):
        size = end - first
        if n == 0:
            start = 0
        elif n == len(segments) - 1:
            start = len(new) - size
        else:
            start = next((j for j in range(pos, len(new) - size + 1)
                          if old[first] == new[j] or same_output(old[first], new[j])), -1)
        if start < pos or start + size > len(new):
            return None
        if n > 0:
            out.append(old[cuts[n - 1]])
        out.extend(new[start : start + size])
        pairs.extend((first + k, len(out) - size + k) for k in range(size))
        pos = start + size
    return out, pairs


def merged(want: str, got: str) -> str:
    """The output to write for a command that printed ``got`` where the page shows ``want``.

    ``want`` is kept if it still matches. Otherwise ``got`` (as :func:`shown`), keeping the
    page's elisions where they still hold: a whole line ``...`` of ``want`` stays, with as many
    lines of ``got`` before the first and after the last as ``want`` had (and each stretch
    between two such lines found again by its first line); a line of ``want`` holding ``...`` is
    kept where it still matches the line of ``got`` in its place."""
    if same_output(want, got):
        return want
    old, new = want.splitlines(), got.splitlines()
    pairs = list(zip(range(len(old)), range(len(new))))
    if any(line.strip() == "..." for line in old):
        cut = _elided_pairs(old, new)
        new, pairs = cut if cut is not None else (new, [])
    for i, j in pairs:
        if "..." in old[i] and same_output(old[i], new[j]):
            new[j] = old[i]
    text = "\n".join(new)
    return text if same_output(text, got) else got


@dataclass
class Ran:
    """One thing of a page that ran: a command, a doctest block or a Python block.

    ``replace`` lists the edits that would make the page show what ran, as
    ``(first, end, lines)``: page lines ``first:end`` (0-based) become ``lines``."""

    where: str
    ok: bool
    message: str = ""
    fatal: bool = False
    replace: list[tuple[int, int, list[str]]] = field(default_factory=list)


class _Recorder(doctest.DocTestRunner):
    """A doctest runner that keeps each failing example with what it printed."""

    def __init__(self) -> None:
        super().__init__(optionflags=doctest.ELLIPSIS)
        self.failed: list[tuple[doctest.Example, str]] = []
        self.raised = 0

    def report_failure(self, out, test, example, got):  # type: ignore[no-untyped-def]
        self.failed.append((example, got))
        super().report_failure(out, test, example, got)

    def report_unexpected_exception(self, out, test, example, exc_info):  # type: ignore[no-untyped-def]
        self.raised += 1
        super().report_unexpected_exception(out, test, example, exc_info)


def run_page(page: str, workdir: Path) -> Iterator[Ran]:
    """Run the console, python and pycon blocks of ``page`` in ``workdir`` (which must hold a copy
    of ``examples/``), yielding what each did. Python blocks that raise propagate."""
    text = (ROOT / page).read_text(encoding="utf-8")
    namespace: dict[str, object] = {"__name__": f"manual:{page}"}
    for block in blocks_of(text):
        if block.skipped or block.language not in ("console", "python", "pycon"):
            continue
        where = f"{page}, line {block.line}"
        if block.language == "pycon":
            source = "\n".join(block.lines)
            test = doctest.DocTestParser().get_doctest(source, namespace, where, page, block.line)
            report = io.StringIO()
            runner = _Recorder()
            with contextlib.chdir(workdir):
                runner.run(test, out=report.write, clear_globs=False)
            edits = []
            for example, got in runner.failed:
                first = block.line + example.lineno + example.source.count("\n")
                want = example.want.rstrip("\n")
                end = first + example.want.count("\n")
                edits.append((first, end, merged(want, shown(got, workdir)).splitlines()))
            yield Ran(where, runner.failures == 0, report.getvalue(), fatal=runner.raised > 0, replace=edits)
            continue
        if block.language == "python":
            with contextlib.chdir(workdir):
                exec(compile("\n".join(block.lines), where, "exec"), namespace)  # noqa: S102
            yield Ran(where, True)
            continue
        for cmd in command_spans(block):
            status, got = run_command(cmd.command, workdir)
            expected_status = 2 if cmd.want.startswith("archquake: error:") else 0
            if status != expected_status:
                yield Ran(where, False, f"`{cmd.command}` exited {status}:\n{got}", fatal=True)
                continue
            if not cmd.want or same_output(cmd.want, got):
                yield Ran(where, True)
                continue
            lines = merged(cmd.want, shown(got, workdir)).splitlines()
            yield Ran(
                where, False, f"`{cmd.command}` printed\n{got}\nthe page shows\n{cmd.want}",
                replace=[(block.line + cmd.first, block.line + cmd.end, lines)],
            )


def test_blocks_of_reads_commands_outputs_and_the_skip_mark():
    """The reader itself, on a page made up here (so a broken reader cannot pass silently)."""
    page = (
        "text\n\n```console\n$ archquake a\nout 1\nout 2\n$ archquake b\n```\n\n"
        "*Not run by the tests: long.*\n\n```console\n$ archquake c\n```\n\n```python\nx = 1\n```\n"
    )
    found = blocks_of(page)
    assert [b.language for b in found] == ["console", "console", "python"]
    assert [b.skipped for b in found] == [False, True, False]
    assert commands_of(found[0]) == [("archquake a", "out 1\nout 2"), ("archquake b", "")]
    assert [(c.first, c.end) for c in command_spans(found[0])] == [(1, 3), (4, 4)]
    assert same_output("a ...\nz", "a b c\nz")
    assert not same_output("a b\n", "a c\n")


def test_merged_keeps_what_still_holds_and_writes_what_changed():
    """The regeneration's rule, on outputs made up here: an output that matches is kept as the
    page wrote it; a changed one is replaced, keeping a ``...`` line and its neighbours' count
    and an elided line that still matches; wall times and the temporary folder are elided."""
    assert merged("a ...\nb", "a 1\nb") == "a ...\nb"
    assert merged("x 1\ny ...\nz 1", "x 2\ny 7\nz 2") == "x 2\ny ...\nz 2"
    assert merged("h 1\n...\nt 1", "h 2\nm\nm\nt 2") == "h 2\n...\nt 2"
    assert merged("h 1\n...", "h 2\nm\nm") == "h 2\n..."
    assert merged("q ... 1", "q 5 2") == "q 5 2"
    assert merged("{\n...\n  rows\n  x ...\n  y 1\n...\n}", "{\na\nb\n  rows\n  x 7\n  y 2\nc\n}") == (
        "{\n...\n  rows\n  x ...\n  y 2\n...\n}")
    assert shown("3.10 s simulated (0.42 s wall)  ") == "3.10 s simulated (... wall)"
    assert shown("file /tmp/x/examples/a.csv", Path("/tmp/x")) == "file ...examples/a.csv"


@pytest.mark.parametrize("page", RUN_PAGES)
def test_page_runs_as_written(page, tmp_path, monkeypatch):
    """Every command of the page succeeds and prints what the page shows; every code block runs."""
    monkeypatch.setenv("MPLBACKEND", "Agg")
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    ran = 0
    for step in run_page(page, tmp_path):
        assert step.ok, f"{step.where}: {step.message}"
        ran += 1
    assert ran > 0, f"{page} shows nothing that runs"


def regenerate(page: str, write: bool) -> tuple[int, int, list[str], list[str]]:
    """Run ``page`` and, with ``write``, rewrite the outputs that changed. Returns the number of
    things run, the number that differ, the problems (failures the tool cannot rewrite) and the
    changes as unified diffs of the page's lines."""
    problems: list[str] = []
    edits: list[tuple[int, int, list[str]]] = []
    ran = differ = 0
    with tempfile.TemporaryDirectory(prefix="archquake-manual-") as folder:
        workdir = Path(folder)
        shutil.copytree(ROOT / "examples", workdir / "examples")
        try:
            for step in run_page(page, workdir):
                ran += 1
                if step.fatal:
                    problems.append(f"{step.where}: {step.message}")
                elif not step.ok:
                    differ += 1
                    edits.extend(step.replace)
                    if not step.replace:
                        problems.append(f"{step.where}: {step.message}")
        except Exception:  # noqa: BLE001 - a Python block of the page raised: report it, go on
            problems.append(f"{page}: a Python block raised (the page's later blocks did not run):\n"
                            + traceback.format_exc(limit=3))
    lines = (ROOT / page).read_text(encoding="utf-8").splitlines()
    changes = [
        "\n".join(difflib.unified_diff(lines[first:end], new, f"{page}:{first + 1}",
                                        f"{page}:{first + 1} now", n=0, lineterm=""))
        for first, end, new in sorted(edits)
    ]
    if write and edits:
        for first, end, new in sorted(edits, reverse=True):
            lines[first:end] = new
        (ROOT / page).write_text("\n".join(lines) + "\n", encoding="utf-8")
    return ran, differ, problems, changes


def main(argv: list[str] | None = None) -> int:
    """``python tests/docs/test_manual.py [--write] [PAGE ...]``: see the module's docstring."""
    parser = argparse.ArgumentParser(description="Run the manual's pages; with --write, rewrite "
                                     "the outputs that changed in place.")
    parser.add_argument("pages", nargs="*", help=f"pages to run (default: all {len(RUN_PAGES)} of RUN_PAGES)")
    parser.add_argument("--write", action="store_true", help="rewrite the outputs that changed")
    args = parser.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    failed = False
    for page in args.pages or RUN_PAGES:
        page = str(Path(page).resolve().relative_to(ROOT))
        ran, differ, problems, changes = regenerate(page, args.write)
        verb = "rewritten" if args.write else "differ"
        print(f"{page}: {ran} run, {differ} {verb}, {len(problems)} failed", flush=True)
        for change in changes if not args.write else []:
            print("  " + change.replace("\n", "\n  "), flush=True)
        for problem in problems:
            print("  " + problem.replace("\n", "\n  "), flush=True)
        failed = failed or bool(problems) or (differ > 0 and not args.write)
    return 1 if failed else 0


def test_manual_builds_strict(tmp_path):
    """``mkdocs build --strict``: no broken link or anchor, every page in the navigation, every
    docstring of the API reference parsed."""
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]
    assert (tmp_path / "site" / "api" / "archquake" / "index.html").exists()


def test_api_reference_prints_no_raw_sphinx_role(tmp_path):
    """The API reference renders docstrings as Markdown (mkdocstrings), where a Sphinx role
    (``:func:`x```) would print raw: the hook ``docs/hooks/roles.py`` makes each one a warning, so
    the strict build fails on it. Oracle: a docstring written with a role, built strict."""
    pkg = tmp_path / "src" / "rolepkg"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text('"""A module."""\n\n\ndef f():\n'
                                     '    """See :func:`g`."""\n\n\ndef g():\n    """G."""\n')
    (tmp_path / "docs" / "hooks").mkdir(parents=True)
    shutil.copy(ROOT / "docs" / "hooks" / "roles.py", tmp_path / "docs" / "hooks" / "roles.py")
    (tmp_path / "docs" / "index.md").write_text("# Roles\n\n::: rolepkg\n")
    (tmp_path / "mkdocs.yml").write_text(
        "site_name: roles\nexclude_docs: |\n  hooks/*.py\nhooks:\n  - docs/hooks/roles.py\n"
        "plugins:\n  - mkdocstrings:\n      handlers:\n        python:\n          paths: [src]\n"
        "          options:\n            docstring_style: numpy\n")
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode != 0 and "raw Sphinx role" in done.stderr, done.stderr[-2000:]
    role = re.compile(r":(?:mod|func|class|meth|attr|data|exc|obj):`")
    found = [f"{p.relative_to(ROOT)}:{n}" for p in sorted((ROOT / "src").rglob("*.py"))
             for n, line in enumerate(p.read_text().splitlines(), 1) if role.search(line)]
    assert found == [], found[:10]


#: Words that belong to how the code was written, not to how it is used.
PRIVATE_HISTORY = re.compile(r"\bissues? #?\d+|\b(?:next|this|previous|later) session\b", re.IGNORECASE)


def test_no_issue_numbers_or_sessions_in_what_users_read():
    """Docs, README, help texts and code comments speak to users: no tracker numbers, no
    sessions. The pattern is checked on a line that has one, so the test can fail."""
    assert PRIVATE_HISTORY.search("the chain of rigid blocks (issue 16)")
    assert PRIVATE_HISTORY.search("design for the next session")
    files = [ROOT / "README.md", *DOCS.rglob("*.md"), *(ROOT / "src").rglob("*.py")]
    found = [
        f"{path.relative_to(ROOT)}:{number}: {line.strip()}"
        for path in files
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if PRIVATE_HISTORY.search(line)
    ]
    assert not found, "\n".join(found)


def test_every_page_the_code_names_exists():
    """Help texts, docstrings and the README send readers to ``docs/...md``: each such page must
    exist (the manual's pages move; a test made up here shows the check can fail)."""
    pattern = re.compile(r"\bdocs/[\w./-]+?\.md\b")
    assert pattern.findall("see docs/no-such-page.md") == ["docs/no-such-page.md"]
    files = [ROOT / "README.md", *(ROOT / "src").rglob("*.py")]
    missing = sorted(
        f"{path.relative_to(ROOT)}: {name}"
        for path in files
        for name in pattern.findall(path.read_text(encoding="utf-8"))
        if not (ROOT / name).exists()
    )
    assert not missing, "\n".join(missing)


if __name__ == "__main__":
    sys.exit(main())
