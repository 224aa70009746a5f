"""Long runs in blocks (generators.stream): the same signal as the in-memory run, bounded memory."""

import numpy as np
import pytest

from generators import (
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)
from generators.stream import simulate_stream

# A pit with random slip and inner-race waviness: every time-dependent term of the kernel
# (cage and shaft angles, waviness phases, the slip sum) must continue across blocks.
DEFECTS = [
    LocalizedDefect(surface="outer", length=0.5e-3, depth=20e-6),
    Waviness(surface="inner", order=8, amplitude=1e-6, phase=0.3),
]
OPERATING = OperatingCondition.from_rpm(1800, 500.0, random_slip=0.01)


@pytest.mark.parametrize(
    "step, oversample",
    [
        (None, None),  # the default: step 2e-5 s, longer than the record interval
        (1e-4, 2),  # five records per step, interpolated
        (4.8828125e-06, 4),  # the step divides the record interval: records on step starts
    ],
)
def test_streamed_blocks_are_the_in_memory_signal(step, oversample):
    settings = SimulationSettings(
        duration=0.2,
        settle_time=0.05,
        step=step,
        oversample=oversample,
        record_contact_loads=True,
    )
    whole = simulate(bearing("6205"), OPERATING, DEFECTS, settings=settings, random_state=3)
    stream = simulate_stream(
        bearing("6205"), OPERATING, DEFECTS, settings=settings, random_state=3, block_samples=700
    )
    blocks = list(stream)
    assert [b.start for b in blocks] == list(range(0, whole.time.size, 700))
    np.testing.assert_array_equal(np.concatenate([b.time for b in blocks]), whole.time)
    for name, reference in whole.signals.items():
        streamed = np.concatenate([b.signals[name] for b in blocks])
        rms = np.sqrt(np.mean(reference**2))
        error = np.abs(streamed - reference) / rms
        # the same steps and filter taps, rounding only (measured <= 1.2e-11), the ends too: the
        # runs record as far beyond their first and last samples as the filter reads (until
        # stop 46 the ten samples at each end saw the filter's line extension, 1.8e-4 of the RMS)
        assert error.max() < 1e-9, name
    loads = np.concatenate([b.contact_loads for b in blocks])
    # a record takes the loads at the nearer end of its step; where it sits half-way the
    # choice follows rounding, so a few records take the other end (one step's change)
    differs = np.abs(loads - whole.contact_loads).max(axis=(1, 2)) > 1e-6 * loads.max()
    assert differs.mean() < 0.02
    step_change = np.abs(np.diff(whole.contact_loads, axis=0)).max()
    assert np.abs(loads - whole.contact_loads).max() <= step_change
    assert {**stream.parameters, "streamed_block_samples": None} == {
        **whole.parameters,
        "streamed_block_samples": None,
    }


def test_memory_is_bounded_by_the_block_and_dopri5_is_refused():
    settings = SimulationSettings(duration=600.0, fs=51200.0)
    stream = simulate_stream(bearing("6205"), OPERATING, settings=settings)
    assert stream.n_samples == 600 * 51200
    assert stream.peak_memory_bytes() < 200e6  # the in-memory run: ~6 GB of records
    with pytest.raises(ParameterError, match="integrator = 'dopri5'"):
        simulate_stream(
            bearing("6205"), OPERATING, settings=SimulationSettings(integrator="dopri5")
        )
    with pytest.raises(ParameterError, match="block_samples = 0"):
        simulate_stream(bearing("6205"), OPERATING, block_samples=0)
