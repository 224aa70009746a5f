"""Reading and writing signals: simulated results to parquet/CSV, measured recordings in.

Signals are written with a ``time`` column [s] and one column per channel named
``<body>_<quantity>_<axis>`` in SI units; the run's parameters, sample rate and characteristic
frequencies go into the parquet key-value metadata (key ``cmtool``) or a JSON sidecar for CSV.
"""

from __future__ import annotations

import json
import math
import os
import re
import tempfile
import zipfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from generators import BearingGeometry, SimulationResult
from generators.stream import SignalStream

from . import __version__
from .csv_layout import CsvLayout, csv_layout, time_unit_size, timestamp_seconds, unit_in_name
from .excel_files import read_excel_table
from .file_variables import rate_and_speed
from .last_file import keep_last_read
from .tdms_files import read_tdms
from .time_axis import spliced_time_axis, time_axis_rate
from .uff_files import read_uff

__all__ = [
    "write_signal",
    "write_signal_stream",
    "estimated_file_bytes",
    "read_signal",
    "atomic_write",
    "to_jsonable",
    "json_text",
    "read_recording",
    "RecordingError",
]

SIGNAL_SCHEMA_VERSION = 1


def to_jsonable(obj: Any) -> Any:
    """Convert numpy scalars/arrays and nested containers to JSON-serialisable values.

    Parameters
    ----------
    obj : object
        A value: dicts (keys made str), lists, tuples, numpy arrays and scalars are
        converted all the way down.

    Returns
    -------
    object
        Python scalars, lists and dicts; a value that is not finite becomes None.
    """
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())  # its values too: a NaN in an array is no JSON
    if isinstance(obj, np.generic):
        return to_jsonable(obj.item())  # a numpy inf becomes a float inf: null too
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj


def json_text(obj: Any) -> str:
    """``obj`` as strict JSON text, indented: :func:`to_jsonable`, and no NaN or Infinity.

    What every JSON result cmtool writes or prints goes through (``tests/tests_cmtool/
    test_house.py::test_json_results_are_strict_json``).

    Parameters
    ----------
    obj : object
        The value (:func:`to_jsonable`).

    Returns
    -------
    str
    """
    return json.dumps(to_jsonable(obj), indent=2, allow_nan=False)


def _process_umask() -> int:
    """The process's umask (read once, at import: setting it is not thread-safe)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


_UMASK = _process_umask()


def atomic_write(path: Path, write: Callable[[Path], object]) -> None:
    """Call ``write(tmp_path)`` then rename the temporary file onto ``path`` (atomic on POSIX).

    A reader never sees half a file, and an interrupted write leaves the previous one.

    Parameters
    ----------
    path : pathlib.Path
        The file written (its folder is created).
    write : callable
        ``write(tmp_path)`` writes the whole file at ``tmp_path`` (beside ``path``).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        write(Path(tmp))
        # mkstemp makes 0600 files; a written result gets the mode the user's umask gives
        os.chmod(tmp, 0o666 & ~_UMASK)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def signal_metadata(result: SimulationResult | SignalStream) -> dict[str, Any]:
    """Metadata stored with a simulated signal (a whole result or a stream of blocks).

    Parameters
    ----------
    result : SimulationResult or SignalStream
        The run.

    Returns
    -------
    dict
        Schema and cmtool versions, ``fs_hz``, ``frequencies_hz``, the run's parameters and
        the units of each quantity (SI), JSON-serialisable.
    """
    return to_jsonable(
        {
            "schema_version": SIGNAL_SCHEMA_VERSION,
            "cmtool_version": __version__,
            "fs_hz": result.fs,
            "frequencies_hz": result.frequencies.as_dict(),
            "parameters": result.parameters,
            "units": {"time": "s", "displacement": "m", "velocity": "m/s", "acceleration": "m/s^2"},
        }
    )


def write_signal(
    result: SimulationResult,
    path: str | os.PathLike,
    *,
    channels: tuple[str, ...] | None = None,
) -> Path:
    """Write a simulated signal to ``.parquet`` or ``.csv`` (with a ``.json`` sidecar).

    Parameters
    ----------
    result : SimulationResult
        Output of :func:`generators.simulate`.
    path : str or PathLike
        Destination; the suffix selects the format.
    channels : tuple of str, optional
        Channels written (default: every channel of the result), after ``time``.

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    frame = result.to_frame()
    if channels is not None:
        frame = frame[["time", *channels]]
    meta = signal_metadata(result)
    suffix = path.suffix.lower()
    if suffix == ".parquet":
        table = pa.Table.from_pandas(frame, preserve_index=False)
        table = table.replace_schema_metadata(
            {**(table.schema.metadata or {}), b"cmtool": json.dumps(meta).encode()}
        )
        atomic_write(path, lambda tmp: pq.write_table(table, tmp))
    elif suffix == ".csv":
        atomic_write(path, lambda tmp: frame.to_csv(tmp, index=False, float_format="%.10g"))
        sidecar = path.with_suffix(path.suffix + ".json")
        atomic_write(sidecar, lambda tmp: tmp.write_text(json.dumps(meta, indent=2)))
    else:
        raise ValueError(f"out = {str(path)!r}: suffix {suffix!r} is not one of .parquet, .csv")
    return path


#: Bytes per value as written, rounded up: parquet stores float64 (noise-like data does not
#: compress; measured 9.7 bytes per value with pages and statistics on a 300 s, 51.2 kHz run
#: of every channel), CSV up to 17 characters and a separator (``%.10g``).
_BYTES_PER_VALUE = {".parquet": 10, ".csv": 18}


def estimated_file_bytes(path: str | os.PathLike, samples: int, channels: int) -> int:
    """Size of a signal file :func:`write_signal` writes (time column included) [bytes].

    Parameters
    ----------
    path : str or PathLike
        Destination (its suffix selects the format: ``.parquet`` or ``.csv``).
    samples : int
        Samples per channel.
    channels : int
        Channels written besides ``time``.

    Returns
    -------
    int
        Bytes.

    Examples
    --------
    >>> estimated_file_bytes("x.parquet", 1000, 1)
    20000
    """
    return int(_BYTES_PER_VALUE[Path(path).suffix.lower()] * samples * (channels + 1))


def write_signal_stream(
    stream: SignalStream,
    path: str | os.PathLike,
    *,
    channels: tuple[str, ...] | None = None,
    progress: Callable[[int], None] | None = None,
) -> Path:
    """Write a streamed simulation (:func:`generators.stream.simulate_stream`) block by block.

    The file is that of :func:`write_signal` (same columns, metadata and formats: a parquet
    row group per block, CSV rows appended), written to a temporary file renamed onto
    ``path`` when the last block is in: a run that diverges or is interrupted leaves nothing.

    Parameters
    ----------
    stream : SignalStream
        The prepared run.
    path : str or PathLike
        Destination ``.parquet`` or ``.csv`` (with a ``.json`` sidecar).
    channels : tuple of str, optional
        Channels written (default: every channel of the stream).
    progress : callable, optional
        Called with the number of samples of each block once it is written.

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    names = list(channels or stream.channels)
    meta = signal_metadata(stream)
    suffix = path.suffix.lower()

    def frames():
        for block in stream:
            data = {"time": block.time}
            data.update({name: block.signals[name] for name in names})
            yield pd.DataFrame(data)
            if progress is not None:
                progress(len(block.time))

    if suffix == ".parquet":

        def write_parquet(tmp: Path) -> None:
            writer = None
            try:
                for frame in frames():
                    table = pa.Table.from_pandas(frame, preserve_index=False)
                    if writer is None:
                        schema = table.schema.with_metadata(
                            {**(table.schema.metadata or {}), b"cmtool": json.dumps(meta).encode()}
                        )
                        writer = pq.ParquetWriter(tmp, schema)
                    writer.write_table(table.replace_schema_metadata(writer.schema.metadata))
            finally:
                if writer is not None:
                    writer.close()

        atomic_write(path, write_parquet)
    elif suffix == ".csv":

        def write_csv(tmp: Path) -> None:
            with open(tmp, "w", newline="") as handle:
                for k, frame in enumerate(frames()):
                    frame.to_csv(handle, index=False, header=k == 0, float_format="%.10g")

        atomic_write(path, write_csv)
        sidecar = path.with_suffix(path.suffix + ".json")
        atomic_write(sidecar, lambda tmp: tmp.write_text(json.dumps(meta, indent=2)))
    else:
        raise ValueError(f"out = {str(path)!r}: suffix {suffix!r} is not one of .parquet, .csv")
    return path


def read_signal(path: str | os.PathLike) -> tuple[pd.DataFrame, dict[str, Any]]:
    """Read a signal written by :func:`write_signal`: ``(frame, metadata)``.

    Parameters
    ----------
    path : path-like
        A ``.parquet`` file, or a ``.csv`` with its ``.csv.json`` metadata beside it.

    Returns
    -------
    frame : pandas.DataFrame
        ``time`` [s] and the channels [SI units].
    metadata : dict
        :func:`signal_metadata` (empty for a CSV without its sidecar).
    """
    path = Path(path)
    if path.suffix.lower() == ".parquet":
        table = pq.read_table(path)
        raw = (table.schema.metadata or {}).get(b"cmtool", b"{}")
        return table.to_pandas(), json.loads(raw)
    frame = pd.read_csv(path)
    sidecar = path.with_suffix(path.suffix + ".json")
    meta = json.loads(sidecar.read_text()) if sidecar.exists() else {}
    return frame, meta


# ----------------------------------------------------------------------- measured recordings


class RecordingError(ValueError):
    """A recording cannot be read as asked (message names the file, variable or channel)."""


#: How a bearing not in the catalog is given (diameters [m], contact angle [deg]).
GEOMETRY_USAGE = "NAME:balls=Z:ball_diameter=d:pitch_diameter=D[:contact_angle_deg=A]"

_GEOMETRY_KEYS = {
    "balls": ("ball_count", int),
    "ball_diameter": ("ball_diameter", float),
    "pitch_diameter": ("pitch_diameter", float),
    "contact_angle_deg": ("contact_angle", float),
}


def split_spec(
    spec: str,
    option: str,
    usage: str,
    keys: dict[str, tuple[str, object]],
    required: tuple,
    error: type[Exception] = ValueError,
) -> tuple[str, dict[str, object]]:
    """Split ``head:key=value:...``; ``keys`` maps a key to (field name, converter).

    Parameters
    ----------
    spec : str
        The specification.
    option : str
        What gave it (an option, a manifest's line): every message names it and the spec.
    usage : str
        The form expected, for the messages.
    keys : dict of str to (str, callable)
        Each key allowed -> the field's name and its converter (``int``, ``float``).
    required : tuple of str
        The keys that must be given.
    error : type
        The exception raised (the command line's own, or
        :class:`generators.ParameterError`).

    Returns
    -------
    head : str
        The text before the first colon.
    fields : dict of str to object
        The converted values under their fields' names.
    """
    parts = spec.split(":")
    head = parts[0].strip()
    fields: dict[str, object] = {}
    for item in parts[1:]:
        if "=" not in item:
            raise error(f"{option} {spec!r}: {item!r} is not key=value (expected {usage})")
        key, value = (s.strip() for s in item.split("=", 1))
        if key not in keys:
            raise error(f"{option} {spec!r}: unknown key {key!r} (allowed: {', '.join(keys)})")
        name, convert = keys[key]
        try:
            fields[name] = convert(value)  # type: ignore[operator]
        except ValueError as err:
            kind = "an integer" if convert is int else "a number"
            raise error(f"{option} {spec!r}: {key}={value!r} is not {kind}") from err
    for key in required:
        if keys[key][0] not in fields:
            raise error(f"{option} {spec!r}: {key}= is missing")
    return head, fields


def geometry_from_spec(spec: str, where: str = "--geometry") -> BearingGeometry:
    """A bearing not in the catalog from its designation and kinematic geometry.

    ``NAME:balls=Z:ball_diameter=d:pitch_diameter=D[:contact_angle_deg=A]``, diameters in m,
    the contact angle in degrees (a maker's tables give it so; default 0, at most 45). The
    fault rates need only these; :class:`generators.BearingGeometry`'s defaults stand for the
    rest (groove conformity 0.52, clearance 10 um, steel).

    Parameters
    ----------
    spec : str
        The specification.
    where : str
        What gave it, for the messages (an option, a manifest's line).

    Returns
    -------
    generators.BearingGeometry

    Raises
    ------
    generators.ParameterError
        A key missing, unknown or not a number, or a value out of its range (named).

    Examples
    --------
    >>> g = geometry_from_spec("6310:balls=8:ball_diameter=20.64e-3:pitch_diameter=77.5e-3")
    >>> g.name, g.ball_count
    ('6310', 8)
    """
    import math

    from generators import BearingGeometry, ParameterError

    name, fields = split_spec(
        str(spec),
        where,
        GEOMETRY_USAGE,
        _GEOMETRY_KEYS,
        ("balls", "ball_diameter", "pitch_diameter"),
        ParameterError,
    )
    if not name:
        raise ParameterError(f"{where} {spec!r}: the designation is missing ({GEOMETRY_USAGE})")
    degrees = float(fields.pop("contact_angle", 0.0))  # type: ignore[arg-type]
    if not 0.0 <= degrees <= 45.0:
        raise ParameterError(
            f"{where} {spec!r}: contact_angle_deg = {degrees:g} deg is outside the allowed "
            "range [0, 45] deg (a deep groove ball bearing)"
        )
    try:
        return BearingGeometry(
            name=name, contact_angle=math.radians(degrees), source=f"given ({where})", **fields
        )
    except ParameterError as err:
        diameters = [fields.get(k) for k in ("ball_diameter", "pitch_diameter")]
        if any(isinstance(d, float) and d > 0.5 for d in diameters):  # a maker's table in mm
            raise ParameterError(
                f"{where} {spec!r}: {err} (diameters are in m: 7.94 mm is 7.94e-3)"
            ) from None
        raise


def _csv_sidecar(path: Path) -> dict[str, Any] | None:
    """The metadata ``write_signal`` puts beside a CSV (``NAME.csv.json``), or None.

    Only a sidecar cmtool wrote counts (its schema version and sample rate); any other JSON of
    that name is left alone, and one that cannot be read is an error naming it.
    """
    sidecar = path.with_suffix(path.suffix + ".json")
    if not sidecar.is_file():
        return None
    try:
        info = json.loads(sidecar.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise RecordingError(f"{sidecar}: not a readable JSON sidecar ({err})") from None
    if not (isinstance(info, dict) and "schema_version" in info and "fs_hz" in info):
        return None
    return info


@keep_last_read
def _mat_variables(path: Path) -> dict[str, Any]:
    """A MAT-file's variables: versions 4-7 by scipy, 7.3 (HDF5) by :mod:`.matlab_hdf5`."""
    from scipy import io as sio

    try:
        data = sio.loadmat(path, squeeze_me=True, struct_as_record=False)
    except NotImplementedError:  # scipy's answer to a MATLAB v7.3 (HDF5) file
        from .matlab_hdf5 import read_mat_v73

        try:
            data = read_mat_v73(path)
        except Exception as err:  # noqa: BLE001 - h5py's errors for a cut or foreign file
            raise RecordingError(
                f"{path}: not a readable MATLAB v7.3 (HDF5) file ({err})"
            ) from None
    except Exception as err:  # noqa: BLE001 - a truncated or foreign file fails in many ways
        raise RecordingError(f"{path}: not a readable MATLAB file ({err})") from None
    return {k: v for k, v in data.items() if not k.startswith("__")}


def _pick(count: int, channel: str | int | None, path: Path) -> int:
    """Index of a channel among ``count``, checked (default 0)."""
    index = 0 if channel is None else channel
    try:
        index = int(index)
    except (TypeError, ValueError):
        raise RecordingError(f"{path}: channel {channel!r} is not a channel number") from None
    if not 0 <= index < count:
        raise RecordingError(
            f"{path}: channel {index} is outside the allowed range [0, {count - 1}]"
        )
    return index


def _real_samples(value: object, path: Path) -> np.ndarray:
    """An array of samples as float64; complex samples refused.

    numpy would drop the imaginary part with only a warning.
    """
    array = np.asarray(value)
    if np.iscomplexobj(array):
        raise RecordingError(
            f"{path}: the samples are complex numbers; a vibration recording is real (save "
            "its real part, or each part as a channel)"
        )
    return np.asarray(array, dtype=float)


def _one_channel(
    x: np.ndarray, channel: str | int | None, path: Path, meta: dict[str, Any]
) -> np.ndarray:
    """The asked channel of an array: its samples along the longer axis (default channel 0).

    A 2-D array holds its channels along its shorter axis (a record is longer than it is
    wide): a column each (samples x channels) or a row each (channels x samples). Their
    count goes to ``meta["channels"]``.
    """
    squeezed = np.squeeze(x) if x.ndim > 2 else x
    if squeezed.ndim > 2:
        raise RecordingError(
            f"{path}: an array of shape {x.shape}; give one record (1-D) or channels x samples"
        )
    if squeezed.ndim == 2 and min(squeezed.shape) > 1:
        meta["channels"] = int(min(squeezed.shape))
        index = _pick(min(squeezed.shape), channel, path)
        rows_are_samples = squeezed.shape[0] >= squeezed.shape[1]
        return squeezed[:, index] if rows_are_samples else squeezed[index]
    _pick(1, channel, path)  # one channel: only 0 (or none) can be asked for
    return squeezed.ravel()


#: Suffixes of delimited text tables, read as a CSV is (a data logger's export is often a
#: tab-separated ``.txt``).
TEXT_TABLES = (".csv", ".txt", ".tsv")


@keep_last_read
def _read_csv_table(path: Path) -> tuple[pd.DataFrame, CsvLayout]:
    """A CSV recording's table of numbers, read in the dialect :func:`csv_layout` finds."""
    try:
        layout = csv_layout(path)
    except ValueError as error:
        raise RecordingError(f"{path}: {error}") from None
    frame = pd.read_csv(
        path,
        sep=layout.pandas_separator,
        decimal=layout.decimal,
        header=None,
        skiprows=layout.data_line,
        index_col=False,
        encoding=layout.encoding,
        encoding_errors="replace",  # numbers are ASCII; a stray byte in a skipped line
    )
    width = len(layout.columns)
    if frame.shape[1] == width + 1 and frame.iloc[:, -1].isna().all():
        frame = frame.iloc[:, :-1]  # the empty field after a separator at each line's end
    if frame.shape[1] != width:
        raise RecordingError(
            f"{path}: the rows from line {layout.data_line + 1} have {frame.shape[1]} fields "
            f"where the table has {width} ({layout.columns})"
        )
    frame.columns = layout.columns
    first = frame.columns[0]
    if not pd.api.types.is_numeric_dtype(frame[first]):  # a logger's time stamps: seconds
        seconds = timestamp_seconds(frame[first].tolist())
        frame[first] = frame[first] if seconds is None else seconds
    for name in frame.columns:
        if not pd.api.types.is_numeric_dtype(frame[name]):
            text = frame[name][pd.to_numeric(frame[name], errors="coerce").isna()]
            text = text[text.notna()]
            raise RecordingError(
                f"{path}: column {name!r} holds text among its numbers ({text.iloc[0]!r}, "
                f"row {int(text.index[0]) + 1} of the table from line {layout.data_line + 1})"
            )
    return frame, layout


def _drive_end_variable(names: list[str], path: Path) -> str | None:
    """The CWRU drive-end variable ``X###_DE_time`` a file holds for its own record.

    A CWRU file holds one record's channels, named after its number (``105.mat``:
    ``X105_DE_time``), but some hold a second record's as well (a normal-baseline file with
    the next one's channels, as distributed). One drive-end variable is the record; of
    several, the one whose number is in the file's name (``99.mat``, ``Normal_2_099.mat``:
    ``X099``); None when the name does not say (the caller asks for ``--variable``).
    """
    if len(names) == 1:
        return names[0]
    numbers = [int(n) for n in re.findall(r"\d+", path.stem)]
    for number in reversed(numbers):  # the record number ends CWRU-derived names
        for name in names:
            digits = name[1:].split("_")[0]
            if digits.isdigit() and int(digits) == number:
                return name
    return None


def read_recording(
    path: str | os.PathLike,
    *,
    variable: str | None = None,
    channel: str | int | None = None,
) -> tuple[np.ndarray, dict[str, Any]]:
    """Read a measured vibration recording: ``(signal, metadata)``.

    Formats: MATLAB ``.mat`` (CWRU files: ``X###_DE_time`` by default, of several the one the
    file's name numbers, rpm from ``X###RPM``;
    MFPT files: struct ``bearing`` with ``gs``, ``sr`` and ``rate``), ``.csv`` and the text
    tables data loggers export as ``.txt`` or ``.tsv`` (a column by name or index; the dialect,
    preamble and units row found by :func:`cmtool.csv_layout.csv_layout`;
    a time column, named ``time``, ``t`` or ``time_s`` or the first column rising in equal
    steps, gives the rate), ``.wav``, ``.npy``/``.npz``, ``.parquet``, LabVIEW's ``.tdms``
    (:func:`cmtool.tdms_files.read_tdms`) and the Universal File Format's data-set 58,
    ``.uff``/``.unv`` (:func:`cmtool.uff_files.read_uff`). Complex samples are refused.

    Parameters
    ----------
    path : str or PathLike
        The file.
    variable : str, optional
        Variable of a .mat/.npz file (default: the drive-end channel of CWRU files, the
        ``bearing`` struct of MFPT files, or the only numeric array).
    channel : str or int, optional
        Column of a CSV/parquet file or a multi-channel WAV/array (default: the first); an
        array's channels lie along its shorter axis (samples x channels or channels x samples).

    Returns
    -------
    signal : ndarray, 1-D float64
        The samples (unit as stored: g for CWRU and MFPT).
    metadata : dict
        ``fs_hz``, ``rpm`` and ``bearing`` when the file holds them (cmtool parquet files,
        cmtool CSV files with their ``.csv.json`` sidecar; the CWRU and MFPT layouts name
        their bearing), ``variable``, ``unit`` when known (g in the CWRU and MFPT layouts;
        a CSV's units row, or a CSV or parquet column's name ending in ``[g]`` or
        ``(m/s^2)``: :func:`cmtool.csv_layout.unit_in_name`), ``warnings`` the reader's own
        (a WAV file cut short: "Reached EOF prematurely ...").
    """
    path = Path(path)
    if not path.is_file():
        raise RecordingError(f"{path}: no such file")
    suffix = path.suffix.lower()
    meta: dict[str, Any] = {"file": str(path)}
    try:
        x = _read_samples(path, suffix, variable, channel, meta)
    except RecordingError:
        raise
    except (ValueError, TypeError, KeyError, OSError, EOFError, zipfile.BadZipFile) as error:
        # a file that is not what its suffix says, or samples that are not numbers
        raise RecordingError(
            f"{path}: cannot be read as a {suffix.lstrip('.')} recording ({error})"
        ) from error
    if x.size < 16:
        raise RecordingError(f"{path}: only {x.size} samples")
    # a copy: the file's parse is kept for its next channel (cmtool.last_file)
    return np.array(x, dtype=float, order="C"), meta


def _read_samples(
    path: Path, suffix: str, variable: str | None, channel: str | int | None, meta: dict
) -> np.ndarray:
    """The samples of one channel of ``path``, read by its format.

    ``meta`` gains what the file says (rate, speed, bearing, unit, variable, channels).
    """
    if suffix == ".mat":
        data = _mat_variables(path)
        meta.update(rate_and_speed(data))  # scalars fs, dt, rpm, ...; a layout's own below
        if variable is None and "bearing" in data:
            variable = "bearing"
        if variable is None:
            de = sorted(k for k in data if k.endswith("_DE_time"))
            numeric = [k for k, v in data.items() if isinstance(v, np.ndarray) and v.size > 16]
            variable = _drive_end_variable(de, path) if de else None
            if variable is None and not de and len(numeric) == 1:
                variable = numeric[0]
            if variable is None and not de and not numeric:
                raise RecordingError(
                    f"{path}: no numeric array of more than 16 samples; it holds {sorted(data)}"
                )
            if variable is None:
                raise RecordingError(
                    f"{path}: choose a variable with --variable; it holds {sorted(data)}"
                )
        if variable not in data:
            raise RecordingError(
                f"{path}: variable {variable!r} not found; it holds {sorted(data)}"
            )
        value = data[variable]
        if hasattr(value, "_fieldnames"):  # MATLAB struct (MFPT)
            fields = value._fieldnames
            if "gs" not in fields:
                raise RecordingError(f"{path}: struct {variable!r} has no 'gs' field ({fields})")
            x = np.asarray(value.gs, dtype=float).ravel()
            if "sr" in fields:
                meta["fs_hz"] = float(np.asarray(value.sr).ravel()[0])
            if "rate" in fields:
                meta["rpm"] = 60.0 * float(np.asarray(value.rate).ravel()[0])
            meta["unit"] = "g"
            meta["bearing"] = "mfpt"  # the MFPT layout: struct bearing.gs/sr/rate
        else:
            x = _one_channel(_real_samples(value, path), channel, path, meta)
            prefix = variable.split("_")[0]
            rpm_key = f"{prefix}RPM"
            if rpm_key in data:
                meta["rpm"] = float(np.asarray(data[rpm_key]).ravel()[0])
            if variable.endswith("_time"):
                meta["unit"] = "g"
            if variable.endswith("_DE_time"):  # the CWRU layout: drive-end SKF 6205
                meta["bearing"] = "6205"
            elif variable.endswith("_FE_time"):  # fan end: SKF 6203
                meta["bearing"] = "6203"
        meta["variable"] = variable
    elif suffix == ".wav":
        import warnings

        from scipy.io import wavfile

        with warnings.catch_warnings(record=True) as caught:  # a cut file: said in the output
            warnings.simplefilter("always", wavfile.WavFileWarning)
            rate, data = wavfile.read(path)
        said = [str(w.message) for w in caught if issubclass(w.category, wavfile.WavFileWarning)]
        if said:
            meta["warnings"] = [f"{path.name}: {message}" for message in said]
        data = np.asarray(data)
        if data.ndim == 2:
            meta["channels"] = int(data.shape[1])
            data = data[:, _pick(data.shape[1], channel, path)]
        else:
            _pick(1, channel, path)  # one channel: only 0 (or none) can be asked for
        if np.issubdtype(data.dtype, np.integer):
            data = data / float(np.iinfo(data.dtype).max)
        x = data.astype(float)
        meta["fs_hz"] = float(rate)
    elif suffix == ".tdms":  # LabVIEW's: cmtool.tdms_files
        x = read_tdms(path, variable, channel, meta)
    elif suffix in (".uff", ".unv"):  # analysers' data-set 58: cmtool.uff_files
        x = read_uff(path, variable, channel, meta)
    elif suffix in (".npy", ".npz"):
        loaded = np.load(path, allow_pickle=False)
        if suffix == ".npz":
            keys = list(loaded.keys())
            if variable is not None and variable not in keys:
                raise RecordingError(f"{path}: variable {variable!r} not found; it holds {keys}")
            scalars = {k: loaded[k] for k in keys if loaded[k].size == 1}
            meta.update(rate_and_speed(scalars))  # np.savez(..., x=x, fs=fs)
            records = [k for k in keys if k not in scalars]
            key = variable or (records[0] if len(records) == 1 else None)
            if key is None:
                raise RecordingError(f"{path}: choose a variable with --variable; it holds {keys}")
            loaded = loaded[key]
            meta["variable"] = key
        x = _one_channel(_real_samples(loaded, path), channel, path, meta)
    elif suffix in (*TEXT_TABLES, ".parquet", ".xlsx"):
        info = None  # a cmtool simulate file's metadata: rate, speed, bearing, SI units
        layout = None
        if suffix in TEXT_TABLES:
            frame, layout = _read_csv_table(path)
            info = _csv_sidecar(path)
        elif suffix == ".xlsx":  # a workbook's first sheet, read as a CSV table is
            frame, layout = read_excel_table(path)
        else:
            frame = pd.read_parquet(path)
            if "signal" in frame.columns and frame["signal"].dtype == object:
                raise RecordingError(
                    f"{path}: a cmtool dataset's file ({len(frame)} signals in its 'signal' "
                    "column), not a recording: `cmtool bench DATASET` and `cmtool evaluate "
                    "MODEL DATASET` score a dataset's signals"
                )
            stored = pq.read_schema(path).metadata or {}
            if b"cmtool" in stored:
                info = json.loads(stored[b"cmtool"])
        simulated = info is not None
        if simulated:
            meta["fs_hz"] = float(info["fs_hz"])
            params = info.get("parameters", {})
            shaft = params.get("operating", {}).get("shaft_frequency")
            if shaft is not None:
                meta["rpm"] = 60.0 * float(shaft)
            name = params.get("bearing", {}).get("name")
            if name:
                meta["bearing"] = str(name)
            load = params.get("operating", {}).get("radial_load")
            if load is not None:
                meta["load_n"] = float(load)
        time_cols = [c for c in frame.columns if str(c).lower() in ("time", "t", "time_s")]
        numeric = [
            c
            for c in frame.columns
            if pd.api.types.is_numeric_dtype(frame[c]) and c not in time_cols
        ]
        if not time_cols and len(numeric) >= 2:
            first = frame[numeric[0]].to_numpy(dtype=float)
            if first[0] in (0.0, 1.0) and np.array_equal(np.diff(first), np.ones(first.size - 1)):
                numeric = numeric[1:]  # a row index or sample number (pandas' to_csv): no time
            elif time_axis_rate(first) is not None:  # a first column rising in equal steps: time
                time_cols, numeric = [numeric[0]], numeric[1:]
        if "housing_acceleration_y" in numeric and channel is None:
            channel = "housing_acceleration_y"  # what an accelerometer on the housing sees
        if not numeric:
            raise RecordingError(f"{path}: no numeric column")
        if channel is None or isinstance(channel, int) or str(channel).isdigit():
            col = numeric[_pick(len(numeric), channel, path)]
            meta["channels"] = len(numeric)
        else:
            if channel not in frame.columns:
                raise RecordingError(
                    f"{path}: column {channel!r} not found; it has {list(frame.columns)}"
                )
            col = channel
        x = frame[col].to_numpy(dtype=float)
        meta["variable"] = str(col)
        if simulated and "_acceleration_" in str(col):
            meta["unit"] = "m/s^2"  # a cmtool simulate file: channels in SI units
        elif layout is not None and layout.vibration_unit(str(col)):
            meta["unit"] = layout.vibration_unit(str(col))  # the file's units row
        elif not simulated and unit_in_name(str(col)):
            meta["unit"] = unit_in_name(str(col))  # the column's name: "acc [g]"
        if time_cols and len(frame) > 2 and "fs_hz" not in meta:
            name, unit = str(time_cols[0]), None
            if layout is not None and layout.units is not None:  # the units row's, first
                unit = layout.units[layout.columns.index(name)]
            times = frame[time_cols[0]].to_numpy(dtype=float) * time_unit_size(name, unit)
            rate, said = time_axis_rate(times), []
            step = float(np.median(np.diff(times)))
            if rate is None and not (math.isfinite(step) and step > 0):  # --fs gives it
                said = [
                    f"{path.name}: column {name!r} is no time axis (its median step is "
                    f"{step:g} s; a time axis rises, and Excel keeps time stamps to the "
                    "millisecond): the rate is not read from it"
                ]
            elif rate is None:  # gaps or jumps back in the record: said, the rate between
                rate, said = spliced_time_axis(times, step, f"{path.name}: {name!r}")
            if said:
                meta.setdefault("warnings", []).extend(said)
            if rate is not None:
                meta["fs_hz"] = rate
    else:
        raise RecordingError(
            f"{path}: unknown format {suffix!r} (mat, csv, txt, tsv, wav, npy, npz, parquet, "
            "tdms, uff, unv, xlsx)"
        )
    return x
