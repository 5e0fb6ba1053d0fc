"""Where numba keeps the compiled kernels, when neither of its own places is writable.

Every kernel is compiled with ``cache=True``: numba writes the machine code beside the sources
(``__pycache__``) or, when the package directory is read-only (a system-wide install), in the
user's cache directory (``$XDG_CACHE_HOME/numba`` or ``~/.cache/numba``). When neither is
writable (a read-only install run by a user without a writable home, as in some containers),
numba refuses to define a cached function at all and the import fails. `ensure_cache_dir`
then points ``NUMBA_CACHE_DIR`` at a per-user directory under the system's temporary
directory, so the kernels still compile once and load afterwards. (It also corrects numba's
reading of an empty ``XDG_CACHE_HOME``, which would put the cache in the working directory.) It runs when
`archquake` is imported, before any kernel module imports numba, and costs a few
``os.access`` calls; a ``NUMBA_CACHE_DIR`` the user set is never changed.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, MutableMapping


def _writable(path: str) -> bool:
    """Whether ``path``, or its nearest existing ancestor (numba creates the rest), is writable."""
    path = os.path.abspath(path)
    while not os.path.exists(path):
        parent = os.path.dirname(path)
        if parent == path:
            return False
        path = parent
    return os.access(path, os.W_OK)


def user_cache_dir(environ: MutableMapping[str, str]) -> str:
    """numba's user-wide cache directory on POSIX (its ``appdirs.user_cache_dir('numba')``).

    A relative path (``numba``, in the working directory) when ``XDG_CACHE_HOME`` is set but
    empty or relative: numba does not ignore it, as the XDG base directory specification asks.
    """
    home_cache = os.path.join(environ.get("HOME") or os.path.expanduser("~"), ".cache")
    return os.path.join(environ.get("XDG_CACHE_HOME", home_cache), "numba")


def ensure_cache_dir(
    environ: MutableMapping[str, str] | None = None,
    package_dir: str | None = None,
    writable: Callable[[str], bool] = _writable,
) -> str | None:
    """Set ``NUMBA_CACHE_DIR`` to a temporary-directory fallback if numba has nowhere to cache.

    Parameters
    ----------
    environ : mapping, optional
        The environment to read and update (default ``os.environ``).
    package_dir : str, optional
        The installed package's directory (default: this file's).
    writable : callable
        ``writable(path) -> bool`` (injectable for tests).

    Returns
    -------
    str or None
        The directory set, or None when numba's own choice stands.
    """
    environ = os.environ if environ is None else environ
    if environ.get("NUMBA_CACHE_DIR") or sys.platform == "win32":
        return None
    package_dir = package_dir or os.path.dirname(os.path.abspath(__file__))
    if writable(package_dir):
        return None
    numbas = user_cache_dir(environ)
    if os.path.isabs(numbas) and writable(numbas):
        return None
    # an empty or relative XDG_CACHE_HOME would put the cache in the working directory
    home_cache = os.path.join(environ.get("HOME") or os.path.expanduser("~"), ".cache", "numba")
    if not os.path.isabs(numbas) and os.path.isabs(home_cache) and writable(home_cache):
        fallback = home_cache
    else:
        import tempfile

        uid = os.getuid() if hasattr(os, "getuid") else 0
        fallback = os.path.join(tempfile.gettempdir(), f"archquake-numba-cache-{uid}")
    environ["NUMBA_CACHE_DIR"] = fallback
    config = sys.modules.get("numba.core.config")
    if config is not None and environ is os.environ:  # numba read the environment already
        config.CACHE_DIR = fallback  # type: ignore[attr-defined]
    return fallback


__all__ = ["ensure_cache_dir", "user_cache_dir"]
