"""Fuzz the command line: hypothesis-generated values for every option of every command, output
paths, malformed record files and study keys.

Oracle: the CLI's promise (docs, errors.py): each call, run in-process through
:func:`archquake.cli.main.main` under a SIGALRM time bound, either exits 0 with a valid result
(``--json`` output that parses; an output file written at exactly the path given) or exits 2
with exactly one stderr line that starts ``archquake: error: `` and names the option (or file,
or study key) at fault. A traceback, a hang past the bound, a second stderr line or a message
that names an internal parameter is a failure.

Each example's work is tiny (5 voussoirs, short times) so that the quick version (a few hundred
examples) runs inside ``make test``; ``pytest -m slow tests/fuzz`` runs ten times as many.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from fuzz_harness import Outcome, call, problem
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

#: Time bound of one call, s: generous against a loaded 2-core machine (the first call of a
#: module also compiles or loads the numba kernels), far below a hang.
TIMEOUT = 60.0

QUICK = settings(max_examples=100, deadline=None, derandomize=True, database=None,
                 suppress_health_check=[HealthCheck.function_scoped_fixture,
                                        HealthCheck.too_slow])
THOROUGH = settings(QUICK, max_examples=600, derandomize=False)

# ------------------------------------------------------------------------------------------
# values
# ------------------------------------------------------------------------------------------
#: Edge values any option may receive: zero, signs, non-finite, overflow, underflow, junk.
EDGE = ["0", "-0", "-1", "nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e150", "-1e150",
        "1e-300", "-1e-300", "5e-324", "", " ", "abc", "1,2", "0x10", "1e", "+", "1e5", "1e400"]


def _outside_float() -> st.SearchStrategy[str]:
    """Floats far outside every option's working range (or not finite), as text."""
    return st.floats(allow_nan=True, allow_infinity=True).filter(
        lambda x: not 1e-4 <= abs(x) <= 1e4).map(repr)


def junk() -> st.SearchStrategy[str]:
    return st.one_of(st.sampled_from(EDGE), _outside_float(),
                     st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=6),
                     st.integers(max_value=2).map(str),
                     st.integers(min_value=10**5).map(str))


def floats_in(low: float, high: float) -> st.SearchStrategy[str]:
    return st.floats(low, high, allow_nan=False, allow_infinity=False).map(repr)


def ints_in(low: int, high: int) -> st.SearchStrategy[str]:
    return st.integers(low, high).map(str)


def value(valid: st.SearchStrategy[str]) -> st.SearchStrategy[str]:
    """Half cheap valid values, half junk."""
    return st.one_of(valid, junk())


ARCH = {
    "--radius": floats_in(0.8, 50.0),
    "--thickness": floats_in(0.01, 3.0),
    "--embrace": floats_in(1.0, 240.0),
    "--voussoirs": ints_in(3, 12),
    "--depth": floats_in(1e-3, 1e4),
    "--density": floats_in(1.0, 1e5),
}
PULSE = ["--pulse", "step", "--magnitude", "0.5", "--duration", "0.1"]
EXCITATION = {
    "--magnitude": floats_in(0.0, 3.0),
    "--duration": floats_in(1e-6, 1.0),
    "--period": floats_in(1e-6, 1.0),
    "--scale": floats_in(0.1, 2.0),
    "--units": st.sampled_from(["g", "m/s2", "G", "m/s^2"]),
    "--pulse": st.sampled_from(["step", "sine", "ramp"]),
    "--record": st.sampled_from(["quake.csv", "missing.csv", "quake.at3", "."]),
}
DEM_OPTIONS = {
    "--stiffness": floats_in(1e9, 1e12),
    "--friction": floats_in(0.3, 2.0),
    "--damping": st.tuples(floats_in(0.01, 10), floats_in(0, 1)).map(",".join),
    "--rayleigh": st.tuples(floats_in(0, 1), floats_in(0, 1e-4)).map(",".join),
    "--dem-assembly": st.sampled_from(["voussoirs", "hinges", "blocks"]),
}

LOADS = {
    "--fill-depth": floats_in(0.0, 3.0),
    "--fill-level": floats_in(4.0, 8.0),
    "--fill-density": floats_in(0.0, 3000.0),
    "--backing": floats_in(0.0, 3.0),
    "--backing-right": floats_in(0.0, 3.0),
    "--point-load": st.tuples(floats_in(0.0, 10.0), floats_in(-50.0, 200.0)).map(",".join),
    "--distributed-load": st.tuples(floats_in(0.0, 5.0), floats_in(0.0, 10.0),
                                    floats_in(0.0, 50.0)).map(",".join),
    "--passive": floats_in(0.0, 1.0),
    "--fill-friction": floats_in(0.0, 60.0),
}
BRIDGE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "7"]

#: command -> (base argv: valid, tiny, with --json; {option: cheap valid values})
COMMANDS: dict[str, tuple[list[str], dict[str, st.SearchStrategy[str]]]] = {
    "static": (["static", "--voussoirs", "5", "--json"],
               {**ARCH, "--voussoirs": ints_in(3, 80),  # the kinematic method's limit is 60
                "--method": st.sampled_from(["auto", "static", "kinematic", "both", "x"])}),
    "static-loads": (["static", *BRIDGE, "--fill-depth", "0.5", "--json"], LOADS),
    "capacity": (["capacity", *BRIDGE, "--fill-depth", "0.5", "--axle", "100", "--positions",
                  "5", "--json"],
                 {**LOADS, "--axle": floats_in(0.0, 500.0), "--dispersion": floats_in(0.0, 60.0),
                  "--position": floats_in(0.0, 10.0), "--positions": ints_in(2, 8),
                  "--patch-length": floats_in(0.0, 2.0)}),
    "min-thickness": (["min-thickness", "--voussoirs", "20", "--json"],
                      {"--embrace": floats_in(1.0, 240.0), "--voussoirs": ints_in(3, 40)}),
    "run": (["run", "--model", "fourlink", *PULSE, "--t-end", "1", "--voussoirs", "5", "--json"],
            {**ARCH, **EXCITATION, **DEM_OPTIONS,
             "--restitution": floats_in(0.0, 1.0), "--t-end": floats_in(0.01, 3.0),
             "--model": st.sampled_from(["fourlink", "analytical", "udec"])}),
    "run-dem": (["run", *PULSE, "--t-end", "0.05", "--voussoirs", "5", "--model", "dem", "--json"],
                {**DEM_OPTIONS, "--t-end": floats_in(0.01, 0.06),
                 "--restitution": floats_in(0.0, 1.0), "--magnitude": floats_in(0.0, 3.0)}),
    "thrust": (["thrust", "--model", "fourlink", *PULSE, "--times", "0.05", "--voussoirs", "5",
                "--json"],
               {**ARCH, **EXCITATION,
                "--times": st.lists(floats_in(0.0, 0.3), min_size=1, max_size=4).map(",".join)}),
    "friction": (["friction", "--model", "fourlink", *PULSE, "--voussoirs", "5", "--json"],
                 {**ARCH, **EXCITATION}),
    "domain": (["domain", "--model", "fourlink", "--durations", "0.3", "--scan", "4", "--precision", "0.1",
                "--max-magnitude", "1", "--voussoirs", "5", "--json"],
               {**ARCH, "--durations": st.one_of(floats_in(0.05, 1.0), st.just("0.2:0.4:2")),
                "--scan": ints_in(2, 8), "--precision": floats_in(0.05, 0.5),
                "--max-magnitude": floats_in(0.5, 2.0), "--workers": ints_in(1, 2),
                "--pulse": st.sampled_from(["step", "sine"])}),
    "record": (["record", "quake.csv", "--units", "g", "--json"],
               {"--scale": floats_in(0.1, 10.0), "--units": st.sampled_from(["g", "m/s2", "ms"])}),
    "spectrum": (["spectrum", "--code", "ntc2018", "--ag", "0.25", "--f0", "2.4", "--tc-star",
                  "0.3", "--periods", "0:2:0.5", "--json"],
                 {"--ag": floats_in(0.01, 3.0), "--f0": floats_in(2.2, 4.0),
                  "--tc-star": floats_in(0.05, 0.8), "--soil": st.sampled_from(["A", "d", "F"]),
                  "--topography": st.sampled_from(["T1", "t4", "T5"]),
                  "--damping": floats_in(0.0, 99.0), "--periods": st.sampled_from(
                      ["0:4:0.1", "0.1,0.5", "1:0.5", "0:20:0.001"]),
                  "--component": st.sampled_from(["horizontal", "vertical", "up"]),
                  "--ground": st.sampled_from(["A", "E"])}),
    "sweep": (["sweep", "study.toml", "--workers", "1", "--no-progress", "--json"],
              {"--workers": ints_in(1, 2), "--chunk-size": ints_in(1, 4),
               "--worker-wait": floats_in(1.0, 10.0), "--scheduler": st.just("nohost")}),
}

#: The default model (the chain of rigid voussoirs) for the commands that integrate it: run in
#: the slow set only (a rigid history costs 0.1-2 s where a four-link one costs milliseconds).
RIGID_COMMANDS: dict[str, tuple[list[str], dict[str, st.SearchStrategy[str]]]] = {
    "run-rigid": (["run", *PULSE, "--voussoirs", "5", "--json"],
                  {**ARCH, **EXCITATION, "--t-end": floats_in(0.01, 3.0),
                   "--friction": floats_in(0.3, 2.0),
                   "--integrator": st.sampled_from(["steps", "events", "x"])}),
    "friction-rigid": (["friction", *PULSE, "--voussoirs", "5", "--json"],
                       {**ARCH, **EXCITATION}),
    "thrust-rigid": (["thrust", *PULSE, "--times", "0.05", "--voussoirs", "5", "--json"],
                     {**ARCH, **EXCITATION, "--times": st.lists(
                         floats_in(0.0, 0.3), min_size=1, max_size=4).map(",".join)}),
}
QUICK_COMMANDS = tuple(COMMANDS)
COMMANDS.update(RIGID_COMMANDS)

#: Refusals that are about the arch itself, not one option (named in the message's own terms).
PHYSICS = ("too thin to stand", "no collapse mechanism", "no-hinging limit", "loses contact")


#: Internal parameter names a user never typed (the issue's examples); study keys such as
#: t_end_s are what the user wrote and are allowed.
INTERNAL = ("t_end ", "t_end=", "max_magnitude_g", "normal_stiffness", "precision_g",
            "coarse_points", "method='")


def check(result: Outcome, named: list[str]) -> None:
    """The promise for ``result``; a refusal must name one of ``named`` (or be a physics one)."""
    trouble = problem(result)
    assert trouble is None, f"{' '.join(map(repr, result.argv))}: {trouble}"
    if result.code == 0:
        if "--json" in result.argv:
            json.loads(result.out)
        return
    line = result.error_lines[0]
    assert not any(word in line for word in INTERNAL), f"internal name in: {line}"
    assert any(n in line for n in named) or any(p in line for p in PHYSICS), (
        f"{' '.join(map(repr, result.argv))}: the message names none of {named}: {line}")


def with_option(base: list[str], option: str, text: str, equals: bool) -> list[str]:
    argv = list(base)
    if option in argv:
        i = argv.index(option)
        del argv[i:i + 2]
    return [*argv, f"{option}={text}"] if equals else [*argv, option, text]


@st.composite
def command_lines(draw, commands=QUICK_COMMANDS):
    """A command, one or two of its options replaced by generated values."""
    name = draw(st.sampled_from(sorted(commands)))
    base, options = COMMANDS[name]
    chosen = draw(st.lists(st.sampled_from(sorted(options)), min_size=1, max_size=2, unique=True))
    argv = base
    for option in chosen:
        text = draw(value(options[option]))
        # a value starting with '-' needs --opt=VALUE (argparse would read it as an option)
        argv = with_option(argv, option, text, equals=text.startswith("-") or draw(st.booleans()))
    return argv, chosen


def _run_options(argv, chosen, scratch):
    result = call(argv, TIMEOUT)
    named = [*chosen, "--record" if "--record" in argv else "--pulse", "quake", "study",
             "--model", "--json"]
    check(result, named)


@QUICK
@given(case=command_lines())
def test_every_option_of_every_command(scratch, case):
    _run_options(*case, scratch)


@pytest.mark.slow
@THOROUGH
@given(case=command_lines())
def test_every_option_of_every_command_thoroughly(scratch, case):
    _run_options(*case, scratch)


@pytest.mark.slow
@THOROUGH
@given(case=command_lines(commands=tuple(RIGID_COMMANDS)))
def test_every_option_of_the_default_model(scratch, case):
    """The chain of rigid voussoirs (the default of run, friction and thrust) under the same
    values: nothing hangs (a motion below the onset takes no step; a long run is refused with
    its estimate), no traceback, one line on a refusal."""
    _run_options(*case, scratch)


# ------------------------------------------------------------------------------------------
# output paths
# ------------------------------------------------------------------------------------------
OUTPUTS = {
    "--plot": (["static", "--voussoirs", "5"], ".png"),
    "--history": (["run", "--model", "fourlink", *PULSE, "--t-end", "0.3", "--voussoirs", "5"],
                  ".csv"),
    "--csv": (["domain", "--model", "fourlink", "--durations", "0.3", "--scan", "3", "--precision", "0.2",
               "--max-magnitude", "1", "--voussoirs", "5"], ".csv"),
    "--export": (["sweep", "study.toml", "--workers", "1", "--no-progress"], ".csv"),
    "--store": (["sweep", "study.toml", "--workers", "1", "--no-progress"], ".sqlite"),
    "--out": (["reproduce", "--only", "no-such-study"], None),
}
PATH_SHAPES = ["out{ext}", "out.PNG", "out", "out.zzz", "out.png.", "missing/out{ext}", ".", "..",
               "", "/", "{scratch}", "/proc/out{ext}", "/proc/self", "out dir/out{ext}",
               "quake.csv", "study.toml", "out{ext}/", "~/nowhere/out{ext}", "é{ext}",
               "deep/er/out{ext}"]


@st.composite
def output_cases(draw):
    option = draw(st.sampled_from(sorted(OUTPUTS)))
    base, ext = OUTPUTS[option]
    shape = draw(st.sampled_from(PATH_SHAPES))
    n = draw(st.integers(0, 10**6))  # a fresh name per example (no file left by an earlier one)
    return option, base, shape, ext, n


def _run_output(scratch: Path, option, base, shape, ext, n):
    text = shape.format(ext=ext or "", scratch=scratch)
    if text.startswith("out") or text.startswith("é"):
        text = f"{n}-{text}"
    before = set(Path(scratch).rglob("*"))
    result = call([*base, f"{option}={text}"], TIMEOUT)
    check(result, [option, "study", "no-such-study"])
    path = Path(text)
    if result.code == 0 and option != "--out":
        assert path.is_file(), f"{option} {text!r}: reported success, no file at the path"
        for added in set(Path(scratch).rglob("*")) - before:
            # only the path asked for (and, for a sweep, its store and export) appear
            assert added.resolve() == path.resolve() or added.suffix in (".sqlite", ".csv") \
                or added.is_dir(), f"{option} {text!r} also wrote {added}"
    after = set(Path(scratch).rglob("*"))
    assert Path(f"{text}.png").resolve() not in {p.resolve() for p in after - before} \
        or text.endswith(".png"), f"{option} {text!r}: wrote {text}.png"


@QUICK
@given(case=output_cases())
def test_output_paths_are_checked_before_the_work(scratch, case):
    _run_output(scratch, *case)


@pytest.mark.slow
@THOROUGH
@given(case=output_cases())
def test_output_paths_thoroughly(scratch, case):
    _run_output(scratch, *case)


# ------------------------------------------------------------------------------------------
# record files
# ------------------------------------------------------------------------------------------
NUMBERS = st.one_of(st.floats(-2, 2, allow_nan=False).map(lambda x: f"{x:.6E}"),
                    st.sampled_from(["nan", "inf", "abc", "", "1e308", "-1e308", "1e-300",
                                     "1.0E+00", "--1"]))


@st.composite
def at2_files(draw) -> bytes:
    """A PEER .AT2 file, well formed or broken: wrong NPTS, DT edge values, truncated or
    non-numeric values, missing header lines, a BOM, CRLF, a Latin-1 byte, empty."""
    values = draw(st.lists(NUMBERS, min_size=0, max_size=12))
    npts = draw(st.one_of(st.just(str(len(values))), st.sampled_from(
        ["0", "-1", "1", "1000000000", "abc", "", "3.5", "1e400"])))
    dt = draw(st.sampled_from(["0.0100", ".0050", "0", "-0.01", "1e6", "1e-300", "1e-15", "nan",
                               "inf", "abc", "", "1e308", "0.5"]))
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", "EVENT, STATION, 000",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS=  {npts}, DT=   {dt} SEC",
             *("  ".join(values[i:i + 5]) for i in range(0, len(values), 5))]
    keep = draw(st.integers(0, len(lines)))
    if draw(st.booleans()):
        lines = lines[:keep]  # truncated
    text = ("\r\n" if draw(st.booleans()) else "\n").join(lines)
    data = text.encode()
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    if draw(st.booleans()):
        data = data.replace(b"EVENT", b"EV\xe9NT")
    return data


@st.composite
def csv_files(draw) -> bytes:
    rows = draw(st.lists(st.tuples(NUMBERS, NUMBERS), min_size=0, max_size=12))
    if draw(st.booleans()):  # mostly a proper time column
        dt = draw(st.sampled_from([0.01, 1e-300, 1e6, 1e-15, 0.0]))
        rows = [(repr(i * dt), a) for i, (_, a) in enumerate(rows)]
    sep = draw(st.sampled_from([",", ";", " ", "\t"]))
    header = draw(st.sampled_from(["", "time,acc\n", "# t (s), a (g)\n"]))
    data = (header + "\n".join(sep.join(r) for r in rows)).encode()
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data
    return data


def _run_record(scratch: Path, data: bytes, suffix: str, n: int, command: str):
    path = scratch / f"rec{n}{suffix}"
    path.write_bytes(data)
    units = [] if suffix == ".AT2" else ["--units", "g"]  # a CSV file does not say its units
    if command == "record":
        argv = ["record", str(path), *units, "--json"]
    else:
        argv = ["run", "--model", "fourlink", "--record", str(path), *units, "--t-end", "1",
                "--voussoirs", "5", "--json"]
    check(call(argv, TIMEOUT), [path.name, "--record", "--scale", "--units"])


record_cases = st.tuples(st.one_of(at2_files().map(lambda d: (d, ".AT2")),
                                   csv_files().map(lambda d: (d, ".csv"))),
                         st.integers(0, 10**6), st.sampled_from(["record", "run"]))


@QUICK
@given(case=record_cases)
def test_malformed_record_files(scratch, case):
    (data, suffix), n, command = case
    _run_record(scratch, data, suffix, n, command)


@pytest.mark.slow
@THOROUGH
@given(case=record_cases)
def test_malformed_record_files_thoroughly(scratch, case):
    (data, suffix), n, command = case
    _run_record(scratch, data, suffix, n, command)


# ------------------------------------------------------------------------------------------
# study files
# ------------------------------------------------------------------------------------------
STUDY_KEYS = {
    "study": {"name": '"fuzz"', "model": '"fourlink"'},
    "arches": {"radius": "10", "thickness_ratio": "0.15", "embrace_deg": "157.5",
               "voussoirs": "5", "depth": "1", "density": "2000"},
    "excitation": {"type": '"step"', "magnitude_g": "0.5", "duration_s": "0.1",
                   "direction": "-1"},
    "options": {"t_end_s": "1.0", "restitution": "0.8"},
}
TOML_VALUES = ["nan", "inf", "-inf", "1e308", "-1", "0", "1e-300", '"abc"', "[]", "[1e308]",
               "[0.1, nan]", "{start = 0, stop = 1, num = 1000000000}",
               "{start = 1, stop = 0, num = 3}", "{start = 0.2, stop = 0.3, num = 2}", "true",
               "1e200", "3", "0.5", "2000", "1e4", "1e5", '"dem"', '"sine"', "[1, -1]", "2.5",
               '"\\u00e9"', "{}"]


@st.composite
def studies(draw):
    table = draw(st.sampled_from(sorted(STUDY_KEYS)))
    key = draw(st.sampled_from(sorted(STUDY_KEYS[table])))
    val = draw(st.one_of(st.sampled_from(TOML_VALUES),
                         st.floats(allow_nan=False, allow_infinity=False).map(repr)))
    lines = []
    for t, keys in STUDY_KEYS.items():
        lines.append(f"[{t}]")
        lines.extend(f"{k} = {val if (t, k) == (table, key) else v}" for k, v in keys.items())
    return key, "\n".join(lines) + "\n", draw(st.integers(0, 10**6))


def _run_study(scratch: Path, key: str, text: str, n: int):
    study = scratch / f"study{n}.toml"
    study.write_text(text)
    argv = ["sweep", str(study), "--workers", "1", "--no-progress", "--json",
            "--store", str(scratch / f"store{n}.sqlite")]
    result = call(argv, TIMEOUT)
    check(result, [key, study.name])
    if result.code == 0:
        summary = json.loads(result.out)
        assert summary["cases_total"] >= 1
        # indeterminate: e.g. t_end_s cutting the run before the excitation ends (outcome.conclude)
        assert all(k in ("collapse", "survives", "no_hinging", "indeterminate", "error",
                         "unstable") for k in summary["outcomes"]), summary["outcomes"]


@QUICK
@given(case=studies())
def test_study_keys(scratch, case):
    _run_study(scratch, *case)


@pytest.mark.slow
@THOROUGH
@given(case=studies())
def test_study_keys_thoroughly(scratch, case):
    _run_study(scratch, *case)


def test_harness_catches_a_traceback_and_a_hang(monkeypatch):
    """The oracle can fail: an exception escaping main() and a call past its bound are reported
    (a fuzz suite whose checker accepts everything would find nothing)."""
    from archquake.cli import main as cli_main

    def boom(argv):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(cli_main, "main", boom)
    crashed = call(["static"], 5)
    assert crashed.crash is not None and "ZeroDivisionError" in problem(crashed)

    def spin(argv):
        while True:
            math.sqrt(2.0)

    monkeypatch.setattr(cli_main, "main", spin)
    hung = call(["static"], 0.2)
    assert hung.timed_out and problem(hung) == "timed out"
