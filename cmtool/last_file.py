"""The last file a reader parsed, kept while it is unchanged on disk.

``cmtool diagnose --tacho`` (and a manifest's ``tacho_channel``) reads a recording's
vibration channel and then its tachometer channel from the same file: with the parse kept, the
second read takes the table already parsed instead of parsing the file again (a CSV of a
minute at 51.2 kHz takes seconds to parse). A file is the same while its resolved path, size
and modification time (to the nanosecond) are; one file per reader is kept.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

__all__ = ["keep_last_read"]

T = TypeVar("T")

_LOCK = threading.Lock()


def keep_last_read(reader: Callable[[Path], T]) -> Callable[[Path], T]:
    """``reader(path)``, its result kept for the next call on the same unchanged file.

    Parameters
    ----------
    reader : callable
        Parses a file: ``reader(path) -> result``. Its result is shared between calls, so
        callers must not change it in place (copy what they hand on).

    Returns
    -------
    callable
        The reader with its last result kept (``cache_clear()`` drops it). Errors are not
        kept: a file that failed is parsed again.
    """
    last: list = [None, None]  # (key, result) of the last file parsed

    @functools.wraps(reader)
    def read(path: Path) -> T:
        stat = path.stat()
        key = (str(path.resolve()), stat.st_size, stat.st_mtime_ns)
        with _LOCK:
            if last[0] == key:
                return last[1]
        result = reader(path)
        with _LOCK:
            last[:] = [key, result]
        return result

    def cache_clear() -> None:
        with _LOCK:
            last[:] = [None, None]

    read.cache_clear = cache_clear  # type: ignore[attr-defined]
    return read
