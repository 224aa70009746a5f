"""The entry-exit timing of a spall's events (features.severity; docs/diagnosis.md, Severity)."""

import numpy as np
import pytest
from scipy import signal as sp_signal

from features import FeatureError, ar_prediction_error, entry_exit_spacing

FS = 48000.0
RATE = 100.0  # impacts per second [Hz]


def _ringing(force: np.ndarray) -> np.ndarray:
    """Two structural modes (3 kHz, 3 % damping; 7 kHz, 5 %) driven by ``force``."""
    x = np.zeros_like(force)
    for frequency, damping, gain in ((3000.0, 0.03, 1.0), (7000.0, 0.05, 0.6)):
        _, a = sp_signal.iirpeak(frequency, 1.0 / (2.0 * damping), FS)
        x += gain * sp_signal.lfilter([1.0], a, force)
    return x


def _impacts(entry_gains, spacing=1.2e-3, noise=0.2, seed=0, between=(), lead=0.0):
    """1 s of impacts at RATE jittered by 1 % (slip), each preceded by an entry event
    ``spacing`` earlier of the next gain of ``entry_gains`` (cycled), and by the (time before
    [s], gain) events of ``between``, and by white noise of RMS 0.2 over the ``lead`` [s]
    before it; through two modes."""
    rng = np.random.default_rng(seed)
    n = int(FS)
    times = np.cumsum((1.0 + 0.01 * rng.standard_normal(int(RATE) + 2)) / RATE)
    force = np.zeros(n)
    for k, t in enumerate(times):
        events = ((0.0, 1.0), (spacing, entry_gains[k % len(entry_gains)]), *between)
        for before, gain in events:
            if 0 <= round((t - before) * FS) < n:
                force[round((t - before) * FS)] += gain
        start, stop = round((t - lead) * FS), round(t * FS)
        if lead and 0 <= start and stop < n:
            force[start:stop] += 0.2 * rng.standard_normal(stop - start)
    x = _ringing(force)
    return x / x.std() + noise * rng.standard_normal(n)


def _spacing(x):
    return entry_exit_spacing(
        x, FS, fault_rate=RATE, shaft_rate=29.0, ball_pass_rate=RATE, max_span_s=3e-3
    )


def test_the_prediction_error_puts_nothing_before_an_impact():
    """The AR filter is causal: a ringing impact becomes a burst at its start, with nothing
    before it (a zero-phase whitening spreads each impact both ways, and its precursors
    read as entry events)."""
    force = np.zeros(int(FS))
    at = np.arange(500, force.size - 500, 480)
    force[at] = 1.0
    x = _ringing(force) + 1e-3 * np.random.default_rng(1).standard_normal(force.size)
    y = ar_prediction_error(x, 48)
    before = sum(np.sum(y[i - 48 : i - 2] ** 2) for i in at)
    after = sum(np.sum(y[i : i + 5] ** 2) for i in at)
    assert before < 0.02 * after


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_two_events_are_timed_and_one_is_not(seed):
    """Entry events at 0.3 of the impact, 1.2 ms before it, in noise at 0.2 of the RMS: the
    spacing to a sample or so; impacts alone: nothing resolved, and why."""
    timed = _spacing(_impacts([0.3], seed=seed))
    assert timed.resolved and timed.impacts >= 60
    assert timed.spacing_s == pytest.approx(1.2e-3, abs=0.03e-3)
    assert timed.split_s <= 0.1e-3 and timed.entry_z > 6.0
    alone = _spacing(_impacts([0.0], seed=seed))
    assert not alone.resolved and np.isnan(alone.spacing_s)
    assert "no entry event" in alone.reason


def test_an_entry_barely_clear_of_the_noise_needs_both_halves_of_the_impacts():
    """Entry events at 0.16 of the impact in noise at 0.2 of the RMS stand just clear in the
    average over every impact, not in the odd or the even impacts' (whose noise is larger):
    no spacing is given for them. At 0.2 of the impact each half places the entry too, in
    most records: a level just clear of a threshold is detected with a probability, so at
    least 8 of 10 noise seeds (until stop 76 three seeds, each resolved, which held by the
    draw of the separation's instrument floor: benchmarks/floor_draws.py entry-exit)."""
    for seed in (0, 2, 4):
        faint = _spacing(_impacts([0.16], seed=seed))
        assert not faint.resolved and "odd and the even" in faint.reason
        assert faint.entry_z > 6.0  # the average over every impact did show it
    clear = [_spacing(_impacts([0.2], seed=seed)) for seed in range(10)]
    resolved = [read for read in clear if read.resolved]
    assert len(resolved) >= 8
    for read in resolved:
        assert read.spacing_s == pytest.approx(1.2e-3, abs=0.03e-3)


def test_the_entry_is_the_earliest_event_before_the_impact():
    """A ball that strikes the spall's floor between its entry and its exit makes a third
    event: the spacing is still the entry's."""
    result = _spacing(_impacts([0.3], between=((0.5e-3, 0.3),)))
    assert result.resolved and result.spacing_s == pytest.approx(1.2e-3, abs=0.03e-3)


def test_an_event_that_runs_into_the_impact_is_no_entry():
    """Noise over the 0.6 ms before each impact (a long event, not a separate one): the
    averaged envelope does not fall back between it and the impact, so nothing is timed."""
    result = _spacing(_impacts([0.0], lead=0.6e-3))
    assert not result.resolved and "no entry event" in result.reason


def test_a_random_part_given_is_not_separated_again():
    """`random_part` (the rule's own, `Evidence.random_part`) gives the identical timing."""
    from features import separate_discrete

    x = _impacts([0.3])
    rest = separate_discrete(x, FS, fundamentals=(29.0, RATE))
    given = entry_exit_spacing(
        x,
        FS,
        fault_rate=RATE,
        shaft_rate=29.0,
        ball_pass_rate=RATE,
        max_span_s=3e-3,
        random_part=rest,
    )
    alone = _spacing(x)
    assert given.resolved and given.spacing_s == alone.spacing_s
    np.testing.assert_array_equal(given.average, alone.average)
    with pytest.raises(FeatureError, match="random_part has shape"):
        entry_exit_spacing(
            x,
            FS,
            fault_rate=RATE,
            shaft_rate=29.0,
            ball_pass_rate=RATE,
            max_span_s=3e-3,
            random_part=rest[:-1],
        )


def test_bad_input_is_refused_by_name():
    x = _impacts([0.3])
    with pytest.raises(FeatureError, match="fs = 2000 Hz"):
        entry_exit_spacing(
            x, 2000.0, fault_rate=RATE, shaft_rate=29.0, ball_pass_rate=RATE, max_span_s=3e-3
        )
    with pytest.raises(FeatureError, match="fault_rate"):
        entry_exit_spacing(
            x, FS, fault_rate=0.0, shaft_rate=29.0, ball_pass_rate=RATE, max_span_s=3e-3
        )
    with pytest.raises(FeatureError, match="max_span_s"):
        entry_exit_spacing(
            x, FS, fault_rate=RATE, shaft_rate=29.0, ball_pass_rate=RATE, max_span_s=-1.0
        )
    with pytest.raises(FeatureError, match="order = 0"):
        ar_prediction_error(x, 0)
