"""LabVIEW TDMS recordings (National Instruments' data acquisition), read by npTDMS.

A TDMS file holds groups of channels; a channel written as a waveform carries its sampling
interval (``wf_increment`` [s]) and often its unit (``unit_string``). The channel read is the
one ``--variable`` names (``group/channel`` or the channel's name), else the one ``--channel``
names or numbers among the file's channels in order, else the first; its rate and unit are
the file's own.
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

import numpy as np

from .csv_layout import unit_in_name
from .last_file import keep_last_read

__all__ = ["read_tdms"]


class _Collect(logging.Handler):
    """A log handler that keeps each warning's message."""

    def __init__(self, said: list[str]) -> None:
        super().__init__(logging.WARNING)
        self.said = said

    def emit(self, record: logging.LogRecord) -> None:
        self.said.append(record.getMessage())


@keep_last_read
def _tdms_file(path: Path) -> tuple[Any, tuple[str, ...]]:
    """The parsed file and what npTDMS logged reading it (a cut file's last segment)."""
    from nptdms import TdmsFile
    from nptdms.log import log_manager

    from .io import RecordingError

    said: list[str] = []  # npTDMS logs a cut file's last segment: said in the diagnosis
    collect = _Collect(said)
    parent, console = logging.getLogger("nptdms"), log_manager.console_handler
    level, console.level = console.level, logging.CRITICAL + 1  # not printed as well
    parent.addHandler(collect)
    try:
        tdms = TdmsFile.read(path)
    except Exception as err:  # noqa: BLE001 - npTDMS's errors for a cut or foreign file
        raise RecordingError(f"{path}: not a readable TDMS file ({err})") from None
    finally:
        parent.removeHandler(collect)
        console.level = level
    return tdms, tuple(said)


def read_tdms(
    path: str | Path, variable: str | None, channel: str | int | None, meta: dict[str, Any]
) -> np.ndarray:
    """One channel of a TDMS file, with its rate and unit in ``meta``.

    Parameters
    ----------
    path : str or Path
        The file.
    variable : str or None
        The channel as ``group/channel``, or its name alone.
    channel : str or int or None
        Else the channel's name, or its number among the file's channels (0 first).
    meta : dict
        Gains ``variable`` (``group/channel``), ``channels`` (how many the file holds),
        ``fs_hz`` (1 / ``wf_increment``) and ``unit`` (``unit_string``, where it is a
        vibration unit: ``g``, ``m/s^2``, ``mm/s``, ...).

    Returns
    -------
    numpy.ndarray
        The channel's samples, float64 [its unit].

    Raises
    ------
    cmtool.io.RecordingError
        The file cannot be read, holds no channel of data, or has none of the name or
        number asked for (the message lists them).
    """
    from .io import RecordingError

    tdms, said = _tdms_file(Path(path))
    if said:
        meta["warnings"] = [f"{Path(path).name}: {message}" for message in said]
    found = {f"{group.name}/{ch.name}": ch for group in tdms.groups() for ch in group.channels()}
    found = {name: ch for name, ch in found.items() if len(ch) > 0}
    names = list(found)
    if not names:
        raise RecordingError(f"{path}: a TDMS file with no channel of data")
    asked = variable if variable is not None else channel
    if asked is None:
        name = names[0]
    elif str(asked) in found:
        name = str(asked)
    elif [n for n in names if n.split("/", 1)[1] == str(asked)]:
        name = next(n for n in names if n.split("/", 1)[1] == str(asked))
    elif variable is None and str(asked).isdigit() and int(asked) < len(names):
        name = names[int(asked)]
    else:
        raise RecordingError(f"{path}: channel {asked!r} not found; it holds {names}")
    meta.update(variable=name, channels=len(names))
    properties = found[name].properties
    increment = properties.get("wf_increment")
    if increment is not None and float(increment) > 0:
        meta["fs_hz"] = 1.0 / float(increment)
    unit = unit_in_name(f"[{properties.get('unit_string', '')}]")
    if unit is not None:
        meta["unit"] = unit
    return np.asarray(found[name][:], dtype=float)
