"""Validation of parameter objects: each bad input names the parameter, its value and range."""

import dataclasses
import math

import pytest

from generators import (
    BearingGeometry,
    Lubricant,
    Material,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
)

G = bearing("6205")


@pytest.mark.parametrize(
    ("field", "value", "fragment"),
    [
        ("ball_count", 0, "ball_count = 0"),
        ("ball_count", 2.5, "ball_count = 2.5"),
        ("ball_diameter", -1e-3, "ball_diameter = -0.001"),
        ("ball_diameter", float("nan"), "ball_diameter = nan"),
        ("pitch_diameter", 5e-3, "pitch_diameter = 0.005"),
        ("radial_internal_clearance", 0.01, "radial_internal_clearance = 0.01"),
        ("inner_groove_curvature", 0.5, "inner_groove_curvature = 0.5"),
        ("outer_groove_curvature", 0.7, "outer_groove_curvature = 0.7"),
        ("contact_angle", -0.1, "contact_angle = -0.1"),
        ("ball_count", 40, "do not fit"),
    ],
)
def test_bearing_geometry_rejects_bad_input(field, value, fragment):
    with pytest.raises(ParameterError, match="allowed") as err:
        dataclasses.replace(G, **{field: value})
    assert fragment in str(err.value)


def test_error_names_range():
    with pytest.raises(ParameterError) as err:
        dataclasses.replace(G, ball_diameter=-1e-3)
    assert "(0, 0.5] m" in str(err.value)


def test_negative_clearance_is_a_preload_not_an_error():
    g = dataclasses.replace(G, radial_internal_clearance=-4e-6)
    assert g.radial_gap == pytest.approx(-2e-6)


def test_clearance_convention():
    # ISO radial internal clearance P_d is total play; per-ball gap is P_d / 2 (docs/model.md 1.1)
    assert bearing("6205", radial_internal_clearance=10e-6).radial_gap == pytest.approx(5e-6)


def test_ball_mass_6205():
    # docs/model.md 6.1: m_b = 2.058e-3 kg
    assert G.ball_mass == pytest.approx(2.058e-3, rel=1e-3)


@pytest.mark.parametrize(
    ("factory", "fragment"),
    [
        (
            lambda: Material(name="x", youngs_modulus=-1.0, poisson_ratio=0.3, density=7850),
            "youngs_modulus",
        ),
        (
            lambda: Material(name="x", youngs_modulus=2e11, poisson_ratio=0.5, density=7850),
            "poisson_ratio",
        ),
        (
            lambda: Lubricant(name="x", viscosity=0.0, pressure_viscosity_coefficient=2e-8),
            "viscosity",
        ),
        (lambda: Rig(shaft_mass=0.0), "shaft_mass"),
        (lambda: Rig(pedestal_stiffness=float("inf")), "pedestal_stiffness"),
        (lambda: OperatingCondition(shaft_frequency=-1.0), "shaft_frequency"),
        (lambda: OperatingCondition(shaft_frequency=30.0, radial_load=-5.0), "radial_load"),
        (lambda: OperatingCondition.from_rpm(-10.0), "rpm"),
        (lambda: Waviness(surface="cage", order=9, amplitude=1e-6), "surface"),
        (lambda: Waviness(surface="outer", order=-1, amplitude=1e-6), "order"),
        (lambda: Waviness(surface="outer", order=9, amplitude=-1e-6), "amplitude"),
        (lambda: Waviness(surface="outer", order=9, amplitude=1e-6, ball=2), "ball"),
        (lambda: Scene(level="everything"), "level"),
        (lambda: SimulationSettings(fs=10.0), "fs"),
        (lambda: SimulationSettings(integrator="euler"), "integrator"),
        (lambda: SimulationSettings(step=1.0), "step"),
        (lambda: SimulationSettings(duration=1e-4, fs=1000.0), "duration"),
    ],
)
def test_other_objects_reject_bad_input(factory, fragment):
    with pytest.raises(ParameterError) as err:
        factory()
    assert fragment in str(err.value)


def test_objects_are_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        G.ball_count = 10  # type: ignore[misc]


def test_operating_condition_from_rpm():
    op = OperatingCondition.from_rpm(1800, radial_load=500)
    assert op.shaft_frequency == 30.0
    assert op.rpm == 1800.0
    assert op.load_angle == pytest.approx(-math.pi / 2)


def test_catalog_has_required_bearings():
    for name in ("6205", "6203", "6305", "6002", "6308", "mfpt"):
        g = bearing(name)
        assert isinstance(g, BearingGeometry)
        assert g.source


def test_catalog_unknown_name():
    with pytest.raises(ParameterError, match="not in the catalog"):
        bearing("9999")


def test_catalog_override():
    assert bearing("6205", radial_internal_clearance=20e-6).radial_internal_clearance == 20e-6


def test_a_run_beyond_the_catalogue_ratings_is_warned_about_and_still_runs(capsys):
    """Over C0r (7850 N for the 6205) or the limiting speed (13,000 rpm) the model integrates
    but no longer describes the bearing well: simulate warns (OperatingRangeWarning), and the
    command line says it in one line. Within both, and for a bearing without ratings, no
    warning."""
    import warnings

    from cmtool.cli import main
    from generators import (
        OperatingRangeWarning,
        SimulationSettings,
        bearing,
        operating_range_warnings,
        simulate,
    )

    g = bearing("6205")
    assert operating_range_warnings(g, OperatingCondition.from_rpm(12999, 7850.0)) == []
    heavy, fast = (
        operating_range_warnings(g, OperatingCondition.from_rpm(1800, 7851.0)),
        operating_range_warnings(g, OperatingCondition.from_rpm(13001, 500.0)),
    )
    assert len(heavy) == 1 and "C0r = 7850 N" in heavy[0] and "1 x" in heavy[0]
    assert len(fast) == 1 and "limiting speed 13000 rpm" in fast[0]
    unrated = dataclasses.replace(g, static_load_rating=None, limiting_speed_rpm=None)
    assert operating_range_warnings(unrated, OperatingCondition.from_rpm(60000, 9e6)) == []
    short = SimulationSettings(
        duration=0.01, settle_time=0.005, channels=("housing_acceleration_y",)
    )
    with pytest.warns(OperatingRangeWarning, match="basic static load rating"):
        simulate(g, OperatingCondition.from_rpm(1800, 2e4), settings=short)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate(g, OperatingCondition.from_rpm(1800, 500.0), settings=short)
    with pytest.raises(ParameterError, match=r"random_state = -1 is outside the allowed range"):
        simulate(g, OperatingCondition.from_rpm(1800, 500.0), settings=short, random_state=-1)
    assert main(["simulate", "--rpm", "20000", "--duration", "0.01", "--settle", "0.005"]) == 0
    err = capsys.readouterr().err
    assert err.startswith("cmtool simulate: warning: shaft speed 20000 rpm is above"), err
    assert err.count("\n") == 1
    # fidelity simulates the scene from three places: the same warning is printed once
    argv = ["fidelity", "--rpm", "14000", "--duration", "0.01", "--settle", "0.005", "--fs"]
    argv += ["12000", "--levels", "shaft", "--steps", "2e-5", "--rtols", "1e-3"]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err.count("warning: shaft speed 14000 rpm is above") == 1, err


@pytest.mark.parametrize(
    ("given", "said"),
    [
        ({"random_state": 1.5}, r"random_state = 1\.5 is not an integer; allowed range \[0, inf\]"),
        ({"defects": "outer"}, r"defects = 'outer' is not a Waviness or LocalizedDefect, or a seq"),
        ({"bearing": "6205"}, r"bearing = '6205' is not a BearingGeometry \(generators\.bearing"),
    ],
)
def test_simulate_refuses_a_seed_defects_or_bearing_it_cannot_use_by_name(given, said):
    """Before: numpy's SeedSequence TypeError for a fractional seed, "defects[0] = 'o'" for a
    string (its letters read as defects), and no hint that a catalog name goes through
    generators.bearing."""
    from generators import simulate

    args = {"bearing": bearing("6205"), "defects": None, "random_state": 0, **given}
    settings = SimulationSettings(duration=0.01, settle_time=0.005)
    with pytest.raises(ParameterError, match=said):
        simulate(
            args["bearing"],
            OperatingCondition.from_rpm(1800, 500.0),
            args["defects"],
            settings=settings,
            random_state=args["random_state"],
        )
