"""The chain of rigid blocks refuses a run it cannot finish in reasonable time, before any step,
with the estimate (the bound of ``ranges.RIGID_MAX_WORK``), as the DEM does."""

import math
import subprocess
import sys

import pytest

from archquake import Arch, StepImpulse
from archquake.errors import InvalidParameterError
from archquake.ranges import RIGID_MAX_WORK
from archquake.rigid import rigid_verdicts, simulate_rigid
from archquake.rigid.model import check_work

BIG = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=2000)
PULSE = StepImpulse.from_g(1.0, 0.2)


def test_the_bound_is_steps_times_the_cube_of_the_blocks():
    steps = 1000
    n = round((RIGID_MAX_WORK / steps) ** (1 / 3)) - 1  # exactly at the bound passes
    check_work(n - 1, steps * 1e-4, 1e-4)
    with pytest.raises(InvalidParameterError, match=r"units of work.*more than 1e\+12"):
        check_work(n + 2, steps * 1e-4, 1e-4)


def test_a_2000_voussoir_run_is_refused_before_it_starts():
    with pytest.raises(InvalidParameterError, match="2000 blocks over 1,000 time steps"):
        simulate_rigid(BIG, PULSE, duration=0.1, time_step=1e-4)
    with pytest.raises(InvalidParameterError, match="for each of 2 histories"):
        rigid_verdicts(BIG, [PULSE, PULSE], duration=0.1, time_step=1e-4)


def test_the_command_line_says_it_in_one_line_and_exits_2():
    p = subprocess.run([sys.executable, "-m", "archquake.cli.main", "run", "--voussoirs", "2000",
                        "--t-end", "0.1", "--pulse", "step", "--magnitude", "1",
                        "--duration", "0.2"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "give fewer --voussoirs or a shorter --t-end" in lines[0]
    assert "Traceback" not in p.stderr
