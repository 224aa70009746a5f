"""Recordings saved as Excel workbooks (``.xlsx``, read by openpyxl through pandas).

The first sheet is read as a CSV recording is (:mod:`cmtool.csv_layout`): lines of notes
may come first, then a header, a units row under it or none, then the table of numbers, whose
first column may hold time stamps (date-times or times of day, as Excel stores them, to the
millisecond: a record of a kHz or more needs a time column in seconds, or --fs). The
result is the table and its layout in :class:`cmtool.csv_layout.CsvLayout`'s terms, which the
rest of :func:`cmtool.io.read_recording` reads as a CSV file's.
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

import numpy as np
import pandas as pd

from .csv_layout import CsvLayout, is_unit

__all__ = ["read_excel_table"]


def _is_number(cell: object) -> bool:
    return isinstance(cell, int | float | np.integer | np.floating) and not isinstance(cell, bool)


def _empty(cell: object) -> bool:
    return cell is None or (isinstance(cell, float) and np.isnan(cell))


def _trimmed(row: list[object]) -> list[object]:
    """A row without its empty cells at the end (an empty cell inside stays: a missing value)."""
    while row and _empty(row[-1]):
        row.pop()
    return row


def _is_stamp(cell: object) -> bool:
    return isinstance(cell, dt.datetime | dt.time | pd.Timestamp)


def _seconds(cells: list[object]) -> np.ndarray:
    """Time stamps (date-times, or times of day) as seconds from the first [s]."""
    if all(isinstance(c, dt.time) and not isinstance(c, dt.datetime) for c in cells):
        cells = [dt.datetime.combine(dt.date(2000, 1, 1), c) for c in cells]  # type: ignore[arg-type]
    stamps = pd.to_datetime(pd.Series(cells)).to_numpy(dtype="datetime64[ns]").astype(np.int64)
    return (stamps - stamps[0]) / 1e9


def read_excel_table(path: str | Path) -> tuple[pd.DataFrame, CsvLayout]:
    """The table of numbers on a workbook's first sheet, with its header and units row.

    Parameters
    ----------
    path : str or Path
        The ``.xlsx`` file.

    Returns
    -------
    frame : pandas.DataFrame
        The table, a column per channel (a first column of time stamps as seconds from the
        first), named by the header (``column 0``, ... without one).
    layout : cmtool.csv_layout.CsvLayout
        Its columns, units row and first data row (``data_line``, 0-based).

    Raises
    ------
    cmtool.io.RecordingError
        The sheet cannot be read, or ends in no table of numbers (the row named).
    """
    from .io import RecordingError

    try:
        sheet = pd.read_excel(path, sheet_name=0, header=None, dtype=object)
    except Exception as err:  # noqa: BLE001 - openpyxl's errors for a cut or foreign file
        raise RecordingError(f"{path}: not a readable Excel workbook ({err})") from None
    sheet = sheet.dropna(axis=1, how="all")  # columns left empty before the table
    rows = [_trimmed(list(row)) for row in sheet.values]
    while rows and not rows[-1]:
        rows.pop()
    if not rows:
        raise RecordingError(f"{path}: the first sheet holds no data")
    width = len(rows[-1])

    def numeric(row: list[object]) -> bool:
        return len(row) == width and all(
            _is_number(c) or (i == 0 and _is_stamp(c)) for i, c in enumerate(row)
        )

    start = len(rows)
    while start > 0 and numeric(rows[start - 1]):
        start -= 1
    if start == len(rows):
        raise RecordingError(f"{path}: row {len(rows)} ({rows[-1][:4]!r}) is no row of numbers")
    header = units = None
    above = [str(c) for c in rows[start - 1]] if start >= 1 else None
    if above is not None and len(above) == width:
        header = above
        second = [str(c) for c in rows[start - 2]] if start >= 2 else None
        if second is not None and len(second) == width and all(is_unit(f) for f in above):
            header, units = second, above
    columns = header if header is not None else [f"column {i}" for i in range(width)]
    table = rows[start:]
    frame = pd.DataFrame(table, columns=[str(c) for c in columns])
    first = frame.columns[0]
    if any(_is_stamp(c) for c in frame[first]):
        frame[first] = _seconds(list(frame[first]))
    frame = frame.astype(float)
    layout = CsvLayout(
        separator=None, decimal=".", data_line=start, columns=list(frame.columns), units=units
    )
    return frame, layout
