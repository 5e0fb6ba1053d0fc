"""``--hinges`` on ida and domain (issue 16): the words of ``archquake run``; a bad combination
is one line naming the option as typed, exit status 2. Oracle: the combination rules written in
docs/mechanism.md ("Hinges that move in use")."""

from __future__ import annotations

import pytest

from archquake.cli.main import main

ARCH = ["--radius", "10", "--thickness", "1.5", "--embrace", "157.5", "--voussoirs", "7"]


@pytest.mark.parametrize("argv, message", [
    (["ida", "--records", "near-field-pulse", "--model", "dem", "--hinges", "moving"],
     "--hinges moving applies only to the analytical model"),
    (["ida", "--records", "near-field-pulse", "--hinges", "moving", "--restitution", "0.5"],
     "--restitution applies to the analytical model with --hinges fixed only"),
    (["domain", "--model", "dem", "--hinges", "fixed"],
     "--hinges fixed applies only to the analytical model"),
    (["domain", "--hinges", "moving", "--impact", "chain"],
     "--restitution and --impact apply to the analytical model with --hinges fixed only"),
    (["domain", "--hinges", "fixed", "--workers", "2"], "--workers"),
])
def test_bad_combinations_are_one_line_exit_2(argv, message, capsys):
    assert main([*argv, *ARCH]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err
