"""A folder of measured recordings described by its ``MANIFEST.csv``, read and checked once.

``cmtool bench``, ``cmtool realism`` and ``cmtool diagnose FOLDER`` take such a folder (the
layout of ``../shared/data``): a row per recording with its ``file`` (relative to the
folder), ``sampling_rate_hz``, ``shaft_rpm`` and, for a labelled benchmark,
``fault_location``; optional ``bearing`` (a catalog name, or a bearing not in it as
:func:`cmtool.io.geometry_from_spec` reads it), ``dataset`` (the rig: ``CWRU`` and ``MFPT``
also name their bearing), ``channel_variable`` (the variable of a ``.mat``/``.npz`` file),
and for a trend ``time`` (when the recording was taken: ISO 8601), ``machine`` (which
machine or measurement point), ``baseline`` (a healthy recording of the same machine,
relative to the folder, that ``cmtool diagnose FOLDER`` compares the recording with) and
``unit`` (the record's unit: an acceleration's, ``g`` or ``m/s^2``, or a velocity's,
``mm/s``, ``m/s`` or ``in/s``; for velocities in mm/s), and for a
recording with a tachometer channel ``tacho_channel`` (its column or number: the speed from
its pulses), ``pulses_per_rev`` (default 1) and ``order_track`` (true: resample to constant
speed first; default false), and ``machine_class`` (the overall velocity's zone: a class of
``cmtool.vibration_zones.MACHINE_CLASSES`` or a site's boundaries, ``1.4/2.8/4.5`` mm/s). A row
that cannot be used is an error naming the manifest, its line, the column, the value and
what is allowed, before any recording is read. Columns are separated by commas, or by
semicolons or tabs as a spreadsheet saves CSV where the decimal mark is a comma (its rates and
speeds may then be written with one: ``1797,5``); rates and speeds may carry a unit
(``12 kHz``, ``1797 rpm``, a shaft's ``29.95 Hz``: :data:`MANIFEST_UNITS`); a byte-order mark
is ignored, a file that is no UTF-8 is read as Windows-1252, and a file name is matched
regardless of case where only one file matches (a manifest written on Windows).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path, PureWindowsPath

import pandas as pd

from generators import BEARINGS, BearingGeometry

from .csv_layout import text_encoding
from .diagnose import CANONICAL, VIBRATION_UNITS
from .io import RecordingError, geometry_from_spec
from .vibration_zones import MACHINE_CLASSES, parse_zone_limits

__all__ = ["MANIFEST_BEARINGS", "MANIFEST_UNITS", "ManifestEntry", "read_manifest"]

#: Bearings of the rigs a manifest's ``dataset`` column may name.
MANIFEST_BEARINGS = {"CWRU": "6205", "MFPT": "mfpt"}

#: Shaft speeds a manifest may give [rpm] (the range of every cmtool command).
_RPM_RANGE = (0.0, 120000.0)


@dataclass(frozen=True)
class ManifestEntry:
    """One recording of a manifest.

    Attributes
    ----------
    file : str
        As the manifest lists it.
    path : Path
        The file.
    fs_hz : float
        Sample rate [Hz].
    rpm : float
        Shaft speed [rev/min].
    bearing : str
        Catalog name of the bearing, or the designation of ``geometry``.
    rig : str
        The ``dataset`` column, else the bearing.
    label : str
        ``fault_location`` as a verdict name (``healthy``, ``outer race``, ``inner race``,
        ``ball``), ``unknown`` where the manifest gives none.
    variable : str or None
        The variable to read (``channel_variable``; None for a struct field such as
        ``bearing.gs``, which the reader finds itself).
    time : pandas.Timestamp or None
        When it was recorded (``time``).
    machine : str or None
        The machine or measurement point (``machine``).
    geometry : BearingGeometry or None
        A bearing not in the catalog, as the ``bearing`` column gave it.
    baseline : Path or None
        A healthy recording of the same machine (``baseline``).
    unit : str or None
        The recording's unit (``unit``: ``cmtool.diagnose.VIBRATION_UNITS``).
    tacho : str or None
        The recording's tachometer channel (``tacho_channel``): the speed from its pulses
        is used, ``shaft_rpm`` compared with it.
    pulses_per_rev : int
        Tachometer pulses per revolution (``pulses_per_rev``, default 1).
    order_track : bool
        Resample the record to constant shaft speed first (``order_track``: true or false,
        default false; needs ``tacho_channel``).
    machine_class : str or tuple of float or None
        The machine's class for the overall velocity's zone (``machine_class``: a key of
        ``cmtool.vibration_zones.MACHINE_CLASSES``, or a site's boundaries A/B, B/C, C/D in
        mm/s written ``1.4/2.8/4.5``).
    """

    file: str
    path: Path
    fs_hz: float
    rpm: float
    bearing: str
    rig: str
    label: str
    variable: str | None
    time: pd.Timestamp | None = None
    machine: str | None = None
    geometry: BearingGeometry | None = None
    baseline: Path | None = None
    unit: str | None = None
    tacho: str | None = None
    pulses_per_rev: int = 1
    order_track: bool = False
    machine_class: str | tuple[float, float, float] | None = None

    @property
    def bearing_or_geometry(self) -> str | BearingGeometry:
        """What ``diagnose_signal`` takes: the geometry if given, else the catalog name."""
        return self.geometry if self.geometry is not None else self.bearing


#: How the ``order_track`` column says yes or no.
_FLAGS = {"true": True, "false": False, "yes": True, "no": False, "1": True, "0": False}


def _text(value: object) -> str | None:
    """A cell as stripped text, None where it is empty."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return None
    text = str(value).strip()
    return text or None


#: Column separators a manifest may use (a spreadsheet saving CSV where the decimal mark is a
#: comma writes semicolons).
MANIFEST_SEPARATORS = (",", ";", "\t")
_DECIMAL_COMMA = re.compile(r"[+-]?\d*,\d+([eE][+-]?\d+)?")


def _manifest_separator(manifest: Path, encoding: str) -> str:
    """The separator of a manifest: the one its header line holds most of (a comma if none)."""
    with open(manifest, encoding=encoding, errors="replace") as handle:
        header = handle.readline()
    counts = [header.count(sep) for sep in MANIFEST_SEPARATORS]
    return MANIFEST_SEPARATORS[counts.index(max(counts))] if max(counts) else ","


#: Units a manifest's numbers may carry after the number (``12 kHz``, ``1797 rpm``), per
#: column: each unit's factor to the column's own (Hz, rpm); a shaft speed in Hz is its
#: rotation frequency (``29.95 Hz``: 1797 rpm). Case is ignored.
MANIFEST_UNITS = {
    "sampling_rate_hz": {"hz": 1.0, "khz": 1e3, "s/s": 1.0, "sps": 1.0, "ks/s": 1e3, "ksps": 1e3},
    "shaft_rpm": {
        "rpm": 1.0,
        "r/min": 1.0,
        "rev/min": 1.0,
        "1/min": 1.0,
        "hz": 60.0,
        "rev/s": 60.0,
    },
}
_NUMBER_AND_UNIT = re.compile(r"(?P<number>.*?\d\.?)\s*(?P<unit>[a-z][a-z/]*|1/min)", re.IGNORECASE)


def _number(
    where: str,
    column: str,
    value: object,
    low: float,
    high: float,
    unit: str,
    decimal_comma: bool = False,
) -> float:
    """A cell as a number in (low, high], or an error naming the row, column and range.

    With ``decimal_comma`` (a manifest whose columns a semicolon or tab separates) a number
    written with a decimal comma (``1797,5``) is read as one. A number may carry one of the
    column's :data:`MANIFEST_UNITS` (``12 kHz``): it is converted to the column's unit.
    """
    text = str(value).strip()
    factor = 1.0
    units = MANIFEST_UNITS.get(column, {})
    written = _NUMBER_AND_UNIT.fullmatch(text)
    if written and units:
        if written["unit"].lower() not in units:
            raise RecordingError(
                f"{where}: {column} = {value!r}: the unit {written['unit']!r} is not one of "
                f"{', '.join(units)} (or none: {unit})"
            )
        factor = units[written["unit"].lower()]
        text = written["number"].strip()
    if decimal_comma and _DECIMAL_COMMA.fullmatch(text):
        text = text.replace(",", ".")
    try:
        number = float(text) * factor
    except ValueError:
        raise RecordingError(f"{where}: {column} = {value!r} is not a number [{unit}]") from None
    if not (math.isfinite(number) and low < number <= high):
        raise RecordingError(
            f"{where}: {column} = {number:g} {unit} is outside the allowed range "
            f"({low:g}, {high:g}] {unit}"
        )
    return number


def _in_folder(folder: Path, name: str) -> tuple[str, Path]:
    """A manifest's file name and its path, written on Windows or not.

    A name with backslashes (``pump3`` backslash ``a.mat``, as a Windows spreadsheet
    writes it) is read with ``/`` where no file has the name as written; a name no file has
    is matched regardless of case where exactly one file does (Windows ignores case:
    ``PUMP3/A.MAT`` for ``pump3/a.mat``).
    """
    path = folder / name
    if "\\" in name and not path.exists():
        name = PureWindowsPath(name).as_posix().removeprefix("./")
        path = folder / name
    if not path.exists():
        found = _ignoring_case(folder, name)
        if found is not None:
            return found.relative_to(folder).as_posix(), found
    return name, path


def _ignoring_case(folder: Path, name: str) -> Path | None:
    """The one path under ``folder`` that is ``name`` regardless of case, else None."""
    here = folder
    for part in Path(name).parts:
        if (here / part).exists():
            here = here / part
            continue
        if not here.is_dir():
            return None
        same = [child for child in here.iterdir() if child.name.casefold() == part.casefold()]
        if len(same) != 1:
            return None
        here = same[0]
    return here


def read_manifest(
    folder: str | Path, *, labelled: bool = False, bearing_default: str = "6205"
) -> list[ManifestEntry]:
    """The recordings a folder's ``MANIFEST.csv`` lists, every row checked.

    Parameters
    ----------
    folder : str or Path
        Holds ``MANIFEST.csv`` and the files it lists.
    labelled : bool
        Every row must give ``fault_location`` (a benchmark scores against it).
    bearing_default : str
        Bearing of rows that name none (no ``bearing``, no known ``dataset``).

    Returns
    -------
    list of ManifestEntry
        In the manifest's order.

    Raises
    ------
    FileNotFoundError
        No ``MANIFEST.csv``, or a file it lists is missing.
    cmtool.io.RecordingError
        A required column is missing, or a row's value cannot be used (the message names the
        manifest's line, the column, the value and what is allowed).
    """
    folder = Path(folder)
    manifest = folder / "MANIFEST.csv"
    if not manifest.is_file():
        raise FileNotFoundError(f"{folder}: no MANIFEST.csv (a folder of recordings needs one)")
    encoding = text_encoding(manifest)  # a Windows spreadsheet's file names: cp1252
    separator = _manifest_separator(manifest, encoding)
    try:
        rows = pd.read_csv(
            manifest, sep=separator, dtype=str, keep_default_na=False, encoding=encoding
        )
    except pd.errors.EmptyDataError:
        raise RecordingError(f"{manifest}: the file holds no data") from None
    required = ["file", "sampling_rate_hz", "shaft_rpm"] + (["fault_location"] if labelled else [])
    missing = [c for c in required if c not in rows.columns]
    if missing:
        raise RecordingError(
            f"{manifest}: no column {', '.join(repr(c) for c in missing)} "
            f"(required: {', '.join(required)}; it has {', '.join(rows.columns)})"
        )
    if rows.empty:
        raise RecordingError(f"{manifest}: lists no recordings")
    labels = ", ".join(sorted(CANONICAL))
    catalog = sorted(BEARINGS)
    entries = []
    for index, row in enumerate(rows.to_dict("records")):
        where = f"{manifest}, line {index + 2}"
        file = _text(row["file"])
        if file is None:
            raise RecordingError(f"{where}: file is empty")
        where = f"{where} ({file})"
        comma = separator != ","
        fs = _number(where, "sampling_rate_hz", row["sampling_rate_hz"], 0.0, 1e7, "Hz", comma)
        rpm = _number(where, "shaft_rpm", row["shaft_rpm"], *_RPM_RANGE, "rpm", comma)
        rig = _text(row.get("dataset"))
        name = _text(row.get("bearing")) or MANIFEST_BEARINGS.get(rig or "", bearing_default)
        geometry = None
        if ":" in name:  # a bearing not in the catalog, by its geometry
            geometry = geometry_from_spec(name, f"{where}: bearing")
            name = geometry.name
        elif name not in catalog:
            raise RecordingError(
                f"{where}: bearing = {name!r} is not in the catalog ({', '.join(catalog)}); "
                "give a bearing not in it as NAME:balls=Z:ball_diameter=d:pitch_diameter=D"
            )
        location = _text(row.get("fault_location"))
        if location is None:
            if labelled:
                raise RecordingError(f"{where}: fault_location is empty (one of {labels})")
            label = "unknown"
        elif location.lower() in CANONICAL:
            label = CANONICAL[location.lower()]
        else:
            raise RecordingError(
                f"{where}: fault_location = {location!r} is not one of {labels}"
                + ("" if labelled else ", or empty")
            )
        variable = _text(row.get("channel_variable"))
        time = _text(row.get("time"))
        if time is not None:
            try:
                time = pd.Timestamp(time)
            except ValueError:
                raise RecordingError(
                    f"{where}: time = {time!r} is not a date and time (ISO 8601, e.g. "
                    "2026-11-28T14:00)"
                ) from None
        file, path = _in_folder(folder, file)
        if not path.is_file():
            raise FileNotFoundError(f"{where}: {path}: no such file")
        unit = _text(row.get("unit"))
        if unit is not None and unit not in VIBRATION_UNITS:
            raise RecordingError(
                f"{where}: unit = {unit!r} is not one of {', '.join(VIBRATION_UNITS)}, or empty"
            )
        tacho = _text(row.get("tacho_channel"))
        pulses = _text(row.get("pulses_per_rev"))
        if pulses is not None and not (pulses.isdigit() and 1 <= int(pulses) <= 10_000):
            raise RecordingError(
                f"{where}: pulses_per_rev = {pulses!r} is not an integer in [1, 10000], or empty"
            )
        track = (_text(row.get("order_track")) or "false").lower()
        if track not in _FLAGS:
            raise RecordingError(
                f"{where}: order_track = {row.get('order_track')!r} is not one of "
                f"{', '.join(_FLAGS)}, or empty"
            )
        if _FLAGS[track] and tacho is None:
            raise RecordingError(f"{where}: order_track needs tacho_channel")
        machine_class = _text(row.get("machine_class"))
        if machine_class is not None and machine_class not in MACHINE_CLASSES:
            try:
                machine_class = parse_zone_limits(machine_class)
            except ValueError:
                raise RecordingError(
                    f"{where}: machine_class = {machine_class!r} is not one of "
                    f"{', '.join(MACHINE_CLASSES)}, nor three zone boundaries in mm/s "
                    "(A/B, B/C, C/D increasing from above 0, e.g. 1.4/2.8/4.5), or empty"
                ) from None
        baseline = _text(row.get("baseline"))
        if baseline is not None:
            baseline = _in_folder(folder, baseline)[1]
            if not baseline.is_file():
                raise FileNotFoundError(f"{where}: baseline {baseline}: no such file")
        entries.append(
            ManifestEntry(
                file=file,
                path=path,
                fs_hz=fs,
                rpm=rpm,
                bearing=name,
                rig=rig or name,
                label=label,
                variable=variable if variable is not None and "." not in variable else None,
                time=time,
                machine=_text(row.get("machine")),
                geometry=geometry,
                baseline=baseline,
                unit=unit,
                tacho=tacho,
                pulses_per_rev=int(pulses) if pulses is not None else 1,
                order_track=_FLAGS[track],
                machine_class=machine_class,
            )
        )
    return entries
