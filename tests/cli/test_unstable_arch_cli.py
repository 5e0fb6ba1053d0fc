"""An arch too thin to stand is refused by every command that analyses it, with one line naming
the minimum thickness, and exit status 2 (never a traceback, never a computed result)."""

from __future__ import annotations

import math

import pytest

from archquake.cli.main import main
from archquake.errors import UnstableArchError
from archquake.geometry import Arch
from archquake.mechanism import PreparedMechanism

THIN = ["--thickness", "0.5"]  # t/R = 0.05 < 0.0592 for 157.5 degrees and 7 voussoirs
PULSE = ["--pulse", "step", "--magnitude", "1", "--duration", "0.2"]


@pytest.mark.parametrize("command", [
    ["static", *THIN],
    ["run", *THIN, *PULSE],
    ["friction", *THIN, *PULSE],
    ["thrust", *THIN, *PULSE, "--times", "0.1"],
    ["domain", *THIN, "--durations", "0.2:0.5:3"],
])
def test_too_thin_arch_is_refused_with_its_minimum_thickness(capsys, command):
    assert main(command) == 2
    err = capsys.readouterr().err.strip()
    assert "too thin" in err and "0.0592" in err and "\n" not in err


def test_prepared_mechanism_refuses_a_thin_arch():
    with pytest.raises(UnstableArchError) as info:
        PreparedMechanism.build(Arch(10.0, 0.5, math.radians(157.5), 7))
    assert info.value.min_thickness_ratio == pytest.approx(0.0592, abs=1e-4)


def test_many_voussoirs_use_the_static_method(capsys):
    assert main(["run", "--model", "fourlink", "--voussoirs", "100", *PULSE, "--json"]) == 0
    assert '"outcome"' in capsys.readouterr().out
