"""The ``archquake`` command line: a thin shell over the library (see :mod:`archquake.cli.main`).

What a user imports from here is the module :mod:`archquake.cli.main`: ``main.main(argv) ->
int`` runs a command as the console script does and returns its exit status
(``from archquake.cli.main import main``). The package imports only that module, which imports
no command, so that the console script pays only for the command it runs.
"""

from archquake.cli import main

__all__ = ["main"]
