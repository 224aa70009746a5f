"""What every subcommand shares: the user-facing error and the progress bar."""

from __future__ import annotations

import logging
import sys

logger = logging.getLogger("cmtool")


class CliError(Exception):
    """A command-line input error (printed without a traceback, exit code 2)."""


def progress_bar(
    total: int, desc: str, unit: str = "run", *, initial: int = 0, unit_scale: bool = False
):
    """The progress bar of every command: tqdm (count, rate, ETA) on stderr, quiet off a tty."""
    from tqdm import tqdm

    return tqdm(
        total=total,
        desc=desc,
        unit=unit,
        unit_scale=unit_scale,
        initial=initial,
        disable=None,
        file=sys.stderr,
    )
