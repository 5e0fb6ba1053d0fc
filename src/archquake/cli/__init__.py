"""The ``archquake`` command line: a thin shell over the library (see :mod:`archquake.cli.main`)."""
