"""What building codes ask of a site: elastic spectra (NTC 2018, EN 1998-1) and the NTC hazard.

Depends only on numpy and the package's constants, errors and ranges, so that the ground
motions, the checks and the command line can all build on it.
"""

from __future__ import annotations

from archquake.codes.spectra import (
    CODES,
    ElasticSpectrum,
    NTCHazard,
    damping_factor,
    ec8_spectrum,
    ntc2018_soil_factors,
    ntc2018_spectrum,
    return_period_years,
)

__all__ = [
    "CODES",
    "ElasticSpectrum",
    "NTCHazard",
    "damping_factor",
    "ec8_spectrum",
    "ntc2018_soil_factors",
    "ntc2018_spectrum",
    "return_period_years",
]
