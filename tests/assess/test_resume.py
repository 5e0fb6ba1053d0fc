"""An assessment interrupted mid-run resumes: ``archquake assess`` is run in a subprocess, sent
SIGINT (what Ctrl-C sends) as soon as its first section's cache entry exists, then rerun.

Oracle: an uninterrupted run of the same file into another folder. The rerun must take every
section the interrupted run finished from the cache (its progress line says ``cached`` and the
entry's file is not rewritten: same mtime and bytes) and give the same numbers in results.json.
The interrupted run must end with one line and exit status 130, no traceback.

The input is small (a semicircle, site PGA only, no suite, no DEM: about 2 s of work after the
first section) so that the test is cheap; the interrupt lands while a later section runs."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

TOML = """[arch]
radius = 5.0
thickness_ratio = 0.15
embrace_deg = 180
voussoirs = 15
friction = 0.6
[seismic]
site_pga_g = 0.2
[options]
model = "fourlink"
restitution = 0.8
dem = false
"""


def _numbers(res: dict) -> dict:
    """results.json without what may differ between runs (timings, cache flags, paths)."""
    drop = {"seconds", "cached", "report_html", "report_md"}

    def clean(x):
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items() if k not in drop}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x

    return clean(res)


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_interrupted_assessment_resumes_from_its_cache(tmp_path):
    from archquake.assess import load_config, run_assessment

    toml = tmp_path / "arch.toml"
    toml.write_text(TOML)
    out = tmp_path / "out"
    cache = out / "cache"
    proc = subprocess.Popen([sys.executable, "-m", "archquake.cli.main", "assess", str(toml),
                             "--out", str(out), "--quick"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=os.environ.copy(),
                            # a shell's background job inherits SIGINT ignored: undo that
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while not list(cache.glob("assess-arch-*.json")) and proc.poll() is None:
        assert time.monotonic() < deadline, "no section finished in 120 s"
        time.sleep(0.005)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    if proc.returncode == 0:
        pytest.skip("the run finished before the interrupt reached it")
    assert proc.returncode == 130, stderr
    assert "Traceback" not in stderr + stdout
    assert stderr.strip().splitlines()[-1] == "archquake: interrupted"
    assert not (out / "results.json").exists()

    finished = {p.name: (p.stat().st_mtime_ns, p.read_bytes())
                for p in cache.glob("assess-*.json")}
    names = {n.split("-")[1] for n in finished}
    assert "arch" in names and "validity" not in names  # interrupted after the first section
    lines: list[str] = []
    again = run_assessment(load_config(toml), out, quick=True, progress=lines.append)
    for name in ("arch", "static", "pulses", "validity"):
        said = [line for line in lines if f"] {name}" in line]
        assert again.cached[name] == (name in names), (name, said)
        assert any("cached" in line for line in said) == (name in names), said
    for file, (mtime, data) in finished.items():
        assert (cache / file).stat().st_mtime_ns == mtime and (cache / file).read_bytes() == data

    fresh = tmp_path / "fresh"
    run_assessment(load_config(toml), fresh, quick=True)
    resumed = json.loads((out / "results.json").read_text())
    assert _numbers(resumed) == _numbers(json.loads((fresh / "results.json").read_text()))
