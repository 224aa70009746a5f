"""``cmtool generate``: write a labelled synthetic dataset from a recipe, locally or on Dask.

Layout of a dataset folder::

    recipe.toml                  the recipe, as given
    data/part-00000.parquet      one file per chunk of cases: metadata columns + ``signal``
    failures/part-00000.parquet  cases whose simulation diverged, with the reason
    _dataset.json                written last: counts, recipe hash, cmtool version

A chunk's data file is written atomically (temporary file, then rename) after its failures
file, so its presence means the chunk is complete: ``--resume`` skips those chunks and an
interrupted run ends with every signal exactly once. Signals depend only on the recipe and the
case index, so the files are identical whatever the number of workers or the finishing order.
``data/`` is a plain directory of parquet files that pandas, pyarrow, DuckDB, Spark and Dask
read directly; ``operating_point_id`` groups cases for leakage-free splits.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import os
import queue
import threading
import tomllib
import warnings
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from generators import OperatingRangeWarning
from generators.cases import CASE_COLUMNS, Case, case_count, column_kind, iter_cases
from generators.content import RecordContentWarning
from generators.recipe import recipe_content_warnings, recipe_rating_warnings, validate_recipe
from generators.synthesis import GENERATOR_REVISION, bound_steps, generate_cases

from . import __version__
from .inputs import checked_workers
from .io import atomic_write, json_text, to_jsonable

__all__ = [
    "load_recipe",
    "generate_dataset",
    "read_dataset",
    "dataset_info",
    "DATASET_SCHEMA_VERSION",
    "DatasetError",
]

#: The metadata columns' version (``generators.cases.CaseRecord``): 6 added ``cage_slip``, 7
#: ``film_entrainment_factor``.
DATASET_SCHEMA_VERSION = 7

#: Arrow type per storage kind of a metadata column (``generators.cases.CaseRecord``).
_ARROW = {
    "text": pa.string(),
    "bool": pa.bool_(),
    "int": pa.int64(),
    "uint": pa.uint64(),
    "float": pa.float64(),
}
_TYPES = {c: _ARROW[column_kind(c)] for c in CASE_COLUMNS}
DATA_SCHEMA = pa.schema(
    [pa.field(c, _TYPES[c]) for c in CASE_COLUMNS] + [pa.field("signal", pa.list_(pa.float32()))]
)
FAILURE_SCHEMA = pa.schema(
    [pa.field(c, _TYPES[c]) for c in CASE_COLUMNS] + [pa.field("error", pa.string())]
)


class DatasetError(ValueError):
    """A dataset folder or recipe cannot be used as asked."""


def load_recipe(path: str | os.PathLike) -> tuple[dict, str]:
    """Read and validate a TOML recipe: ``(normalised recipe, raw text)``.

    Parameters
    ----------
    path : path-like
        The recipe's TOML file.

    Returns
    -------
    recipe : dict
        The recipe validated and normalised (``generators.recipe.validate_recipe``).
    text : str
        Its text as read (stored with the dataset).

    Raises
    ------
    DatasetError
        When the file is missing or not valid TOML; ``generators.ParameterError`` when a key
        or value is not allowed (naming it and its range).
    """
    path = Path(path)
    if not path.is_file():
        raise DatasetError(f"recipe {path}: no such file")
    text = path.read_text()
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DatasetError(f"recipe {path}: not valid TOML ({exc})") from None
    return validate_recipe(raw), text


_THREAD_STATE = threading.local()  # per worker thread: its lane blocks' output buffers


def run_chunk(recipe: dict, cases: list[Case]) -> list[dict]:
    """Generate the rows of one chunk (a Dask task: the client writes them).

    Parameters
    ----------
    recipe : dict
        The validated recipe (:func:`load_recipe`).
    cases : list of generators.cases.Case
        The chunk's cases.

    Returns
    -------
    list of dict
        One row per case (the dataset's columns; failed cases flagged).
    """
    return generate_cases(recipe, cases)


def run_and_write_chunk(
    recipe: dict, cases: list[Case], out: Path, chunk: int, recipe_text: str
) -> tuple[int, int]:
    """Generate one chunk and write its files (a local worker: no rows sent back).

    Parameters
    ----------
    recipe : dict
        The validated recipe (:func:`load_recipe`).
    cases : list of generators.cases.Case
        The chunk's cases.
    out : pathlib.Path
        The dataset folder.
    chunk : int
        The chunk's number (names its parquet files).
    recipe_text : str
        The recipe's text, stored in the files' metadata.

    Returns
    -------
    written, failed : int
        The counts of signals written and of cases that failed (diverged).
    """
    # float64 rows that view this thread's output buffers (reused chunk after chunk: the rows
    # are written before the thread takes its next chunk); _table rounds them to float32
    workspace = getattr(_THREAD_STATE, "workspace", None)
    if workspace is None:
        workspace = _THREAD_STATE.workspace = []
    rows = generate_cases(recipe, cases, signal_dtype=np.float64, workspace=workspace)
    return _write_chunk(out, chunk, rows, recipe_text)


def _table(rows: list[dict], schema: pa.Schema) -> pa.Table:
    columns = {}
    for field in schema:
        values = [row[field.name] for row in rows]
        if field.name == "signal":
            offsets = np.zeros(len(values) + 1, dtype=np.int32)
            np.cumsum([len(v) for v in values], out=offsets[1:])
            flat = np.empty(offsets[-1], dtype=np.float32)
            for start, stop, v in zip(offsets[:-1], offsets[1:], values, strict=True):
                flat[start:stop] = v  # rounded to float32 in the copy
            columns["signal"] = pa.ListArray.from_arrays(pa.array(offsets), pa.array(flat))
        else:
            columns[field.name] = pa.array(values, type=field.type)
    return pa.table(columns, schema=schema)


def _file_metadata(recipe_text: str) -> dict[bytes, bytes]:
    return {
        b"cmtool_version": __version__.encode(),
        b"schema_version": str(DATASET_SCHEMA_VERSION).encode(),
        b"generator_revision": str(GENERATOR_REVISION).encode(),
        b"recipe": recipe_text.encode(),
    }


def _write_chunk(out: Path, chunk: int, rows: list[dict], recipe_text: str) -> tuple[int, int]:
    good = [r for r in rows if r.get("error") is None]
    bad = [r for r in rows if r.get("error") is not None]
    meta = _file_metadata(recipe_text)
    name = f"part-{chunk:05d}.parquet"
    if bad:
        table = _table(bad, FAILURE_SCHEMA).replace_schema_metadata(meta)
        atomic_write(out / "failures" / name, lambda tmp: pq.write_table(table, tmp))
    table = _table(good, DATA_SCHEMA).replace_schema_metadata(meta)
    # the samples without dictionary, compression or statistics: noise-like floats never
    # repeat (pyarrow's abandoned dictionary attempt would leave a 50 % larger file), snappy
    # does not shrink them (measured: same size), and min/max of the samples filter nothing
    # (10-15 % faster writes); the metadata columns keep all three. Batches of 1 M values
    # instead of 1024: a quarter less time in the writer's level encoding of the list.
    metadata_columns = [n for n in table.column_names if n != "signal"]
    atomic_write(
        out / "data" / name,
        lambda tmp: pq.write_table(
            table,
            tmp,
            use_dictionary=metadata_columns,
            write_statistics=metadata_columns,
            compression={**dict.fromkeys(metadata_columns, "snappy"), "signal": "none"},
            write_batch_size=1 << 20,
        ),
    )
    return len(good), len(bad)


def _remove_stale_temporaries(out: Path) -> None:
    """Delete the temporary files a killed run left in the middle of a write.

    ``atomic_write``'s hidden ``.NAME.XXXX.tmp``: readers never see them (pyarrow and Spark
    skip names starting with a dot), but each holds up to a part's worth of disk.
    """
    for folder in (out, out / "data", out / "failures"):
        if folder.is_dir():
            for tmp in folder.glob(".*.tmp"):
                tmp.unlink(missing_ok=True)


def _written_versions(out: Path) -> tuple[int, int] | None:
    """Dataset schema version and generator revision of the first data file in ``out``.

    None when there is no file yet; a file without a generator revision is of revision 1
    (written before stop 46).
    """
    for part in sorted((out / "data").glob("[!.]*.parquet")):
        if _readable(part):  # an unreadable part is generated again (_ChunkFeed)
            meta = pq.read_schema(part).metadata or {}
            version = int(meta.get(b"schema_version", b"0"))
            return version, int(meta.get(b"generator_revision", b"1"))
    return None


def _readable(part: Path) -> bool:
    """Whether a parquet file's footer reads (a cut or overwritten file's does not)."""
    try:
        pq.read_metadata(part)
    except (ValueError, OSError):  # pyarrow's ArrowInvalid is a ValueError
        return False
    return True


def _recipe_hash(recipe: dict) -> str:
    return hashlib.sha256(json.dumps(to_jsonable(recipe), sort_keys=True).encode()).hexdigest()


def generate_dataset(
    recipe_path: str | os.PathLike,
    out: str | os.PathLike,
    *,
    workers: int = 1,
    resume: bool = False,
    scheduler: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, Any]:
    """Generate the dataset of a recipe into ``out`` (see the module docstring).

    Parameters
    ----------
    recipe_path : path
        TOML recipe.
    out : path
        Dataset folder (created).
    workers : int
        Local worker threads, at least 1 (1: no extra thread).
    resume : bool
        Continue an interrupted run in ``out`` (same recipe required).
    scheduler : str, optional
        Address of a Dask distributed scheduler; the chunks run on its workers.
    progress : callable, optional
        ``progress(signals_done, signals_total)`` after each chunk.

    Returns
    -------
    dict
        Summary: counts of signals written, failed and skipped (already present).
    """
    workers = checked_workers(workers)
    recipe, text = load_recipe(recipe_path)
    for message in recipe_rating_warnings(recipe):  # once, not per case
        warnings.warn(message, OperatingRangeWarning, stacklevel=2)
    for message in recipe_content_warnings(recipe):
        warnings.warn(message, RecordContentWarning, stacklevel=2)
    out = Path(out)
    digest = _recipe_hash(recipe)
    stamp = out / "recipe.toml"
    if out.exists() and any(out.iterdir()):
        if not resume:
            raise DatasetError(
                f"out = {str(out)!r} is not empty; use --resume to continue "
                "an interrupted run or choose a new folder"
            )
        if stamp.is_file():
            old = validate_recipe(tomllib.loads(stamp.read_text()))
            if _recipe_hash(old) != digest:
                raise DatasetError(
                    f"out = {str(out)!r} was made from a different recipe; cannot resume"
                )
        written = _written_versions(out)
        if written is not None and written[0] != DATASET_SCHEMA_VERSION:
            raise DatasetError(
                f"out = {str(out)!r} holds files of dataset schema version {written[0]} and "
                f"this cmtool writes version {DATASET_SCHEMA_VERSION} (other columns); cannot "
                "resume: generate into a new folder"
            )
        if written is not None and written[1] != GENERATOR_REVISION:
            raise DatasetError(
                f"out = {str(out)!r} holds signals of generator revision {written[1]} and this "
                f"cmtool generates revision {GENERATOR_REVISION} (the same cases give other "
                "signals; generators.synthesis.GENERATOR_REVISION); cannot resume: generate "
                "into a new folder"
            )
    if scheduler:
        _check_scheduler(scheduler)  # before anything is written: a typo leaves no folder
    out.mkdir(parents=True, exist_ok=True)
    if resume:
        _remove_stale_temporaries(out)
    atomic_write(stamp, lambda tmp: tmp.write_text(text))
    steps: list[dict] = []
    if recipe["model"].get("error_bound") is not None:
        # one step per bearing, rate and condition, from pilots of its stiffest case
        groups = bound_steps(recipe, iter_cases(recipe))
        recipe["model"]["group_steps"] = groups
        steps = [
            {"bearing": b, "fs_hz": fs, "label": label, "step_s": h, "error_estimate": e}
            for (b, fs, label), (h, e) in groups.items()
        ]
    total = case_count(recipe)
    feed = _ChunkFeed(recipe, out)
    done, written, failed = 0, 0, 0
    if progress:
        progress(done, total)
    for counts in _run(recipe, feed, out, text, workers=workers, scheduler=scheduler):
        written += counts[0]
        failed += counts[1]
        done = feed.skipped + written + failed
        if progress:
            progress(done, total)
    if progress and done < total:  # trailing chunks already present
        progress(total, total)
    summary = {
        "name": recipe["name"],
        "signals": total,
        "written": written,
        "failed": failed,
        "skipped_existing": feed.skipped,
        "recipe_sha256": digest,
        "cmtool_version": __version__,
        "schema_version": DATASET_SCHEMA_VERSION,
        "generator_revision": GENERATOR_REVISION,
        "chunks": feed.chunks,
        **({"error_bound_steps": steps} if steps else {}),
    }
    text = json_text(summary)
    atomic_write(out / "_dataset.json", lambda tmp: tmp.write_text(text))
    return summary


def _check_scheduler(scheduler: str) -> None:
    """Connect to a Dask scheduler once, or raise a DatasetError naming its address.

    A bare connection (``distributed.comm.connect``), not a ``Client``: a Client that fails
    to connect stays dask's default client, and every later ``compute()`` in the process
    waits for it. The connection is made in a thread of its own, which works where an event
    loop already runs (a notebook).
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    import dask
    from distributed.comm import connect

    async def probe() -> None:
        timeout = dask.config.get("distributed.comm.timeouts.connect")
        comm = await connect(scheduler, timeout=timeout)
        await comm.close()

    try:
        with ThreadPoolExecutor(1) as thread:
            thread.submit(asyncio.run, probe()).result()
    except (OSError, ValueError, TypeError) as error:  # unreachable; a malformed address
        raise DatasetError(
            f"scheduler = {scheduler!r}: cannot connect ({error}); start one with "
            "`dask scheduler` and give its address, tcp://HOST:8786"
        ) from error


class _ChunkFeed:
    """The chunks still to generate, in order, each expanded when a worker asks for it.

    Cases are drawn one chunk at a time (:func:`generators.cases.iter_cases`, under a
    lock: the draws and ``operating_point_id`` follow the case order), so the first chunk
    starts at once and the drawing of the rest overlaps the simulations instead of delaying
    them. Chunks whose data file exists (an earlier, interrupted run) are counted in
    ``skipped`` and not returned. ``stop()`` makes ``take()`` return None from then on.
    """

    def __init__(self, recipe: dict, out: Path) -> None:
        self._cases = iter_cases(recipe)
        self._size = recipe["chunk_size"]
        self._data = out / "data"
        self._lock = threading.Lock()
        self._stopped = False
        self.chunks = 0  # chunks expanded so far (all of them once take() returned None)
        self.skipped = 0  # signals of chunks already present

    def take(self) -> tuple[int, list[Case]] | None:
        """The next chunk to generate, ``(chunk index, cases)``, or None when done."""
        with self._lock:
            while not self._stopped:
                cases = list(itertools.islice(self._cases, self._size))
                if not cases:
                    return None
                chunk = self.chunks
                self.chunks += 1
                part = self._data / f"part-{chunk:05d}.parquet"
                if part.is_file():
                    if _readable(part):
                        self.skipped += len(cases)
                        continue
                    aside = part.with_name(f".{part.name}.unreadable")
                    part.replace(aside)  # kept, out of the dataset, and generated again
                    warnings.warn(
                        f"{part}: unreadable (cut or overwritten); moved to {aside.name} and "
                        "generated again",
                        stacklevel=2,
                    )
                return chunk, cases
            return None

    def stop(self) -> None:
        """Hand out no more chunks (Ctrl-C or a worker's error)."""
        with self._lock:
            self._stopped = True

    def __iter__(self) -> Iterator[tuple[int, list[Case]]]:
        while (item := self.take()) is not None:
            yield item


def _run(
    recipe: dict,
    feed: _ChunkFeed,
    out: Path,
    recipe_text: str,
    *,
    workers: int,
    scheduler: str | None,
) -> Iterable[tuple[int, int]]:
    """Generate and write the chunks of ``feed``; yield (written, failed) per chunk as done.

    Local workers are threads of this process: the simulation kernels and the parquet writer
    release the GIL (only the per-case set-up, a fraction of a millisecond, is Python), so
    threads use every core without starting and importing a process per worker or sending
    signals between processes. Each takes its next chunk from ``feed`` when it is free and
    writes the chunk's files itself. Dask workers return the rows and this process writes
    them (the cluster's workers need not share this file system).
    """
    if scheduler:
        todo = list(feed)
        if not todo:
            return
        from dask.distributed import Client
        from dask.distributed import as_completed as dask_completed

        with Client(scheduler) as client:
            futures = {
                client.submit(run_chunk, recipe, cs, pure=False, retries=3): c for c, cs in todo
            }
            for fut in dask_completed(futures):
                yield _write_chunk(out, futures[fut], fut.result(), recipe_text)
        return
    if workers <= 1:
        try:
            for c, cs in feed:
                yield run_and_write_chunk(recipe, cs, out, c, recipe_text)
        finally:
            _THREAD_STATE.workspace = None  # this (calling) thread lives on: free its buffers
        return
    results: queue.SimpleQueue = queue.SimpleQueue()

    def work() -> None:
        try:
            while (item := feed.take()) is not None:
                c, cs = item
                results.put(("done", run_and_write_chunk(recipe, cs, out, c, recipe_text)))
        except BaseException as exc:  # reported to the caller, which stops the others
            feed.stop()
            results.put(("error", exc))
        finally:
            results.put(("exit", None))

    pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="cmtool-generate")
    try:
        for _ in range(workers):
            pool.submit(work)
        running = workers
        while running:
            kind, value = results.get()
            if kind == "exit":
                running -= 1
            elif kind == "error":
                raise value
            else:
                yield value
    finally:
        # Ctrl-C or an error: finish the chunks being written, start no new one
        feed.stop()
        pool.shutdown(wait=True)


def dataset_complete(path: str | os.PathLike) -> bool:
    """Whether a dataset folder's generation finished (its ``_dataset.json`` was written).

    ``path`` may be the dataset folder or its ``data/`` folder. A folder of parquet files that
    ``cmtool generate`` did not make (no ``recipe.toml``) counts as complete; a folder that
    does not exist, or holds no parquet file, does not.

    Parameters
    ----------
    path : path-like
        The dataset folder or its ``data/`` folder.

    Returns
    -------
    bool
    """
    path = Path(path)
    root = path.parent if path.name == "data" and not (path / "data").is_dir() else path
    if (root / "_dataset.json").is_file():
        return True
    if (root / "recipe.toml").is_file():
        return False
    return any(root.glob("*.parquet")) or any((root / "data").glob("*.parquet"))


def read_dataset(
    path: str | os.PathLike,
    *,
    columns: list[str] | None = None,
    allow_incomplete: bool = False,
) -> pd.DataFrame:
    """Read the signals of a dataset folder (``data/``) as a DataFrame sorted by index.

    An interrupted ``cmtool generate`` (no ``_dataset.json``) is refused unless
    ``allow_incomplete``: some classes or operating points may be missing from it.

    Parameters
    ----------
    path : path-like
        The dataset folder (or any folder with a ``data/`` folder of parquet files).
    columns : list of str, optional
        Only these columns (default all: ``signal`` [SI unit of the recipe's channel],
        ``label``, ``fs_hz``, ``rpm``, the characteristic frequencies [Hz], the drawn
        parameters and the fault SNR [dB]).
    allow_incomplete : bool
        Read a dataset whose generation did not finish.

    Returns
    -------
    pandas.DataFrame
        One row per signal, sorted by its ``index``.

    Raises
    ------
    DatasetError
        When there is no data, a part is unreadable, a column asked for is missing, or the
        dataset is incomplete and ``allow_incomplete`` is False.
    """
    path = Path(path)
    data = path / "data" if (path / "data").is_dir() else path
    if not data.is_dir() or not any(data.glob("*.parquet")):
        raise DatasetError(f"{path}: no data/*.parquet files")
    if not allow_incomplete and not dataset_complete(path):
        raise DatasetError(
            f"{path}: generation did not finish (no _dataset.json; some classes or operating "
            "points may be missing): finish it with `cmtool generate RECIPE --out "
            f"{path} --resume`, or pass --allow-incomplete to use it as it is"
        )
    try:
        table = pq.read_table(data, columns=columns)
    except (ValueError, OSError) as error:  # pyarrow's ArrowInvalid is a ValueError
        bad = [p.name for p in sorted(data.glob("[!.]*.parquet")) if not _readable(p)]
        if not bad and columns is not None:
            present = set(pq.read_schema(next(data.glob("[!.]*.parquet"))).names)
            missing = [c for c in columns if c not in present]
            if missing:
                raise DatasetError(
                    f"{path}: its signals have no column {', '.join(map(repr, missing))} "
                    "(`cmtool generate` writes every one)"
                ) from error
        if not bad:
            raise
        raise DatasetError(
            f"{path}: {', '.join(bad)} unreadable (cut or overwritten): `cmtool generate "
            f"{path / 'recipe.toml'} --out {path} --resume` generates "
            f"{'it' if len(bad) == 1 else 'them'} again"
        ) from error
    frame = table.to_pandas()
    if "index" in frame.columns:
        frame = frame.sort_values("index").reset_index(drop=True)
    return frame


#: Columns whose range ``dataset info`` prints when the dataset varies them, in this order:
#: the operating point, the bearing's state, the rig, the fault, the chain and the record.
_RANGE_COLUMNS = (
    "rpm",
    "radial_load_n",
    "load_angle_rad",
    "radial_internal_clearance_m",
    "random_slip",
    "ball_jitter_rad",
    "cage_slip",
    "shaft_mass_kg",
    "housing_mass_kg",
    "pedestal_stiffness_n_m",
    "film_entrainment_factor",
    "housing_damping_ratio",
    "shaft_damping_ratio",
    "inner_form_waviness_m",
    "outer_form_waviness_m",
    "ball_form_waviness_m",
    "waviness_order",
    "waviness_amplitude_m",
    "defect_length_m",
    "defect_depth_m",
    "defect_position_rad",
    "fault_snr_db",
    "background_db",
    "snr_db",
    "resonance_hz",
    "fs_hz",
    "duration_s",
)
#: Columns that describe a fault: their range is over the faulty signals, and a column that is
#: 0 for every one of them (a dataset without waviness, say) is not printed.
_FAULT_COLUMNS = ("waviness", "defect", "fault_snr")
#: Angles round the bearing [rad]: shown wrapped to -pi .. pi (a pit drawn relative to the
#: load's direction is stored unwrapped: -4.4 .. 6.4 rad on the CWRU-rig recipe).
_ANGLE_COLUMNS = ("load_angle_rad", "defect_position_rad")


def dataset_info(path: str | os.PathLike) -> str:
    """Counts per label and parameter ranges of a dataset, as text.

    Parameters
    ----------
    path : path-like
        The dataset folder.

    Returns
    -------
    str
        What ``cmtool dataset info`` prints: counts per label, the range of each parameter
        the recipe varies, those it fixes, and how many faults reach the fault SNR that
        ``cmtool train`` keeps.
    """
    path = Path(path)
    present = (
        set(pq.read_schema(next((path / "data").glob("*.parquet"))).names)
        if (path / "data").is_dir() and any((path / "data").glob("*.parquet"))
        else set(_RANGE_COLUMNS)
    )
    ranged = [c for c in _RANGE_COLUMNS if c in present]
    frame = read_dataset(
        path,
        columns=["label", "bearing", *ranged, "operating_point_id"],
        allow_incomplete=True,
    )
    lines = [f"dataset {path}: {len(frame)} signals"]
    if not dataset_complete(path):
        lines[0] += (
            " -- INCOMPLETE: generation did not finish (no _dataset.json); resume it with "
            "`cmtool generate RECIPE --out DIR --resume`"
        )
    failures = path / "failures"
    if failures.is_dir() and any(failures.glob("*.parquet")):
        nfail = pq.read_table(failures, columns=["id"]).num_rows
        lines.append(f"failed simulations: {nfail} (see failures/)")
    lines.append("signals per label:")
    for label, n in frame["label"].value_counts().sort_index().items():
        lines.append(f"  {label:<16s} {n}")
    lines.append(
        f"operating points: {frame['operating_point_id'].nunique()}; bearings: "
        f"{', '.join(sorted(frame['bearing'].unique()))}"
    )
    lines.append("parameter ranges (what the dataset varies):")
    faulty = frame["label"] != "healthy"
    fixed = []
    for col in ranged:
        values = frame[col]
        if col.startswith(_FAULT_COLUMNS):
            values = values[faulty]
        values = values[np.isfinite(values)]
        if col in _ANGLE_COLUMNS:
            values = np.angle(np.exp(1j * values))
        if not len(values) or (col.startswith(_FAULT_COLUMNS) and not (values != 0).any()):
            continue
        if values.min() < values.max():
            lines.append(f"  {col:<28s} {values.min():.6g} .. {values.max():.6g}")
        else:
            fixed.append(f"{col} {values.min():.6g}")
    if fixed:
        lines.append(
            "the same in every signal (a fault's columns: in every fault): " + ", ".join(fixed)
        )
    if "fault_snr_db" in frame.columns and frame.loc[faulty, "fault_snr_db"].notna().any():
        lines.append(_visibility_line(frame[faulty]))
    return "\n".join(lines)


def _visibility_line(faults: pd.DataFrame) -> str:
    """How many faulty signals per label reach ``cmtool train``'s fault-SNR floor."""
    from .classifier import MIN_FAULT_SNR_DB

    snr = faults["fault_snr_db"]
    kept = ~(snr < MIN_FAULT_SNR_DB)  # as classifier.visible_faults: no SNR (NaN) is kept
    parts = [
        f"{label} {int(kept[faults['label'] == label].sum())}/"
        f"{int((faults['label'] == label).sum())}"
        for label in sorted(faults["label"].unique())
    ]
    unmet = int(np.isneginf(snr).sum())
    return (
        f"faults at a fault SNR of {MIN_FAULT_SNR_DB:g} dB or more (what cmtool train keeps): "
        + ", ".join(parts)
        + (f"; {unmet} never met by the races (fault SNR -inf)" if unmet else "")
    )
