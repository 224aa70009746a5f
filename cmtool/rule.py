"""The rule detector's steps that ``cmtool.diagnose.diagnose_signal`` builds its verdict on.

What the rule needs of a record before it weighs it (:func:`rule_context`), its candidates
ranked by their weighed evidence (:func:`rule_candidates`), and a long record weighed segment
by segment (:func:`segment_scan`), with the constants they are set by (docs/diagnosis.md).
``cmtool.diagnose`` re-exports all of them; a benchmark that changes one of the constants sets
it here, where it is read.
"""

from __future__ import annotations

import math

import numpy as np

import features
from generators import BearingGeometry, characteristic_frequencies
from generators.kinematics import BearingFrequencies
from generators.params import check_shaft_speed_rpm

from .diagnosis import DETECTION_DB
from .quality import check_signal_quality

__all__ = [
    "rule_context",
    "rule_candidates",
    "segment_scan",
    "FAULTS",
    "FAULT_NAMES",
    "MIN_RATE_PERIODS",
    "TRUSTED_RATE_PERIODS",
    "SCAN_SEGMENT_S",
    "SCAN_SEGMENT_PERIODS",
    "CONFIDENCE_SCALE_DB",
    "CONFIDENCE_OFFSET_DB",
    "logistic",
    "slowest_fault_rate",
]

# The confidences' calibration: the comment above FAULT_CONFIDENCE in cmtool/diagnose.py.
#: Each fault line's confidence, 1 / (1 + exp(-(margin - offset) / scale)) with the margin of
#: the fault's weighed evidence over the detection threshold [dB]: the probability that the
#: signal has this fault
CONFIDENCE_SCALE_DB = 2.34
CONFIDENCE_OFFSET_DB = -0.51
#: Shortest record [periods of the slowest fault rate]: its envelope spectrum's bins are then
#: 5 % of that rate apart, as far as the rates of a bearing lie from each other at the least.
MIN_RATE_PERIODS = 20
#: Records shorter than this many periods of the slowest fault rate are diagnosed with a
#: warning. Measured in stop 58 on rig-recipe draws cut short: the rule called 3.5 % of the
#: simulated healthy bearings faulty at 20 periods and 1.25 % at 30 (400 records each), 0 and
#: 1 in 100 at 35-50 periods (two draws), 2 in 600 whole 1 s records (81-107 periods); it
#: found 0-6 % of the inner-race pits at 20 periods, 16-52 % at 30, 65-86 % in 1 s
#: (docs/diagnosis.md, "Records of few periods").
TRUSTED_RATE_PERIODS = 40
#: Segments a long record is scanned in when the whole shows no fault [s]: the length of the
#: recipes' signals the rule was measured on (at least ``SCAN_SEGMENT_PERIODS`` of the slowest
#: fault rate). A fault struck in some seconds only (a ball pit whose spin axis drifts) shows
#: there at full strength, where the whole record's envelope spectrum dilutes its lines.
SCAN_SEGMENT_S = 1.0
#: Fewest periods of the slowest fault rate a segment of the scan holds (a machine whose
#: slowest rate is under 40 Hz gets segments longer than ``SCAN_SEGMENT_S``): measured in stop
#: 59 on 8 s records of the CWRU rig's recipe at 250-550 rpm, segments of 20 periods called
#: healthy bearings faulty where segments of 40 did not (docs/diagnosis.md, "Long records of
#: slow machines").
SCAN_SEGMENT_PERIODS = TRUSTED_RATE_PERIODS
#: verdict name -> characteristic frequency used as its evidence
FAULTS = {"outer race": "bpfo", "inner race": "bpfi", "ball": "two_bsf"}
FAULT_NAMES = {key: name for name, key in FAULTS.items()}


def logistic(margin: float, scale: float, offset: float) -> float:
    """A confidence from a margin over the threshold: 1 / (1 + exp(-(margin - offset) / scale)).

    Parameters
    ----------
    margin : float
        The weighed evidence over the detection threshold [dB].
    scale, offset : float
        The calibrated logistic's scale and offset [dB] (``CONFIDENCE_SCALE_DB``, ...).

    Returns
    -------
    float
        The confidence, in (0, 1).
    """
    return 1.0 / (1.0 + math.exp(-(margin - offset) / scale))


def rule_context(
    x: np.ndarray, fs: float, rpm: float, geometry: BearingGeometry
) -> tuple[float, BearingFrequencies, dict[str, float], list[str]]:
    """What the rule detector needs before it weighs a signal, or why it cannot.

    Parameters
    ----------
    x : ndarray
        The signal.
    fs : float
        Sample rate [Hz].
    rpm : float
        Shaft speed [rev/min].
    geometry : BearingGeometry
        The bearing.

    Returns
    -------
    rpm : float
        The speed, checked [rev/min].
    freqs : BearingFrequencies
        The bearing's characteristic frequencies at that speed [Hz].
    ctx : dict of str to float
        ``shaft``, ``ftf``, ``bpfo``, ``bpfi`` and ``two_bsf`` [Hz]: ``fault_evidence``'s
        rates.
    warnings : list of str
        What makes the answer less certain (the signal's quality, the speed, the record).

    Raises
    ------
    ValueError
        When ``fs`` is too low for envelope analysis of these rates, or the record too short
        to tell them apart.
    """
    warnings = check_signal_quality(x)
    rpm = check_shaft_speed_rpm("rpm", rpm)
    if geometry.limiting_speed_rpm is not None and rpm > geometry.limiting_speed_rpm:
        warnings.append(
            f"{rpm:g} rpm is above the catalogue limiting speed of the {geometry.name} "
            f"({geometry.limiting_speed_rpm:g} rpm): check --rpm and --bearing"
        )
    freqs = characteristic_frequencies(geometry, rpm / 60.0)
    ctx = {
        "shaft": freqs.shaft,
        "ftf": freqs.ftf,
        "bpfo": freqs.bpfo,
        "bpfi": freqs.bpfi,
        "two_bsf": freqs.two_bsf,
    }
    fastest = max(ctx["bpfo"], ctx["bpfi"], ctx["two_bsf"])
    # the demodulation band (3 x the fastest rate wide) must fit under the analyser span
    # fs / 2.56, with the rates' third harmonics inside it
    needed = features.separation.ANALYSER_RATIO * features.table.MIN_BAND_FACTOR * fastest
    if fs < needed:
        raise ValueError(
            f"fs = {fs:g} Hz is too low to diagnose this bearing at {rpm:g} rpm: envelope "
            f"analysis of fault rates up to {fastest:.1f} Hz needs fs >= {needed:.0f} Hz"
        )
    slowest = slowest_fault_rate(ctx)
    shortest = MIN_RATE_PERIODS / slowest
    if x.size / fs < shortest:
        raise ValueError(
            f"the record is {x.size / fs:.3g} s long ({x.size} samples at {fs:g} Hz); telling "
            f"the fault rates apart needs at least {MIN_RATE_PERIODS} periods of the slowest "
            f"({slowest:.1f} Hz): {shortest:.3g} s, {int(math.ceil(shortest * fs))} samples"
        )
    periods = x.size / fs * slowest
    if periods < TRUSTED_RATE_PERIODS:
        warnings.append(
            f"record of {x.size / fs:.2f} s holds {periods:.0f} periods of the slowest fault "
            f"rate ({slowest:.1f} Hz), fewer than {TRUSTED_RATE_PERIODS}: on simulated records "
            "of 20-30 periods the rule called 1-4 healthy bearings in 100 faulty and missed "
            "most faults (docs/diagnosis.md, 'Records of few periods'); record longer"
        )
    if not features.evidence.cage_lines_weighed(x.size / fs, freqs.ftf):
        warnings.append(
            f"record of {x.size / fs:.2f} s holds {x.size / fs * freqs.ftf:.1f} cage "
            f"revolutions, fewer than {features.evidence.MIN_CAGE_REVOLUTIONS:g}: the ball's "
            "cage-rate lines are not weighed (a ball pit is judged on its 2 x BSF lines and "
            "their sidebands alone)"
        )
    return rpm, freqs, ctx, warnings


def slowest_fault_rate(ctx: dict[str, float]) -> float:
    """The slowest of the bearing's fault rates (BPFO, BPFI, 2 x BSF).

    Parameters
    ----------
    ctx : dict of str to float
        The bearing's rates [Hz] (:func:`rule_context`).

    Returns
    -------
    float
        The slowest of ``bpfo``, ``bpfi`` and ``two_bsf`` [Hz].
    """
    return min(ctx[key] for key in FAULTS.values())


def segment_scan(x: np.ndarray, fs: float, ctx: dict[str, float]) -> dict | None:
    """The rule's evidence in each segment of a long record (``SCAN_SEGMENT_S``).

    Each segment is weighed as a record of its own (:func:`rule_candidates`) against the
    threshold for a false alarm of ``features.FALSE_ALARM / segments`` (Bonferroni: a fault
    counts in at most that share of healthy records over all the segments together).

    Parameters
    ----------
    x : ndarray
        The record [any unit].
    fs : float
        Its sample rate [Hz].
    ctx : dict of str to float
        The bearing's rates [Hz] (``rule_context``), ``ftf`` included.

    Returns
    -------
    dict or None
        None for a record shorter than two segments. Else ``segments``, ``segment_s`` [s],
        ``margins_db`` (each fault's weighed evidence over the segment's threshold, segment by
        segment [dB]: above 0 detected there) and ``found``: None, or the fault of the segment
        where a detected fault stands furthest over that threshold, with the segment's place
        [s], band [Hz], threshold and margin [dB] and the fault's false-alarm probability in
        the segment; with a fault found, ``candidates`` (that segment's,
        :func:`rule_candidates` on its threshold) and ``envelope`` (its envelope spectrum:
        frequencies [Hz], amplitudes), for the verdict and the plots.
    """
    seconds = max(SCAN_SEGMENT_S, SCAN_SEGMENT_PERIODS / slowest_fault_rate(ctx))
    n = int(round(seconds * fs))
    count = x.size // n
    if count < 2:
        return None
    out: dict = {"segments": count, "segment_s": round(n / fs, 6), "found": None}
    margins: dict[str, list[float]] = {}
    best = None
    for i in range(count):
        evidence = features.fault_evidence(x[i * n : (i + 1) * n], fs, ctx)
        selection = evidence.selection
        threshold = features.detection_threshold_db(
            len(selection.bands),
            features.FALSE_ALARM / count,
            selection.searched_bins,
            selection.floor_bins,
        )
        candidates = rule_candidates(evidence, ctx, threshold)
        for c in candidates:
            margins.setdefault(c["fault"], []).append(round(c["evidence_db"] - threshold, 2))
        margin = candidates[0]["evidence_db"] - threshold
        if candidates[0]["detected"] and (best is None or margin > best[0]):
            best = (margin, i, threshold, candidates, evidence)
    out["margins_db"] = margins
    if best is not None:
        margin, i, threshold, candidates, evidence = best
        out["found"] = {
            "fault": candidates[0]["fault"],
            "segment": i,
            "start_s": round(i * n / fs, 6),
            "end_s": round((i + 1) * n / fs, 6),
            "false_alarm_probability": candidates[0]["false_alarm_probability"],
            "band_hz": [round(b, 2) for b in evidence.selection.band],
            "threshold_db": round(threshold, 2),
            "margin_db": round(margin, 2),
        }
        out["candidates"] = candidates
        out["envelope"] = (evidence.envelope_frequencies, evidence.envelope_amplitude)
    return out


def rule_candidates(
    evidence: features.Evidence, ctx: dict[str, float], threshold_db: float | None = None
) -> list[dict]:
    """The rule detector's candidates, one per fault, ranked by their weighed evidence.

    Parameters
    ----------
    evidence : features.Evidence
        ``features.fault_evidence`` of the signal.
    ctx : dict of str to float
        The bearing's rates [Hz]: ``bpfo``, ``bpfi`` and ``two_bsf`` at least.
    threshold_db : float, optional
        Detection threshold [dB] (default the evidence's own: a false alarm of
        ``features.FALSE_ALARM`` per fault).

    Returns
    -------
    list of dict
        Per fault: its rate and the line found [Hz], the envelope lines [dB], the weighed
        evidence [dB] and its false-alarm probability, the lines weighed, whether it is
        detected (evidence at the threshold or above), the lines a stronger fault explains
        and its confidence; the strongest first (ties by the fundamental).
    """
    threshold = evidence.threshold_db if threshold_db is None else threshold_db
    candidates = []
    for name, key in FAULTS.items():
        snr = [r for r, _ in evidence.lines[key]]
        weighed = evidence.combined[key]
        harmonics = int(sum(s >= DETECTION_DB / 2 for s in snr))
        margin = weighed["evidence_db"] - threshold
        sidebands = evidence.features[f"evidence_{key}_sideband_snr"]
        candidates.append(
            {
                "fault": name,
                "frequency_hz": round(ctx[key], 3),
                "found_hz": round(evidence.lines[key][0][1], 3),
                "envelope_snr_db": [round(s, 2) for s in snr],
                "harmonics_above_6db": harmonics,
                "sideband_snr_db": round(sidebands, 2) if key in ("bpfi", "two_bsf") else None,
                "evidence_db": round(weighed["evidence_db"], 2),
                "false_alarm_probability": float(f"{weighed['false_alarm']:.3g}"),
                "lines_weighed": [
                    {"line": n, "snr_db": r, "false_alarm_probability": float(f"{p:.3g}")}
                    for n, r, p in weighed["lines"]
                ],
                "detected": bool(weighed["evidence_db"] >= threshold),
                # lines on a stronger detected fault's series
                # (features.evidence.explain_shared_lines): counted as absent in this fault's
                # weighing
                "explained": [
                    {"line": line, "by": FAULT_NAMES[other], "harmonic": k}
                    for line, other, k in weighed.get("explained", [])
                ],
                "confidence": round(logistic(margin, CONFIDENCE_SCALE_DB, CONFIDENCE_OFFSET_DB), 4),
            }
        )
    # ranked by the weighed evidence of each fault's line family (fundamental, harmonics,
    # sidebands), ties by the fundamental
    candidates.sort(key=lambda c: (c["evidence_db"], c["envelope_snr_db"][0]), reverse=True)
    return candidates
