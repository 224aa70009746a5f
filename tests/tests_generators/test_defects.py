"""Local defects: parameters, the ball's path over a pit, the kernel table, simulate().

The path is checked against its closed form: a ball of reduced rolling radius R_x pivoting over
the nearer edge sinks s(e) = R_x - sqrt(R_x^2 - e^2) (e the distance to that edge), never more
than the pit depth; the kernel's rate must equal the time derivative of its value.
"""

import dataclasses
import math

import numpy as np
import pytest

from generators import (
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    SimulationSettings,
    bearing,
    contact_geometry,
    defect_path,
    sagitta,
    simulate,
)
from generators import _kernels as K
from generators.model import prepare

INCH = 25.4e-3


@pytest.fixture(scope="module")
def b6205():
    return bearing("6205")


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"surface": "cage", "length": 1e-4, "depth": 1e-5}, "surface"),
        ({"surface": "outer", "length": 0.0, "depth": 1e-5}, "length"),
        ({"surface": "outer", "length": 1.0, "depth": 1e-5}, "length"),
        ({"surface": "outer", "length": 1e-4, "depth": -1e-6}, "depth"),
        ({"surface": "outer", "length": 1e-4, "depth": 1e-5, "ball": 2}, "ball"),
        ({"surface": "ball", "length": 1e-4, "depth": 1e-5, "ball": -1}, "ball"),
        ({"surface": "outer", "length": 1e-4, "depth": 1e-5, "latitude": 0.3}, "latitude"),
        ({"surface": "ball", "length": 1e-4, "depth": 1e-5, "axis_drift": 1e5}, "axis_drift"),
    ],
)
def test_bad_defect_names_parameter(kwargs, name):
    with pytest.raises(ParameterError, match=name):
        LocalizedDefect(**kwargs)


def test_ball_index_checked_against_bearing(b6205):
    op = OperatingCondition.from_rpm(1800, 500)
    with pytest.raises(ParameterError, match="ball = 9"):
        prepare(b6205, op, LocalizedDefect(surface="ball", length=1e-4, depth=1e-5, ball=9))


def test_sagitta_closed_form():
    assert sagitta(5e-3, 0.0) == 0.0
    # small e: e^2 / (2 R)
    assert sagitta(5e-3, 1e-4) == pytest.approx(1e-8 / 1e-2, rel=1e-3)
    assert sagitta(5e-3, 6e-3) == 5e-3


def test_defect_path_cwru_pits(b6205):
    """CWRU 0.007/0.021 inch pits, 0.011 inch deep: bridged; the sink is the sagitta."""
    rx_o = contact_geometry(b6205, "outer").rx
    rx_i = contact_geometry(b6205, "inner").rx
    for diameter in (0.007 * INCH, 0.021 * INCH):
        for surface in ("outer", "inner", "ball"):
            d = LocalizedDefect(surface=surface, length=diameter, depth=0.011 * INCH)
            path = defect_path(b6205, d)
            assert path.bridged
            assert path.max_sink_outer == pytest.approx(sagitta(rx_o, diameter / 2), rel=1e-12)
            assert path.max_sink_inner == pytest.approx(sagitta(rx_i, diameter / 2), rel=1e-12)
    # the 0.007 inch pit sinks the ball by ~0.8 um at the outer race, far less than its depth
    small = defect_path(b6205, LocalizedDefect(surface="outer", length=0.007 * INCH, depth=1e-4))
    assert 0.7e-6 < small.max_sink < 0.9e-6
    # a wide shallow spall is followed to its floor
    wide = defect_path(b6205, LocalizedDefect(surface="outer", length=2e-3, depth=1e-6))
    assert not wide.bridged and wide.max_sink == 1e-6
    # angular width: length over the surface radius at the contact
    outer_radius = 0.5 * (b6205.pitch_diameter + b6205.ball_diameter)
    assert small.half_width == pytest.approx(0.5 * 0.007 * INCH / outer_radius)


def _kernel_profile(b6205, defect, surface_row, times, shaft_angle_rate=0.0):
    op = OperatingCondition.from_rpm(1800, 500)
    prep = prepare(b6205, op, defect, random_state=1)
    z = b6205.ball_count
    out = np.zeros((8, z))
    values, rates = [], []
    for t in times:
        theta0 = prep.p[K.P_CAGE_ANGLE0] + prep.p[K.P_CAGE_SPEED] * t
        shaft = prep.p[K.P_SHAFT_ANGLE0] + prep.p[K.P_SHAFT_SPEED] * t
        trig = K._trig(prep.wav)
        K._phases(t, prep.p, prep.wav, trig)
        K._waviness(prep.wav, z, theta0, shaft, t, prep.p, trig, out, K.DEFECTS_ALL)
        values.append(out[surface_row].copy())
        rates.append(out[surface_row + 1].copy())
    return prep, np.array(values), np.array(rates)


@pytest.mark.parametrize(("surface", "row"), [("outer", 0), ("inner", 2), ("ball", 4)])
def test_kernel_path_matches_closed_form_and_its_rate(b6205, surface, row):
    length, depth = 0.5e-3, 3e-6  # reaches the floor (sagitta at the centre ~6.5 um)
    defect = LocalizedDefect(surface=surface, length=length, depth=depth, position=0.3)
    times = np.linspace(0.0, 0.2, 200001)
    prep, values, rates = _kernel_profile(b6205, defect, row, times)
    path = defect_path(b6205, defect)
    # never deeper than the floor, reaches it, and is zero outside the pit
    assert values.min() == pytest.approx(-depth, rel=1e-12)
    assert values.max() == 0.0
    # rate = d(value)/dt (central differences, away from the kinks)
    dt = times[1] - times[0]
    numeric = (values[2:] - values[:-2]) / (2 * dt)
    # (all three samples on the same smooth arc: not across an edge, the floor or the centre)
    smooth = (rates[:-2] * rates[1:-1] > 0) & (rates[1:-1] * rates[2:] > 0)
    assert smooth.sum() > 100
    assert np.allclose(rates[1:-1][smooth], numeric[smooth], rtol=2e-3, atol=1e-6 * rates.max())
    # depth of a bridged pit is the sagitta (no floor contact)
    shallow = LocalizedDefect(surface=surface, length=0.2e-3, depth=1e-3, position=0.3)
    _, v2, _ = _kernel_profile(b6205, shallow, row, times)
    rx = path.bridge_radius_outer if surface != "inner" else path.bridge_radius_inner
    # (the V-shaped bottom is sampled every 1 us: the deepest sample misses the centre by up
    # to half a sample, ~1 um of rolling at a 2e-2 slope: < 0.5 % of the sink)
    assert -v2.min() == pytest.approx(sagitta(rx, 0.1e-3), rel=5e-3)
    assert -v2.min() <= sagitta(rx, 0.1e-3)


def test_ball_defect_hits_both_races_once_per_spin(b6205):
    defect = LocalizedDefect(surface="ball", length=0.3e-3, depth=1e-3, position=0.0, ball=3)
    op = OperatingCondition.from_rpm(1800, 500)
    prep = prepare(b6205, op, defect, random_state=1)
    spin = prep.p[K.P_BALL_SPIN_SPEED]
    times = np.linspace(0, 2 * (2 * math.pi / spin), 40001)
    _, outer, _ = _kernel_profile(b6205, defect, 4, times)
    _, inner, _ = _kernel_profile(b6205, defect, 6, times)
    # only ball 3 carries it
    assert np.all(outer[:, [j for j in range(9) if j != 3]] == 0)
    # two hits per contact in two spins, half a spin apart between the contacts
    hits_o = np.flatnonzero(np.diff((outer[:, 3] < 0).astype(int)) == 1)
    hits_i = np.flatnonzero(np.diff((inner[:, 3] < 0).astype(int)) == 1)
    assert len(hits_o) == 2 and len(hits_i) == 2
    period = 2 * math.pi / spin
    assert times[hits_o[1]] - times[hits_o[0]] == pytest.approx(period, rel=1e-3)
    assert abs(times[hits_i[0]] - times[hits_o[0]]) == pytest.approx(period / 2, rel=1e-3)


def test_default_step_resolves_the_pit(b6205):
    """Near the pit the default RK4 steps are at most 1 / DEFECT_STEPS of a passage; the
    scene's step is kept elsewhere."""
    from generators.steps import DEFECT_STEPS

    op = OperatingCondition.from_rpm(1800, 500)
    d = LocalizedDefect(surface="outer", length=0.1e-3, depth=1e-4)
    r = simulate(b6205, op, d, settings=SimulationSettings(duration=0.02, settle_time=0.01))
    path = defect_path(b6205, d)
    passage = 2 * path.half_width / (2 * math.pi * r.frequencies.ftf)
    stats = r.parameters["integrator_stats"]
    healthy = simulate(b6205, op, settings=SimulationSettings(duration=0.02, settle_time=0.01))
    assert stats["step_s"] == healthy.parameters["integrator_stats"]["step_s"]
    assert stats["defect_step_s"] <= passage / DEFECT_STEPS * 1.0001
    assert stats["defect_step_s"] < stats["step_s"]
    record = r.parameters["defects"][0]
    assert record["kind"] == "LocalizedDefect"
    assert record["max_sink_m"] == pytest.approx(path.max_sink)


def test_zero_depth_is_healthy(b6205):
    op = OperatingCondition.from_rpm(1800, 500)
    s = SimulationSettings(duration=0.05, settle_time=0.02, fs=12800)
    healthy = simulate(b6205, op, settings=s)
    zero = simulate(b6205, op, LocalizedDefect(surface="inner", length=1e-4, depth=0.0), settings=s)
    assert np.array_equal(healthy["housing_acceleration_y"], zero["housing_acceleration_y"])


def _pit_table(b6205, surface, slip, jitter):
    """Kernel parameters and table of a 0.5 mm pit (met often) at 1800 rpm, 500 N, with slip."""
    op = OperatingCondition.from_rpm(1800, 500, random_slip=slip, ball_jitter=jitter)
    defect = LocalizedDefect(surface=surface, length=0.5e-3, depth=1e-4, latitude=0.0)
    prep = prepare(b6205, op, defect, random_state=4)
    return prep.p, prep.wav, b6205.ball_count


@pytest.mark.parametrize("surface", ["outer", "inner", "ball"])
def test_pit_rows_skipped_only_where_they_add_nothing(b6205, surface):
    """RK4 skips a pit's rows (and the slip angles at the half step) in steps where
    ``_defect_near`` finds no contact within reach: there, at any time inside the step, the rows
    must add exactly nothing. Checked at 4 instants in each of 20,000 steps of 20 us, with
    random slip and pocket jitter (the contact angles wander), for a pit wide enough to be met
    often (0.5 mm)."""
    p, wav, z = _pit_table(b6205, surface, 0.02, 0.01)
    dt = 2e-5
    trig = K._trig(wav)
    at_start = K._scratch(z)
    full, bare = K._scratch(z), K._scratch(z)
    skipped = met = acts = 0
    for n in range(20000):
        t = n * dt
        K._time_terms_at(t, p, wav, trig, at_start)  # the slip angles at the step's start
        if K._defect_near(wav, p, t, 1.5 * dt, at_start):
            K._phases(t + 0.5 * dt, p, wav, trig)
            K._time_terms(t + 0.5 * dt, p, wav, trig, full, K.DEFECTS_ALL)
            K._time_terms(t + 0.5 * dt, p, wav, trig, bare, K.DEFECTS_NONE)
            acts += not np.array_equal(full[:8], bare[:8])
            met += 1
            continue
        skipped += 1
        for frac in (0.0, 0.25, 0.5, 1.0):
            ts = t + frac * dt
            K._phases(ts, p, wav, trig)
            K._time_terms(ts, p, wav, trig, full, K.DEFECTS_ALL)
            K._time_terms(ts, p, wav, trig, bare, K.DEFECTS_NONE)
            np.testing.assert_array_equal(full[:8], bare[:8])
    assert acts > 50 and skipped > 10000  # both branches, and the pit really acts


@pytest.mark.parametrize(
    ("surface", "slip", "jitter"),
    [("outer", 0.02, 0.01), ("inner", 0.02, 0.01), ("ball", 0.02, 0.01), ("outer", 0.0, 0.0)],
)
def test_defect_test_skipped_only_where_it_would_say_no(b6205, surface, slip, jitter):
    """After a step with no contact in reach, RK4 skips the reach test for the steps
    ``_defect_clear_steps`` promises: ``_defect_near`` (the test itself, checked against the
    pit rows above) must say no at every one of them. Checked at each of 20,000 steps of 20 us,
    with random slip and pocket jitter, for a 0.5 mm pit; the skips must also be long (the
    point of them)."""
    p, wav, z = _pit_table(b6205, surface, slip, jitter)
    dt = 2e-5
    trig = K._trig(wav)
    scratch = K._scratch(z)
    slip_rate = K._slip_rate_bound(wav, z)
    near = np.zeros(20000, dtype=bool)
    promised = np.zeros(20000, dtype=np.int64)
    for n in range(20000):
        t = n * dt
        K._time_terms_at(t, p, wav, trig, scratch)
        near[n] = K._defect_near(wav, p, t, 1.5 * dt, scratch)
        promised[n] = K._defect_clear_steps(wav, p, t, 1.5 * dt, scratch, dt, slip_rate)
    for n in np.flatnonzero(promised > 0):
        assert not near[n + 1 : n + 1 + promised[n]].any(), (n, promised[n])
    # the steps RK4 tests: one after each skip
    tested, n = 0, 0
    while n < near.size:
        tested += 1
        n += 1 + max(promised[n], 0)
    assert near.sum() > 50 and tested < 0.2 * near.size


@pytest.mark.parametrize("surface", ["outer", "inner", "ball"])
def test_a_pit_only_table_skips_its_zero_rows_to_the_same_bytes(b6205, surface):
    """Away from the pits, RK4 evaluates only the clock of a table that holds local defects
    and slip only (its rows stay zero until a step near a pit writes them). A harmonic row of
    zero amplitude at the table's head adds exactly nothing but turns that shortcut off: the
    two runs must agree to the last bit."""
    from generators.model import integrate

    op = OperatingCondition.from_rpm(1797, 400, random_slip=0.01, ball_jitter=0.005)
    defect = LocalizedDefect(surface=surface, length=0.3e-3, depth=1e-4, latitude=0.0)
    settings = SimulationSettings(duration=0.05, settle_time=0.02, fs=12000.0)
    prep = prepare(b6205, op, defect, settings=settings, random_state=3)
    zero = np.zeros((1, prep.wav.shape[1]))
    zero[0, K.W_SURFACE], zero[0, K.W_ORDER] = K.SURF_OUTER, 9.0
    padded = dataclasses.replace(prep, wav=np.ascontiguousarray(np.vstack([zero, prep.wav])))
    channel = "housing_acceleration_y"
    shortcut = integrate(prep)[channel]
    full = integrate(padded)[channel]
    assert np.any(shortcut != integrate(prepare(b6205, op, settings=settings))[channel])
    np.testing.assert_array_equal(shortcut, full)


@pytest.mark.parametrize("surface", ["outer", "inner", "ball"])
@pytest.mark.parametrize(("length", "split"), [(0.2e-3, True), (0.6e-3, False)])
def test_rk4_shortcuts_near_pits_agree_with_dopri5(b6205, surface, length, split):
    """RK4 skips the reach test between pit passages, evaluates only the clock terms there and
    leaves the slip rows unrotated until a step reads them (computing them afresh then);
    DOPRI5 evaluates every term at every stage. For a 0.2 mm pit (RK4 splits the steps near
    it) and a 0.6 mm one (whose passage the default step resolves: not split, and until stop 37
    every term evaluated at every step) with 10 % slip and 0.05 rad pocket jitter, the pit's
    signature (faulty minus healthy) of the two must agree to 8 % RMS: measured 1.8-3.3 % for
    0.2 mm (RK4's own error near the pit), 0.15-0.34 % for 0.6 mm; with the slip rows read
    stale (the fresh computation left out) 27-64 %."""
    from generators.prepared import plan_run

    op = OperatingCondition.from_rpm(1797, 400, random_slip=0.1, ball_jitter=0.05)
    defect = LocalizedDefect(surface=surface, length=length, depth=1e-4, latitude=0.0)
    channel = ("housing_acceleration_y",)
    base = SimulationSettings(duration=0.1, settle_time=0.02, fs=12000.0, channels=channel)
    assert (plan_run(prepare(b6205, op, defect, settings=base)).fine_steps > 1) == split
    healthy = simulate(b6205, op, settings=base)[channel[0]]
    signatures = [
        simulate(b6205, op, defect, settings=settings, random_state=3)[channel[0]] - healthy
        for settings in (base, dataclasses.replace(base, integrator="dopri5", rtol=1e-7))
    ]
    rk4, dopri5 = signatures
    assert np.linalg.norm(dopri5) > 30 * np.linalg.norm(healthy)  # the pit is met
    assert np.linalg.norm(rk4 - dopri5) <= 0.08 * np.linalg.norm(dopri5)


@pytest.mark.parametrize("surface", ["outer", "inner"])
def test_a_lagging_cage_moves_a_pits_impact_rate(b6205, surface):
    """cage_slip s (the cage at 1 - s of its kinematic speed): an outer-race pit is struck at
    (1 - s) BPFO, an inner-race pit at BPFI + s BPFO (the inner race meets lagging balls
    faster). The envelope of the impacts' ringing (2-5 kHz) has its line there, 3 % of the
    rate (3-5 Hz) from the kinematic one, within a bin of 1 Hz."""
    from scipy import signal as sp_signal

    from generators import characteristic_frequencies

    slip, fs = 0.03, 12000.0
    op = OperatingCondition.from_rpm(1797, 400.0, cage_slip=slip)
    pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
    settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
    x = simulate(b6205, op, pit, settings=settings)["housing_acceleration_y"]
    sos = sp_signal.butter(4, (2000.0, 5000.0), btype="bandpass", fs=fs, output="sos")
    env = np.abs(sp_signal.hilbert(sp_signal.sosfiltfilt(sos, x)))
    spec = np.abs(np.fft.rfft((env - env.mean()) * np.hanning(env.size)))
    freqs = np.fft.rfftfreq(env.size, 1 / fs)
    kinematic = characteristic_frequencies(b6205, 1797 / 60)
    if surface == "outer":
        expected, kinematic_rate = (1 - slip) * kinematic.bpfo, kinematic.bpfo
    else:
        expected, kinematic_rate = kinematic.bpfi + slip * kinematic.bpfo, kinematic.bpfi
    near = (freqs > 0.9 * kinematic_rate) & (freqs < 1.1 * kinematic_rate)
    found = freqs[near][np.argmax(spec[near])]
    assert found == pytest.approx(expected, abs=1.0)
    assert abs(found - kinematic_rate) > 2.5
