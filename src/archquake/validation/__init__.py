"""What archquake is checked against, kept apart from the models:

- :mod:`archquake.validation.paper`: every number De Lorenzis, DeJong & Ochsendorf (2007) state,
  with its tolerance, the reason for it and its page; Oppenheim's arch; the figures' parameters;
- :mod:`archquake.validation.housner`: the closed forms of a rigid rocking block (Housner 1963).

``archquake reproduce`` and the tests under ``tests/paper`` read them from here.
"""
