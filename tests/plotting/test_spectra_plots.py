"""Spectra figures draw what they are given: the curves' data are the spectra's values in g.

Oracle: the library's spectra (tested in tests/codes and tests/ground) read back from the
drawn lines."""

from __future__ import annotations

import numpy as np

from archquake.codes import ntc2018_spectrum
from archquake.ground.response_spectra import RecordSpectra
from archquake.ground.selection import select_records
from archquake.plotting.spectra import (
    plot_elastic_spectrum,
    plot_record_spectra,
    plot_selection,
)

SITE = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
PERIODS = np.linspace(0.1, 2.0, 20)


def _candidates() -> RecordSpectra:
    rng = np.random.default_rng(0)
    sa = SITE.sa(PERIODS) * np.exp(rng.normal(0.0, 0.2, (12, PERIODS.size)))
    names = tuple(f"r{i}" for i in range(12))
    return RecordSpectra(PERIODS, sa, names, (None,) * 12, names, np.full(12, np.inf))


def test_elastic_spectrum_lines():
    ax = plot_elastic_spectrum(SITE, PERIODS, damping=0.08)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), SITE.sa(PERIODS, 0.08) / SITE.g)
    ax = plot_elastic_spectrum(SITE, PERIODS, displacement=True)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), SITE.sd(PERIODS))


def test_record_spectra_and_selection_lines():
    cands = _candidates()
    ax = plot_record_spectra(cands)
    mean = [line for line in ax.lines if line.get_label() == "mean"][0]
    np.testing.assert_allclose(mean.get_ydata(), cands.mean / cands.g)
    sel = select_records(cands, SITE.sa, count=4, restarts=1)
    ax = plot_selection(sel, target_label="site")
    by_label = {line.get_label(): line for line in ax.lines}
    np.testing.assert_allclose(by_label["site"].get_ydata(), SITE.sa(PERIODS) / SITE.g)
    np.testing.assert_allclose(by_label["mean"].get_ydata(), sel.mean / SITE.g)
    scaled = [line for label, line in by_label.items() if " x " in label]
    assert len(scaled) == 4
