"""The paper regenerated, side by side: every study of De Lorenzis, DeJong & Ochsendorf (2007)
run again, each number the paper states set beside archquake's with a tolerance and a mark, and
the figures (with the distinct-element overlays) in one self-contained report.

Run it with `run_studies` or ``archquake reproduce --quick --out DIR``.

Examples
--------
>>> from archquake.reproduce import STUDIES
>>> [s.name for s in STUDIES][:3]
['static', 'figure4', 'figure5']
"""

from archquake.reproduce.core import Figure, Row, Study, StudyResult
from archquake.reproduce.registry import STUDIES
from archquake.reproduce.runner import Reproduction, StudyRun, cache_path, run_studies

__all__ = [
    "STUDIES",
    "Figure",
    "Reproduction",
    "Row",
    "Study",
    "StudyResult",
    "StudyRun",
    "cache_path",
    "run_studies",
]
