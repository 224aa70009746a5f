"""The text output of ``cmtool diagnose FILE``: the verdict, what it assumed and its evidence."""

from __future__ import annotations

from ..diagnose import Diagnosis, explained_lines
from ..report import model_verdict_text
from ..vibration_zones import zone_text
from ..waviness import comparison_text


def print_diagnosis(diagnosis: Diagnosis) -> None:
    """Print the text output of one diagnosis (``cmtool diagnose FILE``).

    Parameters
    ----------
    diagnosis : cmtool.diagnose.Diagnosis
        The diagnosis to print: its verdict, the assumptions it rests on (bearing, speed [rpm],
        sample rate [Hz], record length [s], channel, band [Hz]), each candidate's evidence
        [dB], the velocity bands and what else it holds.
    """
    a = diagnosis.assumptions
    print(
        f"{a['file']}: {diagnosis.verdict} (confidence "
        f"{diagnosis.confidence:.2f}); envelope band {diagnosis.band_hz[0]:.0f}-"
        f"{diagnosis.band_hz[1]:.0f} Hz, threshold {diagnosis.threshold_db:.1f} dB"
    )
    seen = a.get("spectrum_rpm")
    if a.get("speed_source", "given") != "given":  # the line's speed used (spectrum, auto)
        speed = f" (the spectrum's 1x line; {a['rpm_given']:g} rpm given)"
    else:
        speed = f" (the spectrum's 1x line: {seen:g} rpm)" if seen is not None else ""
    if "speed_measured" in a:
        speed = f" (from the {a['speed_measured']})"
    print(
        f"  assumed: bearing {a['bearing']}, {a['rpm']:g} rpm"
        + speed
        + f", fs {a['fs_hz']:g} Hz, {a['record_s']:g} s ({a['samples']} samples), "
        f"channel {a['channel']}"
    )
    if slices := a.get("lattice_slices"):
        print(
            "  periodic part also fitted: the series k BPFI + n BPFO, k = "
            + ", ".join(f"{k:+d}" for k in slices)
            + " (this record holds lines there; a wavy inner race of Z lobes puts its own there)"
        )
    if a.get("instrument_floor", "").startswith("added"):  # a recording's own floor: no line
        print(f"  instrument floor {a['instrument_floor']}")
    if "bearing_geometry" in a:
        print(f"  bearing geometry {a['bearing_geometry']}")
    for c in diagnosis.candidates:
        cage = [w for w in c.get("lines_weighed", []) if w["line"] == "cage 1x"]
        print(
            f"  {c['fault']:<11s} {c['frequency_hz']:9.3f} Hz  envelope SNR "
            f"{c['envelope_snr_db'][0]:6.1f} / {c['envelope_snr_db'][1]:6.1f} / "
            f"{c['envelope_snr_db'][2]:6.1f} dB (1x/2x/3x)"
            + (f", cage rate {cage[0]['snr_db']:.1f} dB" if cage else "")
            + f", weighed {c['evidence_db']:5.1f} dB"
            + ("  DETECTED" if c["detected"] else "")
            + (f"  ({shared})" if (shared := explained_lines(c)) else "")
        )
    print(f"  basis: {diagnosis.basis}")
    if theirs := (diagnosis.baseline or {}).get("baseline_fault_margin_db"):
        ours = diagnosis.baseline["fault_margin_db"]
        b = diagnosis.baseline
        print(
            f"  against the baseline ({b['record_s']:g} s at {b['fs_hz']:g} Hz, its band "
            f"{b['band_hz'][0]:.0f}-{b['band_hz'][1]:.0f} Hz, threshold {b['threshold_db']:.1f} "
            "dB; margins over each threshold, shown, not weighed): "
            + ", ".join(
                f"{f} {m:+.1f} dB (baseline {theirs[f]:+.1f}, rise {m - theirs[f]:+.1f})"
                for f, m in ours.items()
            )
        )
    change = (diagnosis.baseline or {}).get("velocity_bands_change_db", {})
    in_mm_s = diagnosis.velocity_bands_mm_s
    bands = ", ".join(
        f"{k} {v:.3g}" + (f" ({change[k]:+.1f} dB)" if change.get(k) is not None else "")
        for k, v in (in_mm_s or diagnosis.velocity_bands or {}).items()
    )
    unit = f"mm/s, the signal in {a['unit']}" if in_mm_s else "signal unit x s: --unit for mm/s"
    print(f"  velocity RMS (ISO 15242 bands, {unit}): {bands}")
    overall = diagnosis.overall_velocity
    if overall:
        low, high = overall["band_hz"]
        value = (
            f"{overall['rms_mm_s']:.3g} mm/s"
            if overall["rms_mm_s"] is not None
            else f"{overall['rms']:.3g} (signal unit x s)"
        )
        print(f"  overall velocity RMS (ISO 10816-3 band, {low:g}-{high:g} Hz): {value}")
        if zone := overall.get("zone"):
            print(f"  vibration zone {zone_text(zone)}")
    if diagnosis.waviness:
        w = diagnosis.waviness
        over = w.get("over_baseline_db")
        print(
            f"  waviness hint: {w['surface']} race order ~{w['order']} at {w['line_hz']} Hz"
            + ("" if over is None else f", {over:+.1f} dB over the baseline")
            + comparison_text(w)
        )
    if diagnosis.model_verdict:
        print(f"  model: {model_verdict_text(diagnosis.model_verdict)}")
    if diagnosis.severity:
        print(f"  fault size: {diagnosis.severity['reason']}")
    for w in diagnosis.warnings:
        print(f"  warning: {w}")
