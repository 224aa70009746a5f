"""Keep numba's on-disk cache of the kernels consistent with their sources.

numba keys a cached function on its own source file only (a hash of that file). The kernels
inline functions across files: ``_integrators``, ``_lanes`` and ``_static_kernels`` compile
the contact laws and time terms of ``_kernels`` into their own machine code. An edit of
``_kernels.py`` alone (a checkout, a ``git pull`` of an editable install, a developer's
change) would leave the others' cached code stale: it would load and run the old contact law
with the new parameter layout. So the first import of ``_kernels`` compares one hash of every
kernel source with the one recorded beside the cache, and where they differ removes the
kernel modules' cache files (they are compiled again on first use) and records the new hash.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Sequence
from pathlib import Path

#: The modules whose compiled code inlines each other's functions.
KERNEL_MODULES = ("_kernels", "_rhs", "_integrators", "_lanes", "_static_kernels")
#: File beside the cache that records the sources' hash.
STAMP = "cmtool-kernels.sha256"


def sources_digest(package: Path, modules: Sequence[str] = KERNEL_MODULES) -> str:
    """SHA-256 of the kernel modules' sources, in order (hex).

    Parameters
    ----------
    package : pathlib.Path
        The package's folder.
    modules : sequence of str
        The kernel modules' names.

    Returns
    -------
    str
    """
    digest = hashlib.sha256()
    for name in modules:
        digest.update((package / f"{name}.py").read_bytes())
    return digest.hexdigest()


def clear_stale(cache_dir: Path, digest: str, modules: Sequence[str] = KERNEL_MODULES) -> int:
    """Remove the modules' numba cache files in ``cache_dir`` unless ``digest`` is recorded.

    Nothing is raised for a cache directory that cannot be read or written (numba then
    compiles without caching, or another process cleans it).

    Parameters
    ----------
    cache_dir : pathlib.Path
        numba's cache directory.
    digest : str
        The sources' digest (:func:`sources_digest`).
    modules : sequence of str
        The kernel modules' names.

    Returns
    -------
    int
        The number of files removed.
    """
    stamp = cache_dir / STAMP
    try:
        if stamp.read_text().strip() == digest:
            return 0
    except OSError:
        pass
    removed = 0
    try:
        for path in cache_dir.iterdir():
            module = path.name.split(".", 1)[0]
            if module in modules and path.suffix in (".nbi", ".nbc"):
                try:
                    path.unlink()
                    removed += 1
                except FileNotFoundError:
                    pass
        temporary = stamp.with_name(f"{STAMP}.{os.getpid()}.tmp")
        temporary.write_text(digest + "\n")
        os.replace(temporary, stamp)
    except OSError:
        pass
    return removed


def guard(dispatcher: object) -> None:
    """Run :func:`clear_stale` for the cache directory of a cached numba ``dispatcher``.

    Parameters
    ----------
    dispatcher : object
        A numba dispatcher compiled with ``cache=True``.
    """
    cache = getattr(dispatcher, "_cache", None)
    path = getattr(cache, "_cache_path", None)
    if path:
        clear_stale(Path(path), sources_digest(Path(__file__).parent))
