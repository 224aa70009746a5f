"""Numerical stability at the extremes (docs/model.md 7.4).

Every case runs in each scene and integrator, and its outcome is fixed: ``DIVERGES`` names
the cases that must stop with a SimulationDivergedError naming scene and time (one ball off
its load line: nothing holds the shaft), every other case must run through with finite output,
displacements below the divergence limit and a housing velocity below
``MAX_HOUSING_VELOCITY``. Never NaN, never a hang (DOPRI5 has a step budget). Measured peaks
of the housing y velocity (mm/s; shaft+housing/full/DOPRI5/shaft): C5 clearance 0.14-0.31,
no load with gravity 0.07-0.12, 13000 rpm 6.2 (36.6 in the shaft scene), 20 um waviness
5.7-9.5, order 100 3.1-4.0, soft pedestal 0.28-3.4, every other case below 0.05.
"""

import dataclasses

import numpy as np
import pytest

from generators import (
    BearingGeometry,
    OperatingCondition,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)

pytestmark = pytest.mark.validation

SHORT = SimulationSettings(fs=10240.0, duration=0.05, settle_time=0.02)
G = bearing("6205")
OP = OperatingCondition.from_rpm(1800, 500.0)
OUTER9 = Waviness(surface="outer", order=9, amplitude=1e-6)
# m/s: beyond any running machine (ISO 10816-3's zone D, damage, starts at 11 mm/s RMS for the
# largest machines) and 2.7 times the largest peak measured here (36.6 mm/s at 13000 rpm)
MAX_HOUSING_VELOCITY = 0.1

RUNS = [
    ("shaft+housing", "rk4"),
    ("full", "rk4"),
    ("shaft+housing", "dopri5"),
    ("shaft", "rk4"),
]

MANY_BALLS = BearingGeometry(
    name="30 balls", ball_count=30, ball_diameter=3e-3, pitch_diameter=40e-3
)
ONE_BALL = dataclasses.replace(G, name="one ball", ball_count=1)

CASES = {
    "zero clearance": dict(geometry=bearing("6205", radial_internal_clearance=0.0)),
    "large clearance (C5, 60 um)": dict(geometry=bearing("6205", radial_internal_clearance=60e-6)),
    "preload (-4 um)": dict(geometry=bearing("6205", radial_internal_clearance=-4e-6)),
    "no load, gravity only": dict(operating=OperatingCondition.from_rpm(1800, 0.0)),
    "no load, no gravity": dict(
        operating=OperatingCondition.from_rpm(1800, 0.0), rig=Rig(gravity=False)
    ),
    "huge load (7 kN ~ C0r)": dict(operating=OperatingCondition.from_rpm(1800, 7000.0)),
    "10 rpm": dict(operating=OperatingCondition.from_rpm(10, 500.0)),
    "limiting speed 13000 rpm": dict(operating=OperatingCondition.from_rpm(13000, 500.0)),
    "waviness 1 nm": dict(defects=[Waviness(surface="outer", order=9, amplitude=1e-9)]),
    "waviness 20 um > clearance": dict(
        defects=[Waviness(surface="outer", order=9, amplitude=20e-6)]
    ),
    "waviness order 1": dict(defects=[Waviness(surface="inner", order=1, amplitude=1e-6)]),
    "waviness order 100": dict(
        defects=[
            Waviness(surface="outer", order=100, amplitude=0.1e-6),
            Waviness(surface="inner", order=100, amplitude=0.1e-6),
        ]
    ),
    # one ball starts on the load line; as the cage turns it leaves it and nothing holds the
    # shaft: the run must end with a runaway error (or finish if the record is short)
    "one ball": dict(
        geometry=ONE_BALL, operating=OperatingCondition.from_rpm(1800, 50.0), cage_angle=-np.pi / 2
    ),
    "30 balls": dict(geometry=MANY_BALLS),
    "very stiff housing (1e11 N/m)": dict(rig=Rig(pedestal_stiffness=1e11)),
    "very soft pedestal (1e4 N/m)": dict(rig=Rig(pedestal_stiffness=1e4)),
}


def run_case(case, level, integrator):
    spec = CASES[case]
    settings = dataclasses.replace(
        SHORT, integrator=integrator, cage_angle=spec.get("cage_angle", 0.0)
    )
    return simulate(
        spec.get("geometry", G),
        spec.get("operating", OP),
        spec.get("defects", [OUTER9]),
        scene=Scene(level=level, ehl=True),
        rig=spec.get("rig"),
        settings=settings,
        random_state=0,
    )


@pytest.mark.parametrize(("level", "integrator"), RUNS)
@pytest.mark.parametrize("case", list(CASES))
def test_extreme_case_is_finite_bounded_or_reported(case, level, integrator):
    if case in DIVERGES:
        with pytest.raises(SimulationDivergedError, match="runaway") as stop:
            run_case(case, level, integrator)
        assert stop.value.scene == level and 0.0 < stop.value.time < 0.07
        return
    r = run_case(case, level, integrator)
    for name, x in r.signals.items():
        assert np.all(np.isfinite(x)), name
    assert np.abs(r["housing_velocity_y"]).max() < MAX_HOUSING_VELOCITY
    limit = r.parameters["settings"]["max_displacement"]
    if limit is not None:
        assert np.abs(r["shaft_displacement_y"]).max() < limit
    if case == "no load, no gravity":
        # nothing loads the balls (clearance, no force): no contact, no vibration at all
        assert np.abs(r["housing_velocity_y"]).max() < 1e-15


# the cases that must stop with a clear error: one ball leaves the load line as the cage turns
# and nothing holds the shaft (a runaway); every other case must run through
DIVERGES = {"one ball"}


def test_one_ball_off_the_load_line_has_no_static_equilibrium():
    from generators import ParameterError

    with pytest.raises(ParameterError, match="static equilibrium not found"):
        simulate(ONE_BALL, OperatingCondition.from_rpm(1800, 50.0), settings=SHORT)


def test_dopri5_step_budget_stops_instead_of_hanging():
    tight = dataclasses.replace(
        SHORT, integrator="dopri5", rtol=1e-12, atol_displacement=1e-20, max_steps_per_second=1e3
    )
    with pytest.raises(SimulationDivergedError, match="step budget"):
        simulate(G, OP, OUTER9, scene=Scene(level="full", ehl=True), settings=tight)


@pytest.mark.parametrize(("rpm", "newton"), [(1800, 0.23), (3600, 0.91), (10000, 7.0)])
def test_centrifugal_ball_force_loads_the_outer_race(rpm, newton):
    # docs/model.md 2: F_c = m_b w_c^2 D / 2 = 0.23 / 0.91 / 7.0 N for a 6205 at 1800 / 3600 / 10000
    # rpm. Balls outside the load zone press on the outer race with F_c alone.
    settings = dataclasses.replace(SHORT, record_contact_loads=True, duration=0.02)
    r = simulate(
        G,
        OperatingCondition.from_rpm(rpm, 500.0),
        None,
        scene=Scene(level="full", ehl=False),
        rig=Rig(gravity=False),
        settings=settings,
    )
    outer = r.contact_loads[:, 1, :]
    unloaded = outer[r.contact_loads[:, 0, :] == 0.0]  # no inner contact: outside the zone
    assert unloaded.size > 0
    assert np.median(unloaded) == pytest.approx(newton, rel=0.03)
