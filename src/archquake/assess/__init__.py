"""The assessment of one arch, end to end: the arch, its static capacity, pulse
failure domains, records (IDA and fragility), the distinct-element check, the models' validity
and a verdict, in one report (``archquake assess ARCH.toml --out DIR``).

It sits beside `archquake.reproduce` and shares its result type, cache and report style.
"""

from archquake.assess.config import AssessConfig, load_config, parse_config
from archquake.assess.runner import Assessment, run_assessment, section_names

__all__ = ["AssessConfig", "Assessment", "load_config", "parse_config", "run_assessment",
           "section_names"]
