"""``cmtool diagnose``, ``realism``, ``bench`` and ``demo``: signals judged."""

from __future__ import annotations

import argparse
import logging
import math
import sys
from pathlib import Path

from generators import (
    BEARINGS,
)
from generators.params import check_shaft_speed_rpm

from .common import CliError, StageBars, check_output_folder, progress_bar
from .data import check_training_overlap

logger = logging.getLogger("cmtool")


def cmd_diagnose(args: argparse.Namespace) -> int:
    """Diagnose a recording (or each recording a folder's MANIFEST.csv lists).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool diagnose`` (``cmtool diagnose --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    from ..speeds import differs_from_file, tacho_speed
    from ..waviness import check_load_n

    check_output_folder("--report", args.report, "a folder for report.md")
    if args.load is not None:
        check_load_n(args.load, "--load")  # refused before any work
    if Path(args.recording).is_dir():
        if getattr(args, "tacho", None) is not None:
            raise CliError(
                "--tacho reads one recording's speed; a folder's MANIFEST.csv names each "
                "recording's tacho_channel (and pulses_per_rev, order_track)"
            )
        return _diagnose_folder(args)
    from ..io import read_recording

    x, meta = read_recording(args.recording, variable=args.variable, channel=args.channel)
    warnings = list(meta.get("warnings", []))  # the reader's (a cut WAV file)
    channels = meta.get("channels", 1)
    channel = str(meta.get("variable") or args.channel or "first")
    if channels > 1 and args.channel is None:  # the first picked for the user: say so
        channel = str(meta.get("variable") or f"0 (the first of {channels})")
        warnings.append(
            f"{Path(args.recording).name} holds {channels} channels; channel {channel} was "
            "diagnosed (--channel N for another)"
        )
    fs = args.fs if args.fs is not None else meta.get("fs_hz")
    if fs is None:  # why a time column gave none, if one did not
        why = "".join(f" ({w})" for w in warnings if "is no time axis" in w)
        raise CliError(f"{args.recording}: the file holds no sample rate; give --fs{why}")
    rpm = check_shaft_speed_rpm("--rpm", args.rpm) if args.rpm is not None else meta.get("rpm")
    tacho = None
    if getattr(args, "order_track", False) and getattr(args, "tacho", None) is None:
        raise CliError("--order-track needs --tacho (the shaft's angle comes from its pulses)")
    if getattr(args, "tacho", None) is not None:
        rpm, tacho, said, x = tacho_speed(
            args.recording,
            args.variable,
            args.tacho,
            args.pulses_per_rev,
            args.order_track,
            x,
            float(fs),
            rpm,
            "--rpm" if args.rpm is not None else "the file's",
        )
        warnings += said
    else:
        warnings += differs_from_file(meta, args.fs, args.rpm, "--fs", "--rpm")
    if rpm is None:
        raise CliError(f"{args.recording}: the file holds no shaft speed; give --rpm or --tacho")
    geometry = None
    if args.geometry:
        from .specs import parse_geometry

        geometry = parse_geometry(args.geometry)
    name = args.bearing or (geometry.name if geometry is not None else meta.get("bearing"))
    if name is None:
        raise CliError(
            f"{args.recording}: the file does not say which bearing it is; give --bearing "
            f"(one of {', '.join(sorted(BEARINGS))}) or --geometry"
        )
    if (args.bearing or geometry) and meta.get("bearing") and name != meta["bearing"]:
        given = f"--bearing {args.bearing}" if args.bearing else f"--geometry {name}"
        warnings.append(f"{given} differs from the file's {meta['bearing']}")
    load, load_said = _load_from_file(args.load, meta.get("load_n"))
    warnings += load_said
    model = _model(args)
    baseline = baseline_fs = None
    if args.baseline:
        from ..diagnose import check_clipping

        baseline, base_meta = read_recording(
            args.baseline, variable=args.variable, channel=args.channel
        )
        baseline_fs = base_meta.get("fs_hz", float(fs))
        if not args.allow_clipping:
            check_clipping(baseline, f"--baseline {args.baseline}")
    diagnosis = _diagnose_one(
        args,
        x,
        float(fs),
        float(rpm),
        geometry if geometry is not None else name,
        model,
        file=Path(args.recording).name,
        channel=channel,
        source=str(args.recording),
        unit=args.unit or meta.get("unit"),
        baseline=baseline,
        baseline_fs=baseline_fs,
        warnings=warnings,
        tacho=tacho is not None,
        load_n=load,
    )
    if args.load is None and load is not None:
        diagnosis.assumptions["load_n"] = (
            f"{load:g} N, the file's (the radial load it was simulated at)"
        )
    if tacho is not None:
        diagnosis.assumptions["speed_measured"] = tacho
    if args.report:
        report = _write_report(diagnosis, Path(args.report), x, float(fs))
        if not args.json:
            print(f"wrote {report}")
    if args.json:
        from ..io import json_text

        print(json_text(diagnosis.to_dict()))
    else:
        from .diagnosis_text import print_diagnosis

        print_diagnosis(diagnosis)
    return 0


def _model(args: argparse.Namespace):
    """The ``--model`` bundle, or None."""
    if not args.model:
        return None
    from ..classifier import load_model

    return load_model(args.model)


def _load_from_file(given: float | None, held: float | None) -> tuple[float | None, list[str]]:
    """The radial load the waviness prediction takes, and a warning where two disagree.

    ``--load`` (``given``), else the file's (``held``: a ``cmtool simulate`` file holds the
    load it was simulated at).
    """
    from generators import ParameterError

    from ..speeds import GIVEN_AGAINST_FILE
    from ..waviness import check_load_n

    if held is None:
        return given, []
    if given is not None:
        if abs(held - given) > GIVEN_AGAINST_FILE * given:
            return given, [f"--load {given:g} N differs from the file's {held:g} N; using --load"]
        return given, []
    try:
        return check_load_n(held, "the file's radial load"), []
    except ParameterError as error:
        return None, [f"{error}: the waviness prediction assumes its default load"]


def _diagnose_one(
    args: argparse.Namespace,
    x,
    fs: float,
    rpm: float,
    bearing,
    model,
    *,
    file: str,
    channel: str,
    source: str,
    unit: str | None = None,
    baseline=None,
    baseline_fs: float | None = None,
    warnings: list[str] | None = None,
    tacho: bool = False,
    load_n: float | None = None,
    machine_class=None,
):
    """One recording's diagnosis, its assumptions completed (clipping refused first).

    ``file``: the name the output shows; ``source``: the path clipping errors name;
    ``tacho``: the speed is a tachometer's (``--speed-source`` then defaults to given);
    ``machine_class``: the manifest's, else ``--machine-class`` or ``--zone-limits``.
    """
    from ..diagnose import check_clipping, diagnose_signal

    if not args.allow_clipping:
        check_clipping(x, source)
    diagnosis = diagnose_signal(
        x,
        fs,
        rpm,
        bearing,
        model=model,
        baseline=baseline,
        baseline_fs=baseline_fs,
        load_n=args.load if load_n is None else load_n,
        unit=unit,
        speed_source=args.speed_source or ("given" if tacho else "auto"),
        machine_class=machine_class
        or getattr(args, "machine_class", None)
        or getattr(args, "zone_limits", None),
    )
    diagnosis.warnings = list(warnings or []) + diagnosis.warnings
    diagnosis.assumptions["channel"] = channel
    diagnosis.assumptions["file"] = file
    if not isinstance(bearing, str):
        diagnosis.assumptions["bearing_geometry"] = (
            f"given: {bearing.ball_count} balls, ball diameter {bearing.ball_diameter:g} m, "
            f"pitch diameter {bearing.pitch_diameter:g} m, contact angle "
            f"{math.degrees(bearing.contact_angle):g} deg (the healthy model for waviness "
            f"takes groove conformity {bearing.inner_groove_curvature:g} inner and "
            f"{bearing.outer_groove_curvature:g} outer, radial clearance "
            f"{bearing.radial_internal_clearance * 1e6:g} um, {bearing.ball_material.name} balls "
            f"and {bearing.ring_material.name} rings)"
        )
    return diagnosis


def _write_report(diagnosis, folder: Path, x, fs: float) -> Path:
    from ..diagnose import write_report

    return write_report(diagnosis, folder, title=diagnosis.assumptions["file"], x=x, fs=fs)


SPALL_COLUMNS = ("length", "low", "high")  # spall_<k>_mm: the size and its interval [mm]
#: Columns of ``verdicts.csv`` (``cmtool diagnose FOLDER --report OUT``).
VERDICT_COLUMNS = (
    "file",
    "machine",
    "time",
    "verdict",
    "confidence",
    "basis",
    "margin_db",
    "bearing",
    "rpm",
    "spectrum_rpm",
    "speed_source",
    "fs_hz",
    "band_low_hz",
    "band_high_hz",
    "outer_race_margin_db",
    "inner_race_margin_db",
    "ball_margin_db",
    "outer_race_baseline_margin_db",
    "inner_race_baseline_margin_db",
    "ball_baseline_margin_db",
    "velocity_low",
    "velocity_medium",
    "velocity_high",
    "velocity_overall",
    "velocity_unit",
    "zone",
    "zone_limits_mm_s",
    "velocity_low_change_db",
    "velocity_medium_change_db",
    "velocity_high_change_db",
    "baseline",
    "waviness_hint",
    *(f"spall_{k}_mm" for k in SPALL_COLUMNS),
    "warnings",
    "manifest_label",
    "error",
)


def _diagnose_folder(args: argparse.Namespace) -> int:
    """Every recording a folder's MANIFEST.csv lists: a line (or JSON object) each.

    The manifest gives each recording's rate, speed and bearing (and its ``baseline``, a
    healthy recording of the same machine, where it names one), so --fs, --rpm, --bearing,
    --geometry and --baseline are refused; a recording that cannot be diagnosed is reported
    in its row and the rest go on (exit code 1 if any failed). With --report, each
    recording's report goes to a folder of its own and the table to ``verdicts.csv``; where
    the manifest dates two or more recordings of a machine, ``trend.png`` (or one per
    machine) shows each fault's evidence over the threshold and the velocity bands in time.
    """
    import pandas as pd

    from ..io import atomic_write
    from ..manifest import read_manifest

    given = [
        flag
        for flag, value in (
            ("--fs", args.fs),
            ("--rpm", args.rpm),
            ("--bearing", args.bearing),
            ("--geometry", args.geometry),
            ("--baseline", args.baseline),
        )
        if value is not None
    ]
    if given:
        raise CliError(
            f"{args.recording} is a folder: its MANIFEST.csv gives each recording's rate, "
            f"speed and bearing; {', '.join(given)} cannot be given with it"
        )
    entries = read_manifest(args.recording)
    model = _model(args)
    out = Path(args.report) if args.report else None
    rows, results = [], []
    bar = progress_bar(len(entries), "diagnose", unit="recording")
    tasks = [(args, entry, out) for entry in entries]
    workers = min(getattr(args, "workers", 1) or 1, len(entries))
    if workers > 1:
        from concurrent.futures import ProcessPoolExecutor

        from features.transformer import WarningRelay

        relay = WarningRelay()  # a worker's warnings, here and once
        with ProcessPoolExecutor(
            max_workers=workers, initializer=_folder_worker, initargs=(model,)
        ) as pool:
            for (row, result), caught in pool.map(_folder_row_kept, tasks):
                relay(caught)
                rows.append(row)
                results.append(result)
                bar.update(1)
    else:
        _folder_worker(model)
        try:
            for task in tasks:
                row, result = _folder_row(task)
                rows.append(row)
                results.append(result)
                bar.update(1)
        finally:
            _FOLDER_WORKER.clear()
    bar.close()
    table = pd.DataFrame(rows, columns=list(VERDICT_COLUMNS))
    trends = []
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        atomic_write(out / "verdicts.csv", lambda tmp: table.to_csv(tmp, index=False))
        trends = _plot_trends(table, out)
        index = _index_text(table, trends, out)
        atomic_write(out / "index.md", lambda tmp: tmp.write_text(index))
    if args.json:
        from ..io import json_text

        print(json_text(results))
    else:
        for row in rows:
            if row["error"]:
                print(f"{row['file']}: not diagnosed: {row['error']}")
                continue
            speed = f"{row['rpm']:g} rpm"
            if row["speed_source"] not in (None, "given"):  # the line's speed was used
                speed = f"{row['spectrum_rpm']:g} rpm, the 1x line's ({row['rpm']:g} given)"
            print(
                f"{row['file']}: {row['verdict']} (confidence {row['confidence']:.2f}, "
                f"margin {row['margin_db']:+.1f} dB; {row['bearing']}, {speed})"
                + (f"; waviness hint: {row['waviness_hint']}" if row["waviness_hint"] else "")
                + (f"; {row['warnings'].count(' | ') + 1} warning(s)" if row["warnings"] else "")
            )
        if out is not None:
            print(f"wrote {out / 'index.md'}, {out / 'verdicts.csv'} and a report per recording")
        for path in trends:
            print(f"wrote {path}")
    return 1 if table["error"].notna().any() else 0


#: One process's model while it diagnoses a folder's recordings (set by _folder_worker).
_FOLDER_WORKER: dict = {}


def _folder_worker(model) -> None:
    _FOLDER_WORKER["model"] = model


def _folder_row_kept(task) -> tuple[tuple[dict, dict], list]:
    """:func:`_folder_row` in a worker process, with the warnings it raised."""
    from features.transformer import keeping_warnings

    return keeping_warnings(_folder_row, task)


#: The manifest's columns a folder's JSON object repeats under ``manifest``.
_MANIFEST_KEYS = ("bearing", "rpm", "fs_hz", "machine", "baseline", "manifest_label")


def _folder_row(task) -> tuple[dict, dict]:
    """One manifest entry's row of ``verdicts.csv`` and its JSON object (report written)."""
    from ..io import read_recording
    from ..speeds import differs_from_file, manifest_tacho_speed

    args, entry, out = task
    row = dict.fromkeys(VERDICT_COLUMNS)
    row.update(file=entry.file, bearing=entry.bearing, rpm=entry.rpm, fs_hz=entry.fs_hz)
    row.update(machine=entry.machine, time=entry.time)
    if entry.baseline is not None:
        row["baseline"] = entry.baseline.relative_to(Path(args.recording)).as_posix()
    row["manifest_label"] = None if entry.label == "unknown" else entry.label
    # what the manifest says of the recording, in its JSON object whether diagnosed or not
    listed = {"manifest": {k: row[k] for k in _MANIFEST_KEYS if row[k] is not None}}
    if entry.time is not None:
        listed["manifest"]["time"] = entry.time.isoformat()
    try:
        variable = entry.variable or args.variable  # the manifest's, else --variable
        x, meta = read_recording(entry.path, variable=variable, channel=args.channel)
        rpm, measured = entry.rpm, None
        if entry.tacho is not None:
            rpm, measured, said, x = manifest_tacho_speed(entry, variable, x)
            row["rpm"] = rpm
        else:
            said = differs_from_file(
                meta, entry.fs_hz, entry.rpm, "the manifest's sampling_rate_hz", "shaft_rpm"
            )
        said = list(meta.get("warnings", [])) + said  # the reader's first (a cut WAV file)
        baseline = baseline_fs = None
        if entry.baseline is not None:
            baseline, base_meta = read_recording(  # its own variable: found, or --variable
                entry.baseline, variable=args.variable, channel=args.channel
            )
            baseline_fs = base_meta.get("fs_hz", entry.fs_hz)
        diagnosis = _diagnose_one(
            args,
            x,
            entry.fs_hz,
            rpm,
            entry.bearing_or_geometry,
            _FOLDER_WORKER.get("model"),
            file=entry.file,
            channel=str(variable or meta.get("variable") or args.channel or "first"),
            source=str(entry.path),
            unit=entry.unit or args.unit or meta.get("unit"),  # the manifest's, --unit, the file's
            baseline=baseline,
            baseline_fs=baseline_fs,
            warnings=said,
            tacho=measured is not None,
            machine_class=entry.machine_class,
        )
        if measured is not None:
            diagnosis.assumptions["speed_measured"] = measured
    except (ValueError, FileNotFoundError) as error:  # this recording only
        row["error"] = str(error)
        return row, {"file": entry.file, "error": str(error), "verdict": None, **listed}
    top = diagnosis.candidates[0]
    wav, size = diagnosis.waviness, diagnosis.severity or {}
    row.update(
        verdict=diagnosis.verdict,
        confidence=diagnosis.confidence,
        basis=diagnosis.basis,
        margin_db=round(top["evidence_db"] - diagnosis.threshold_db, 2),
        spectrum_rpm=diagnosis.assumptions.get("spectrum_rpm"),
        speed_source=diagnosis.assumptions.get("speed_source"),
        band_low_hz=diagnosis.band_hz[0],
        band_high_hz=diagnosis.band_hz[1],
        waviness_hint=None if not wav else f"{wav['surface']} race order ~{wav['order']}",
        warnings=" | ".join(diagnosis.warnings) or None,
        spall_length_mm=size.get("length_mm"),  # a spall's size (docs/diagnosis.md)
    )
    row["spall_low_mm"], row["spall_high_mm"] = size.get("interval_mm") or (None, None)
    for c in diagnosis.candidates:
        row[f"{c['fault'].replace(' ', '_')}_margin_db"] = round(
            c["evidence_db"] - diagnosis.threshold_db, 2
        )
    bands = diagnosis.velocity_bands_mm_s or diagnosis.velocity_bands or {}
    for band, value in bands.items():
        row[f"velocity_{band}"] = value
    overall = diagnosis.overall_velocity or {}
    row["velocity_overall"] = overall.get("rms_mm_s" if diagnosis.velocity_bands_mm_s else "rms")
    row["velocity_unit"] = "mm/s" if diagnosis.velocity_bands_mm_s else "signal unit x s"
    zone = overall.get("zone") or {}  # where a class was given: A-D and its boundaries
    row["zone"] = zone.get("zone")
    row["zone_limits_mm_s"] = "/".join(f"{v:g}" for v in zone.get("limits_mm_s", ())) or None
    for band, change in (diagnosis.baseline or {}).get("velocity_bands_change_db", {}).items():
        row[f"velocity_{band}_change_db"] = change
    for fault, margin in (diagnosis.baseline or {}).get("baseline_fault_margin_db", {}).items():
        row[f"{fault.replace(' ', '_')}_baseline_margin_db"] = margin
    if out is not None:
        _write_report(diagnosis, out / _report_folder(entry.file), x, entry.fs_hz)
    return row, {"file": entry.file, **diagnosis.to_dict(), **listed}  # as an error's object


def _index_text(table, trends: list[Path], out: Path) -> str:
    """``index.md`` of a folder's diagnoses: a row and a report link per recording, the trends.

    A ``zone`` column (the overall velocity's, A-D) where any recording was given a class.
    """
    import pandas as pd

    def given(value) -> bool:
        return value is not None and not (pd.api.types.is_scalar(value) and pd.isna(value))

    zoned = any(given(z) for z in table["zone"])
    head = ["recording", "machine", "time", "verdict", "confidence", "margin [dB]"]
    head += ["zone", "report"] if zoned else ["report"]
    lines = [
        f"# Diagnoses: {len(table)} recordings",
        "",
        "| " + " | ".join(head) + " |",
        "|" + "---|" * len(head),
    ]

    for row in table.to_dict("records"):
        folder = _report_folder(row["file"])
        failed = given(row["error"])
        cells = [
            row["file"],
            row["machine"] if given(row["machine"]) else "",
            str(row["time"]) if given(row["time"]) else "",
            f"not diagnosed: {row['error']}" if failed else row["verdict"],
            f"{row['confidence']:.2f}" if given(row["confidence"]) else "",
            f"{row['margin_db']:+.1f}" if given(row["margin_db"]) else "",
            *([row["zone"] if given(row["zone"]) else ""] if zoned else []),
            "" if failed else f"[report]({folder}/report.md)",
        ]
        lines.append("| " + " | ".join(str(c).replace("|", "/") for c in cells) + " |")
    lines += ["", "The table with every column: [verdicts.csv](verdicts.csv).", ""]
    for path in trends:
        lines += [f"![{path.stem}]({path.relative_to(out).as_posix()})", ""]
    return "\n".join(lines)


def _plot_trends(table, out: Path) -> list[Path]:
    """``trend.png`` per machine with two or more dated, diagnosed recordings of one unit."""
    import pandas as pd

    from ..plots import plot_trend

    dated = table[table["time"].notna() & table["error"].isna()].copy()
    dated["machine"] = dated["machine"].fillna("")
    paths = []
    groups = [(m, part.sort_values("time")) for m, part in dated.groupby("machine", sort=True)]
    for machine, part in groups:
        if len(part) < 2:
            continue
        if part["velocity_unit"].nunique() > 1:
            print(
                f"no trend of {machine or 'the recordings'}: their velocity units differ "
                "(give --unit)",
                file=sys.stderr,
            )
            continue
        name = "trend.png" if len(groups) == 1 else f"trend_{_report_folder(machine)}.png"
        faults = ("outer race", "inner race", "ball")
        paths.append(
            plot_trend(
                pd.to_datetime(part["time"]).tolist(),
                {f: part[f"{f.replace(' ', '_')}_margin_db"].tolist() for f in faults},
                {b: part[f"velocity_{b}"].tolist() for b in ("low", "medium", "high", "overall")},
                out / name,
                title=f"trend{' of ' + machine if machine else ''}: {len(part)} recordings",
                band_unit=str(part["velocity_unit"].iloc[0]),
                spall_mm=tuple(part[f"spall_{k}_mm"].astype(float) for k in SPALL_COLUMNS),
                zone_limits_mm_s=_shared_zone_limits(part),
            )
        )
    return paths


def _shared_zone_limits(part) -> tuple[float, float, float] | None:
    """The zone boundaries [mm/s] every recording of a machine's trend was judged by.

    None where some recording has none (no class given, or no unit) or they differ.
    """
    limits = part["zone_limits_mm_s"].dropna().unique()
    if len(limits) != 1 or part["zone_limits_mm_s"].isna().any():
        return None
    return tuple(float(v) for v in str(limits[0]).split("/"))  # type: ignore[return-value]


def _report_folder(file: str) -> str:
    """A report folder's name for a manifest's file (its path with separators replaced)."""
    return str(Path(file).with_suffix("")).replace("/", "__").replace("\\", "__")


def cmd_realism(args: argparse.Namespace) -> int:
    """Tell simulated from measured signals: ROC AUC and the features that give it away.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool realism`` (``cmtool realism --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_folder("--out", args.out, "a folder for realism.json and realism.png")
    import numpy as np

    from ..datasets import read_dataset
    from ..realism import plot_realism, realism, recording_segments

    simulated = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    duration = float(np.median(simulated["duration_s"])) if "duration_s" in simulated else 1.0
    measured = recording_segments(args.recordings, duration)
    with StageBars("realism") as progress:
        result = realism(
            simulated,
            measured,
            feature_set=args.feature_set,
            n_jobs=args.workers,
            progress=progress,
        )
    print(
        f"measured vs simulated: ROC AUC {result['auc']:.3f} (0.5: indistinguishable, 1: "
        f"every recording recognised); {result['segments']} segments of {duration:g} s from "
        f"{result['recordings']} recordings against {result['simulated']} simulated signals, "
        f"{result['folds']}-fold cross-validation grouped by recording, "
        f"{result['feature_set']} features"
        + (
            f" (left out, they repeat the context: {', '.join(result['context_left_out'])})"
            if result["context_left_out"]
            else ""
        )
    )
    for column, name in (("rig", "rig"), ("label", "class")):
        for value, part in result["auc_by"].get(column, {}).items():
            against = "simulated" if part["against"] == "all" else f"simulated {value}"
            print(
                f"  {name} {value}: ROC AUC {part['auc']:.3f} ({part['segments']} segments "
                f"against {part['simulated']} {against})"
            )
            for d in part.get("differences", [])[:3]:
                print(
                    f"      {d['feature']:<36s} {d['direction']:<15s} {d['measured_median']:.3g} "
                    f"against {d['simulated_median']:.3g} (its AUC {d['auc']:.2f})"
                )
    print(
        "what gives the simulation away (random-forest importance; medians, measured against "
        "simulated; measured segments outside the simulated 1-99 % range):"
    )
    for d in result["differences"][:10]:
        unit = "" if d["unit"] in ("", "-") else f" {d['unit']}"
        outside = d["measured_below_range"] + d["measured_above_range"]
        print(
            f"  {d['feature']:<40s} {d['importance']:.3f}  {d['direction']:<15s} "
            f"{d['measured_median']:.3g} against {d['simulated_median']:.3g}{unit}, "
            f"{outside:.0%} outside"
        )
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        from ..io import atomic_write, json_text

        kept = {k: v for k, v in result.items() if k != "scores"}
        text = json_text(kept)
        atomic_write(out / "realism.json", lambda tmp: tmp.write_text(text))
        print(f"wrote {plot_realism(result, out / 'realism.png')}")
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    """Run detectors over a labelled dataset; print and write the scores, curves and report.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool bench`` (``cmtool bench --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    import pandas as pd

    from .. import bench
    from ..plots import plot_confusion

    check_output_folder("--out", args.out, "a folder for the tables and plots")
    out = Path(args.out) if args.out else None
    for spec in args.detector:
        bench.load_callable(spec)  # a wrong plug-in is refused before any work
    model = None
    in_sample = 0.0
    if args.model:
        from ..classifier import load_model

        model = load_model(args.model)
        if not (Path(args.dataset) / "MANIFEST.csv").is_file():
            from ..datasets import read_dataset

            in_sample = check_training_overlap(
                model,
                read_dataset(
                    args.dataset, columns=["signal"], allow_incomplete=args.allow_incomplete
                ),
                args,
            )
            if in_sample:
                print(
                    f"IN-SAMPLE: {in_sample:.0%} of these signals trained the model; its rates "
                    "below are not a measure of accuracy"
                )
    bar = None

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = progress_bar(total, "bench", "signal")
        bar.update(done - bar.n)

    results = bench.run_bench(
        args.dataset,
        model=model,
        detectors=args.detector,
        bearing=args.bearing,
        progress=progress,
        allow_incomplete=args.allow_incomplete,
        workers=args.workers,
    )
    if bar is not None:
        bar.close()
    if in_sample:
        results["in_sample"] = True
    summary, curves = bench.score_summary(results)
    snr_column = next((c for c in ("fault_snr_db", "snr_db") if c in results), None)
    by_snr = by_snr_fault = None
    if snr_column is not None:
        columns = ["detector", "snr_db", "pd_at_pfa_0.01", "ci_low", "ci_high", "signals", "bin"]
        snr_table = bench.by_factor(results, snr_column)
        if len(snr_table):
            by_snr = snr_table.rename(columns={"value": "snr_db"})[columns]
            per_fault = {
                f: bench.by_factor(results, snr_column, fault=f) for f in bench.FAULT_CLASSES
            }
            by_snr_fault = pd.concat(  # a fault the dataset lacks has no rows, and no panel
                [by_snr.assign(fault="all")]
                + [
                    t.rename(columns={"value": "snr_db"})[columns].assign(fault=f)
                    for f, t in per_fault.items()
                    if len(t)
                ],
                ignore_index=True,
            )
    factors = {
        c: bench.by_factor(results, c)
        for c in bench.FACTORS
        if c not in ("fault_snr_db", "snr_db") and c in results and results[c].nunique() > 1
    }
    factors = {c: t for c, t in factors.items() if len(t)}  # none without faulty signals
    tag = " [IN-SAMPLE]" if in_sample else ""
    print(f"== ROC area and detection at fixed false-alarm rates{tag}")
    print(summary.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    if by_snr is not None:
        print(f"== detection at false alarm 0.01 against {snr_column}{tag}")
        print(by_snr.drop(columns=["bin"]).to_string(index=False, float_format="{:.3f}".format))
    labels = bench.summarise(results)["overall"]
    print(f"== the detectors' own labels{tag}")
    print(labels.to_string(float_format=lambda v: f"{v:.3f}"))
    confusion = bench.confusion_tables(results)
    pairs = list(dict.fromkeys(zip(confusion["detector"], confusion["rig"], strict=True)))
    frames = {pair: bench.confusion_frame(confusion, *pair) for pair in pairs}
    print(f"== the detectors' own labels by class (rows: true class, columns: verdict){tag}")
    for (detector, rig), frame in frames.items():
        print(f"-- {detector}" + ("" if rig == "all" else f", {rig}"))
        print(frame.to_string())
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        if in_sample:
            for frame in (summary, labels):
                frame["in_sample"] = True
        from ..io import atomic_write

        tables = {
            "results.csv": results,
            "summary.csv": summary,
            "confusion.csv": confusion.assign(**({"in_sample": True} if in_sample else {})),
        }
        if by_snr is not None:
            if in_sample:
                by_snr = by_snr.assign(in_sample=True)
            tables["by_snr.csv"] = by_snr.drop(columns=["bin"])
            tables["by_snr_fault.csv"] = by_snr_fault.drop(columns=["bin"])
        if factors:
            table = pd.concat([t.assign(factor=c) for c, t in factors.items()], ignore_index=True)
            tables["by_factor.csv"] = table
        for name, frame in tables.items():
            atomic_write(out / name, lambda tmp, frame=frame: frame.to_csv(tmp, index=False))
        atomic_write(out / "labels.csv", lambda tmp: labels.to_csv(tmp))
        title = f"{Path(args.dataset).name}{tag}"
        written = [bench.plot_roc(curves, out / "roc.png", title=f"ROC: {title}")]
        for (detector, rig), frame in frames.items():
            written.append(
                plot_confusion(
                    frame.to_numpy(),
                    list(frame.index),
                    out / bench.confusion_plot_name(detector, rig),
                    columns=list(frame.columns),
                    title=f"{detector}" + ("" if rig == "all" else f", {rig}") + f": {title}",
                )
            )
        if by_snr is not None:
            written.append(
                bench.plot_pd_vs_snr(
                    by_snr_fault, out / "pd_vs_snr.png", title=f"detection against SNR: {title}"
                )
            )
        written.append(
            bench.write_report(
                out / "report.md",
                Path(args.dataset).name,
                summary,
                by_snr if by_snr is not None else summary.iloc[0:0],
                factors,
                in_sample=in_sample,
                confusion=confusion,
            )
        )
        for path in written:
            print(f"wrote {path}")
    return 0


def cmd_demo(args: argparse.Namespace) -> int:
    """The main job on the embedded default.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool demo`` (``cmtool demo --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_folder("--out", args.out, "a folder for the demo's results")
    from ..demo import run_demo

    return run_demo(Path(args.out))
