"""The dynamic model against a slow reference, its static start, and its basic contracts.

Tolerances:
* REFERENCE_RTOL_DRY = 1e-6: same equations and contact law as tests/reference.py, RK4 at
  0.1 us vs DOP853 at rtol 1e-11 over 4 ms (observed 3e-7 for the full scene).
* REFERENCE_RTOL_EHL = 1e-6: the kernel interpolates the implicit film equation from a table
  (cubic Hermite, 2048 nodes), the reference solves it with brentq to 1e-13 (observed 3.6e-8;
  the two-Newton-step solution used outside the table gives 1.5e-5).
* STATIC_ACCEL: the static start leaves a residual acceleration from the solver tolerances and
  the rate terms of the rotating cage; 1 m/s^2 is 1e-3 of the load acceleration Q / M_s.
"""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from generators import (
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    _integrators,
    bearing,
    resolve_scene,
    simulate,
    static_load_distribution,
)
from generators import _kernels as K
from generators.model import CHANNELS, prepare

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from reference import reference_solution, rk4_records  # noqa: E402

REFERENCE_RTOL_DRY = 1e-6
REFERENCE_RTOL_EHL = 1e-6
STATIC_ACCEL = 1.0

G6205 = bearing("6205")
OP = OperatingCondition.from_rpm(1800, 500.0)
DEFECTS = [
    Waviness(surface="outer", order=9, amplitude=1e-6),
    Waviness(surface="inner", order=10, amplitude=0.5e-6, phase=0.3),
    Waviness(surface="ball", order=2, amplitude=0.3e-6, phase=None),
]


def kernel_states(prep, n, record_dt, substeps):
    return rk4_records(prep, record_dt, n, substeps)


@pytest.mark.parametrize(
    ("level", "ehl", "rtol"),
    [
        ("shaft", False, REFERENCE_RTOL_DRY),
        ("shaft+housing", False, REFERENCE_RTOL_DRY),
        ("full", False, REFERENCE_RTOL_DRY),
        ("shaft", True, REFERENCE_RTOL_EHL),
        ("shaft+housing", True, REFERENCE_RTOL_EHL),
    ],
)
def test_kernel_matches_numpy_reference(level, ehl, rtol):
    prep = prepare(G6205, OP, DEFECTS, scene=Scene(level=level, ehl=ehl), random_state=1)
    n, record_dt = 101, 4e-5
    st, _ = kernel_states(prep, n, record_dt, 40)
    ref = reference_solution(prep, np.arange(n) * record_dt)
    nd = len(prep.y0) // 2
    ref = ref[:, [0, 1, 2, 3, nd, nd + 1, nd + 2, nd + 3]]
    vel_err = np.abs(st[:, 4:] - ref[:, 4:]).max() / np.abs(ref[:, 4:]).max()
    assert vel_err < rtol
    disp = ref[:, :4] - ref[0, :4]
    assert np.abs(st[:, :4] - ref[:, :4]).max() / np.abs(disp).max() < rtol


@pytest.mark.validation
def test_full_scene_with_ehl_matches_reference():
    prep = prepare(G6205, OP, DEFECTS[:1], scene=Scene(level="full", ehl=True), random_state=1)
    n, record_dt = 51, 4e-5
    st, _ = kernel_states(prep, n, record_dt, 40)
    ref = reference_solution(prep, np.arange(n) * record_dt)
    nd = len(prep.y0) // 2
    ref = ref[:, [nd, nd + 1, nd + 2, nd + 3]]
    assert np.abs(st[:, 4:] - ref).max() / np.abs(ref).max() < REFERENCE_RTOL_EHL


def test_the_film_holds_scene_fulls_unloaded_balls_at_low_speed():
    """At 370 rpm a 6205's unloaded balls are held on the outer race by hundredths of a newton
    of centrifugal force; without the film between ball and race apart they chattered,
    opening and closing the outer contacts 456 times a second where a steady load zone makes
    2 Z FTF = 44 (docs/model.md 7.4). With it (62 N, 5 um clearance, scene full with EHL) each
    ball enters and leaves the load zone once per cage turn (outer loads over 0.1 N: within
    10 % of 2 Z FTF), and what is not periodic at the ball pass is under 8 % of the housing's
    RMS (12 % without the film's term, 5 % with it)."""
    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(
        fs=12000.0,
        duration=1.0,
        channels=("housing_acceleration_y",),
        record_contact_loads=True,
    )
    r = simulate(
        g,
        OperatingCondition.from_rpm(370, 62.0),
        scene=Scene(level="full", ehl=True),
        settings=settings,
    )
    loaded = r.contact_loads[:, 1, :] > 0.1
    transitions = np.abs(np.diff(loaded.astype(int), axis=0)).sum() / settings.duration
    assert transitions == pytest.approx(2 * g.ball_count * r.frequencies.ftf, rel=0.1)
    x = r["housing_acceleration_y"]
    t = np.arange(x.size) / r.fs
    orders = np.arange(1, int(0.45 * r.fs // r.frequencies.bpfo) + 1)
    phase = 2 * np.pi * np.outer(t, orders * r.frequencies.bpfo)
    basis = np.hstack([np.cos(phase), np.sin(phase), np.ones((x.size, 1))])
    rest = x - basis @ np.linalg.lstsq(basis, x, rcond=None)[0]
    assert np.std(rest) < 0.08 * np.std(x)


@pytest.mark.parametrize("level", ["shaft", "shaft+housing", "full"])
@pytest.mark.parametrize("ehl", [False, True])
def test_static_start_is_an_equilibrium(level, ehl):
    # frozen cage (speeds zero): the start state must have (almost) no acceleration
    prep = prepare(G6205, OP, scene=Scene(level=level, ehl=ehl))
    p = prep.p.copy()
    if level == "full":
        # keep the centrifugal term of the cage frame but no rate terms
        p[K.P_SHAFT_SPEED] = p[K.P_BALL_SPIN_SPEED] = 0.0
    else:
        p[K.P_SHAFT_SPEED] = p[K.P_CAGE_SPEED] = p[K.P_BALL_SPIN_SPEED] = 0.0
    dydt = np.zeros_like(prep.y0)
    loads = np.zeros((2, 9))
    _integrators._rhs_once(prep.scene_code, int(ehl), 0.0, prep.y0, p, prep.wav, dydt, loads)
    nd = len(prep.y0) // 2
    assert np.abs(dydt[nd : nd + 4]).max() < STATIC_ACCEL
    if level == "full":
        assert np.abs(dydt[nd + 4 :]).max() < 1e3 * STATIC_ACCEL  # ball: 2 g, forces of 1e2 N


@pytest.mark.parametrize("level", ["shaft", "shaft+housing", "full"])
@pytest.mark.parametrize("ehl", [False, True])
def test_static_start_is_an_equilibrium_of_the_reference_equations(level, ehl):
    """The start the package computes, checked against docs/model.md's equations written
    independently (tests/reference.py): a wrong contact constant or film moves it off."""
    from reference import ReferenceModel

    prep = prepare(G6205, OP, scene=Scene(level=level, ehl=ehl))
    acc = ReferenceModel(prep).frozen_accelerations(prep.y0)
    assert np.abs(acc[:4]).max() < STATIC_ACCEL  # 1e-3 of Q / M_s
    if level == "full":
        assert np.abs(acc[4:]).max() < 1e3 * STATIC_ACCEL


def test_static_start_equals_static_load_distribution():
    rig = Rig(gravity=False)
    prep = prepare(G6205, OP, scene=Scene(level="shaft+housing", ehl=False), rig=rig)
    st = static_load_distribution(G6205, 500.0, cage_angle=0.0)
    rel = prep.y0[0:2] - prep.y0[2:4]
    np.testing.assert_allclose(rel, st.displacement, rtol=1e-9, atol=1e-15)
    # housing sits on its pedestal: k_h x_h = load
    assert prep.y0[3] == pytest.approx(-500.0 / rig.pedestal_stiffness, rel=1e-12)


def test_ehl_start_is_film_closer():
    # T12: the films act as a negative clearance of about h_i + h_o. The dry bearing with its
    # diametral clearance reduced by 2 (h_i + h_o) at Q_max must sit within 5 % of the same
    # place (lighter balls have slightly thicker films: h ~ Q^-0.067).
    dry = prepare(G6205, OP, scene=Scene(level="shaft+housing", ehl=False))
    wet = prepare(G6205, OP, scene=Scene(level="shaft+housing", ehl=True))
    shift = (wet.y0[1] - wet.y0[3]) - (dry.y0[1] - dry.y0[3])
    p = wet.p
    film = (p[K.P_FILM_INNER] + p[K.P_FILM_OUTER]) * wet.max_ball_load**K.FILM_EXPONENT
    closer = bearing("6205", radial_internal_clearance=G6205.radial_internal_clearance - 2 * film)
    equivalent = prepare(closer, OP, scene=Scene(level="shaft+housing", ehl=False))
    expected = (equivalent.y0[1] - equivalent.y0[3]) - (dry.y0[1] - dry.y0[3])
    assert shift > film > 0
    assert shift == pytest.approx(expected, rel=0.05)


def test_result_channels_and_frame():
    st = SimulationSettings(fs=10240.0, duration=0.05, settle_time=0.01)
    r = simulate(G6205, OP, DEFECTS[0], settings=st)
    assert set(r.signals) == set(CHANNELS)
    assert r.time.shape == (512,)
    frame = r.to_frame()
    assert list(frame.columns) == ["time", *CHANNELS]
    for v in r.signals.values():
        assert np.all(np.isfinite(v))
    assert r.parameters["scene"]["resolved_level"] == "shaft+housing"
    assert r.frequencies.bpfo == pytest.approx(3.58478 * 30.0, rel=1e-4)


def test_contact_loads_recorded_on_request():
    st = SimulationSettings(fs=5120.0, duration=0.02, settle_time=0.01, record_contact_loads=True)
    r = simulate(G6205, OP, settings=st, scene=Scene(level="full", ehl=False))
    assert r.contact_loads.shape == (r.time.size, 2, 9)
    # Stribeck with clearance: Q_max ~ 5 F_r / Z (docs/model.md 3.4); the static solution of
    # this bearing gives 4.87, the running one (varying compliance, ball inertia) 5.11
    static = static_load_distribution(G6205, 500.0).max_ball_load
    assert r.contact_loads.max() * 9 / 500.0 == pytest.approx(5.0, abs=0.25)
    assert r.contact_loads.max() == pytest.approx(static, rel=0.08)
    assert r.contact_loads.min() >= 0.0


def test_divergence_is_reported_not_returned():
    # an RK4 step far beyond the ball-mode stability limit must stop with a clear error
    st = SimulationSettings(fs=5120.0, duration=0.05, settle_time=0.0, step=1e-4)
    with pytest.raises(SimulationDivergedError, match=r"full/dry at t = ") as err:
        simulate(G6205, OP, settings=st, scene=Scene(level="full", ehl=False))
    assert err.value.scene == "full"
    assert err.value.time >= 0.0


def test_a_run_that_diverges_at_its_default_step_runs_again_at_a_shorter_one():
    """A dry `full` 6205 under no load with a 1 mm x 20 um ball pit on its rolling circle, 1800
    rpm: the pit knocks the ball into firmer contact than the static start that sets the
    default step (14.3 us) and RK4 diverges there; half the step runs through (docs/model.md
    7.2). The result is that of the shorter step given, and the default step given diverges."""
    import dataclasses

    from generators import LocalizedDefect, StepShortenedWarning
    from generators.prepared import plan_run

    pit = LocalizedDefect(surface="ball", length=1e-3, depth=2e-5)
    loose = OperatingCondition.from_rpm(1800, 0.0)
    dry_full = Scene(level="full", ehl=False)
    st = SimulationSettings(
        fs=12000.0, duration=0.05, settle_time=0.01, channels=("housing_acceleration_y",)
    )
    with pytest.warns(StepShortenedWarning, match="diverged at its default RK4 step"):
        r = simulate(G6205, loose, pit, scene=dry_full, settings=st, random_state=1)
    stats = r.parameters["integrator_stats"]
    default = plan_run(prepare(G6205, loose, pit, scene=dry_full, settings=st)).dt
    assert stats["step_halvings"] >= 1 and stats["step_s"] <= default / 2.0
    given = dataclasses.replace(st, step=stats["step_s"])
    again = simulate(G6205, loose, pit, scene=dry_full, settings=given, random_state=1)
    np.testing.assert_array_equal(r["housing_acceleration_y"], again["housing_acceleration_y"])
    with pytest.raises(SimulationDivergedError, match="full/dry"):
        simulate(G6205, loose, pit, scene=dry_full, settings=dataclasses.replace(st, step=default))


def test_same_seed_same_signal():
    st = SimulationSettings(fs=5120.0, duration=0.02, settle_time=0.005)
    ball = Waviness(surface="ball", order=4, amplitude=0.5e-6, phase=None)
    a = simulate(G6205, OP, ball, settings=st, random_state=7)
    b = simulate(G6205, OP, ball, settings=st, random_state=7)
    c = simulate(G6205, OP, ball, settings=st, random_state=8)
    np.testing.assert_array_equal(a["housing_velocity_y"], b["housing_velocity_y"])
    assert not np.array_equal(a["housing_velocity_y"], c["housing_velocity_y"])


def test_bad_inputs_named():
    with pytest.raises(ParameterError, match="bearing"):
        simulate("6205", OP)
    with pytest.raises(ParameterError, match="defects\\[0\\]"):
        simulate(G6205, OP, ["outer"])
    with pytest.raises(ParameterError, match="ball = 12"):
        simulate(G6205, OP, Waviness(surface="ball", order=2, amplitude=1e-7, ball=12))
    with pytest.raises(ParameterError, match="level"):
        Scene(level="half")
    with pytest.raises(ParameterError, match="integrator"):
        SimulationSettings(integrator="euler")


def test_zero_speed_runs_static():
    st = SimulationSettings(fs=5120.0, duration=0.02, settle_time=0.005)
    r = simulate(G6205, OperatingCondition(shaft_frequency=0.0, radial_load=500.0), settings=st)
    assert np.abs(r["housing_velocity_y"]).max() < 1e-6


def test_auto_scene_rule():
    st = SimulationSettings()
    lvl, _ = resolve_scene(Scene(level="auto"), G6205, OP, Rig(), st)
    assert lvl == "shaft+housing"  # default pedestal is softer than the bearing
    lvl, why = resolve_scene(Scene(level="auto"), G6205, OP, Rig(pedestal_stiffness=1e11), st)
    assert lvl == "shaft" and "coupling" in why
    # output band reaching towards the ball mode (~45 kHz) needs ball masses
    lvl, why = resolve_scene(Scene(level="auto"), G6205, OP, Rig(), SimulationSettings(fs=200000.0))
    assert lvl == "full" and "ball mode" in why
    # very high speed: centrifugal ball force comparable to the ball loads
    fast = OperatingCondition.from_rpm(13000, 20.0)
    low_band = SimulationSettings(fs=5120.0)
    lvl, why = resolve_scene(Scene(level="auto"), G6205, fast, Rig(), low_band)
    assert lvl == "full" and "centrifugal" in why


def test_cage_slip_moves_the_simulated_ball_pass_line():
    """The line in the simulated spectrum moves, not just the reported frequency."""
    import features

    settings = SimulationSettings(fs=5120.0, duration=1.0, settle_time=0.1)
    wavy = Waviness(surface="outer", order=9, amplitude=1e-6)  # its line sits at BPFO
    lines = {}
    for slip in (0.0, 0.05):
        op = OperatingCondition.from_rpm(1800, 500.0, cage_slip=slip)
        r = simulate(G6205, op, wavy, settings=settings)
        f, a = features.amplitude_spectrum(r["housing_velocity_y"], r.fs)
        near = (f > 90) & (f < 120)
        lines[slip] = (f[near][np.argmax(a[near])], r.frequencies.bpfo)
    assert lines[0.05][1] == pytest.approx(0.95 * 3.58478 * 30.0, rel=1e-4)
    for found, bpfo in lines.values():
        assert abs(found - bpfo) <= 1.0  # one bin of the 1 s record
    assert lines[0.0][0] - lines[0.05][0] > 4.0  # 107.5 -> 102.2 Hz


def test_rk4_stability_radius_matches_the_analytic_limits():
    from generators.model import rk4_stability_radius

    # imaginary axis: |R(iy)|^2 = 1 - y^6/72 + y^8/576 -> y = sqrt(8) exactly
    # real axis: 1 - r + r^2/2 - r^3/6 + r^4/24 = -1, root 2.785293563...
    r = rk4_stability_radius(np.array([np.pi / 2, np.pi, -np.pi, 0.3]))
    np.testing.assert_allclose(r, [math.sqrt(8.0), 2.7852935634, 2.7852935634, math.sqrt(8.0)])
    # inside the region just below the radius, outside just above, at any angle
    for phi in np.linspace(np.pi / 2, np.pi, 7):
        rad = rk4_stability_radius(phi)[0]
        for scale, inside in ((0.999, True), (1.001, False)):
            z = scale * rad * np.exp(1j * phi)
            assert bool(abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) <= 1.0) == inside


def test_default_step_skips_tracing_rays_only_where_that_changes_nothing():
    """``default_step`` skips RK4's ray tracing when even the narrowest radius allows the
    accuracy step: the step must equal min(accuracy step, stability step) every time, in
    scenes where the accuracy step wins and where stability does (the full scene)."""
    from generators.prepared import prepare
    from generators.steps import (
        DEFAULT_STEP_MASSLESS,
        _narrowest_radius,
        default_step,
        rk4_stability_radius,
        stability_step,
    )

    # the bound is below the radius along every ray
    rays = np.linspace(np.pi / 2, np.pi, 20001)
    assert _narrowest_radius() < rk4_stability_radius(rays).min()
    # the bound comes from the companion-matrix roots: the same boundary as the scan's
    from generators.steps import _boundary_radius_by_roots

    some = rays[::97]
    by_roots = _boundary_radius_by_roots(some)
    np.testing.assert_allclose(by_roots, rk4_stability_radius(some), atol=1e-8)
    assert _narrowest_radius() > 0.998 * rk4_stability_radius(rays).min()  # and a close one
    seen = set()
    for level in ("shaft", "shaft+housing", "full"):
        for ehl in (False, True):
            for name, load in (("6205", 50.0), ("6308", 20000.0), ("6002", 500.0)):
                op = OperatingCondition.from_rpm(3000, load)
                prep = prepare(bearing(name), op, None, scene=Scene(level=level, ehl=ehl))
                args = (prep.scene_code, prep.ehl, prep.p, prep.wav, prep.y0)
                expected = min(DEFAULT_STEP_MASSLESS, stability_step(*args))
                assert default_step(level, *args) == expected
                seen.add(expected == DEFAULT_STEP_MASSLESS)
    assert seen == {True, False}  # both branches met


def test_default_step_is_stable_and_twice_that_is_not():
    # full/dry: the ball radial mode sets the step; RK4 at the default step runs, at 1.6 times
    # it (twice the stability limit's safety margin of 0.8) diverges
    from generators.steps import STABILITY_SAFETY

    st = SimulationSettings(fs=25600.0, duration=0.02, settle_time=0.01)
    r = simulate(G6205, OP, settings=st, scene=Scene(level="full", ehl=False))
    step = r.parameters["integrator_stats"]["step_s"]
    assert np.all(np.isfinite(r["housing_velocity_y"]))
    too_long = step / STABILITY_SAFETY * 1.25
    with pytest.raises(SimulationDivergedError):
        simulate(
            G6205,
            OP,
            settings=SimulationSettings(fs=25600.0, duration=0.02, settle_time=0.01, step=too_long),
            scene=Scene(level="full", ehl=False),
        )


def test_unbalance_force_gives_the_quasi_static_rotating_response():
    """m_u e w^2 rotating with the shaft: far below the bearing's natural frequencies the
    shaft follows it through the static stiffness, in phase (x with cos, y with sin)."""
    from generators import Rig, Scene, static_load_distribution

    geometry, operating = bearing("6205"), OperatingCondition.from_rpm(1800, 500.0)
    settings = SimulationSettings(
        duration=0.5,
        settle_time=0.1,
        fs=5120.0,
        channels=("shaft_displacement_x", "shaft_displacement_y"),
    )
    scene = Scene(level="shaft", ehl=False)  # the dry Hertz stiffness is the static one

    def response(unbalance):
        run = simulate(
            geometry, operating, scene=scene, rig=Rig(unbalance=unbalance), settings=settings
        )
        return run

    base, one, two = response(0.0), response(1e-4), response(2e-4)
    omega = 2 * np.pi * operating.shaft_frequency
    t = base.time + settings.settle_time  # the shaft angle is omega t from t = 0
    basis = np.c_[np.cos(omega * t), np.sin(omega * t)]

    def first_order(run, channel):  # (cos, sin) amplitudes of the 1x line of the difference
        d = run[channel] - base[channel]
        return np.linalg.lstsq(basis, d - d.mean(), rcond=None)[0]

    k_r = static_load_distribution(geometry, 500.0).radial_stiffness
    force = 1e-4 * omega**2  # 3.55 N, against 500 N of load: the linear range
    cos_y, sin_y = first_order(one, "shaft_displacement_y")
    # the load direction: F / k_r (k_r at one cage position; the ball-pass stiffness variation
    # of nine balls and the dynamic amplification (30 Hz / ~1.5 kHz)^2 stay below 3 %)
    assert sin_y == pytest.approx(force / k_r, rel=0.03)
    assert abs(cos_y) < 0.01 * abs(sin_y)  # no phase lag below resonance
    cos_x, sin_x = first_order(one, "shaft_displacement_x")
    assert cos_x > 0 and abs(sin_x) < 0.01 * cos_x  # x follows F cos(omega t)
    # linear in the unbalance (doubled: doubled, to 0.1 %)
    assert first_order(two, "shaft_displacement_y")[1] == pytest.approx(2 * sin_y, rel=1e-3)
    assert first_order(two, "shaft_displacement_x")[0] == pytest.approx(2 * cos_x, rel=1e-3)


def test_the_anti_alias_decimation_keeps_the_band_and_removes_what_would_alias():
    """The record (oversample x fs) is decimated by a zero-phase FIR: a line inside the output
    band keeps amplitude and phase, one above the output Nyquist does not fold back."""
    from generators._kernels import N_OUT_ACCEL, N_OUT_STATE
    from generators.decimation import decimate

    fs, factor, n = 10000.0, 4, 4 * 10000
    t = np.arange(n) / (factor * fs)
    in_band = np.sin(2 * np.pi * 1000.0 * t + 0.3)
    above = np.sin(2 * np.pi * 7000.0 * t)  # would alias to 3000 Hz at fs = 10 kHz
    state = np.zeros((n, N_OUT_STATE))
    state[:, 7] = in_band + above  # housing_velocity_y's column
    out = decimate(state, np.zeros((n, N_OUT_ACCEL)), factor, ["housing_velocity_y"])
    y = out["housing_velocity_y"]
    tt = np.arange(y.size) / fs
    inner = slice(100, -100)  # away from the filter's edge extension
    expected = np.sin(2 * np.pi * 1000.0 * tt + 0.3)
    np.testing.assert_allclose(y[inner], expected[inner], atol=1e-3)  # measured 3e-4
    alias = np.abs(np.fft.rfft(y[inner] * np.hanning(y[inner].size)))
    freqs = np.fft.rfftfreq(y[inner].size, 1 / fs)
    ratio = alias[np.argmin(np.abs(freqs - 3000.0))] / alias[np.argmin(np.abs(freqs - 1000.0))]
    assert ratio < 10 ** (-60 / 20)  # measured -70 dB (Kaiser window, beta 5)
    # the acceleration is that velocity's derivative, by the same FIR and a differentiator
    acc = decimate(state, np.zeros((n, N_OUT_ACCEL)), factor, ["housing_acceleration_y"], t[1])
    a = acc["housing_acceleration_y"]
    slope = 2 * np.pi * 1000.0 * np.cos(2 * np.pi * 1000.0 * tt + 0.3)
    # (the 7 kHz line's acceleration is 7 times the 1 kHz one's: what folds of it at -70 dB
    # is 2.6e-3 of the 1 kHz slope, measured)
    np.testing.assert_allclose(a[inner], slope[inner], atol=4e-3 * 2 * np.pi * 1000.0)
    folded = np.abs(np.fft.rfft(a[inner] * np.hanning(a[inner].size)))
    ratio = folded[np.argmin(np.abs(freqs - 3000.0))] / folded[np.argmin(np.abs(freqs - 1000.0))]
    assert ratio < 7.0 * 10 ** (-60 / 20)  # measured -53.6 dB: -70 dB of the 7 kHz line


@pytest.mark.parametrize("level", ["shaft", "shaft+housing"])
def test_natural_frequencies_match_the_reference_jacobian(level):
    """docs/model.md 7.5 applied to the equations written independently (tests/reference.py):
    the package's linearisation and the reference's agree (a wrong stiffness moves both the
    free decay and the package's eigenvalues, but not the reference's)."""
    from reference import ReferenceModel

    from generators import natural_frequencies

    scene = Scene(level=level, ehl=False)
    frozen = OperatingCondition(shaft_frequency=0.0, radial_load=500.0)
    prep = prepare(G6205, frozen, scene=scene)
    model = ReferenceModel(prep)
    n = prep.y0.size
    jac = np.empty((n, n))
    for i in range(n):  # central differences: 1e-11 m and 1e-7 m/s (7.5)
        h = 1e-11 if i < n // 2 else 1e-7
        up, down = prep.y0.copy(), prep.y0.copy()
        up[i] += h
        down[i] -= h
        jac[:, i] = (model.rhs(0.0, up) - model.rhs(0.0, down)) / (2 * h)
    if level == "shaft":  # the housing's one-way estimate is not part of the dynamics
        keep = [0, 1, 4, 5]
        jac = jac[np.ix_(keep, keep)]
    lam = np.linalg.eigvals(jac)
    reference = np.sort(np.abs(lam.imag[lam.imag > 1e-6]) / (2 * np.pi))[::-1]
    package = natural_frequencies(G6205, OP, scene=scene)
    np.testing.assert_allclose(package, reference, rtol=1e-5)
    # and docs/model.md 7.1's table (3 digits): 1.45 kHz (shaft), 1.85 kHz (shaft+housing)
    assert package[0] == pytest.approx({"shaft": 1450.0, "shaft+housing": 1850.0}[level], rel=0.01)
