"""Reading and writing signals: simulated results to parquet/CSV, measured recordings in.

Signals are written with a ``time`` column [s] and one column per channel named
``<body>_<quantity>_<axis>`` in SI units; the run's parameters, sample rate and characteristic
frequencies go into the parquet key-value metadata (key ``cmtool``) or a JSON sidecar for CSV.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from generators import SimulationResult

from . import __version__

__all__ = ["write_signal", "read_signal", "atomic_write", "to_jsonable"]

SIGNAL_SCHEMA_VERSION = 1


def to_jsonable(obj: Any) -> Any:
    """Convert numpy scalars/arrays and nested containers to JSON-serialisable values."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj


def atomic_write(path: Path, write) -> None:
    """Call ``write(tmp_path)`` then rename the temporary file onto ``path`` (atomic on POSIX)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        write(Path(tmp))
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def signal_metadata(result: SimulationResult) -> dict[str, Any]:
    """Metadata stored with a simulated signal."""
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


def write_signal(result: SimulationResult, path: str | os.PathLike) -> Path:
    """Write a simulated signal to ``.parquet`` or ``.csv`` (with a ``.json`` sidecar).

    Parameters
    ----------
    result : SimulationResult
        Output of :func:`generators.simulate`.
    path : str or PathLike
        Destination; the suffix selects the format.

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    frame = result.to_frame()
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


def read_signal(path: str | os.PathLike) -> tuple[pd.DataFrame, dict[str, Any]]:
    """Read a signal written by :func:`write_signal`: ``(frame, metadata)``."""
    path = Path(path)
    if path.suffix.lower() == ".parquet":
        table = pq.read_table(path)
        raw = (table.schema.metadata or {}).get(b"cmtool", b"{}")
        return table.to_pandas(), json.loads(raw)
    frame = pd.read_csv(path)
    sidecar = path.with_suffix(path.suffix + ".json")
    meta = json.loads(sidecar.read_text()) if sidecar.exists() else {}
    return frame, meta
