"""Run one ``archquake`` command line in-process, with a time bound, and say what came out.

The fuzz tests call :func:`call` with generated arguments and check the CLI's promise with
:func:`check`: exit 2 with exactly one stderr line starting ``archquake: error: `` that names
the option, or exit 0, and never an exception escaping :func:`archquake.cli.main.main`, within
the time bound.
"""

from __future__ import annotations

import contextlib
import faulthandler
import io
import os
import signal
import traceback
from collections.abc import Sequence
from dataclasses import dataclass

os.environ.setdefault("MPLBACKEND", "Agg")

#: A tiny valid study: one 5-voussoir arch under one step impulse (one case).
STUDY = """\
[study]
name = "fuzz"
model = "fourlink"

[arches]
radius = 10
thickness_ratio = 0.15
embrace_deg = 157.5
voussoirs = 5

[excitation]
type = "step"
magnitude_g = 0.5
duration_s = 0.1

[options]
t_end_s = 1.0
"""

PREFIX = "archquake: error: "


class CallTimeout(BaseException):
    """Raised by the alarm inside a call that outlived its time bound (a BaseException so that
    no ``except Exception`` in the package swallows it)."""


@dataclass(frozen=True)
class Outcome:
    argv: tuple[str, ...]
    code: int | None
    out: str
    err: str
    crash: str | None  # the traceback of an exception that escaped main()
    timed_out: bool

    @property
    def error_lines(self) -> list[str]:
        return [line for line in self.err.splitlines() if line.strip()]


def _alarm(signum, frame):
    raise CallTimeout


def call(argv: Sequence[str], timeout: float = 30.0) -> Outcome:
    """``archquake ARGV`` through :func:`archquake.cli.main.main` with stdout and stderr
    captured, interrupted after ``timeout`` seconds (SIGALRM; main thread only)."""
    from archquake.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    code, crash, timed_out = None, None, False
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    # SIGALRM cannot interrupt compiled (numba) code: past twice the bound, dump every thread's
    # stack and end the process, so that a runaway kernel fails the run instead of hanging it
    faulthandler.dump_traceback_later(2 * timeout + 30, exit=True)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main(list(argv))
            except SystemExit as exc:  # --help, --version
                code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except CallTimeout:
        timed_out = True
    except Exception:  # noqa: BLE001  (a bug: reported, not raised, so the fuzz can count them)
        crash = traceback.format_exc()
    finally:
        faulthandler.cancel_dump_traceback_later()
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    return Outcome(tuple(argv), code, out.getvalue(), err.getvalue(), crash, timed_out)


def problem(result: Outcome, option: str | None = None) -> str | None:
    """What breaks the CLI's promise in ``result`` (None: nothing). ``option`` is the option
    the refusal must name (as typed, e.g. ``--duration``), when one is known."""
    if result.timed_out:
        return "timed out"
    if result.crash is not None:
        return "traceback: " + result.crash.strip().splitlines()[-1]
    if result.code == 0:
        return None
    if result.code != 2:
        return f"exit status {result.code}"
    lines = result.error_lines
    if len(lines) != 1:
        return f"{len(lines)} stderr lines: {lines[:3]}"
    line = lines[0]
    if not line.startswith(PREFIX) or line.count("archquake: error") != 1:
        return f"bad prefix: {line}"
    if option is not None and option not in line:
        return f"does not name {option}: {line}"
    return None


def numba_lock_on_disk() -> tuple[str | None, bool]:
    """In a pool worker: the name of numba's per-process lock, and whether the name is still
    linked (a named POSIX semaphore shows in /dev/shm as sem.NAME). Here so that a worker can
    import it by name."""
    from pathlib import Path

    from numba.np.ufunc import parallel

    lock = parallel._backend_init_process_lock
    name = getattr(getattr(lock, "_semlock", None), "name", None)
    return name, bool(name) and Path("/dev/shm", "sem." + name.lstrip("/")).exists()
