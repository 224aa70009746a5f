"""What every subcommand shares: the user-facing error, option types and the progress bar."""

from __future__ import annotations

import argparse
import logging
import math
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tqdm import tqdm

logger = logging.getLogger("cmtool")


class CliError(Exception):
    """A command-line input error (printed without a traceback, exit code 2)."""


MAX_SEED = 2**32 - 1  # numpy's and scikit-learn's seeds


def check_output_file(option: str, path: str | None, what: str = "a file") -> None:
    """Refuse, before any work, an output file that is an existing folder.

    Parameters
    ----------
    option : str
        The option that gave it (named in the error).
    path : str or None
        The file (None: not asked for).
    what : str
        What the option wants, for the error.

    Raises
    ------
    CliError
        When ``path`` is a folder.
    """
    from pathlib import Path

    if path and Path(path).is_dir():
        raise CliError(f"{option} {path!r} is a folder; give {what}")


def check_output_folder(option: str, path: str | None, what: str = "a folder") -> None:
    """Refuse, before any work, an output folder that is an existing file.

    Parameters
    ----------
    option : str
        The option that gave it (named in the error).
    path : str or None
        The folder (None: not asked for).
    what : str
        What the option wants, for the error.

    Raises
    ------
    CliError
        When ``path`` is a file.
    """
    from pathlib import Path

    if path and Path(path).exists() and not Path(path).is_dir():
        raise CliError(f"{option} {path!r} is a file; give {what}")


def seed_int(text: str) -> int:
    """An argparse type: a random seed, an integer in [0, 2**32 - 1].

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    int
    """
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if not 0 <= value <= MAX_SEED:
        raise argparse.ArgumentTypeError(f"{value} is outside the allowed range [0, {MAX_SEED}]")
    return value


def finite_float(text: str) -> float:
    """An argparse type: a finite number (no nan, no inf).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    float
    """
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def positive_float(text: str) -> float:
    """An argparse type: a finite number above 0.

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    float
    """
    value = finite_float(text)
    if value <= 0.0:
        raise argparse.ArgumentTypeError(f"{value:g} is outside the allowed range (0, inf)")
    return value


def progress_bar(
    total: int, desc: str, unit: str = "run", *, initial: int = 0, unit_scale: bool = False
) -> tqdm:
    """The progress bar of every command: tqdm (count, rate, ETA) on stderr, quiet off a tty.

    Parameters
    ----------
    total : int
        The count to reach.
    desc : str
        The bar's label.
    unit : str
        What is counted.
    initial : int
        The count already done (a resumed run).
    unit_scale : bool
        Show large counts with SI prefixes.

    Returns
    -------
    tqdm.tqdm
    """
    from tqdm import tqdm as bar

    return bar(
        total=total,
        desc=desc,
        unit=unit,
        unit_scale=unit_scale,
        initial=initial,
        disable=None,
        file=sys.stderr,
    )


class StageBars:
    """``progress(stage, done, total)`` shown as a progress bar per stage (``COMMAND: stage``).

    What a stage counts is ``units[stage]``, else ``unit``.

    A stage's bar is closed when the next stage reports; use as a context manager so that the
    last one is closed too.
    """

    def __init__(
        self, command: str, unit: str = "signal", units: dict[str, str] | None = None
    ) -> None:
        self.command, self.unit, self.units = command, unit, dict(units or {})
        self.bars: dict[str, tqdm] = {}

    def __call__(self, stage: str, done: int, total: int) -> None:
        """Move ``stage``'s bar to ``done`` of ``total``."""
        if stage not in self.bars:
            self.close()
            unit = self.units.get(stage, self.unit)
            self.bars[stage] = progress_bar(total, f"{self.command}: {stage}", unit)
        self.bars[stage].update(done - self.bars[stage].n)

    def close(self) -> None:
        """Close every bar."""
        for bar in self.bars.values():
            bar.close()

    def __enter__(self) -> StageBars:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
