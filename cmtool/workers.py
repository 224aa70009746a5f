"""Work in a process pool whose warnings reach the caller, each once.

A warning raised in a worker process is shown by that process: with two workers a plug-in's
warning was printed twice, and never reached a caller's own warning filters or
``warnings.catch_warnings``. :func:`keeping_warnings` runs one task in the worker and returns
what it warned with its result; :class:`WarningRelay` raises each in the calling process, once
per category and message.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any

#: What a worker sends back of one warning: its category and message.
CaughtWarning = tuple[type[Warning], str]


def keeping_warnings(function: Callable[..., Any], *args: Any) -> tuple[Any, list[CaughtWarning]]:
    """``function(*args)`` and the warnings it raised (category, message), in order.

    The worker's own filters still apply (an ignored warning is not kept); a warning kept is
    not shown by the worker.

    Examples
    --------
    >>> import warnings
    >>> keeping_warnings(lambda v: warnings.warn(f"slow: {v}") or v, 3)
    (3, [(<class 'UserWarning'>, 'slow: 3')])
    """
    with warnings.catch_warnings(record=True) as caught:
        result = function(*args)
    return result, [(w.category, str(w.message)) for w in caught]


class WarningRelay:
    """Raises the warnings workers kept in this process, each category and message once."""

    def __init__(self) -> None:
        self._seen: set[CaughtWarning] = set()

    def __call__(self, caught: list[CaughtWarning]) -> None:
        """Warn of each of ``caught`` not yet warned of."""
        for category, message in caught:
            if (category, message) not in self._seen:
                self._seen.add((category, message))
                warnings.warn(message, category, stacklevel=2)
