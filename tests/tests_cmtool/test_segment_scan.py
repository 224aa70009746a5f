"""A long record whose fault is struck in some seconds only (cmtool.rule.segment_scan,
stop 55): when the whole record's envelope shows no fault, each segment is weighed against
the threshold for FALSE_ALARM / segments (docs/diagnosis.md, "Faults struck in some seconds
only")."""

import json

import numpy as np
import pytest

import features
from cmtool.diagnose import SCAN_SEGMENT_S, diagnose_signal, rule_candidates, segment_scan
from generators import bearing, characteristic_frequencies

FS, RPM = 12000.0, 1797.0
FREQS = characteristic_frequencies(bearing("6205"), RPM / 60.0)
CTX = {
    "bpfo": FREQS.bpfo,
    "bpfi": FREQS.bpfi,
    "two_bsf": FREQS.two_bsf,
    "shaft": FREQS.shaft,
    "ftf": FREQS.ftf,
}


def _record(amplitude: float, seconds: float = 10.0, burst=(0.0, 1.0), seed: int = 0):
    """White noise of unit RMS, and a ball pit's impacts (2 x BSF, 1 % random spacing) ringing
    at 3 kHz (5 % damping) during ``burst`` [s] only."""
    rng = np.random.default_rng(seed)
    x = rng.standard_normal(int(seconds * FS))
    t = np.arange(int(0.01 * FS)) / FS
    ring = np.exp(-2 * np.pi * 3000.0 * 0.05 * t) * np.sin(2 * np.pi * 3000.0 * t)
    impact = burst[0]
    while impact < burst[1]:
        i = int(impact * FS)
        part = x[i : i + ring.size]
        part += amplitude * ring[: part.size]
        impact += (1.0 + 0.01 * rng.standard_normal()) / FREQS.two_bsf
    return x


class _Unsure:
    """A stand-in model that reads every segment as ball, 0.6 against healthy 0.4."""

    classes_ = np.array(["ball", "healthy"])

    def predict_proba(self, frame):
        return np.tile([0.6, 0.4], (len(frame), 1))


def test_a_ball_pit_struck_in_one_second_of_ten_is_found_in_that_second(tmp_path):
    x = _record(2.5)
    d = diagnose_signal(x, FS, RPM, "6205", waviness=False)
    found = d.segment_scan["found"]
    assert d.verdict == "ball" and found["fault"] == "ball" and found["segment"] == 0
    assert (found["start_s"], found["end_s"]) == (0.0, 1.0) and d.segment_scan["segments"] == 10
    # the whole record's envelope does not show it: the rule alone called it healthy
    whole = features.fault_evidence(x, FS, CTX)
    assert not any(c["detected"] for c in rule_candidates(whole, CTX))
    # ten segments: the threshold is that of a false alarm of 1e-5 per segment, higher
    one = features.fault_evidence(x[: int(FS)], FS, CTX).threshold_db
    assert found["threshold_db"] > one + 1.0 and found["margin_db"] > 0
    assert d.candidates[0]["fault"] == "ball" and d.candidates[0]["detected"]
    # every fault's margin, segment by segment: the ball's over 0 in the first second only
    margins = d.segment_scan["margins_db"]
    assert set(margins) == {"ball", "inner race", "outer race"}
    assert all(len(v) == 10 for v in margins.values())
    assert margins["ball"][0] == found["margin_db"] and max(margins["ball"][1:]) < 0.0
    assert "seconds 0-1 of the record" in d.basis and d.confidence > 0.9
    out = json.loads(json.dumps(d.to_dict()))
    assert out["segment_scan"]["found"]["segment"] == 0 and "segment_scan" in out["assumptions"]
    assert "1e-05 per fault and segment" in out["assumptions"]["segment_scan"]
    # every threshold the JSON states for the verdict is the segment's; the whole record's
    # is kept under its own name
    assert out["threshold_db"] == out["assumptions"]["threshold_db"] == found["threshold_db"]
    assert out["envelope_band_hz"] == out["assumptions"]["band_hz"] == found["band_hz"]
    assert out["assumptions"]["whole_record_threshold_db"] == round(whole.threshold_db, 2)
    # with a model the headline says what the model adds, and still where the rule looked
    with_model = diagnose_signal(x, FS, RPM, "6205", waviness=False, model=_Unsure())
    assert with_model.verdict == "ball" and "agree (ball)" in with_model.basis
    assert "the rule's evidence is that of seconds 0-1" in with_model.basis
    # the report: its envelope spectrum is that segment's, and says so
    from unittest import mock

    import cmtool.plots
    from cmtool.report import write_report

    with (
        mock.patch.object(cmtool.plots, "plot_spectrum", return_value=tmp_path / "p.png") as plot,
        mock.patch.object(
            cmtool.plots, "plot_segment_evidence", return_value=tmp_path / "s.png"
        ) as by_segment,
    ):
        write_report(d, tmp_path, title="t", x=x, fs=FS)
    envelope = [c for c in plot.call_args_list if c.args[2].name == "envelope.png"][0]
    assert envelope.kwargs["title"].endswith("seconds 0-1")
    assert envelope.args[1] is d.spectra.envelope_amplitude
    report = (tmp_path / "report.md").read_text()
    assert "seconds 0-1 of the record" in report
    # the segments' evidence is plotted, the found one marked, and the report says so
    (segment_s, plotted, path), kwargs = by_segment.call_args
    assert (segment_s, plotted, path.name) == (1.0, margins, "segments.png")
    assert kwargs["found"] == found
    assert "## Segment by segment" in report and "The verdict rests on seconds 0-1." in report
    # the same impacts over the whole record: the whole record shows them, no scan
    spread = diagnose_signal(_record(2.5, burst=(0.0, 10.0)), FS, RPM, "6205", waviness=False)
    assert spread.verdict == "ball" and spread.segment_scan is None


def test_noise_stays_healthy_and_short_records_are_not_scanned(tmp_path):
    x = _record(0.0, seed=1)
    d = diagnose_signal(x, FS, RPM, "6205", waviness=False)
    assert d.verdict == "healthy" and d.segment_scan["found"] is None
    assert d.segment_scan["segments"] == 10 and d.segment_scan["segment_s"] == SCAN_SEGMENT_S
    assert max(max(v) for v in d.segment_scan["margins_db"].values()) < 0.0
    # the report plots the segments' evidence (drawn for real here) and says none shows a fault
    from cmtool.report import write_report

    write_report(d, tmp_path, title="noise", x=x, fs=FS)
    report = (tmp_path / "report.md").read_text()
    assert "No segment shows a fault." in report and "![segments](segments.png)" in report
    assert (tmp_path / "segments.png").stat().st_size > 1000
    # a record shorter than two segments is weighed whole, as before
    assert segment_scan(_record(0.0, seconds=1.9), FS, CTX) is None
    short = diagnose_signal(_record(2.5, seconds=1.9), FS, RPM, "6205", waviness=False)
    assert short.segment_scan is None


def test_a_burst_one_segment_alone_would_call_is_held_to_the_corrected_threshold():
    """At 1.5 the first second's ball lines pass that second's own threshold (a false alarm
    of 1e-4) but not the one for ten segments (1e-5): the record stays healthy."""
    x = _record(1.5)
    first = features.fault_evidence(x[: int(FS)], FS, CTX)
    assert rule_candidates(first, CTX)[0]["detected"]
    d = diagnose_signal(x, FS, RPM, "6205", waviness=False)
    assert d.verdict == "healthy" and d.segment_scan["found"] is None


def test_a_slow_machines_segments_hold_forty_periods_of_its_slowest_rate():
    """At 250 rpm a 6205's BPFO is 14.9 Hz: 1 s segments would hold 15 periods, 20 periods
    (the shortest record diagnosed) 1.34 s; on 8 s CWRU-rig records at 250 rpm segments of 20
    periods called 6 of 38 healthy bearings faulty, segments of 40 none (stop 59,
    docs/diagnosis.md "Long records of slow machines"). The segments hold 40 periods."""
    rpm = 250.0
    bpfo = characteristic_frequencies(bearing("6205"), rpm / 60.0).bpfo
    x = np.random.default_rng(5).standard_normal(int(8.0 * FS))
    d = diagnose_signal(x, FS, rpm, "6205", waviness=False)
    scan = d.segment_scan
    assert scan["segment_s"] * bpfo == pytest.approx(40.0, abs=0.01)
    assert scan["segments"] == int(8.0 * bpfo / 40.0)  # 2.68 s: two whole segments in 8 s
    assert (
        f"{scan['segments']} segments of {scan['segment_s']:g} s" in (d.assumptions["segment_scan"])
    )
    # a machine whose slowest rate is above 40 Hz keeps 1 s segments
    fast = diagnose_signal(x[: int(3.0 * FS)], FS, RPM, "6205", waviness=False)
    assert fast.segment_scan["segment_s"] == SCAN_SEGMENT_S and fast.segment_scan["segments"] == 3
