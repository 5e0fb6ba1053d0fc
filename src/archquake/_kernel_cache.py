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

numba checks a cached kernel against its own source file only, not against the files whose
functions and constants it compiled in (an open limitation of numba's cache): after an edit
to the rigid chain's step alone, the verdict kernels, which inline it, would load their old
machine code, silently. `stamp_kernels` (called by every kernel module before its first
kernel) makes the stamp of each archquake kernel cover all of `KERNEL_SOURCES`: an edit to any
of them, as a ``git pull`` of a source checkout makes, compiles every kernel afresh (once;
``archquake warm`` does it for all). Hashing these files costs about a millisecond, once a
process.
"""

from __future__ import annotations

import functools
import hashlib
import os
import sys
from collections.abc import Callable, MutableMapping
from typing import Any

#: The modules that define numba kernels (``@numba.njit(cache=True)``).
KERNEL_MODULES: tuple[str, ...] = (
    "archquake.ground._kernel",
    "archquake.ground.measures",
    "archquake.blocks._kernels",
    "archquake.mechanism._kernels",
    "archquake.rigid._input_kernels",
    "archquake.rigid._step_kernels",
    "archquake.rigid._force_kernels",
    "archquake.rigid._event_kernels",
    "archquake.rigid._verdict_kernels",
    "archquake.domains._kernels",
    "archquake.ida._kernels",
    "archquake.dem._kernels",
)
#: The other modules the kernel modules import: their functions (``register_jitable``) and
#: constants are compiled into the kernels.
KERNEL_DEPENDENCIES: tuple[str, ...] = (
    "archquake._dopri",
    "archquake._kernel_cache",
    "archquake._validate",
    "archquake.blocks",
    "archquake.constants",
    "archquake.errors",
    "archquake.ground.base",
    "archquake.mechanism.kinematics",
    "archquake.outcome",
    "archquake.ranges",
)
#: Every source a kernel's machine code may depend on: a cached kernel is valid only for the
#: contents they had when it was compiled.
KERNEL_SOURCES: tuple[str, ...] = KERNEL_MODULES + KERNEL_DEPENDENCIES
_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def source_file(module: str) -> str:
    """The source file of the archquake module ``module`` (dotted), without importing it."""
    parts = module.split(".")[1:]
    base = os.path.join(_PACKAGE_DIR, *parts)
    return os.path.join(base, "__init__.py") if os.path.isdir(base) else base + ".py"


def kernel_stamp() -> bytes:
    """SHA-256 of the contents of `KERNEL_SOURCES`, in their order (memoised on their sizes
    and modification times, as numba memoises its own source hashes)."""
    files = [source_file(m) for m in KERNEL_SOURCES]
    return _hash_files(tuple((f, os.stat(f).st_mtime_ns, os.stat(f).st_size) for f in files))


@functools.lru_cache(maxsize=4)
def _hash_files(stats: tuple[tuple[str, int, int], ...]) -> bytes:
    h = hashlib.sha256()
    for path, _, _ in stats:
        with open(path, "rb") as f:
            data = f.read()
        h.update(os.path.relpath(path, _PACKAGE_DIR).encode() + b"\0")
        h.update(len(data).to_bytes(8, "little") + data)
    return h.digest()


def _stamped(base: Any) -> Any:
    """numba's cache locator ``base``, for archquake's own kernels only, with a source stamp
    that also covers `KERNEL_SOURCES`."""

    class Stamped(base):
        @classmethod
        def from_function(cls, py_func, py_file):
            if os.path.commonpath([os.path.abspath(py_file), _PACKAGE_DIR]) == _PACKAGE_DIR:
                return super().from_function(py_func, py_file)
            return None

        def get_source_stamp(self):
            return (super().get_source_stamp(), kernel_stamp())

    Stamped.__name__ = Stamped.__qualname__ = f"Stamped{base.__name__}"
    return Stamped


def stamp_kernels() -> None:
    """Make numba's cache check archquake's kernels against all of `KERNEL_SOURCES` (module
    docstring). Idempotent; every kernel module calls it before defining its first kernel.
    The locators are numba's own (``NUMBA_CACHE_DIR``, beside the sources, the user's cache),
    in numba's order, so the cache stays where numba puts it."""
    from numba.core import caching

    impl: Any = getattr(caching, "CacheImpl", None) or vars(caching)["_CacheImpl"]
    if getattr(impl, "_archquake_stamped", False):
        return
    own = [_stamped(getattr(caching, name, None) or getattr(caching, "_" + name))
           for name in ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator")]
    impl._locator_classes = own + list(impl._locator_classes)
    impl._archquake_stamped = True


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


__all__ = ["KERNEL_DEPENDENCIES", "KERNEL_MODULES", "KERNEL_SOURCES", "ensure_cache_dir",
           "kernel_stamp", "source_file", "stamp_kernels", "user_cache_dir"]
