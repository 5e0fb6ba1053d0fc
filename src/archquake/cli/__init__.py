"""The ``archquake`` command line: a thin shell over the library (see `archquake.cli.main`).

What a user imports from here is the module `archquake.cli.main`: ``main.main(argv) ->
int`` runs a command as the console script does and returns its exit status
(``from archquake.cli.main import main``). The package imports nothing itself, so that the
console script pays only for the command it runs.
"""

__all__ = ["main"]


def __getattr__(name: str):
    # ``archquake.cli.main`` on first access, so that ``python -m archquake.cli.main`` runs a
    # module that was not imported before
    if name == "main":
        import importlib

        return importlib.import_module("archquake.cli.main")
    raise AttributeError(f"module 'archquake.cli' has no attribute {name!r}")
