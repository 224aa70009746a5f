"""How a measured recording's CSV file is laid out: separator, decimal mark, header, preamble.

Instruments and spreadsheets write CSV files in several dialects: a comma, a semicolon, a tab
or spaces between columns; a decimal point or (with semicolons, tabs or spaces) a decimal
comma, as spreadsheets in much of Europe write them; lines of metadata before the table; a
row of units under the header; a separator at the end of each line. Read in the wrong dialect
a file can still look like numbers and be wrong: a decimal-comma column read with commas
between columns becomes two columns of integers, and a separator at each line's end makes
pandas take the first column for the row labels and shift the others by one.
:func:`csv_layout` therefore finds the dialect under which the file's first lines are a
table:

- the data are the lines from the first one after which every line splits into the same
  number of fields, each a number (or empty: a missing value, refused later as not finite);
- the line before them is the header if it splits into as many fields; a row of units
  (``s``, ``g``, ``m/s^2``, ``[mm/s]``, ...) may stand between the header and the data; any
  other lines before them are a preamble and are skipped;
- a dialect under which the line before the data splits into as many fields as the data (a
  header) wins over one under which it does not (``acc`` over ``0,125`` is one column with a
  decimal comma, not two columns of integers); then the dialect with more columns, then the
  separators in the order of ``SEPARATORS``.

A file that is no table under any dialect is refused with the line where its table breaks
(numbers before a line of text are not a preamble: a table interrupted by text is refused, not
read from the interruption on).
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = [
    "CsvLayout",
    "csv_layout",
    "is_unit",
    "text_encoding",
    "timestamp_seconds",
    "unit_in_name",
    "SAMPLE_LINES",
    "SEPARATORS",
    "TIME_UNITS",
    "UNITS",
    "time_unit_size",
]

#: Lines at the start of a file read to find its layout (pandas reads the rest with it).
SAMPLE_LINES = 200
#: Column separators tried, in order of preference where two give the same table (None:
#: runs of spaces or tabs).
SEPARATORS = (";", "\t", ",", None)
#: Units a units row may hold (lower case, brackets removed), and the acceleration unit each
#: names for ``read_recording`` (None: a unit of another quantity).
UNITS = {
    "s": None,
    "ms": None,
    "us": None,
    "\u00b5s": None,
    "\u03bcs": None,
    "sec": None,
    "hz": None,
    "v": None,
    "mv": None,
    "mm/s": "mm/s",
    "m/s": "m/s",
    "in/s": "in/s",
    "ips": "in/s",
    "um": None,
    "-": None,
    "": None,
    "g": "g",
    "m/s^2": "m/s^2",
    "m/s2": "m/s^2",
    "m/s\u00b2": "m/s^2",
    "m s^-2": "m/s^2",
}
#: Units a time column may be written in, and their size [s].
TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "\u00b5s": 1e-6, "\u03bcs": 1e-6}
_TIME_SUFFIX = re.compile(r".*[_ ](s|sec|ms|us)$", re.IGNORECASE)
#: A time stamp a logger writes in its first column: a clock time, after an ISO date or not
#: (``2026-11-30 03:45:00.016500``, ``2026-11-30T03:45:00.0165Z``, ``03:45:00,0165``).
_TIMESTAMP = re.compile(
    r"(\d{4}-\d{2}-\d{2}[T ])?\d{1,2}:\d{2}:\d{2}([.,]\d+)?(Z|[+-]\d{2}:?\d{2})?"
)
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(nan|inf|infinity)", re.I)


@dataclass(frozen=True)
class CsvLayout:
    """A CSV file's dialect and where its table starts.

    Attributes
    ----------
    separator : str or None
        The column separator; None for runs of spaces or tabs.
    decimal : str
        The decimal mark, ``.`` or ``,``.
    data_line : int
        The file's line (0-based, blank lines counted) where the numbers start.
    columns : list of str
        The columns' names: the header's fields (a repeated name gets ``.1``, ``.2``, ...),
        or ``column 0``, ``column 1``, ... without a header.
    units : list of str or None
        The row of units under the header, as written, if the file has one.
    encoding : str
        ``utf-8-sig`` (UTF-8, a byte-order mark skipped), or ``cp1252`` where the file's
        first lines are no UTF-8 (a Windows spreadsheet's ``m/s\u00b2`` or ``\u00b5m``).
    """

    separator: str | None
    decimal: str
    data_line: int
    columns: list[str]
    units: list[str] | None
    encoding: str = "utf-8-sig"

    @property
    def pandas_separator(self) -> str:
        """The separator as ``pandas.read_csv``'s ``sep`` takes it."""
        return r"\s+" if self.separator is None else self.separator

    def vibration_unit(self, column: str) -> str | None:
        """The vibration unit the units row gives a column, if any.

        Parameters
        ----------
        column : str
            One of :attr:`columns`.

        Returns
        -------
        str or None
            An acceleration's (``g``, ``m/s^2``) or a velocity's (``mm/s``, ``m/s``,
            ``in/s``), or None (no units row, or another quantity's unit).
        """
        if self.units is None or column not in self.columns:
            return None
        return UNITS.get(_unit_key(self.units[self.columns.index(column)]))


_BRACKETED = re.compile(r".*?[\[(]\s*([^\[\]()]+?)\s*[\])]\s*$")


def unit_in_name(name: str) -> str | None:
    """The vibration unit a column's name gives in brackets at its end, if any.

    Parameters
    ----------
    name : str
        A column's name, e.g. ``acc [g]``, ``Beschleunigung (m/s^2)``, ``AI0 [m/s\u00b2]``,
        ``velocity [mm/s]``.

    Returns
    -------
    str or None
        An acceleration's (``g``, ``m/s^2``) or a velocity's (``mm/s``, ``m/s``, ``in/s``);
        None when the name ends in no bracketed unit or in another quantity's (``(V)``).

    Examples
    --------
    >>> unit_in_name("acc [g]"), unit_in_name("DE (m/s2)"), unit_in_name("velocity [mm/s]")
    ('g', 'm/s^2', 'mm/s')
    >>> unit_in_name("AI0 (V)") is None
    True
    """
    match = _BRACKETED.fullmatch(str(name))
    return None if match is None else UNITS.get(_unit_key(match.group(1)))


def time_unit_size(name: str, unit: str | None = None) -> float:
    """The size [s] of a time column's unit: its units row's, else its name's.

    Parameters
    ----------
    name : str
        The column's name: a bracketed unit at its end (``time [ms]``, ``t (us)``) or a
        suffix (``time_ms``) says it.
    unit : str, optional
        Its entry in the file's units row (``ms``), which comes first.

    Returns
    -------
    float
        The unit's size [s]: 1e-3 for ms, 1e-6 for us; 1 where nothing says (seconds).

    Examples
    --------
    >>> time_unit_size("time [ms]"), time_unit_size("t_us"), time_unit_size("t", "ms")
    (0.001, 1e-06, 0.001)
    >>> time_unit_size("Time (s)"), time_unit_size("time")
    (1.0, 1.0)
    """
    for text in (unit, *(m.group(1) for m in [_BRACKETED.fullmatch(str(name))] if m)):
        if text is not None and _unit_key(text) in TIME_UNITS:
            return TIME_UNITS[_unit_key(text)]
    suffix = _TIME_SUFFIX.fullmatch(str(name).strip())
    return TIME_UNITS[suffix.group(1).lower()] if suffix else 1.0


def _unit_key(text: str) -> str:
    return text.strip().strip("[]()").strip().lower()


def _fields(line: str, separator: str | None) -> list[str]:
    """A line's fields under a separator, unquoted; a trailing empty field dropped."""
    parts = line.split() if separator is None else line.split(separator)
    parts = [p.strip().strip('"').strip("'").strip() for p in parts]
    if len(parts) > 1 and parts[-1] == "":
        parts = parts[:-1]  # a separator at the end of the line
    return parts


def _is_number(field: str, decimal: str) -> bool:
    if field == "":
        return True  # a missing value: read as NaN, refused as not finite downstream
    if decimal == ",":
        if "." in field:
            return False
        field = field.replace(",", ".")
    return _NUMBER.fullmatch(field) is not None


def _is_row(fields: list[str], width: int, decimal: str) -> bool:
    """A row of numbers, the first of which may be a time stamp (``_TIMESTAMP``)."""
    return len(fields) == width and all(
        _is_number(f, decimal) or (i == 0 and _TIMESTAMP.fullmatch(f) is not None)
        for i, f in enumerate(fields)
    )


def timestamp_seconds(values: Sequence[object]) -> np.ndarray | None:
    """A column of time stamps as seconds from its first, or None if it holds other text.

    Parameters
    ----------
    values : sequence
        The column's fields as read (text).

    Returns
    -------
    numpy.ndarray or None
        Seconds from the first time stamp [s] (a clock time alone is read as a time of
        day); None where a field is no time stamp.

    Examples
    --------
    >>> timestamp_seconds(["2026-11-30 03:45:00.000", "2026-11-30 03:45:00.0005"]).tolist()
    [0.0, 0.0005]
    >>> timestamp_seconds(["03:45:00,25", "03:45:00,5"]).tolist()
    [0.0, 0.25]
    """
    import pandas as pd

    text = [str(v).strip() for v in values]
    if not text or not all(_TIMESTAMP.fullmatch(t) for t in text):
        return None
    text = [t.replace(",", ".") for t in text]
    if _CLOCK.fullmatch(text[0]):
        stamps = pd.to_timedelta(text).to_numpy(dtype="timedelta64[ns]").astype(np.int64)
    else:
        stamps = pd.to_datetime(text, format="ISO8601").to_numpy(dtype="datetime64[ns]")
        stamps = stamps.astype(np.int64)
    return (stamps - stamps[0]) / 1e9


_CLOCK = re.compile(r"\d{1,2}:\d{2}:\d{2}(\.\d+)?")


def _is_units(fields: list[str]) -> bool:
    return all(is_unit(f) for f in fields) and any(f.strip() for f in fields)


def is_unit(text: str) -> bool:
    """Whether a field is a unit a units row holds (``UNITS``: ``s``, ``g``, ``[mm/s]``, ``V``).

    Parameters
    ----------
    text : str
        The field.

    Returns
    -------
    bool
        True for a known unit, bracketed or not, or an empty field.
    """
    return _unit_key(text) in UNITS


def _table_start(rows: list[list[str]], decimal: str) -> tuple[int, int] | None:
    """(index of the first data row, fields per row), or None if the rows end in no table."""
    width = len(rows[-1])
    start = len(rows)
    for i in range(len(rows) - 1, -1, -1):
        if not _is_row(rows[i], width, decimal):
            break
        start = i
    if start == len(rows) or all(f == "" for f in rows[start]):
        return None
    return start, width


def _unique(names: list[str]) -> list[str]:
    seen: dict[str, int] = {}
    out = []
    for name in names:
        count = seen.get(name, 0)
        out.append(name if count == 0 else f"{name}.{count}")
        seen[name] = count + 1
    return out


def text_encoding(path: str | Path) -> str:
    """The encoding of a text file: UTF-8 if its first 64 kB decode as it, else Windows-1252.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str
        ``utf-8-sig`` (a byte-order mark skipped) or ``cp1252``.
    """
    with open(path, "rb") as handle:
        head = handle.read(65536)
    try:
        codecs.getincrementaldecoder("utf-8")().decode(head, final=False)
    except UnicodeDecodeError:
        return "cp1252"
    return "utf-8-sig"


def csv_layout(path: str | Path) -> CsvLayout:
    """Find the dialect, header and first data line of a CSV recording.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    CsvLayout
        Its separator, decimal mark, first data line, column names and units row.

    Raises
    ------
    ValueError
        The file has no lines, or its first ``SAMPLE_LINES`` lines end in no table of
        numbers under any dialect (the message names the line where the table breaks).
    """
    encoding = text_encoding(path)
    lines: list[tuple[int, str]] = []  # (line number, text) of the non-blank lines
    with open(path, encoding=encoding, errors="replace") as handle:
        for number, text in enumerate(handle):
            if number >= SAMPLE_LINES:
                break
            if text.strip():
                lines.append((number, text.rstrip("\r\n")))
    if not lines:
        raise ValueError("the file holds no data")
    best: tuple[tuple[bool, int, int], CsvLayout] | None = None
    broken: tuple[int, str] | None = None  # a line that interrupts a table
    for preference, separator in enumerate(SEPARATORS):
        rows = [_fields(text, separator) for _, text in lines]
        for decimal in (".", ","):
            if decimal == "," and separator == ",":
                continue
            found = _table_start(rows, decimal)
            if found is None:
                continue
            start, width = found
            header = units = None
            first = start  # the first row of header, units and data
            if start >= 1 and len(rows[start - 1]) == width:
                header, first = rows[start - 1], start - 1
                if start >= 2 and len(rows[start - 2]) == width and _is_units(header):
                    header, units, first = rows[start - 2], rows[start - 1], start - 2
            if any(_is_row(r, width, decimal) for r in rows[:first]):
                broken = broken or lines[start - 1]
                continue  # numbers before the table: it breaks, it does not start, there
            columns = header if header is not None else [f"column {i}" for i in range(width)]
            layout = CsvLayout(
                separator=separator,
                decimal=decimal,
                data_line=lines[start][0],
                columns=_unique([str(c) for c in columns]),
                units=units,
                encoding=encoding,
            )
            key = (header is not None, width, -preference)
            if best is None or key > best[0]:
                best = (key, layout)
    if best is None and broken is not None:
        number, text = broken
        raise ValueError(f"line {number + 1} ({text[:60]!r}) interrupts the table of numbers")
    if best is None:
        number, text = lines[-1]
        raise ValueError(
            f"line {number + 1} ({text[:60]!r}) is no row of numbers with ',', ';', a tab or "
            "spaces between columns and '.' or ',' as the decimal mark"
        )
    return best[1]
