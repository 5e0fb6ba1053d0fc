"""archquake.plotting: the only package that imports matplotlib.

Plot functions take a result and an optional ``ax``, draw into it (a new figure if None) and
return it; they never call ``show()`` and never choose a backend, so importing this package in a
notebook leaves its backend alone. Functions that write a file go through the one helper
:func:`archquake.plotting.figures.save`.
"""
