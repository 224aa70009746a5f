"""Typed, validated, frozen parameter objects of the bearing model (all values SI).

Lifetimes, as in ROSS's ``state.py``:

* built once per bearing: :class:`Material`, :class:`BearingGeometry`, :class:`Lubricant`;
* built once per test rig: :class:`Rig`;
* built once per run: :class:`OperatingCondition`, :class:`Waviness`, :class:`Scene`,
  :class:`SimulationSettings`.

Every object validates itself in ``__post_init__`` and raises
:class:`~generators.ParameterError` naming the field, its value and the allowed range.
Make variants with :func:`dataclasses.replace`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ._validate import ParameterError, check_choice, check_int, check_real

__all__ = [
    "Material",
    "BearingGeometry",
    "Lubricant",
    "Rig",
    "OperatingCondition",
    "Waviness",
    "Scene",
    "SimulationSettings",
    "STEEL_52100",
    "LUBRICANTS",
    "SURFACES",
    "SCENE_LEVELS",
    "INTEGRATORS",
    "CHANNELS",
    "MAX_SHAFT_SPEED_RPM",
    "check_shaft_speed_rpm",
    "operating_range_warnings",
]

GRAVITY = 9.81  # [m/s^2]


@dataclass(frozen=True, slots=True, kw_only=True)
class Material:
    """Elastic material of balls or rings.

    Attributes
    ----------
    name : str
        Label.
    youngs_modulus : float
        Young's modulus E [Pa].
    poisson_ratio : float
        Poisson's ratio nu [-].
    density : float
        Mass density [kg/m^3].
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float

    def __post_init__(self) -> None:
        check_real("youngs_modulus", self.youngs_modulus, low=1e9, high=1e13, unit="Pa")
        check_real("poisson_ratio", self.poisson_ratio, low=0.0, high=0.5, high_inclusive=False)
        check_real("density", self.density, low=100.0, high=30000.0, unit="kg/m^3")


#: AISI 52100 bearing steel (docs/model.md 6.1: E = 2.08e11 Pa, nu = 0.3, 7850 kg/m^3).
STEEL_52100 = Material(name="AISI 52100", youngs_modulus=2.08e11, poisson_ratio=0.3, density=7850.0)


@dataclass(frozen=True, slots=True, kw_only=True)
class BearingGeometry:
    """Geometry and materials of a single-row deep groove ball bearing.

    Attributes
    ----------
    name : str
        Designation, e.g. ``"6205"``.
    ball_count : int
        Number of balls Z (N_b) [-].
    ball_diameter : float
        Ball diameter d [m].
    pitch_diameter : float
        Pitch (ball-centre circle) diameter D [m].
    contact_angle : float
        Nominal contact angle alpha [rad]; 0 for a radially loaded deep groove bearing.
    inner_groove_curvature : float
        Inner groove conformity f_i = r_i / d [-], in (0.5, 0.6].
    outer_groove_curvature : float
        Outer groove conformity f_o = r_o / d [-], in (0.5, 0.6].
    radial_internal_clearance : float
        ISO radial internal clearance P_d [m]: the total radial play of one ring relative to the
        other (Harris's diametral clearance). The per-ball gap with the rings concentric is
        ``radial_gap = P_d / 2``. Negative values model a preload (interference).
    ball_material, ring_material : Material
        Elastic materials.
    static_load_rating : float or None
        Catalogue basic static load rating C_0r [N]; ``None`` when not published.
    limiting_speed_rpm : float or None
        Catalogue limiting speed [rpm]; ``None`` when not published.
    source : str
        Where the numbers come from.
    """

    name: str
    ball_count: int
    ball_diameter: float
    pitch_diameter: float
    contact_angle: float = 0.0
    inner_groove_curvature: float = 0.52
    outer_groove_curvature: float = 0.52
    radial_internal_clearance: float = 10e-6
    ball_material: Material = STEEL_52100
    ring_material: Material = STEEL_52100
    static_load_rating: float | None = None
    limiting_speed_rpm: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        check_int("ball_count", self.ball_count, low=1, high=60)
        d = check_real(
            "ball_diameter", self.ball_diameter, low=0.0, high=0.5, low_inclusive=False, unit="m"
        )
        check_real(
            "pitch_diameter", self.pitch_diameter, low=0.0, high=5.0, low_inclusive=False, unit="m"
        )
        if self.pitch_diameter <= self.ball_diameter:
            raise ParameterError(
                f"pitch_diameter = {self.pitch_diameter:g} m must exceed ball_diameter = {d:g} m "
                f"(allowed range ({d:g}, 5] m)"
            )
        check_real(
            "contact_angle", self.contact_angle, low=0.0, high=math.radians(45.0), unit="rad"
        )
        check_real(
            "inner_groove_curvature",
            self.inner_groove_curvature,
            low=0.5,
            high=0.6,
            low_inclusive=False,
        )
        check_real(
            "outer_groove_curvature",
            self.outer_groove_curvature,
            low=0.5,
            high=0.6,
            low_inclusive=False,
        )
        check_real(
            "radial_internal_clearance",
            self.radial_internal_clearance,
            low=-0.2 * self.ball_diameter,
            high=0.2 * self.ball_diameter,
            unit="m",
        )
        # balls must fit on the pitch circle: Z d < pi D
        if self.ball_count * self.ball_diameter >= math.pi * self.pitch_diameter:
            raise ParameterError(
                f"ball_count = {self.ball_count} balls of {self.ball_diameter:g} m do not fit on "
                f"a pitch circle of {self.pitch_diameter:g} m (allowed ball_count < "
                f"{math.pi * self.pitch_diameter / self.ball_diameter:.1f})"
            )
        if self.static_load_rating is not None:
            check_real(
                "static_load_rating",
                self.static_load_rating,
                low=0.0,
                low_inclusive=False,
                unit="N",
            )
        if self.limiting_speed_rpm is not None:
            check_real(
                "limiting_speed_rpm",
                self.limiting_speed_rpm,
                low=0.0,
                low_inclusive=False,
                unit="rpm",
            )

    @property
    def radial_gap(self) -> float:
        """Per-ball radial gap c_r = P_d / 2 with the rings concentric [m]."""
        return 0.5 * self.radial_internal_clearance

    @property
    def diameter_ratio(self) -> float:
        """Gamma = d cos(alpha) / D [-]."""
        return self.ball_diameter * math.cos(self.contact_angle) / self.pitch_diameter

    @property
    def ball_mass(self) -> float:
        """Mass of one ball m_b [kg]."""
        return self.ball_material.density * math.pi * self.ball_diameter**3 / 6.0

    @property
    def effective_modulus(self) -> float:
        """Hamrock's effective modulus E' = 2 / ((1-nu_a^2)/E_a + (1-nu_b^2)/E_b) [Pa]."""
        a, b = self.ball_material, self.ring_material
        return 2.0 / (
            (1 - a.poisson_ratio**2) / a.youngs_modulus
            + (1 - b.poisson_ratio**2) / b.youngs_modulus
        )


@dataclass(frozen=True, slots=True, kw_only=True)
class Lubricant:
    """Lubricant at its operating temperature (isoviscous Newtonian, Barus pressure-viscosity).

    Attributes
    ----------
    name : str
        Label.
    viscosity : float
        Dynamic viscosity eta_0 at ambient pressure and bearing temperature [Pa s].
    pressure_viscosity_coefficient : float
        Barus coefficient alpha_p [1/Pa].
    film_factor : float
        Multiplier on the film thickness (starvation/grease < 1) [-].
    """

    name: str
    viscosity: float
    pressure_viscosity_coefficient: float
    film_factor: float = 1.0

    def __post_init__(self) -> None:
        check_real("viscosity", self.viscosity, low=1e-4, high=10.0, unit="Pa s")
        check_real(
            "pressure_viscosity_coefficient",
            self.pressure_viscosity_coefficient,
            low=1e-9,
            high=1e-7,
            unit="1/Pa",
        )
        check_real("film_factor", self.film_factor, low=0.0, high=2.0, low_inclusive=False)


#: Lubricant presets of docs/model.md 4.2 (values recalled from the literature, [R]).
LUBRICANTS: dict[str, Lubricant] = {
    "VG68": Lubricant(
        name="ISO VG 68 mineral oil, 40 C", viscosity=0.059, pressure_viscosity_coefficient=2.0e-8
    ),
    "VG32": Lubricant(
        name="ISO VG 32 mineral oil, 40 C", viscosity=0.028, pressure_viscosity_coefficient=1.8e-8
    ),
    "grease": Lubricant(
        name="grease, mineral base oil ~100 mm2/s at 40 C",
        viscosity=0.09,
        pressure_viscosity_coefficient=2.0e-8,
        film_factor=0.7,
    ),
}


@dataclass(frozen=True, slots=True, kw_only=True)
class Rig:
    """Test-rig structure around the bearing (docs/model.md 6.3 defaults, [A]).

    Attributes
    ----------
    shaft_mass : float
        Shaft plus inner race mass per bearing M_s [kg].
    housing_mass : float
        Housing plus outer race mass M_h [kg].
    pedestal_stiffness : float
        Housing support stiffness k_h [N/m], same in x and y.
    pedestal_damping : float
        Housing support damping c_h [N s/m].
    shaft_damping : float
        Viscous damping of the shaft motion c_s [N s/m].
    contact_damping_time : float
        Dry contact (material) damping as a time constant tau [s]: c = tau * dQ/ddelta, so the
        damping vanishes continuously at contact onset (docs/model.md 1.2, option D1).
    film_damping_factor : float
        Multiplier on the squeeze-film damping of docs/model.md (4.5) (option D2) [-].
    film_entrainment_factor : float
        The film's load at light load as a share of a flooded contact's rigid-isoviscous
        load (docs/model.md 4.6), in [0, 1]: 0 (default) leaves the film carrying nothing
        until the EHL contact begins, 1 is fully flooded; starvation lies between. Needs the
        film (``Scene(ehl=True)``) and massless balls (scene ``shaft`` or ``shaft+housing``) [-].
    lubricant : Lubricant
        Lubricant (used when the scene has the EHL film).
    loading_stiffness : float
        0 for a constant (dead-weight) radial load; > 0 for a loading spring between shaft and
        ground preloaded to the radial load at static equilibrium (docs/model.md 1.3) [N/m].
    gravity : bool
        Apply gravity (-y) to shaft, housing and balls.
    unbalance : float
        Shaft unbalance m_u e [kg m]; force m_u e w_s^2 rotating with the shaft.
    """

    shaft_mass: float = 1.0
    housing_mass: float = 2.0
    pedestal_stiffness: float = 5e7
    pedestal_damping: float = 1e3
    shaft_damping: float = 600.0
    contact_damping_time: float = 2e-7
    film_damping_factor: float = 1.0
    film_entrainment_factor: float = 0.0
    lubricant: Lubricant = field(default_factory=lambda: LUBRICANTS["VG68"])
    loading_stiffness: float = 0.0
    gravity: bool = True
    unbalance: float = 0.0

    def __post_init__(self) -> None:
        check_real("shaft_mass", self.shaft_mass, low=1e-3, high=1e4, unit="kg")
        check_real("housing_mass", self.housing_mass, low=1e-3, high=1e5, unit="kg")
        check_real("pedestal_stiffness", self.pedestal_stiffness, low=1e3, high=1e13, unit="N/m")
        check_real("pedestal_damping", self.pedestal_damping, low=0.0, high=1e7, unit="N s/m")
        check_real("shaft_damping", self.shaft_damping, low=0.0, high=1e7, unit="N s/m")
        check_real("contact_damping_time", self.contact_damping_time, low=0.0, high=1e-4, unit="s")
        check_real("film_damping_factor", self.film_damping_factor, low=0.0, high=10.0)
        check_real("film_entrainment_factor", self.film_entrainment_factor, low=0.0, high=1.0)
        check_real("loading_stiffness", self.loading_stiffness, low=0.0, high=1e12, unit="N/m")
        check_real("unbalance", self.unbalance, low=0.0, high=10.0, unit="kg m")
        if not isinstance(self.gravity, bool):
            raise ParameterError(f"gravity = {self.gravity!r} must be True or False")


#: Highest shaft speed every command, recipe and parameter object accepts [rpm]: a 2 kHz shaft
#: rate, above the catalogue limiting speed of any bearing here.
MAX_SHAFT_SPEED_RPM = 120000.0
#: The largest radial load the model takes [N].
MAX_RADIAL_LOAD_N = 1e7


def check_shaft_speed_rpm(name: str, rpm: object, *, standing: bool = False) -> float:
    """Check a shaft speed [rpm] against the one range of the toolkit; return it as a float.

    (0, 120000] rpm, or [0, 120000] where a standing shaft makes sense (``standing=True``: a
    simulation's static start).

    Parameters
    ----------
    name : str
        The parameter's name in the message.
    rpm : object
        The speed given [rev/min].
    standing : bool
        Allow 0.

    Returns
    -------
    float
        The speed [rev/min].

    Raises
    ------
    ParameterError
        Naming ``name``, the value and the allowed range.

    Examples
    --------
    >>> check_shaft_speed_rpm("rpm", 1797)
    1797.0
    """
    return check_real(
        name, rpm, low=0.0, high=MAX_SHAFT_SPEED_RPM, low_inclusive=standing, unit="rpm"
    )


@dataclass(frozen=True, slots=True, kw_only=True)
class OperatingCondition:
    """Shaft speed and radial load.

    Attributes
    ----------
    shaft_frequency : float
        Shaft rotation frequency f_s [Hz] (inner ring turns, outer ring stationary).
    radial_load : float
        Radial load on the shaft Q [N] (0 allowed: gravity only).
    load_angle : float
        Direction of the load, measured counter-clockwise from +x [rad]; -pi/2 is straight down.
    cage_slip : float
        Cage slip s: the cage turns at (1 - s) times its kinematic speed [-].
    random_slip : float
        Standard deviation of the random fluctuation of the cage speed, relative to its mean
        [-] (real bearings: 0.01-0.02, Randall and Antoni 2011). The balls then meet a local
        defect at randomly varying intervals: its impacts are second-order cyclostationary
        and their harmonics smeared, the more the higher (docs/realism.md). 0: periodic.
    ball_jitter : float
        Standard deviation of each ball's own random angular offset within its cage pocket
        [rad] (independent per ball; 0: none).
    """

    shaft_frequency: float
    radial_load: float = 500.0
    load_angle: float = -math.pi / 2
    cage_slip: float = 0.0
    random_slip: float = 0.0
    ball_jitter: float = 0.0

    def __post_init__(self) -> None:
        check_real(
            "shaft_frequency",
            self.shaft_frequency,
            low=0.0,
            high=MAX_SHAFT_SPEED_RPM / 60.0,
            unit="Hz",
        )
        check_real("radial_load", self.radial_load, low=0.0, high=MAX_RADIAL_LOAD_N, unit="N")
        check_real("load_angle", self.load_angle, low=-2 * math.pi, high=2 * math.pi, unit="rad")
        check_real("cage_slip", self.cage_slip, low=0.0, high=0.5)
        check_real("random_slip", self.random_slip, low=0.0, high=0.1)
        check_real("ball_jitter", self.ball_jitter, low=0.0, high=0.1, unit="rad")

    @classmethod
    def from_rpm(
        cls, rpm: float, radial_load: float = 500.0, **kwargs: float
    ) -> OperatingCondition:
        """Build from a shaft speed in revolutions per minute (0 to 120 000, standing allowed).

        Parameters
        ----------
        rpm : float
            Shaft speed [rev/min], 0 .. 120,000.
        radial_load : float
            Radial load on the shaft [N].
        **kwargs : float
            The other attributes (``load_angle`` [rad], ``cage_slip``, ``random_slip``,
            ``ball_jitter``, ...), as for the class.

        Returns
        -------
        OperatingCondition
            With ``shaft_frequency`` = rpm / 60 [Hz].
        """
        check_shaft_speed_rpm("rpm", rpm, standing=True)
        return cls(shaft_frequency=float(rpm) / 60.0, radial_load=radial_load, **kwargs)

    @property
    def rpm(self) -> float:
        """Shaft speed [rpm]."""
        return self.shaft_frequency * 60.0


SURFACES = ("outer", "inner", "ball")


@dataclass(frozen=True, slots=True, kw_only=True)
class Waviness:
    """One harmonic of surface waviness, w(psi) = amplitude * cos(order * psi + phase).

    Positive w means material protruding toward the contact (docs/model.md section 5).

    Attributes
    ----------
    surface : {"outer", "inner", "ball"}
        Which surface carries the waviness. Ball waviness is applied to every ball with its
        own random phase (drawn from the simulation's ``random_state``) unless ``ball`` selects
        a single ball.
    order : int
        Number of waves per circumference N_w [-] (0 is a uniform radius change A_0).
    amplitude : float
        Amplitude A_m [m] (radius deviation, not peak to peak).
    phase : float or None
        Phase [rad]; ``None`` draws it from the simulation's random state.
    ball : int or None
        For ``surface="ball"``: index of the single ball that carries it (0-based); ``None``
        puts it on every ball.
    """

    surface: str
    order: int
    amplitude: float
    phase: float | None = 0.0
    ball: int | None = None

    def __post_init__(self) -> None:
        check_choice("surface", self.surface, SURFACES)
        check_int("order", self.order, low=0, high=500)
        check_real("amplitude", self.amplitude, low=0.0, high=1e-3, unit="m")
        if self.phase is not None:
            check_real("phase", self.phase, low=-100.0, high=100.0, unit="rad")
        if self.ball is not None:
            if self.surface != "ball":
                raise ParameterError(f"ball = {self.ball} is only valid with surface='ball'")
            check_int("ball", self.ball, low=0, high=59)


@dataclass(frozen=True, slots=True, kw_only=True)
class LocalizedDefect:
    """A local defect (spall, pit) on a race or a ball: a pit of given size and depth.

    A ball passing the pit pivots over its edges: it sinks by the sagitta
    R_x - sqrt(R_x^2 - e^2) of its reduced radius R_x in the rolling direction (e the distance
    to the nearer edge) and reaches the floor only when the pit is wider than
    2 sqrt(2 R_x depth). A narrow, deep pit is bridged; see :func:`generators.defect_path_depth`.

    Attributes
    ----------
    surface : {"outer", "inner", "ball"}
        The surface that carries the pit.
    length : float
        Size of the pit in the rolling direction [m] (arc length on the surface, e.g. the
        diameter of an EDM pit: 0.1778e-3 m for the CWRU 0.007 inch faults).
    depth : float
        Depth of the pit [m] (the ball never sinks more than this).
    position : float or None
        Angle of the pit centre [rad]: for the outer race in the fixed frame (measured CCW
        from +x; -pi/2 is 6 o'clock, the centre of the load zone under the default downward
        load); for the inner race on the ring at t = 0; for a ball on the ball, from its outer
        contact point at t = 0. ``None`` draws it from the simulation's random state.
    ball : int
        For ``surface="ball"``: index of the ball that carries it (0-based).
    latitude : float or None
        Ball pits: angle of the pit from the ball's rolling circle at t = 0 [rad] (0: on it,
        every spin meets both races; ``None`` draws it from the random state). The races meet
        the pit only while it lies within the contact track (the contact ellipse's half width
        plus half the pit), so a pit off the rolling circle strikes intermittently.
    axis_drift : float
        Ball pits: rate at which the ball's spin axis turns the pit across the rolling circle
        [rad/s] (0: a fixed axis). Real balls' axes wander (cage and ball-ball contacts), one
        reason ball faults are the hardest to see (Smith and Randall 2015).
    """

    surface: str
    length: float
    depth: float
    position: float | None = -math.pi / 2
    ball: int = 0
    latitude: float | None = 0.0
    axis_drift: float = 0.0

    def __post_init__(self) -> None:
        check_choice("surface", self.surface, SURFACES)
        check_real("length", self.length, low=0.0, high=0.05, low_inclusive=False, unit="m")
        check_real("depth", self.depth, low=0.0, high=1e-3, unit="m")
        if self.position is not None:
            check_real("position", self.position, low=-100.0, high=100.0, unit="rad")
        if self.ball != 0 and self.surface != "ball":
            raise ParameterError(f"ball = {self.ball} is only valid with surface='ball'")
        check_int("ball", self.ball, low=0, high=59)
        if self.surface != "ball" and (self.latitude not in (0.0, None) or self.axis_drift):
            raise ParameterError(
                f"latitude = {self.latitude}, axis_drift = {self.axis_drift} are only valid "
                "with surface='ball'"
            )
        if self.latitude is not None:
            check_real("latitude", self.latitude, low=-100.0, high=100.0, unit="rad")
        check_real("axis_drift", self.axis_drift, low=-1e4, high=1e4, unit="rad/s")


SCENE_LEVELS = ("shaft", "shaft+housing", "full", "auto")


@dataclass(frozen=True, slots=True, kw_only=True)
class Scene:
    """What the model includes.

    Attributes
    ----------
    level : {"shaft", "shaft+housing", "full", "auto"}
        ``shaft``: 2 DOF shaft on massless balls, rigid housing (the housing output is a
        one-way estimate: the transmitted bearing force driving the pedestal);
        ``shaft+housing``: 4 DOF, massless balls; ``full``: shaft, housing and one radial DOF per
        ball; ``auto``: the cheapest level whose dropped physics is below ``auto_error_bound``.
    ehl : bool
        Include the EHL film (thickness in the contact approach, film damping).
    auto_error_bound : float
        Relative error bound used by ``auto`` [-].
    """

    level: str = "shaft+housing"
    ehl: bool = True
    auto_error_bound: float = 0.05

    def __post_init__(self) -> None:
        check_choice("level", self.level, SCENE_LEVELS)
        if not isinstance(self.ehl, bool):
            raise ParameterError(f"ehl = {self.ehl!r} must be True or False")
        check_real(
            "auto_error_bound", self.auto_error_bound, low=0.0, high=1.0, low_inclusive=False
        )

    @property
    def label(self) -> str:
        """Short label such as ``shaft+housing/ehl``."""
        return f"{self.level}/{'ehl' if self.ehl else 'dry'}"


INTEGRATORS = ("rk4", "dopri5")

#: Output channels, ``<body>_<quantity>_<axis>`` in SI units (m, m/s, m/s^2).
CHANNELS = tuple(
    f"{body}_{quantity}_{axis}"
    for body in ("housing", "shaft")
    for quantity in ("displacement", "velocity", "acceleration")
    for axis in ("x", "y")
)


@dataclass(frozen=True, slots=True, kw_only=True)
class SimulationSettings:
    """Sampling, record length and integrator settings.

    Attributes
    ----------
    fs : float
        Output sample rate [Hz].
    duration : float
        Recorded duration after settling [s].
    settle_time : float
        Simulated time discarded before recording [s].
    integrator : {"rk4", "dopri5"}
        Fixed-step classical Runge-Kutta or adaptive Dormand-Prince 5(4).
    step : float or None
        RK4 step [s]; ``None`` uses the scene default (chosen from the measured speed/accuracy
        trade). Shortened by at most 20 % where that puts the records on a fixed pattern of
        the step grid (:func:`generators.steps.rk4_schedule`); the step used is in the result's
        ``integrator_stats``.
    rtol : float
        Relative tolerance of dopri5 [-].
    atol_displacement : float
        Absolute tolerance of dopri5 on displacements [m] (velocities use it times 1e3 1/s).
    oversample : int or None
        Record samples per output sample (the record is decimated by a zero-phase anti-alias
        FIR; an acceleration is the velocity record's derivative through it); ``None``: RK4
        records at 2-4 x fs, toward 96 kHz (:func:`generators.steps.default_oversample`: 4 x fs
        up to 25.6 kHz, 2 x fs from 48 kHz), DOPRI5 and error-bound runs at 4 x fs.
    record_contact_loads : bool
        Also return the per-ball contact loads at the output samples.
    max_displacement : float or None
        Divergence limit on any displacement [m]; ``None`` derives it from the geometry.
    cage_angle : float
        Initial cage angle theta_0 (angle of ball 0 from +x) [rad].
    max_steps_per_second : float
        Step budget of dopri5 per simulated second: an adaptive run that needs more steps
        stops with an error instead of running on (5e6 means an average step of 0.2 us, five
        times below what the fastest mode of the full scene needs).
    channels : tuple of str or None
        Output channels to produce (names from ``CHANNELS``); ``None`` for all. Fewer channels
        save the anti-alias decimation time.
    error_bound : float or None
        RK4 only, when ``step`` is None: the longest step whose relative error in the
        amplitudes of the bearing's characteristic lines and in each octave band of the
        spectrum above 500 Hz is at most this, measured by pilot runs at h, h / 2 and h / 4
        (:mod:`generators.accuracy`) [-]; ``None`` keeps the scene's default step. An
        explicit ``step`` wins.
    """

    fs: float = 25600.0
    duration: float = 1.0
    settle_time: float = 0.1
    integrator: str = "rk4"
    step: float | None = None
    rtol: float = 1e-6
    atol_displacement: float = 1e-12
    oversample: int | None = None
    record_contact_loads: bool = False
    max_displacement: float | None = None
    cage_angle: float = 0.0
    channels: tuple[str, ...] | None = None
    max_steps_per_second: float = 5e6
    error_bound: float | None = None

    def __post_init__(self) -> None:
        check_real("fs", self.fs, low=100.0, high=1e7, unit="Hz")
        check_real("duration", self.duration, low=0.0, high=3600.0, low_inclusive=False, unit="s")
        check_real("settle_time", self.settle_time, low=0.0, high=3600.0, unit="s")
        check_choice("integrator", self.integrator, INTEGRATORS)
        if self.step is not None:
            check_real("step", self.step, low=1e-9, high=1e-3, unit="s")
        if self.error_bound is not None:
            check_real("error_bound", self.error_bound, low=1e-6, high=0.5)
        check_real("rtol", self.rtol, low=1e-13, high=1e-1)
        check_real("atol_displacement", self.atol_displacement, low=1e-20, high=1e-6, unit="m")
        if self.oversample is not None:
            check_int("oversample", self.oversample, low=1, high=1000)
        if self.max_displacement is not None:
            check_real(
                "max_displacement",
                self.max_displacement,
                low=0.0,
                high=1.0,
                low_inclusive=False,
                unit="m",
            )
        check_real("cage_angle", self.cage_angle, low=-100.0, high=100.0, unit="rad")
        check_real(
            "max_steps_per_second", self.max_steps_per_second, low=1e2, high=1e10, unit="1/s"
        )
        if self.channels is not None:
            if isinstance(self.channels, str) or not self.channels:
                raise ParameterError(f"channels = {self.channels!r} must be a non-empty tuple")
            for c in self.channels:
                if c not in CHANNELS:
                    raise ParameterError(f"channels: {c!r} is not one of {', '.join(CHANNELS)}")
            object.__setattr__(self, "channels", tuple(self.channels))
        if self.duration * self.fs < 16:
            raise ParameterError(
                f"duration = {self.duration:g} s at fs = {self.fs:g} Hz gives "
                f"{self.duration * self.fs:.0f} samples; at least 16 are needed"
            )


def operating_range_warnings(bearing: BearingGeometry, operating: OperatingCondition) -> list[str]:
    """What a run leaves of the bearing's catalogue ratings: one message per rating exceeded.

    A radial load over the basic static load rating C0r (ISO 76: the most loaded contact at
    4,200 MPa, where a ball bearing's raceways begin to yield permanently) is beyond the
    elastic Hertz contact of this model; a speed over the limiting speed is where gyroscopic
    moments and contact-angle changes, outside this planar model, begin to matter
    (docs/model.md 7.4). Bearings without published ratings give none.

    Parameters
    ----------
    bearing : BearingGeometry
        The bearing (``static_load_rating`` [N], ``limiting_speed_rpm`` [rev/min]).
    operating : OperatingCondition
        The radial load [N] and shaft speed [Hz].

    Returns
    -------
    list of str
    """
    messages = []
    rating = bearing.static_load_rating
    if rating is not None and operating.radial_load > rating:
        messages.append(
            f"radial_load = {operating.radial_load:g} N is {operating.radial_load / rating:.3g} "
            f"x the {bearing.name}'s basic static load rating C0r = {rating:g} N: its most "
            "loaded contact would yield (ISO 76), which the elastic Hertz contact of the "
            "model does not describe"
        )
    limit = bearing.limiting_speed_rpm
    if limit is not None and operating.rpm > limit:
        messages.append(
            f"shaft speed {operating.rpm:g} rpm is above the {bearing.name}'s limiting speed "
            f"{limit:g} rpm: gyroscopic moments and contact-angle changes, outside this planar "
            "model, begin to matter (docs/model.md 7.4)"
        )
    return messages
