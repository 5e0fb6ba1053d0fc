"""The ``archquake`` command line: a thin shell over the library (see :mod:`archquake.cli.main`)."""

import sys
from typing import TYPE_CHECKING

from archquake._lazy import attach

if TYPE_CHECKING:  # pragma: no cover - what the lazy name resolves to, for type checkers
    from archquake.cli.main import main

#: ``main(argv) -> int`` loads on first access: the console script imports
#: :mod:`archquake.cli.main` itself, and nothing else is paid for on start-up.
__getattr__, __dir__ = attach(sys.modules[__name__], {"main": "archquake.cli.main"})

__all__ = ["main"]
