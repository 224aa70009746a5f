"""A line shared by two faults' harmonic series counts for the stronger fault only."""

import numpy as np
import pytest

from features import FeatureError, fault_evidence
from features.evidence import FALSE_ALARM, SHARED_LINE_SLIP, explain_shared_lines

BPFO, BPFI, TWO_BSF = 107.36, 162.19, 141.17  # a 6205 at 1797 rpm [Hz]


def _family(lines):
    """(name, (ratio dB, found Hz, bins searched, floor bins)) as fault_evidence records them."""
    return [(name, (ratio, found, 5, 60)) for name, ratio, found in lines]


def _outer_pit_families(bpfi_2x_found):
    return {
        "bpfo": _family([("1x", 40.0, BPFO), ("2x", 38.0, 2 * BPFO), ("3x", 36.0, 3 * BPFO)]),
        # the inner race's 2x searched within the slip finds the outer race's 3x
        "bpfi": _family(
            [("1x", 3.0, BPFI), ("2x", 36.0, bpfi_2x_found), ("3x", 2.0, 3 * BPFI)]
            + [("1x-", 2.0, BPFI - 29.95), ("1x+", 1.0, BPFI + 29.95)]
        ),
        # the ball's 3x finds a slip sideband of the outer race's 4x
        "two_bsf": _family(
            [("1x", 2.0, TWO_BSF), ("2x", 1.0, 2 * TWO_BSF), ("3x", 30.0, 4 * BPFO - 5.0)]
            + [("1x-", 1.0, TWO_BSF - 11.93), ("1x+", 2.0, TWO_BSF + 11.93)]
        ),
    }


def test_the_outer_races_harmonics_count_for_it_not_for_the_other_faults():
    families = _outer_pit_families(3 * BPFO)
    combined = explain_shared_lines(families, 6, 5, 60, 0.1)
    assert combined["bpfo"]["explained"] == []
    assert combined["bpfi"]["explained"] == [("2x", "bpfo", 3)]
    assert combined["two_bsf"]["explained"] == [("3x", "bpfo", 4)]
    assert combined["bpfo"]["false_alarm"] <= FALSE_ALARM
    # weighed without the shared lines, neither other fault is detected
    assert combined["bpfi"]["false_alarm"] > FALSE_ALARM
    assert combined["two_bsf"]["false_alarm"] > FALSE_ALARM
    # the strongest fault's weighing is the one it had alone
    alone = explain_shared_lines({"bpfo": families["bpfo"]}, 6, 5, 60, 0.1)["bpfo"]
    assert combined["bpfo"]["evidence_db"] == alone["evidence_db"]
    # and the explained lines counted, the other faults would have been detected
    for fault in ("bpfi", "two_bsf"):
        raw = explain_shared_lines({fault: families[fault]}, 6, 5, 60, 0.1)[fault]
        assert raw["false_alarm"] <= FALSE_ALARM < combined[fault]["false_alarm"]


def test_a_line_off_the_stronger_series_and_a_fault_not_detected_explain_nothing():
    # the inner race's own 2x, 2.3 Hz from 3 x BPFO (0.7 %), beyond the tolerance at 3 x BPFO
    # for a slip allowance of SHARED_LINE_SLIP per order? Only if it is wider than the gap:
    gap = 2 * BPFI - 3 * BPFO
    tolerance = 0.1 + SHARED_LINE_SLIP * 3 * BPFO
    assert gap < tolerance  # at 3 x BPFO a 6205's 2 x BPFI cannot be told from it: shared
    off = 3 * BPFO + 1.2 * tolerance
    combined = explain_shared_lines(_outer_pit_families(off), 6, 5, 60, 0.1)
    assert combined["bpfi"]["explained"] == []
    # an outer race that is not detected explains nothing: the shared line then goes the other
    # way, to the inner race, which its 36 dB at 2 x BPFI makes the detected fault
    weak = _outer_pit_families(3 * BPFO)
    weak["bpfo"] = _family([("1x", 3.0, BPFO), ("2x", 2.0, 2 * BPFO), ("3x", 2.0, 3 * BPFO)])
    combined = explain_shared_lines(weak, 6, 5, 60, 0.1)
    assert combined["bpfi"]["explained"] == [] and combined["bpfi"]["detected"]
    assert combined["bpfo"]["explained"] == [("3x", "bpfi", 2)]


def test_an_inner_race_faults_sidebands_are_its_own():
    """Lines at k BPFI -/+ m f_shaft (m <= 2) belong to a detected inner-race fault."""
    shaft = 29.95
    families = {
        "bpfi": _family(
            [("1x", 30.0, BPFI), ("2x", 25.0, 2 * BPFI), ("3x", 22.0, 3 * BPFI)]
            + [("1x-", 30.0, BPFI - shaft), ("1x+", 30.0, BPFI + shaft)]
        ),
        # the ball's 1x- finds BPFI - f_shaft, its 3x 3 BPFI - 2 f_shaft
        "two_bsf": _family(
            [("1x", 2.0, TWO_BSF), ("2x", 2.0, 2 * TWO_BSF), ("3x", 13.0, 3 * BPFI - 2 * shaft)]
            + [("1x-", 13.0, BPFI - shaft - 2.0), ("1x+", 8.0, TWO_BSF + 11.93)]
        ),
        "bpfo": _family([("1x", 8.0, BPFO), ("2x", 2.0, 2 * BPFO), ("3x", 20.0, 2 * BPFI)]),
    }
    spacings = {"bpfi": shaft, "two_bsf": 11.93, "bpfo": 0.0}
    combined = explain_shared_lines(families, 6, 5, 60, 0.5, spacings)
    assert combined["two_bsf"]["explained"] == [("3x", "bpfi", 3), ("1x-", "bpfi", 1)]
    assert combined["bpfo"]["explained"] == [("3x", "bpfi", 2)]
    # without the sideband spacing only the harmonic is explained
    plain = explain_shared_lines(families, 6, 5, 60, 0.5)
    assert plain["two_bsf"]["explained"] == []


def test_the_balls_cage_lines_leave_the_lines_another_fault_explains_out():
    """The ball's cage lines (FTF, 2 x FTF) join its family after the shared lines are given
    away: the outer race's 4x that the ball's 3x found still counts for the outer race."""
    from features.evidence import _with_cage_lines

    families = _outer_pit_families(3 * BPFO)
    combined = explain_shared_lines(families, 6, 5, 60, 0.1)
    cage = _family([("cage 1x", 3.0, 11.93), ("cage 2x", 2.0, 23.86)])
    ball = _with_cage_lines(combined["two_bsf"], families["two_bsf"], cage, 6, 5, 60)
    assert ball["explained"] == [("3x", "bpfo", 4)]
    assert [name for name, *_ in ball["lines"]] == ["1x", "2x", "3x", "1x-", "1x+"] + [
        "cage 1x",
        "cage 2x",
    ]
    assert dict((n, r) for n, r, _ in ball["lines"])["3x"] == 0.0
    assert not ball["detected"]
    # strong cage lines do make a ball of it
    loud = _family([("cage 1x", 30.0, 11.93), ("cage 2x", 25.0, 23.86)])
    assert _with_cage_lines(combined["two_bsf"], families["two_bsf"], loud, 6, 5, 60)["detected"]


def test_the_band_is_the_one_the_weighed_evidence_stands_highest_in_among_the_top_ones(
    monkeypatch,
):
    """features.evidence.best_band_evidence: with EVIDENCE_BANDS = 1 (as shipped) the band is
    the one a fault rate's line ranks highest (fault_band's), and envelope_spectrum's
    automatic band is the same; with more, the kept band is one of the bands the line ranks
    highest and its weighed evidence stands at least as far over the threshold."""
    import dataclasses

    import numpy as np

    import features
    import features.evidence as fe
    from features.separation import fault_band

    fs = 12000.0
    ctx = {"bpfo": BPFO, "bpfi": BPFI, "two_bsf": TWO_BSF, "shaft": 29.95, "ftf": 11.93}
    rng = np.random.default_rng(5)
    x = rng.standard_normal(int(fs))
    t = np.arange(int(0.01 * fs)) / fs
    ring = np.exp(-2 * np.pi * 2500.0 * 0.05 * t) * np.sin(2 * np.pi * 2500.0 * t)
    impact = 0.0
    while impact < 1.0 - 0.01:  # an outer race's impacts, 1 % jitter, ringing at 2.5 kHz
        i = int(impact * fs)
        x[i : i + ring.size] += 0.8 * ring
        impact += (1.0 + 0.01 * rng.standard_normal()) / BPFO

    def margin(evidence):
        return max(v["evidence_db"] for v in evidence.combined.values()) - evidence.threshold_db

    shipped = fe.fault_evidence(x, fs, ctx)
    rates = {k: ctx[k] for k in fe.EVIDENCE_FAULTS}
    alone = fault_band(shipped.random_part, fs, rates, ctx["ftf"])
    assert fe.EVIDENCE_BANDS == 1 and shipped.selection.band == alone.band
    _, _, band = features.envelope_spectrum(x, fs, fault_frequencies=ctx, return_band=True)
    assert band == shipped.selection.band
    monkeypatch.setattr(fe, "EVIDENCE_BANDS", 6)
    kept = fe.fault_evidence(x, fs, ctx)
    top = [tuple(alone.bands[i]) for i in np.argsort(-alone.scores_db.max(axis=1))[:6]]
    assert tuple(kept.selection.band) in top
    _, _, band = features.envelope_spectrum(x, fs, fault_frequencies=ctx, return_band=True)
    assert band == kept.selection.band != shipped.selection.band  # the library's is the rule's
    for b in top:  # and it is the highest of them, each family's test counted six times
        band_b = dataclasses.replace(alone, band=b)
        other = fe._evidence_in_band(shipped.random_part, fs, ctx, band_b, 6)
        assert margin(kept) >= margin(other) - 1e-9
        once = fe._evidence_in_band(shipped.random_part, fs, ctx, band_b)
        assert margin(once) > margin(other)  # which costs evidence: 7 tests, not 2


def test_the_cage_lines_are_weighed_only_in_records_of_enough_cage_revolutions():
    """features.evidence.MIN_CAGE_REVOLUTIONS: a record holding 10 or more cage revolutions
    weighs the ball's cage lines (FTF, 2 x FTF), a shorter one does not (its cage line lies a
    few bins from 0 Hz, where slow envelope changes stand), and the rest of the ball's family
    is weighed either way."""
    import numpy as np

    import features.evidence as fe

    fs, ftf = 12000.0, 11.93
    ctx = {"bpfo": BPFO, "bpfi": BPFI, "two_bsf": TWO_BSF, "shaft": 29.95, "ftf": ftf}
    x = np.random.default_rng(3).standard_normal(int(fs))

    def ball_lines(record):
        return [
            name for name, *_ in fe.fault_evidence(record, fs, ctx).combined["two_bsf"]["lines"]
        ]

    assert fe.MIN_CAGE_REVOLUTIONS == 10.0
    assert fe.cage_lines_weighed(1.0, ftf) and not fe.cage_lines_weighed(0.5, ftf)
    whole, short = ball_lines(x), ball_lines(x[: int(0.5 * fs)])  # 11.9 and 6.0 revolutions
    assert {"cage 1x", "cage 2x"} <= set(whole)
    assert not {"cage 1x", "cage 2x"} & set(short)
    assert [n for n in whole if not n.startswith("cage")] == short  # 1x-3x and sidebands


RATES = {"bpfo": BPFO, "bpfi": BPFI, "two_bsf": TWO_BSF, "shaft": 29.95, "ftf": 11.93}


@pytest.mark.parametrize(
    ("name", "value", "said"),
    [
        ("bpfi", 1600.0, r"'bpfi'\] = 1600 Hz is too high for fs = 12000 Hz.*below 1562\.5 Hz"),
        ("bpfo", -1.0, r"'bpfo'\] = -1\.0 Hz is outside the allowed range \(0, inf\)"),
        ("shaft", 7000.0, r"'shaft'\] = 7000 Hz is outside the allowed range \(0, 6000\) Hz"),
        ("ftf", float("nan"), r"'ftf'\] = nan Hz"),
    ],
)
def test_fault_evidence_names_a_rate_it_cannot_weigh(name, value, said):
    """A rate that is no frequency, or too fast for the record's rate, is refused by its key
    (before: an internal min_frequency, or scipy's CZT, in the message); the fastest rate
    the bands allow, just under fs / (2.56 x 3), is weighed."""
    x = np.random.default_rng(0).standard_normal(12000)
    with pytest.raises(FeatureError, match=r"fault_frequencies\[" + said):
        fault_evidence(x, 12000.0, {**RATES, name: value})
    assert fault_evidence(x, 12000.0, {**RATES, "bpfi": 1562.0}).threshold_db > 0


def test_the_weighed_evidence_columns_explain_a_ball_line_in_the_inner_races_window():
    """``evidence_<fault>_weighed_db`` is each fault's weighed evidence over the threshold (what
    the rule's verdict rests on). On the MFPT bearing at 25 Hz a ball pit's lower cage sideband,
    2 x BSF - FTF = 117.6 Hz, lies 1.1 % under BPFI (118.9 Hz), inside BPFI's slip window: the
    raw BPFI line of a ball pit stands high, its weighed evidence does not (the line counts for
    the ball), which is what lets a model tell this ball pit from an inner race (stop 78)."""
    from scipy import signal as sp_signal

    ctx = {  # the MFPT bearing at 25 Hz (generators.characteristic_frequencies)
        "shaft": 25.0,
        "ftf": 10.140562,
        "bpfo": 81.124498,
        "bpfi": 118.875502,
        "two_bsf": 127.727933,
    }
    fs, n = 48828.0, 2 * 48828
    rng = np.random.default_rng(78)
    times = np.arange(0.0, n / fs, 1.0 / ctx["two_bsf"])
    times = times + rng.normal(0.0, 0.005 / ctx["two_bsf"], times.size)  # slip
    impacts = np.zeros(n)
    index = np.clip(np.round(times * fs).astype(int), 0, n - 1)
    # the pit strikes hard only while its ball crosses the load zone: once per cage turn
    impacts[index] = (1.0 + np.cos(2.0 * np.pi * ctx["ftf"] * times)) ** 2
    x = sp_signal.lfilter(*sp_signal.iirpeak(6000.0, 20.0, fs), impacts)
    x = x / x.std() + 0.5 * rng.standard_normal(n)
    e = fault_evidence(x, fs, ctx)
    for fault in ("bpfo", "bpfi", "two_bsf"):
        weighed = e.combined[fault]["evidence_db"] - e.threshold_db
        assert e.features[f"evidence_{fault}_weighed_db"] == pytest.approx(weighed)
    # the ball's lower cage sideband stands in the inner race's window, well over its floor
    assert e.features["evidence_bpfi_h1_snr"] > 10.0
    assert e.lines["bpfi"][0][1] == pytest.approx(ctx["two_bsf"] - ctx["ftf"], abs=0.6)
    # weighed, it is the ball's: detected, the inner race far under it and under the threshold
    assert e.features["evidence_two_bsf_weighed_db"] > 0.0
    assert e.features["evidence_bpfi_weighed_db"] < 0.0
    assert e.features["evidence_two_bsf_weighed_db"] - e.features["evidence_bpfi_weighed_db"] > 10.0
