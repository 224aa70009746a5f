"""Universal File Format recordings (UFF/UNV data-set 58: a measured function), read by pyuff.

Modal and signal analysers' software exports time records as UFF data-set 58 (ASCII) or 58b
(binary): one function per data-set, with its abscissa's increment and kind and its
ordinate's unit. The records read are the file's time responses (function type 1, or a
general function whose abscissa is time, data type 17) with real samples; the one
``--variable`` names (the data-set's first ID line), else the one ``--channel`` names or
numbers among them in order (0 first), else the first. Its rate is one over the abscissa's
increment, or over the step of its abscissa's values where they are listed (values off a
straight line are refused); its unit the ordinate's units label where that is a vibration
unit (``g``, ``m/s^2``, ``mm/s``, ...). The header holds the increment to six significant
digits (E13.5, in the binary form 58b too), so the rate is the one of fewest significant
digits among those whose increment prints as the file's: 8.33333e-05 s gives 12000 Hz, not
12000.0048 (every rate the file allows lies within 1e-5 of it).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from .csv_layout import unit_in_name
from .last_file import keep_last_read

__all__ = ["read_uff"]

#: UFF function type 1: a time response; 0: general or unknown (then the abscissa says).
_TIME_RESPONSE, _GENERAL = 1, 0
#: UFF specific data type 17: time (the abscissa of a time record).
_TIME = 17
#: UFF ordinate data types 5 and 6: complex, single and double precision.
_COMPLEX = (5, 6)


@keep_last_read
def _time_records(path: Path) -> tuple[list[dict[str, Any]], int]:
    """The file's data-sets 58 that are time records, and how many data-sets it holds."""
    import pyuff

    from .io import RecordingError

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # pyuff warns of fields it fills in
            uff = pyuff.UFF(str(path))
            types = [int(t) for t in np.atleast_1d(uff.get_set_types())]
            sets = [uff.read_sets(i) for i, t in enumerate(types) if t == 58]
    except Exception as err:  # noqa: BLE001 - pyuff raises Exception for a foreign file
        raise RecordingError(f"{path}: not a readable UFF file ({err})") from None
    if not types:
        raise RecordingError(f"{path}: not a readable UFF file (no data-set in it)")
    records = [
        s
        for s in sets
        if int(s.get("func_type", -1)) == _TIME_RESPONSE
        or (
            int(s.get("func_type", -1)) == _GENERAL
            and int(s.get("abscissa_spec_data_type", 0)) == _TIME
        )
    ]
    return records, len(types)


def _name(record: dict[str, Any]) -> str:
    return str(record.get("id1", "")).strip()


def _rate(increment: float) -> float:
    """The rate [Hz] of a header's increment [s], which holds six significant digits (E13.5).

    Of the rates whose increment prints as this one, the one of fewest significant digits:
    an analyser's 12000 Hz is written 8.33333e-05 s, whose inverse is 12000.0048.
    """
    unit = 10.0 ** (math.floor(math.log10(increment)) - 5)
    low, high = 1.0 / (increment + 0.51 * unit), 1.0 / (increment - 0.51 * unit)
    rate = 1.0 / increment
    for digits in range(1, 17):
        rounded = float(f"{rate:.{digits}g}")
        if low <= rounded <= high:
            return rounded
    return rate


def _listed_step(times: np.ndarray, path: Path, name: str) -> float:
    """The step [s] of an abscissa whose values are listed: a straight line through them.

    Refused where a value lies off the line by more than 5 % of a step beyond what six
    significant digits (an ASCII data-set's) can hold.
    """
    from .io import RecordingError

    k = np.arange(times.size)
    step, start = np.polyfit(k, times, 1)
    off = float(np.max(np.abs(times - (start + step * k))))
    if step <= 0.0 or off > 0.05 * step + 1e-5 * float(np.max(np.abs(times))):
        raise RecordingError(
            f"{path}: record {name!r} is not evenly sampled (its abscissa's values lie up to "
            f"{off:.3g} s off a straight line of step {step:.6g} s)"
        )
    return float(step)


def read_uff(
    path: str | Path, variable: str | None, channel: str | int | None, meta: dict[str, Any]
) -> np.ndarray:
    """One time record of a UFF file (data-set 58 or 58b), with its rate and unit in ``meta``.

    Parameters
    ----------
    path : str or Path
        The file (``.uff`` or ``.unv``).
    variable : str or None
        The record by its first ID line (``id1``).
    channel : str or int or None
        Else the record's ID line, or its number among the file's time records (0 first).
    meta : dict
        Gains ``variable`` (the record's ID line), ``channels`` (how many time records the
        file holds), ``fs_hz`` (one over the abscissa's step) and ``unit`` (the ordinate's
        units label, where it is a vibration unit: ``g``, ``m/s^2``, ``mm/s``, ...).

    Returns
    -------
    numpy.ndarray
        The record's samples, float64 [its unit].

    Raises
    ------
    cmtool.io.RecordingError
        The file cannot be read, holds no time record (its data-set types are said), has
        none of the name or number asked for (the message lists them), or the record is
        complex or unevenly sampled.
    """
    from .io import RecordingError

    path = Path(path)
    records, count = _time_records(path)
    if not records:
        raise RecordingError(
            f"{path}: a UFF file with no time record (a data-set 58 of function type 1) among "
            f"its {count} data-sets"
        )
    names = [_name(r) for r in records]
    asked = variable if variable is not None else channel
    if asked is None:
        index = 0
    elif str(asked) in names:
        index = names.index(str(asked))
    elif variable is None and str(asked).isdigit() and int(asked) < len(records):
        index = int(asked)
    else:
        shown = ", ".join(f"{i}: {n!r}" for i, n in enumerate(names))
        raise RecordingError(f"{path}: record {asked!r} not found; it holds {shown}")
    record = records[index]
    if int(record.get("ord_data_type", 2)) in _COMPLEX or np.iscomplexobj(record["data"]):
        raise RecordingError(f"{path}: record {names[index]!r} holds complex values, not samples")
    meta.update(variable=names[index], channels=len(records))
    increment = float(record.get("abscissa_inc", 0.0))
    listed = int(record.get("abscissa_spacing", 1)) == 0 and len(record["x"]) > 1
    if listed:
        increment = _listed_step(np.asarray(record["x"], dtype=float), path, names[index])
    if increment > 0.0:
        meta["fs_hz"] = 1.0 / increment if listed else _rate(increment)
    unit = unit_in_name(f"[{str(record.get('ordinate_axis_units_lab', '')).strip()}]")
    if unit is not None:
        meta["unit"] = unit
    return np.asarray(record["data"], dtype=float)
