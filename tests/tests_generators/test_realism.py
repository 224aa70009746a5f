"""Random slip of local-defect impacts and the measurement chain (docs/realism.md)."""

import math

import numba
import numpy as np
import pytest
from scipy import signal as sp_signal

from generators import (
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    SimulationSettings,
    bearing,
    simulate,
)
from generators import _kernels as K
from generators.measurement import (
    MachineBackground,
    StructuralMode,
    SupportStructure,
    anti_alias_filter,
    band_power,
    digitise,
    electronic_noise,
    fault_band,
    fault_band_powers,
    machine_background,
    sensor_response,
    transfer_path,
)
from generators.model import prepare, slip_line_factor

G6205 = bearing("6205")


@numba.njit(cache=True)
def _outer_race_excitation(p, wav, fs, n):
    """Sum over the balls of the outer-race pit depth they see (the kernel's time terms)."""
    trig = K._trig(wav)
    scratch = K._scratch(int(p[K.P_BALL_COUNT]))
    z = int(p[K.P_BALL_COUNT])
    out = np.zeros(n)
    for i in range(n):
        K._time_terms_at(i / fs, p, wav, trig, scratch)
        total = 0.0
        for j in range(z):
            total += scratch[0, j]
        out[i] = total
    return out


def _lines(prep, fs, seconds, harmonics):
    e = _outer_race_excitation(prep.p, prep.wav, fs, int(fs * seconds))
    bpfo = prep.p[K.P_CAGE_SPEED] * G6205.ball_count / (2 * np.pi)
    t = np.arange(e.size) / fs
    return np.array([np.mean(e * np.exp(-2j * np.pi * k * bpfo * t)) for k in harmonics])


def test_slip_smears_the_impact_lines_as_the_theory_of_random_phase_says():
    """Coherent part of harmonic k of BPFO shrinks by prod J0(k Z a_m) (random-phase sum).

    Six seeds of 30 s: the time average of exp(-i k Z psi) converges to its expectation; the
    scatter of one seed's ratio was measured at 0.003-0.023, so 0.04 is five standard errors
    of the six-seed mean.
    """
    harmonics = (1, 2, 3, 4, 6)
    pit = LocalizedDefect(surface="outer", length=3e-3, depth=20e-6)
    fs, seconds = 10000.0, 30.0
    periodic = prepare(G6205, OperatingCondition.from_rpm(1797, 300.0), pit, random_state=0)
    reference = _lines(periodic, fs, seconds, harmonics)
    op = OperatingCondition.from_rpm(1797, 300.0, random_slip=0.012, ball_jitter=0.004)
    measured, theory = [], []
    for seed in range(6):
        prep = prepare(G6205, op, pit, random_state=seed)
        measured.append(_lines(prep, fs, seconds, harmonics) / reference)
        theory.append([slip_line_factor(prep.wav, k * G6205.ball_count) for k in harmonics])
    measured = np.abs(np.mean(measured, axis=0))
    theory = np.mean(theory, axis=0)
    assert theory[0] > 0.9 and theory[-1] < 0.2  # the test spans weak to strong smearing
    np.testing.assert_allclose(measured, theory, atol=0.04)
    assert np.all(np.diff(measured) < 0)  # the higher the harmonic, the more it is smeared


def test_no_slip_adds_no_rows_and_slip_only_with_a_local_defect():
    op = OperatingCondition.from_rpm(1797, 300.0, random_slip=0.02, ball_jitter=0.01)
    healthy = prepare(G6205, op, random_state=1)
    assert healthy.wav.shape[0] == 0
    pit = LocalizedDefect(surface="inner", length=0.2e-3, depth=0.1e-3)
    plain = prepare(G6205, OperatingCondition.from_rpm(1797, 300.0), pit, random_state=1)
    slipping = prepare(G6205, op, pit, random_state=1)
    np.testing.assert_array_equal(slipping.wav[: plain.wav.shape[0]], plain.wav)
    slip = slipping.wav[plain.wav.shape[0] :]
    assert np.all(slip[:, K.W_SURFACE] == K.SURF_SLIP)
    cage = slip[slip[:, K.W_BALL] == -1]
    # the cage rows' speed fluctuation has the requested standard deviation
    speed = cage[:, K.W_SLIP_ANGLE] * cage[:, K.W_SLIP_RATE] / slipping.p[K.P_CAGE_SPEED]
    assert math.sqrt(np.sum(speed**2) / 2) == pytest.approx(0.02, rel=1e-12)
    pockets = slip[slip[:, K.W_BALL] >= 0]
    assert sorted(set(pockets[:, K.W_BALL].astype(int))) == list(range(G6205.ball_count))
    assert math.sqrt(np.sum(pockets[pockets[:, K.W_BALL] == 3, K.W_SLIP_ANGLE] ** 2) / 2) == (
        pytest.approx(0.01, rel=1e-12)
    )


@pytest.mark.parametrize("surface", ["outer", "inner", "ball"])
def test_a_slipping_fault_keeps_its_energy_but_loses_its_periodicity(surface):
    settings = SimulationSettings(
        fs=12000.0, duration=0.5, settle_time=0.05, channels=("housing_acceleration_y",)
    )
    pit = LocalizedDefect(surface=surface, length=0.5e-3, depth=0.2e-3, position=-math.pi / 2)
    runs = {}
    for slip in (0.0, 0.02):
        op = OperatingCondition.from_rpm(1797, 400.0, random_slip=slip, ball_jitter=0.005)
        runs[slip] = simulate(G6205, op, pit, settings=settings, random_state=3)[
            "housing_acceleration_y"
        ]
    assert np.all(np.isfinite(runs[0.02]))
    assert not np.array_equal(runs[0.0], runs[0.02])
    assert np.std(runs[0.02]) == pytest.approx(np.std(runs[0.0]), rel=0.2)


def test_slip_parameters_are_validated():
    with pytest.raises(ParameterError, match=r"random_slip = 0\.5.*\[0, 0\.1\]"):
        OperatingCondition.from_rpm(1797, 300.0, random_slip=0.5)
    with pytest.raises(ParameterError, match="ball_jitter"):
        OperatingCondition.from_rpm(1797, 300.0, ball_jitter=-0.1)


def _gain_at(y_of_x, fs, f):
    n = int(fs)
    t = np.arange(n) / fs
    x = np.sin(2 * np.pi * f * t)
    y = y_of_x(x)[n // 2 :]
    return np.sqrt(2) * np.std(y)


def test_transfer_path_modes_ring_at_their_frequencies_with_their_gains():
    fs = 48000.0
    modes = (
        StructuralMode(frequency=2000.0, damping=0.02, gain=1.0),
        StructuralMode(frequency=7000.0, damping=0.05, gain=0.5),
    )
    path = lambda x: transfer_path(x, fs, modes)  # noqa: E731
    assert _gain_at(path, fs, 2000.0) == pytest.approx(1.0, abs=0.02)
    assert _gain_at(path, fs, 7000.0) == pytest.approx(0.5, abs=0.02)
    assert _gain_at(path, fs, 4500.0) < 0.15  # between the modes
    x = np.random.default_rng(0).standard_normal(4096)
    np.testing.assert_array_equal(transfer_path(x, fs, ()), x)
    # modes above the band are out of reach of the record
    np.testing.assert_array_equal(transfer_path(x, 12000.0, modes[1:]), x)


def test_sensor_anti_alias_and_converter():
    fs = 48000.0
    sensor = lambda x: sensor_response(x, fs, 5000.0, 0.05)  # noqa: E731
    assert _gain_at(sensor, fs, 200.0) == pytest.approx(1.0, abs=0.01)
    assert _gain_at(sensor, fs, 5000.0) == pytest.approx(1 / (2 * 0.05), rel=0.05)
    aa = lambda x: anti_alias_filter(x, fs, 0.4, 8)  # noqa: E731
    assert _gain_at(aa, fs, 0.4 * fs) == pytest.approx(1 / math.sqrt(2), abs=0.02)
    assert _gain_at(aa, fs, 0.2 * fs) == pytest.approx(1.0, abs=0.01)
    assert _gain_at(aa, fs, 0.49 * fs) < 0.3
    x = np.linspace(-2.0, 2.0, 1001)
    y, clipped = digitise(x, 4, 1.0)
    assert clipped == pytest.approx(np.mean((x >= 1.0 - 2.0 / 16) | (x < -1.0)))
    assert len(np.unique(y)) == 16 and y.max() == pytest.approx(1.0 - 2.0 / 16)
    inside = np.abs(x) < 0.8
    assert np.max(np.abs(y - x)[inside]) <= 1.0 / 16 + 1e-12  # half a step
    with pytest.raises(ParameterError, match="bits"):
        digitise(x, 1, 1.0)


def test_the_electronics_noise_is_white_at_its_level_under_the_record():
    """``electronic_noise``: white noise whatever the record, its RMS ``floor_db`` under the
    record's (a tone's here); a level outside [-120, 0] dB names the parameter."""
    t = np.arange(48000) / 48000.0
    x = 3.0 * np.sin(2 * np.pi * 1000.0 * t)
    y, noise_rms = electronic_noise(x, -40.0, np.random.default_rng(4))
    assert noise_rms == pytest.approx(3.0 / math.sqrt(2) * 0.01, rel=1e-9)
    noise = y - x
    assert np.std(noise) == pytest.approx(noise_rms, rel=0.02)
    # white: no lag of its autocorrelation over 0.02 of its power (4 sigma for 48,000 samples)
    lags = [np.mean(noise[k:] * noise[:-k]) / np.mean(noise * noise) for k in (1, 2, 5)]
    assert max(abs(r) for r in lags) < 0.02, lags
    with pytest.raises(ParameterError, match=r"floor_db = 3.*\[-120, 0\] dB"):
        electronic_noise(x, 3.0, np.random.default_rng(4))


def test_machine_background_holds_its_lines_and_coloured_noise():
    fs, n = 12000.0, 120000
    rng = np.random.default_rng(5)
    modes = (StructuralMode(frequency=3000.0, damping=0.05),)
    spec = MachineBackground(
        broadband_rms=0.5,
        shaft_harmonics=(1.0, 0.5),
        line_frequency=60.0,
        line_harmonics=(0.0, 0.7),
        other_lines=((91.4, 0.3),),
    )
    y = machine_background(n, fs, 30.0, spec, modes, rng)
    f = np.fft.rfftfreq(n, 1 / fs)
    amp = 2 * np.abs(np.fft.rfft(y)) / n
    for freq, a in ((30.0, 1.0), (60.0, 0.5), (120.0, 0.7), (91.4, 0.3)):
        assert amp[np.argmin(np.abs(f - freq))] == pytest.approx(a, rel=0.1)
    noise = y - machine_background(
        n,
        fs,
        30.0,
        MachineBackground(
            shaft_harmonics=(1.0, 0.5), line_harmonics=(0.0, 0.7), other_lines=((91.4, 0.3),)
        ),
        modes,
        np.random.default_rng(5),
    )
    assert np.std(noise) == pytest.approx(0.5, rel=0.05)
    # coloured by the structure: most of its power within an octave of the mode
    octave = band_power(noise, fs, (3000 / math.sqrt(2), 3000 * math.sqrt(2)))
    assert octave / np.var(noise) > 0.6


def test_fault_band_finds_the_ringing_resonance():
    fs = 12000.0
    t = np.arange(24000) / fs
    impacts = np.zeros_like(t)
    impacts[:: int(fs / 107)] = 1.0
    ring = sp_signal.lfilter(*sp_signal.iirpeak(3500.0, 20.0, fs), impacts)
    low, high = fault_band(ring, fs)
    assert low < 3500.0 < high and high / low == pytest.approx(2.0, rel=1e-9)


def test_fault_band_is_where_the_fault_stands_out_most_over_the_rest():
    """Given everything else (``rest``), the band is the octave where the signature's power
    over the rest's is largest, not the octave of the signature's own peak: impacts ringing
    at 1 kHz (strong) and 4 kHz (10 dB weaker) under a machine whose noise rings at 1 kHz
    stand out at 4 kHz, where a detector finds them."""
    fs = 12000.0
    rng = np.random.default_rng(3)
    impacts = np.zeros(24000)
    impacts[:: int(fs / 107)] = 1.0
    low_ring = sp_signal.lfilter(*sp_signal.iirpeak(1000.0, 10.0, fs), impacts)
    high_ring = sp_signal.lfilter(*sp_signal.iirpeak(4000.0, 10.0, fs), impacts)
    signature = low_ring + high_ring * np.std(low_ring) / np.std(high_ring) / np.sqrt(10.0)
    rest = sp_signal.lfilter(*sp_signal.iirpeak(1000.0, 5.0, fs), rng.standard_normal(24000))
    rest = 10.0 * rest + 0.01 * rng.standard_normal(24000)
    peak_band = fault_band(signature, fs)
    assert peak_band[0] < 1000.0 < peak_band[1]
    band = fault_band(signature, fs, rest=rest)
    assert band[0] < 4000.0 < band[1] <= 0.45 * fs  # an octave, or its part under 0.45 fs

    def ratio(b):
        return band_power(signature, fs, b) / band_power(rest, fs, b)

    assert ratio(band) > 10.0 * ratio(peak_band)
    # the chain's single pass over both records gives the same band and powers
    assert fault_band_powers(signature, rest, fs) == (
        band,
        band_power(signature, fs, band),
        band_power(rest, fs, band),
    )


BALL_PITS = """
name = "ball-pits"
seed = 5
chunk_size = 16
[operating]
rpm = 1797
load_n = { min = 100, max = 500 }
random_slip = 0.01
ball_jitter_rad = 0.005
[sensor]
fs_hz = 12000
duration_s = 0.2
settle_s = 0.05
background_db = 10
fault_snr_db = 0
modes = 2
mode_hz = { min = 1000, max = 5000 }
[[conditions]]
label = "ball"
surface = "ball"
defect = "localized"
length_m = 0.3e-3
depth_m = 0.1e-3
axis_drift_rad_s = { min = 0, max = 0.2 }
count = 16
"""


def test_an_untouched_ball_pit_runs_as_its_healthy_twin_and_reaches_no_snr():
    """A ball pit the races never meet over the run (docs/realism.md 5) is simulated as the
    healthy bearing it is: the generator decides it from the latitude the pit sweeps, which
    must agree with the kernel's contact-track factor at every instant of the run."""
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import _setup, _untouched, generate_cases

    recipe = validate_recipe(tomllib.loads(BALL_PITS))
    cases = expand_cases(recipe)
    shared: dict = {}
    untouched = []
    for case in cases:
        job = _setup(recipe, case, "housing_acceleration_y", shared)
        faulty = prepare(
            G6205,
            OperatingCondition.from_rpm(case.rpm, case.radial_load_n, random_slip=0.01),
            LocalizedDefect(
                surface="ball",
                length=0.3e-3,
                depth=0.1e-3,
                latitude=None,
                axis_drift=case.defect_axis_drift_rad_s,
            ),
            settings=job.healthy.settings,
            random_state=np.random.default_rng(case.seed),
        )
        rows = [r for r in range(faulty.wav.shape[0]) if faulty.wav[r, K.W_SURFACE] >= 5]
        rows = [r for r in rows if faulty.wav[r, K.W_SURFACE] != K.SURF_SLIP]
        t = np.linspace(0.0, 0.25 + 1e-3, 5001)
        touched = any(K._track_factor(faulty.wav, r, ti)[0] > 0.0 for r in rows for ti in t)
        assert _untouched(faulty, job.healthy.settings) == (not touched)
        untouched.append(job.run is job.healthy)
    assert 0 < sum(untouched) < len(cases)  # both kinds in the draw
    # and integrated once: until stop 37 an untouched pit's run went to the lanes twice (as
    # the case's run and as its twin, the same object), a third of a rig recipe's lane work
    from generators import synthesis

    integrated = []

    def counting(preps, channel, **kwargs):
        integrated.extend(preps)
        return simulate_lanes(preps, channel, **kwargs)

    simulate_lanes = synthesis.simulate_lanes
    synthesis.simulate_lanes = counting
    try:
        frame = generate_cases(recipe, cases)
    finally:
        synthesis.simulate_lanes = simulate_lanes
    assert len({id(p) for p in integrated}) == len(integrated)
    # one lane run per case: an untouched pit's run, or a touched pit's healthy twin (its
    # faulty run goes to the one-signal kernel)
    assert len(integrated) == len(cases)
    for row, inert in zip(frame, untouched, strict=True):
        assert (row["fault_snr_db"] == -math.inf) == inert, (row["fault_snr_db"], inert)


def test_the_chain_filters_and_psd_equal_scipys_designs():
    """The closed-form sections and the vectorised Welch PSD (generators.measurement, written
    for speed) against scipy's bilinear/tf2sos and welch, which they replace."""
    from generators import measurement

    rng = np.random.default_rng(4)
    for fs, f0, zeta in ((12000.0, 3000.0, 0.05), (48000.0, 900.0, 0.01), (25600.0, 9000.0, 0.3)):
        w = measurement._prewarped(f0, fs)
        b, a = sp_signal.bilinear([2 * zeta * w, 0.0], [1.0, 2 * zeta * w, w * w], fs)
        np.testing.assert_allclose(
            measurement._band_pass(fs, f0, zeta), sp_signal.tf2sos(b, a), atol=1e-14
        )
        b, a = sp_signal.bilinear([w * w], [1.0, 2 * zeta * w, w * w], fs)
        np.testing.assert_allclose(
            measurement._bilinear_biquad((0.0, w * w), (2 * zeta * w, w * w), fs),
            sp_signal.tf2sos(b, a),
            atol=1e-14,
        )
    for n in (48000, 12001, 700, 512):
        x = rng.standard_normal(n)
        f, psd = sp_signal.welch(x, 1000.0, nperseg=min(512, n))
        f2, psd2 = measurement._welch(x, 1000.0, min(512, n))
        np.testing.assert_array_equal(f, f2)
        np.testing.assert_allclose(psd2, psd, rtol=1e-12)
    # a stack through the structure is each record through it
    stack = rng.standard_normal((2, 6000))
    modes = (measurement.StructuralMode(frequency=2000.0, damping=0.04, gain=0.5),)
    both = measurement.transfer_path(stack, 12000.0, modes)
    for row, record in zip(both, stack, strict=True):
        np.testing.assert_array_equal(row, measurement.transfer_path(record, 12000.0, modes))


def _scipy_causal(sos, x, fs):
    """What generators.measurement._causal computed with scipy before its numba kernel."""
    n = x.shape[-1]
    pad = min(n - 1, int(round(0.25 * fs)))
    lead = 2.0 * x[..., :1] - x[..., pad:0:-1]
    padded = np.concatenate([lead, x], axis=-1)
    zi = sp_signal.sosfilt_zi(sos)
    zi = zi.reshape(zi.shape[:1] + (1,) * (x.ndim - 1) + zi.shape[1:]) * padded[None, ..., :1]
    return sp_signal.sosfilt(sos, padded, axis=-1, zi=zi)[0][..., pad:]


def test_machine_background_lines_are_cosines_to_rounding():
    """The background's lines come from angle addition over blocks (generators._filters.
    add_line), not a cosine a sample: each must be a cos(2 pi f t + phase) to rounding, for
    record lengths that do and do not fill the last block. 1e-11 of its amplitude: the
    reference's own argument reaches 2 pi f t ~ 8e3 rad over 1 s, whose rounding alone is
    1e-12 rad (observed 1.5e-12)."""
    for n, fs in ((12000, 12000.0), (48013, 48000.0)):
        for frequency, amplitude in ((29.95, 1.0), (1234.5, 0.3)):
            spec = MachineBackground(other_lines=((frequency, amplitude),))
            y = machine_background(n, fs, 30.0, spec, (), np.random.default_rng(9))
            phase = np.random.default_rng(9).uniform(0.0, 2 * math.pi)
            t = np.arange(n) / fs
            expected = amplitude * np.cos(2 * math.pi * frequency * t + phase)
            assert np.max(np.abs(y - expected)) <= 1e-11 * amplitude


def test_the_chain_filters_run_as_scipys_sosfilt_from_steady_state():
    """The numba cascade (generators._filters) gives scipy's sosfilt with sosfilt_zi times the
    lead-in's first sample, to the last bit, for one record, a stack, several modes summed
    and an offset record (the steady state matters); the closed-form Butterworth has scipy's
    response (to 1e-12) and filters as scipy's design does (to 1e-9 of the RMS)."""
    from generators import measurement

    rng = np.random.default_rng(5)
    fs = 12000.0
    x = rng.standard_normal((2, 9000)) + 3.0
    for sos in (sp_signal.butter(7, 0.8, output="sos"), measurement._band_pass(fs, 2500.0, 0.02)):
        np.testing.assert_array_equal(measurement._causal(sos, x, fs), _scipy_causal(sos, x, fs))
        np.testing.assert_array_equal(
            measurement._causal(sos, x[0], fs), _scipy_causal(sos, x[0], fs)
        )
    modes = (
        StructuralMode(frequency=1500.0, damping=0.03, gain=0.7),
        StructuralMode(frequency=4000.0, damping=0.06, gain=1.3),
    )
    expected = np.zeros_like(x)
    for m in modes:
        expected += m.gain * _scipy_causal(
            measurement._band_pass(fs, m.frequency, m.damping), x, fs
        )
    np.testing.assert_array_equal(transfer_path(x, fs, modes), expected)
    for order in (1, 2, 5, 6, 7, 8):
        for cutoff in (0.1, 0.38, 0.45, 0.49):
            ours = measurement.butterworth_low_pass(order, cutoff)
            theirs = sp_signal.butter(order, 2.0 * cutoff, output="sos")
            _, h_ours = sp_signal.sosfreqz(ours, 2048)
            _, h_theirs = sp_signal.sosfreqz(theirs, 2048)
            np.testing.assert_allclose(h_ours, h_theirs, rtol=0, atol=1e-12)
            y = anti_alias_filter(x[0], fs, cutoff, order)
            np.testing.assert_allclose(y, _scipy_causal(theirs, x[0], fs), atol=1e-9 * np.std(y))
    with pytest.raises(ValueError, match="order"):
        measurement.butterworth_low_pass(0, 0.4)


LOAD_DIRECTION = """
name = "load-direction"
seed = 3
[operating]
rpm = 1797
load_n = 400
clearance_m = 5e-6
load_angle_deg = [0, -90]
[sensor]
fs_hz = 12000
duration_s = 0.3
settle_s = 0.05
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = 0.3e-3
depth_m = 0.1e-3
count = 2
[[conditions]]
label = "healthy"
count = 2
"""


def test_a_recipe_draws_the_loads_direction_and_the_outer_pit_follows_its_load_zone():
    """``operating.load_angle_deg`` turns the load away from the sensor's axis y (the rigs do
    not publish where it points; docs/realism.md 5). An outer-race pit's recipe position is
    read from the load, so the default pit stays at the load zone's centre (0 rad for a load
    along x), and its impacts, along the load, reach the vertical sensor through the
    bearing's cross-coupling only: 18 times weaker than under a vertical load (a quarter here),
    while the healthy bearing vibrates more in its lightly loaded direction (10 times; 2 here)."""
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import generate_cases

    recipe = validate_recipe(tomllib.loads(LOAD_DIRECTION))
    cases = expand_cases(recipe)
    assert [c.load_angle_rad for c in cases] == [0.0, -math.pi / 2] * 2
    assert [c.defect_position_rad for c in cases[:2]] == [0.0, -math.pi / 2]
    horizontal, vertical, healthy_horizontal, healthy_vertical = generate_cases(recipe, cases)
    assert (horizontal["load_angle_rad"], horizontal["defect_position_rad"]) == (0.0, 0.0)
    assert np.std(horizontal["signal"]) < 0.25 * np.std(vertical["signal"])
    assert np.std(healthy_horizontal["signal"]) > 2 * np.std(healthy_vertical["signal"])


RIG_STRUCTURE = """
name = "rig-structure"
seed = 4
[operating]
rpm = 1797
load_n = 400
[model]
shaft_mass_kg = [1, 4]
housing_mass_kg = [2, 16]
pedestal_stiffness_n_m = [5e7, 5e7]
film_damping_factor = [1, 0.1]
[sensor]
fs_hz = 12000
duration_s = 0.5
settle_s = 0.1
[[conditions]]
label = "healthy"
count = 2
"""


def test_a_recipe_draws_the_rigs_structure_and_the_housing_mode_follows_it():
    """``[model] shaft_mass_kg``, ``housing_mass_kg``, ``pedestal_stiffness_n_m`` and
    ``film_damping_factor`` (not
    published by the rigs: docs/realism.md 5) give each case its own Rig: the housing's mode
    on its pedestal, near sqrt(k / m_h) / 2 pi (800 Hz at 2 kg and 5e7 N/m), falls by about
    sqrt(8) at 16 kg (with a 4 kg shaft), and the signal with it."""
    import tomllib

    from generators import _kernels as K
    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import _setup, generate_cases

    recipe = validate_recipe(tomllib.loads(RIG_STRUCTURE))
    cases = expand_cases(recipe)
    masses = [(c.shaft_mass_kg, c.housing_mass_kg, c.pedestal_stiffness_n_m) for c in cases]
    assert masses == [(1.0, 2.0, 5e7), (4.0, 16.0, 5e7)]
    p = [_setup(recipe, c, "housing_acceleration_y", {}).run.p for c in cases]
    assert [(q[K.P_SHAFT_MASS], q[K.P_HOUSING_MASS]) for q in p] == [(1.0, 2.0), (4.0, 16.0)]
    # and the squeeze film's damping, a tenth of docs/model.md 4.4's estimate in the second
    assert [c.film_damping_factor for c in cases] == [1.0, 0.1]
    assert p[1][K.P_SQUEEZE_INNER] == pytest.approx(0.1 * p[0][K.P_SQUEEZE_INNER], rel=1e-12)
    light, heavy = generate_cases(recipe, cases)
    assert light["housing_mass_kg"] == 2.0 and heavy["housing_mass_kg"] == 16.0
    assert not np.allclose(light["signal"], heavy["signal"])
    from generators import OperatingCondition, Rig, Scene, bearing, natural_frequencies

    lowest = []
    for row in (light, heavy):
        rig = Rig(
            shaft_mass=row["shaft_mass_kg"],
            housing_mass=row["housing_mass_kg"],
            pedestal_stiffness=row["pedestal_stiffness_n_m"],
        )
        op = OperatingCondition.from_rpm(1797, 400.0)
        scene = Scene(level="shaft+housing")
        modes = natural_frequencies(bearing("6205"), op, scene=scene, rig=rig)
        lowest.append(float(np.min(modes)))
    assert lowest[1] < 0.6 * lowest[0], lowest


RIG_DAMPING = """
name = "rig-damping"
seed = 5
bearings = ["6205"]
[operating]
rpm = 1797
load_n = 400
clearance_m = 5e-6
[model]
scene = "shaft+housing"
ehl = false
shaft_mass_kg = [1, 1, 5, 5]
housing_mass_kg = [20, 20, 1, 1]
pedestal_stiffness_n_m = [2e8, 2e8, 2e7, 2e7]
{ratios}
[sensor]
fs_hz = 12000
duration_s = 0.2
[[conditions]]
label = "healthy"
count = 4
"""


def _lowest_mode_damping(run) -> float:
    """Damping ratio -Re(lambda) / |lambda| of the lowest oscillatory mode of a prepared run
    (the right-hand side linearised at its static start, docs/model.md 7.5)."""
    from generators.steps import jacobian

    lam = np.linalg.eigvals(jacobian(run.scene_code, run.ehl, run.p, run.wav, run.y0))
    osc = lam[lam.imag > 1.0]
    lowest = osc[np.argmin(np.abs(osc))]
    return float(-lowest.real / abs(lowest))


def test_a_recipe_draws_the_dashpots_as_damping_ratios():
    """``[model] housing_damping_ratio`` and ``shaft_damping_ratio`` set the pedestal damping
    to 2 zeta_h sqrt(k_h M_h) and the shaft damping to 2 zeta_s sqrt(k_r M_s), k_r the
    bearing's static radial stiffness at the case's load: a drawn structure keeps a plausible
    damping. With the Rig's fixed dashpots, a 20 kg housing on 2e8 N/m has its lowest mode at
    about 1.4 % damping and a 1 kg one on 2e7 N/m with a 5 kg shaft at 6.5 %; with zeta_h =
    0.05 and zeta_s = 0.03 both lie between 5 and 9 % (the two dashpots share the coupled
    modes: the lowest mode's ratio sits between zeta_h and zeta_h + zeta_s)."""
    import tomllib

    from generators import _kernels as K
    from generators import bearing, static_load_distribution
    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import _setup, generate_cases

    fixed = validate_recipe(tomllib.loads(RIG_DAMPING.format(ratios="")))
    drawn = validate_recipe(
        tomllib.loads(
            RIG_DAMPING.format(
                ratios="housing_damping_ratio = [0.05, 0.05, 0.05, 0.05]\n"
                "shaft_damping_ratio = [0.03, 0.03, 0.03, 0.03]"
            )
        )
    )
    k_r = static_load_distribution(
        bearing("6205", radial_internal_clearance=5e-6), 400.0
    ).radial_stiffness
    for recipe, ratios in ((fixed, False), (drawn, True)):
        cases = expand_cases(recipe)
        runs = [_setup(recipe, c, "housing_acceleration_y", {}).run for c in cases[::2]]
        zetas = [_lowest_mode_damping(run) for run in runs]
        if not ratios:
            assert all(np.isnan(c.housing_damping_ratio) for c in cases)
            assert [run.p[K.P_PEDESTAL_DAMPING] for run in runs] == [1e3, 1e3]
            assert [run.p[K.P_SHAFT_DAMPING] for run in runs] == [600.0, 600.0]
            assert zetas[0] < 0.02 and zetas[1] > 0.05, zetas
            continue
        assert [c.housing_damping_ratio for c in cases] == [0.05] * 4
        assert [c.shaft_damping_ratio for c in cases] == [0.03] * 4
        for run, (m_s, m_h, k_h) in zip(runs, ((1.0, 20.0, 2e8), (5.0, 1.0, 2e7)), strict=True):
            assert run.p[K.P_PEDESTAL_DAMPING] == pytest.approx(0.1 * np.sqrt(k_h * m_h), rel=1e-12)
            assert run.p[K.P_SHAFT_DAMPING] == pytest.approx(0.06 * np.sqrt(k_r * m_s), rel=1e-12)
        assert all(0.05 < z < 0.09 for z in zetas), zetas
    # the columns reach the dataset rows
    row = generate_cases(drawn, expand_cases(drawn)[:1])[0]
    assert (row["housing_damping_ratio"], row["shaft_damping_ratio"]) == (0.05, 0.03)
    row = generate_cases(fixed, expand_cases(fixed)[:1])[0]
    assert np.isnan(row["housing_damping_ratio"]) and np.isnan(row["shaft_damping_ratio"])


def test_the_support_structure_moves_the_housing_as_a_two_mass_model():
    """A force on the housing through ``SupportStructure.response`` (times M_h): the mass line
    (gain 1) far above the modes, the spring line M_h w^2 / k_h far below them (statics: the
    housing on its support, the shaft riding along), and its largest gain at the coupled
    system's lower natural frequency (undamped two-mass eigenvalue, within the 1 Hz bins)."""
    ms, mh, kr, kh = 2.0, 10.0, 8e7, 5e7
    support = SupportStructure(
        shaft_mass=ms,
        housing_mass=mh,
        bearing_stiffness=kr,
        pedestal_stiffness=kh,
        shaft_damping=200.0,
        pedestal_damping=300.0,
    )
    fs, n = 48000.0, 48000
    t = np.arange(n) / fs

    def gain(f):  # f on a bin of the record (the filter is circular)
        out = support.response(np.sin(2 * np.pi * f * t), fs)
        return np.std(out) / np.std(np.sin(2 * np.pi * f * t))

    # undamped eigenfrequencies of [[ms, 0], [0, mh]] x'' + [[kr, -kr], [-kr, kr + kh]] x = 0
    w2 = np.linalg.eigvals(np.linalg.solve(np.diag([ms, mh]), [[kr, -kr], [-kr, kr + kh]]))
    f_low, f_high = np.sort(np.sqrt(w2.real)) / (2 * np.pi)
    assert gain(round(20 * f_high)) == pytest.approx(1.0, rel=0.02)
    f = round(f_low / 20)
    assert gain(f) == pytest.approx(mh * (2 * np.pi * f) ** 2 / kh, rel=0.02)
    impulse = support.response(np.r_[1.0, np.zeros(n - 1)], fs)
    spectrum = np.abs(np.fft.rfft(impulse))  # 1 Hz bins
    assert abs(np.argmax(spectrum[1:4000]) + 1 - f_low) <= 2.0
    # and the machine's broadband noise carries the housing's mode once the support is given
    background = MachineBackground(broadband_rms=1.0)
    plain = machine_background(n, fs, 30.0, background, (), np.random.default_rng(2))
    through = machine_background(n, fs, 30.0, background, (), np.random.default_rng(2), support)
    octave = (f_low / math.sqrt(2), f_low * math.sqrt(2))
    assert band_power(plain, fs, octave) < 0.1
    assert band_power(through, fs, octave) > 5 * band_power(plain, fs, octave)


def test_a_force_on_the_rotor_fills_the_housing_antiresonance_at_the_shaft_mode():
    """A force on the housing is absorbed by the shaft at sqrt(k_r / M_s) (the housing's
    antiresonance: the numerator M_s s^2 + c_s s + k_r), where the bearing's own forces ring;
    a force on the shaft reaches the housing there with a resonance, M_h w^2 k_r / |det|, and
    falls as k_r / (M_s w^2) far above the modes. ``MachineBackground.rotor_force_ratio``
    adds it (0: the housing's force alone, the same draws as before)."""
    ms, mh, kr, kh = 2.0, 10.0, 8e7, 5e7
    cs, ch = 200.0, 300.0
    support = SupportStructure(
        shaft_mass=ms,
        housing_mass=mh,
        bearing_stiffness=kr,
        pedestal_stiffness=kh,
        shaft_damping=cs,
        pedestal_damping=ch,
    )
    fs, n = 48000.0, 48000
    zero = np.zeros(n)
    impulse = np.r_[1.0, np.zeros(n - 1)]
    housing = np.abs(np.fft.rfft(support.response(impulse, fs)))  # 1 Hz bins
    shaft = np.abs(np.fft.rfft(support.response(zero, fs, impulse)))
    f_shaft = round(math.sqrt(kr / ms) / (2 * math.pi))  # 1007 Hz
    w = 2 * np.pi * f_shaft
    s = 1j * w
    det = (ms * s**2 + cs * s + kr) * (mh * s**2 + ch * s + kh + kr) - kr * kr
    assert shaft[f_shaft] == pytest.approx(mh * w**2 * kr / abs(det), rel=1e-6)
    assert housing[f_shaft] < 0.03 * shaft[f_shaft]  # the antiresonance the rotor fills
    w_high = 2 * np.pi * 20000
    assert shaft[20000] == pytest.approx(kr / (ms * w_high**2), rel=0.02)
    # the two forces add linearly
    both = support.response(impulse, fs, impulse)
    assert np.allclose(both, support.response(impulse, fs) + support.response(zero, fs, impulse))
    # in the machine's background: the octave round the shaft mode filled, 0 the same as none
    octave = (f_shaft / math.sqrt(2), f_shaft * math.sqrt(2))
    noise = {}
    for ratio in (0.0, 3.0):
        background = MachineBackground(broadband_rms=1.0, rotor_force_ratio=ratio)
        rng = np.random.default_rng(4)
        noise[ratio] = machine_background(n, fs, 30.0, background, (), rng, support)
    old = machine_background(
        n, fs, 30.0, MachineBackground(broadband_rms=1.0), (), np.random.default_rng(4), support
    )
    assert np.array_equal(noise[0.0], old)
    assert band_power(noise[3.0], fs, octave) > 3 * band_power(noise[0.0], fs, octave)
    with pytest.raises(ParameterError, match="rotor_force_ratio"):
        MachineBackground(rotor_force_ratio=-1.0)
    with pytest.raises(ParameterError, match="shaft_force has shape"):
        support.response(impulse, fs, impulse[:-1])


def test_an_unloaded_bearing_keeps_a_support_structure_and_a_shaft_damping():
    """A recipe's load may be 0 N: a bearing with clearance is then loaded by the shaft's
    weight alone (the model applies it), and that is the stiffness the damping ratio and the
    machine noise's structure use; without gravity the shaft is free of the housing (k_r = 0)
    and the structure is the housing on its support, finite everywhere."""
    from generators import Rig, static_load_distribution
    from generators.synthesis import bearing_stiffness

    g = bearing("6205", radial_internal_clearance=10e-6)
    assert static_load_distribution(g, 0.0).radial_stiffness == 0.0
    weight = static_load_distribution(g, 2.0 * 9.81).radial_stiffness
    assert bearing_stiffness(g, 0.0, Rig(shaft_mass=2.0)) == weight > 1e6
    assert bearing_stiffness(g, 0.0, Rig(shaft_mass=2.0, gravity=False)) == 0.0
    loaded = static_load_distribution(g, 300.0).radial_stiffness
    assert bearing_stiffness(g, 300.0, Rig(shaft_mass=2.0)) == loaded
    free = SupportStructure(
        shaft_mass=1.0,
        housing_mass=4.0,
        bearing_stiffness=0.0,
        pedestal_stiffness=4e7,
        shaft_damping=0.0,
        pedestal_damping=400.0,
    )
    fs, n = 12000.0, 12000
    out = free.response(np.random.default_rng(1).standard_normal(n), fs)
    assert np.all(np.isfinite(out))
    spectrum = np.abs(np.fft.rfft(free.response(np.r_[1.0, np.zeros(n - 1)], fs)))
    # the housing alone on its support: sqrt(k_h / M_h) / 2 pi = 503 Hz
    assert abs(np.argmax(spectrum[1:]) + 1 - math.sqrt(4e7 / 4.0) / (2 * math.pi)) <= 2.0


UNLOADED = """
name = "unloaded"
seed = 6
bearings = ["6205"]
[operating]
rpm = 1797
load_n = 0
clearance_m = 10e-6
[model]
scene = "shaft+housing"
ehl = false
shaft_damping_ratio = 0.03
housing_damping_ratio = 0.05
[sensor]
fs_hz = 12000
duration_s = 0.2
background_db = 10
modes = 2
mode_hz = { min = 1000, max = 4000 }
[[conditions]]
label = "healthy"
count = 1
"""


def test_a_recipe_at_zero_load_generates_with_its_structure():
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import generate_cases

    recipe = validate_recipe(tomllib.loads(UNLOADED))
    (row,) = generate_cases(recipe, expand_cases(recipe))
    assert row["error"] is None and np.all(np.isfinite(row["signal"]))
    assert np.std(row["signal"]) > 0.0


def test_a_recipe_draws_the_rotor_force_into_its_chain_and_without_it_keeps_its_draws():
    """``[background] rotor_force_db`` is drawn last of the chain's background (its value in
    the ``chain`` JSON, within the range); the same recipe without the key draws every other
    value of the chain as before and its record differs only by the rotor's noise."""
    import json
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import generate_cases

    text = UNLOADED.replace("load_n = 0", "load_n = 300")
    text += "\n[background]\nfloor_db = { min = -20, max = 0 }\n"
    plain = validate_recipe(tomllib.loads(text))
    drawn = validate_recipe(tomllib.loads(text + "rotor_force_db = { min = -10, max = 10 }\n"))
    (without,) = generate_cases(plain, expand_cases(plain))
    (with_rotor,) = generate_cases(drawn, expand_cases(drawn))
    chain_without, chain_with = json.loads(without["chain"]), json.loads(with_rotor["chain"])
    assert "rotor_force_db" not in chain_without
    assert -10.0 <= chain_with.pop("rotor_force_db") <= 10.0
    assert chain_with == chain_without
    assert not np.array_equal(without["signal"], with_rotor["signal"])
