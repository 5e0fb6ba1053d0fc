"""The exceptions archquake raises for bad input and for physics it cannot honour.

Every user-facing error message is one line that says what is wrong and how to fix it.
The CLI prints ``str(error)`` and exits with status 2 for any `ArchquakeError`;
any other exception is a bug and keeps its traceback.
"""

from __future__ import annotations


class ArchquakeError(Exception):
    """Base class of all errors archquake raises on purpose."""


class InvalidParameterError(ArchquakeError, ValueError):
    """A parameter is outside its valid range (message names it and the range)."""


class InvalidTypeError(ArchquakeError, TypeError):
    """An argument is of the wrong kind (message names it and what it accepts)."""


class CorruptStoreError(ArchquakeError, ValueError):
    """A results store is damaged or is not an archquake store (message names the file)."""


class UnstableArchError(ArchquakeError, ValueError):
    """The arch cannot stand under its own weight (message names the minimum thickness)."""

    def __init__(self, message: str, min_thickness_ratio: float | None = None):
        super().__init__(message)
        self.min_thickness_ratio = min_thickness_ratio

    def __reduce__(self):  # keep picklable with the extra attribute (Dask, process pools)
        return (type(self), (str(self), self.min_thickness_ratio))


class GroundMotionFormatError(ArchquakeError, ValueError):
    """An accelerogram file is malformed (message names the file, line and the fix)."""


class StudyFileError(ArchquakeError, ValueError):
    """A sweep study file is malformed (message names the key and what is expected)."""


class SolverError(ArchquakeError, RuntimeError):
    """An integrator could not proceed (step size underflow, toggle reached unexpectedly)."""


class UsageError(ArchquakeError):
    """A malformed command line."""


class ClusterLostError(ArchquakeError):
    """The Dask scheduler went away, or the cluster had no worker for too long. Every case
    that had completed is in the store; rerunning the same sweep resumes."""


class ModelUnavailableError(ArchquakeError):
    """A study asks for a model this build of archquake does not provide (a fault of the
    installation, not of a case: the sweep runner lets it stop the sweep instead of storing
    it)."""


__all__ = [
    "ArchquakeError",
    "ClusterLostError",
    "ModelUnavailableError",
    "UsageError",
    "InvalidParameterError",
    "InvalidTypeError",
    "CorruptStoreError",
    "UnstableArchError",
    "GroundMotionFormatError",
    "StudyFileError",
    "SolverError",
]
