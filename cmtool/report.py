"""``report.md`` of one diagnosis, with its spectrum, envelope spectrum and kurtogram plots."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .diagnose import explained_lines
from .diagnosis import Diagnosis
from .io import atomic_write, json_text
from .vibration_zones import zone_text

__all__ = ["model_verdict_text", "write_report"]

#: The envelope plot's marker of each fault verdict.
_VERDICT_MARKERS = {"outer race": "bpfo", "inner race": "bpfi", "ball": "two_bsf"}


def model_verdict_text(model_verdict: dict, *, bold: bool = False) -> str:
    """A trained model's verdict as an analyst reads it.

    "outer waviness (probability 0.93; inner waviness 0.05, healthy 0.02, ball waviness 0.00),
    2 segments of the record averaged": each class named with what it was trained on (the
    bundle's ``class_kinds``: waviness or local fault), the others by falling probability;
    where the segments voted, the ones averaged ("the 3 of 10 segments read as a local fault
    (more than the model's false-alarm rate 0.01 makes likely) averaged").

    Parameters
    ----------
    model_verdict : dict
        :attr:`cmtool.diagnosis.Diagnosis.model_verdict`.
    bold : bool
        The verdict's class in Markdown bold (the report).

    Returns
    -------
    str
    """
    kinds = model_verdict.get("class_kinds") or {}
    suffix = {"waviness": " waviness", "localized": " local fault"}

    def name(label: str) -> str:
        return f"{label}{suffix.get(kinds.get(label, ''), '')}"

    label = str(model_verdict["label"])
    head = f"**{name(label)}**" if bold else name(label)
    probabilities = model_verdict.get("probabilities") or {}
    if label in probabilities:
        others = sorted(
            ((c, p) for c, p in probabilities.items() if c != label), key=lambda item: -item[1]
        )
        rest = "".join(
            f", {name(c)} {p:.2f}" if i else f"; {name(c)} {p:.2f}"
            for i, (c, p) in enumerate(others)
        )
        head += f" (probability {probabilities[label]:.2f}{rest})"
    segments = model_verdict.get("segments")
    combined = model_verdict.get("segments_combined", "all")
    if segments and combined != "all":  # the segments voted (cmtool.pooling)
        head += f", {combined} averaged"
    elif segments:
        head += f", {segments} segment{'s' if segments > 1 else ''} of the record averaged"
    return head


def _quantity(diagnosis: Diagnosis) -> str:
    """The waveform's axis label: acceleration in its unit where the diagnosis knows it."""
    unit = diagnosis.assumptions.get("unit")
    if unit and "quantity" in diagnosis.assumptions:  # a velocity record, shown as given
        return f"velocity [{unit}]"
    return f"acceleration [{unit}]" if unit else "signal"


def write_report(
    diagnosis: Diagnosis, out: str | Path, *, title: str, x: np.ndarray, fs: float
) -> Path:
    """Write ``report.md`` with the spectrum, envelope spectrum, waveform and kurtogram plots.

    Parameters
    ----------
    diagnosis : Diagnosis
        The diagnosis (:func:`cmtool.diagnose.diagnose_signal`).
    out : path-like
        The report's folder (created).
    title : str
        The record's name, in the report's and the plots' titles.
    x : ndarray
        The record diagnosed [its unit] (for the time waveform).
    fs : float
        Its sample rate [Hz].

    Returns
    -------
    pathlib.Path
        ``report.md``'s path (``diagnosis.json`` and the PNGs beside it).
    """
    from .plots import (
        plot_entry_exit,
        plot_kurtogram,
        plot_segment_evidence,
        plot_spectrum,
        plot_waveform,
    )
    from .waviness import comparison_text

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    sp = diagnosis.spectra
    f = diagnosis.frequencies
    markers = {"shaft": f["shaft"], "bpfo": f["bpfo"], "bpfi": f["bpfi"], "two_bsf": f["two_bsf"]}
    fault = _VERDICT_MARKERS.get(diagnosis.verdict)  # the verdict's marker, None if healthy
    spec_png = plot_spectrum(
        sp.frequencies,
        sp.amplitude,
        out / "spectrum.png",
        title=f"{title}: amplitude spectrum",
        ylabel="amplitude",
        markers=markers,
        fmax=min(fs / 2, 20 * f["bpfi"]),
    )
    scanned = (diagnosis.segment_scan or {}).get("found")  # a fault found in one segment
    seconds = f", seconds {scanned['start_s']:g}-{scanned['end_s']:g}" if scanned else ""
    env_png = plot_spectrum(
        sp.envelope_frequencies,
        sp.envelope_amplitude,
        out / "envelope.png",
        title=f"{title}: envelope spectrum, band {sp.band[0]:.0f}-{sp.band[1]:.0f} Hz{seconds}",
        ylabel="envelope amplitude",
        markers=markers,
        fmax=min(fs / 2, 5 * f["bpfi"]),
        log=False,
        top_from=0.5 * f["ftf"],
        emphasis=fault,
        sidebands={"inner race": f["shaft"], "ball": f["ftf"]}.get(diagnosis.verdict),
    )
    wave_png = plot_waveform(
        x[: diagnosis.assumptions.get("samples", x.size)],
        fs,
        out / "waveform.png",
        title=title,
        shaft_hz=f["shaft"],
        band=tuple(sp.band) if sp.band is not None else None,
        fault_hz=f[fault] if fault else None,
        fault_name=diagnosis.verdict if fault else None,
        ylabel=_quantity(diagnosis),
    )
    paths = [spec_png, env_png, wave_png]
    if sp.kurtogram is not None:
        paths.append(plot_kurtogram(sp.kurtogram, out / "kurtogram.png", title=title))
    scan = diagnosis.segment_scan
    if scan and scan.get("margins_db"):  # the whole record showed no fault: its segments
        paths.append(
            plot_segment_evidence(
                scan["segment_s"],
                scan["margins_db"],
                out / "segments.png",
                title=f"{title}: each fault's evidence by segment of {scan['segment_s']:g} s",
                found=scanned,
            )
        )
    timing, size = diagnosis.entry_exit, diagnosis.severity or {}
    if timing is not None and timing.average.size:  # the spall's timing (Fault size)
        length = f": spall about {size['length_mm']:.2f} mm" if size.get("estimated") else ""
        paths.append(
            plot_entry_exit(
                timing.average,
                fs,
                out / "entry_exit.png",
                title=f"{title}: {timing.impacts} {diagnosis.verdict} impacts averaged{length}",
                spacing_s=timing.spacing_s if timing.resolved else None,
            )
        )
    lines = [
        f"# Diagnosis: {title}",
        "",
        f"**Verdict: {diagnosis.verdict}** (confidence {diagnosis.confidence:.2f}; "
        f"{diagnosis.basis})",
        "",
    ]
    if diagnosis.model_verdict:
        lines += [f"Model verdict: {model_verdict_text(diagnosis.model_verdict, bold=True)}", ""]
    if diagnosis.waviness:
        w = diagnosis.waviness
        lines += [
            f"Waviness hint: {w['surface']} race, order about {w['order']} (line "
            f"{w['line_hz']} Hz, {w['snr_db']} dB above the floor"
            + comparison_text(w)
            + f"; {w['note']})",
            "",
        ]
    if diagnosis.velocity_bands:
        lines += [
            "## Velocity (ISO 15242 bands: 50-300, 300-1800, 1800-10000 Hz; ISO 10816-3 "
            "overall), RMS [signal unit x s]",
            "",
            "| band | RMS | RMS [mm/s] | over baseline [dB] |",
            "|---|---|---|---|",
        ]
        change = (diagnosis.baseline or {}).get("velocity_bands_change_db", {})
        in_mm_s = diagnosis.velocity_bands_mm_s or {}
        for name, value in diagnosis.velocity_bands.items():
            mm_s = f"{in_mm_s[name]:.4g}" if name in in_mm_s else "- (unit not known: --unit)"
            lines.append(f"| {name} | {value:.4g} | {mm_s} | {change.get(name, '-')} |")
        overall = diagnosis.overall_velocity
        if overall:
            low, high = overall["band_hz"]
            mm_s = "-" if overall["rms_mm_s"] is None else f"{overall['rms_mm_s']:.4g}"
            name = f"overall (ISO 10816-3, {low:g}-{high:g} Hz)"
            lines.append(f"| {name} | {overall['rms']:.4g} | {mm_s} | - |")
        lines.append("")
        if overall and overall.get("zone"):
            lines += [f"Vibration zone {zone_text(overall['zone'])}.", ""]
    if theirs := (diagnosis.baseline or {}).get("baseline_fault_margin_db"):
        lines += [
            "## Against the baseline",
            "",
            "Each fault's weighed evidence over its threshold, in this record and in the "
            "baseline (in its own band, against its own threshold). Shown, not weighed in the "
            "verdict: a bearing's own form errors can stand over the threshold in a healthy "
            'baseline, and no rise over it tells them from a pit (docs/diagnosis.md, "Local '
            'faults against a baseline"). The baseline: '
            f"{diagnosis.baseline['record_s']:g} s at {diagnosis.baseline['fs_hz']:g} Hz, "
            f"band {diagnosis.baseline['band_hz'][0]:.0f}-{diagnosis.baseline['band_hz'][1]:.0f}"
            f" Hz, threshold {diagnosis.baseline['threshold_db']:.1f} dB.",
            "",
            "| fault | margin [dB] | baseline margin [dB] | rise [dB] |",
            "|---|---|---|---|",
        ]
        for fault, margin in diagnosis.baseline["fault_margin_db"].items():
            rise = margin - theirs[fault]
            lines.append(f"| {fault} | {margin:+.1f} | {theirs[fault]:+.1f} | {rise:+.1f} |")
        lines.append("")
    if diagnosis.severity:
        lines += ["## Fault size", "", diagnosis.severity["reason"], ""]
        if timing is not None and timing.average.size:
            lines += [
                "Figure entry_exit.png: the record's random part, its ringing removed (an AR "
                "prediction-error filter), squared envelope averaged over the impacts aligned "
                "on each; a ball entering a spall makes an event before the impact at its exit "
                "(docs/diagnosis.md, Severity).",
                "",
            ]
    if diagnosis.warnings:
        lines += ["## Warnings", ""] + [f"- {w}" for w in diagnosis.warnings] + [""]
    if scan and scan.get("margins_db"):
        lines += [
            "## Segment by segment",
            "",
            f"The whole record's envelope showed no fault, so each of its {scan['segments']} "
            f"segments of {scan['segment_s']:g} s was weighed as a record of its own, against "
            "the threshold for the record's false-alarm probability shared over the segments "
            "(figure segments.png: above 0 dB a fault is detected in that segment). "
            + (
                f"The verdict rests on seconds {scanned['start_s']:g}-{scanned['end_s']:g}."
                if scanned
                else "No segment shows a fault."
            ),
            "",
        ]
    lines += [
        "## Evidence (envelope spectrum, dB above the local noise floor)",
        "",
        "| fault | frequency [Hz] | 1x | 2x | 3x | sidebands | weighed [dB] | detected "
        "| confidence | lines of another fault |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in diagnosis.candidates:
        s = c["envelope_snr_db"]
        lines.append(
            f"| {c['fault']} | {c['frequency_hz']} | {s[0]} | {s[1]} | {s[2]} | "
            f"{c['sideband_snr_db'] if c['sideband_snr_db'] is not None else '-'} | "
            f"{c['evidence_db']} | {'yes' if c['detected'] else 'no'} | {c['confidence']} | "
            f"{explained_lines(c) or '-'} |"
        )
    lines += [
        "",
        f"Detection threshold: {diagnosis.threshold_db:.1f} dB on the weighed evidence of each "
        "fault's lines (fundamental, 2x, 3x, first sidebands; false-alarm probability about "
        "1e-4 per fault for Gaussian noise, counting every band searched). A line that lies on "
        "a stronger detected fault's harmonics or their sidebands (a 6205's 2 x BPFI and 3 x "
        "BPFO are 0.7 % apart) counts for that fault only: the last column names them.",
        "",
        "## Assumptions",
        "",
        *[f"- {k}: {v}" for k, v in diagnosis.assumptions.items()],
        "",
        "## Characteristic frequencies [Hz]",
        "",
    ]
    lines += [f"- {k}: {v}" for k, v in diagnosis.frequencies.items()]
    lines += ["", "## Plots", ""] + [f"![{p.stem}]({p.name})" for p in paths]
    report = out / "report.md"
    text = "\n".join(lines) + "\n"
    atomic_write(report, lambda tmp: tmp.write_text(text))
    data = json_text(diagnosis.to_dict())
    atomic_write(out / "diagnosis.json", lambda tmp: tmp.write_text(data))
    return report
