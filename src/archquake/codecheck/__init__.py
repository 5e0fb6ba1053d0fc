"""The code check of a local mechanism by kinematic analysis (NTC 2018 §8.7.1, Circolare 2019
C8.7.1.2): the arch's collapse mechanism as an equivalent oscillator and its capacity curve
(`kinematic`), the limit states' checks against the site's spectra
(`check`), and the time-history route on the rigid chain
(`timehistory`).

It sits above the models it reads (the four-link kinematics, the rigid chain's run to a
verdict) and below the report and the command line.
"""
