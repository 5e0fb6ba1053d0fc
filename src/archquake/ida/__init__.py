"""Incremental dynamic analysis (IDA) and collapse fragility of arches under record suites.

>>> from archquake.ida import HuntFill, propose_levels
>>> propose_levels([], [], HuntFill(start=0.37, ceiling=5.0))
[0.37]
"""

from archquake.ida.analysis import IdaResult, RecordIda, incremental_dynamic_analysis
from archquake.ida.huntfill import HuntFill, Interval, collapsed_at, intervals, propose_levels

__all__ = [
    "HuntFill",
    "IdaResult",
    "Interval",
    "RecordIda",
    "collapsed_at",
    "incremental_dynamic_analysis",
    "intervals",
    "propose_levels",
]
