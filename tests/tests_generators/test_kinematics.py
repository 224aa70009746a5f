"""Characteristic frequencies against the published multipliers and identities.

Published multipliers (x shaft frequency): ../shared/data/README.md (CWRU Bearing Data Center
tables for the 6205/6203, MFPT documentation). They are given to 4-5 significant digits, so the
tolerance is one unit in the 4th significant digit: PUBLISHED_RTOL = 5e-4 (the CWRU 6203 FTF,
0.3817 published vs 0.38164 from its geometry, is the largest difference, 1.6e-4).
"""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from generators import (
    ParameterError,
    bearing,
    characteristic_frequencies,
    waviness_passage_frequencies,
)

PUBLISHED_RTOL = 5e-4
ANALYTIC_RTOL = 1e-12

PUBLISHED = {
    "6205": {"bpfo": 3.5848, "bpfi": 5.4152, "ftf": 0.39828, "bsf": 2.3567, "two_bsf": 4.7135},
    "6203": {"bpfo": 3.0530, "bpfi": 4.9469, "ftf": 0.3817, "bsf": 1.9938, "two_bsf": 3.9874},
    "mfpt": {"bpfo": 3.245, "bpfi": 4.755, "ftf": 0.4056, "bsf": 2.5546, "two_bsf": 5.109},
}


@pytest.mark.parametrize("name", sorted(PUBLISHED))
def test_published_multipliers(name):
    orders = characteristic_frequencies(bearing(name), 1.0).orders()
    for key, value in PUBLISHED[name].items():
        assert orders[key] == pytest.approx(value, rel=PUBLISHED_RTOL), key


def test_cwru_bpfo_at_1797_rpm():
    # CWRU: BPFO 107.36 Hz at 1797 rpm (docs/model.md section 2)
    f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    assert f.bpfo == pytest.approx(107.36, abs=0.005)
    assert f.ftf == pytest.approx(11.93, abs=0.005)
    assert f.bpfi == pytest.approx(162.19, abs=0.005)
    assert f.bsf == pytest.approx(70.58, abs=0.005)


@settings(deadline=None, max_examples=60)
@given(
    name=st.sampled_from(["6205", "6203", "6305", "6002", "6308", "mfpt"]),
    fs=st.floats(min_value=0.1, max_value=500.0),
)
def test_identities(name, fs):
    g = bearing(name)
    f = characteristic_frequencies(g, fs)
    z = g.ball_count
    assert f.bpfo + f.bpfi == pytest.approx(z * fs, rel=ANALYTIC_RTOL)
    assert f.bpfo == pytest.approx(z * f.ftf, rel=ANALYTIC_RTOL)
    assert f.two_bsf == pytest.approx(2 * f.bsf, rel=ANALYTIC_RTOL)
    gamma = g.ball_diameter / g.pitch_diameter
    assert f.bsf == pytest.approx(
        g.pitch_diameter / (2 * g.ball_diameter) * fs * (1 - gamma**2), rel=1e-12
    )


def test_cage_slip_slows_cage():
    g = bearing("6205")
    f0 = characteristic_frequencies(g, 30.0)
    f1 = characteristic_frequencies(g, 30.0, cage_slip=0.1)
    assert f1.ftf == pytest.approx(0.9 * f0.ftf)
    assert f1.bpfo == pytest.approx(0.9 * f0.bpfo)


def test_bad_speed():
    with pytest.raises(ParameterError, match="shaft_frequency_hz = 0"):
        characteristic_frequencies(bearing("6205"), 0.0)
    with pytest.raises(ParameterError, match="shaft_frequency_hz = nan"):
        characteristic_frequencies(bearing("6205"), math.nan)


def test_wpf_outer_rules():
    # docs/model.md 2.1: outer order k excites q BPFO; k = qZ +- 1 radial, k = qZ load only
    g = bearing("6205")
    f = characteristic_frequencies(g, 30.0)
    for k, direction in ((8, "radial"), (9, "load"), (10, "radial")):
        lines = waviness_passage_frequencies(g, 30.0, "outer", k, max_harmonic=1)
        assert lines[0].frequency == pytest.approx(f.bpfo)
        assert lines[0].direction == direction
        assert lines[0].strength == "strong"
    weak = waviness_passage_frequencies(g, 30.0, "outer", 5, max_harmonic=1)
    assert weak[0].strength == "weak"


def test_wpf_inner_matches_model_md_table():
    # docs/model.md 2.1: 6205 at 1800 rpm, k = 8, 9, 10, 17, 18, 19 -> 132.4, 162.4, 192.4, 294.8,
    # 324.8, 354.8 Hz (the q with |k - qZ| <= 1). docs/model.md's values are built from a BPFI
    # rounded to 162.4 Hz; T8 asks for "within one frequency bin" of a 1 s record (1 Hz):
    # abs = 0.5 Hz.
    # The exact rule (2.1), f = k f_s - q Z f_c, is checked to machine precision.
    g = bearing("6205")
    expected = {8: 132.4, 9: 162.4, 10: 192.4, 17: 294.8, 18: 324.8, 19: 354.8}
    for k, freq in expected.items():
        strong = [
            ln
            for ln in waviness_passage_frequencies(g, 30.0, "inner", k)
            if ln.strength == "strong"
        ]
        assert len(strong) == 1
        assert strong[0].frequency == pytest.approx(freq, abs=0.5)
        f = characteristic_frequencies(g, 30.0)
        q = strong[0].harmonic
        assert strong[0].frequency == pytest.approx(k * 30.0 - q * 9 * f.ftf, rel=ANALYTIC_RTOL)
        assert strong[0].frequency == pytest.approx(
            q * f.bpfi + (k - q * 9) * 30.0, rel=ANALYTIC_RTOL
        )


def test_wpf_ball_even_orders_only():
    g = bearing("6205")
    f = characteristic_frequencies(g, 30.0)
    assert waviness_passage_frequencies(g, 30.0, "ball", 3) == []
    lines = waviness_passage_frequencies(g, 30.0, "ball", 4)
    freqs = sorted(ln.frequency for ln in lines)
    assert freqs == pytest.approx([4 * f.bsf - f.ftf, 4 * f.bsf, 4 * f.bsf + f.ftf])


def test_wpf_bad_surface():
    with pytest.raises(ParameterError, match="surface = 'cage'"):
        waviness_passage_frequencies(bearing("6205"), 30.0, "cage", 9)
