"""The four-link model's one name in the comparisons: the attributes it had under its earlier
name, ``analytical``, are read for one more release, each with a DeprecationWarning that names
the attribute to read instead, and return the very object the new name holds (identity, no
tolerance)."""

from __future__ import annotations

import types
import warnings

import numpy as np
import pytest

from archquake.compare.domains import DomainComparison
from archquake.compare.histories import HistoryComparison
from archquake.compare.snapshots import HingeComparison


def _history() -> HistoryComparison:
    fourlink = types.SimpleNamespace(impact_times=np.array([0.61, 1.02]))
    return HistoryComparison(fourlink, object(), "hinges", 0.6, 1e-4, 2e-3, 0.25, 3.5)


@pytest.mark.parametrize("old, new", [
    ("analytical", "fourlink"),
    ("analytical_seconds", "fourlink_seconds"),
    ("analytical_first_impact", "fourlink_first_impact"),
])
def test_history_comparison_reads_its_former_names(old, new):
    c = _history()
    with pytest.warns(DeprecationWarning,
                      match=f"^HistoryComparison.{old} is deprecated and will be removed in the "
                            f"next release: use HistoryComparison.{new}$"):
        value = getattr(c, old)
    now = getattr(c, new)
    assert value is now if old == "analytical" else value == now  # a property: a new float
    assert c.fourlink_first_impact == 0.61 and c.fourlink_seconds == 0.25


def test_domain_and_hinge_comparisons_read_their_former_name():
    domain = object()
    dc = DomainComparison(domain, label="R = 10 m")
    with pytest.warns(DeprecationWarning, match="^DomainComparison.analytical is deprecated.*"
                                                "use DomainComparison.fourlink$"):
        assert dc.analytical is domain is dc.fourlink
    hinges = ((0, 3, 5, 7), None)
    hc = HingeComparison((0.2, 0.5), hinges, ((), ()), (), object())
    with pytest.warns(DeprecationWarning, match="^HingeComparison.analytical is deprecated.*"
                                                "use HingeComparison.fourlink$"):
        assert hc.analytical is hinges is hc.fourlink
    rows = hc.rows()
    assert [r["fourlink_joints"] for r in rows] == [[0, 3, 5, 7], None]
    assert all("analytical_joints" not in r for r in rows)


def test_the_new_names_do_not_warn():
    c = _history()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert c.fourlink_first_impact == 0.61
        assert c.fourlink.impact_times.size == 2


def test_the_former_names_are_not_fields():
    """The constructor and ``dataclasses.fields`` know the new names only (so ``to_dict()``
    and ``dataclasses.replace`` do not meet the old ones)."""
    from dataclasses import fields

    for cls in (HistoryComparison, DomainComparison, HingeComparison):
        names = {f.name for f in fields(cls)}
        assert "fourlink" in names and not any(n.startswith("analytical") for n in names)


def test_analytical_impacts_is_fourlink_impacts_under_its_former_name(oppenheim):
    """Oracle: the same function on the same arch, every number equal to the bit."""
    from archquake.compare.impacts import analytical_impacts, fourlink_impacts

    with pytest.warns(DeprecationWarning, match="^analytical_impacts is deprecated.*"
                                                "use fourlink_impacts$"):
        old = analytical_impacts(oppenheim)
    now = fourlink_impacts(oppenheim)
    assert old[0] == now[0] and old[3] == now[3]
    assert np.array_equal(old[2], now[2], equal_nan=True)
    assert {law: summary["ct"] for law, summary in old[1].items()} == \
        {law: summary["ct"] for law, summary in now[1].items()}
