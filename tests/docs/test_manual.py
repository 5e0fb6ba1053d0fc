"""The manual builds, and its guide runs as written.

Oracles: MkDocs itself (``mkdocs build --strict`` turns every broken link, missing anchor, page
left out of the navigation and docstring the API reference cannot parse into a failure), and the
command line and library (every ``$ archquake ...`` line of a guide page is run, and the output
printed under it must be what the command prints; every Python block is executed).

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
  says why in that paragraph (a visible marker, kept for long runs only).

Each page runs in its own temporary folder holding a copy of ``examples/``, so the commands'
relative paths are those of a clone.
"""

from __future__ import annotations

import contextlib
import doctest
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"

#: The pages whose commands and code are run: the README's tour, getting started, the guide by
#: task and the pages on the models. Reference pages, the API and the research notes are built,
#: not run.
RUN_PAGES = (
    "README.md",
    "docs/getting-started.md",
    "docs/guide/arch.md",
    "docs/guide/site.md",
    "docs/guide/records.md",
    "docs/guide/report.md",
    "docs/models/rigid.md",
    "docs/models/fourlink.md",
)

SKIP_MARK = "*Not run by the tests"
FENCE = re.compile(r"^```(\w*)\s*$")


@dataclass(frozen=True)
class Block:
    """One fenced block of a page: its language, first line number and lines."""

    language: str
    line: int
    lines: tuple[str, ...]
    skipped: bool


def blocks_of(text: str) -> list[Block]:
    """The fenced blocks of a Markdown page, in order, each marked skipped or not."""
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


def commands_of(block: Block) -> list[tuple[str, str]]:
    """The ``(command, expected output)`` pairs of a console block."""
    pairs: list[tuple[str, list[str]]] = []
    for line in block.lines:
        if line.startswith("$ "):
            pairs.append((line[2:], []))
        elif pairs:
            pairs[-1][1].append(line)
        elif line.strip():
            raise AssertionError(f"line {block.line}: output before any command: {line!r}")
    return [(cmd, "\n".join(out).strip("\n")) for cmd, out in pairs]


def run_command(command: str, cwd: Path) -> tuple[int, str]:
    """Run one command of a page in ``cwd``; ``archquake`` runs in this process (compiled kernels
    are shared between the commands), anything else in a shell. Returns (status, stdout)."""
    argv = shlex.split(command)
    if argv[0] != "archquake":
        done = subprocess.run(command, shell=True, cwd=cwd, capture_output=True, text=True, timeout=600)
        return done.returncode, done.stdout + done.stderr
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
    assert same_output("a ...\nz", "a b c\nz")
    assert not same_output("a b\n", "a c\n")


@pytest.mark.parametrize("page", RUN_PAGES)
def test_page_runs_as_written(page, tmp_path, monkeypatch):
    """Every command of the page succeeds and prints what the page shows; every code block runs."""
    monkeypatch.setenv("MPLBACKEND", "Agg")
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    text = (ROOT / page).read_text(encoding="utf-8")
    namespace: dict[str, object] = {"__name__": f"manual:{page}"}
    ran = 0
    for block in blocks_of(text):
        if block.skipped or block.language not in ("console", "python", "pycon"):
            continue
        where = f"{page}, line {block.line}"
        if block.language == "pycon":
            monkeypatch.chdir(tmp_path)
            source = "\n".join(block.lines)
            test = doctest.DocTestParser().get_doctest(source, namespace, where, page, block.line)
            report = io.StringIO()
            runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
            runner.run(test, out=report.write, clear_globs=False)
            assert runner.failures == 0, f"{where}:\n{report.getvalue()}"
            ran += 1
            continue
        if block.language == "python":
            monkeypatch.chdir(tmp_path)
            exec(compile("\n".join(block.lines), where, "exec"), namespace)  # noqa: S102
            ran += 1
            continue
        for command, want in commands_of(block):
            status, got = run_command(command, tmp_path)
            expected_status = 2 if want.startswith("archquake: error:") else 0
            assert status == expected_status, f"{where}: `{command}` exited {status}:\n{got}"
            if want:
                assert same_output(want, got), f"{where}: `{command}` printed\n{got}\nthe page shows\n{want}"
            ran += 1
    assert ran > 0, f"{page} shows nothing that runs"


def test_manual_builds_strict(tmp_path):
    """``mkdocs build --strict``: no broken link or anchor, every page in the navigation, every
    docstring of the API reference parsed."""
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, timeout=600,
    )
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]
    assert (tmp_path / "site" / "api" / "archquake" / "index.html").exists()


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
