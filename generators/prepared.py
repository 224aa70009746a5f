"""A run made ready for the kernels (:func:`prepare`).

The scene resolved, parameters packed, the static start found, the step schedule planned, and
the record of every parameter.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from . import _kernels as K
from ._validate import (
    OperatingRangeWarning,
    ParameterError,
    SimulationDivergedError,
    check_int,
)
from .decimation import filter_reach
from .defects import defect_path
from .kinematics import BearingFrequencies, characteristic_frequencies
from .packing import (
    Defect,
    as_defects,
    contact_geometries,
    pack_parameters,
    slip_rows,
    waviness_table,
    with_film_tables,
)
from .params import (
    BearingGeometry,
    LocalizedDefect,
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
    operating_range_warnings,
)
from .start import static_state
from .static import static_load_distribution
from .steps import (
    DEFAULT_OVERSAMPLE,
    default_oversample,
    default_step_and_growth,
    defect_substeps,
    rk4_schedule,
)

SCENE_CODES = {"shaft": K.SCENE_SHAFT, "shaft+housing": K.SCENE_SHAFT_HOUSING, "full": K.SCENE_FULL}

#: Slowest shaft [Hz] (1 rpm) at which the EHL film is modelled; slower runs are dry.
EHL_MIN_SHAFT_FREQUENCY = 1.0 / 60.0


STATUS_REASONS = {
    K.STATUS_NONFINITE: "non-finite state (NaN or inf)",
    K.STATUS_RUNAWAY: "runaway displacement beyond the physical limit",
    K.STATUS_STEP_COLLAPSE: "adaptive step size collapsed",
    K.STATUS_TOO_MANY_STEPS: "adaptive integrator exceeded its step budget",
}


def resolve_scene(
    scene: Scene,
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    settings: SimulationSettings,
) -> tuple[str, str]:
    """Pick the model level for ``scene.level == "auto"`` and say why.

    Rule (each estimate is a relative error of the dropped physics, compared with
    ``scene.auto_error_bound``):

    * ``full`` is needed when the ball radial mode f_ball = sqrt((k_i + k_o) / m_b) / 2 pi lies
      too close to the analysis band f_max = fs / 2.56 (the usual analyser convention): the
      quasi-static error of massless balls at f_max is ~ (f_max / f_ball)^2 > bound; or when
      the centrifugal ball force
      m_b w_c^2 D / 2 exceeds bound times the largest static ball load;
    * otherwise ``shaft`` suffices when the housing is much stiffer than the bearing
      (k_b / (k_b + k_h) < bound: the relative error of the one-way housing coupling);
    * otherwise ``shaft+housing``.

    Parameters
    ----------
    scene : Scene
        The scene asked for (``level`` and ``auto_error_bound``).
    geometry : BearingGeometry
        Bearing geometry and materials.
    operating : OperatingCondition
        Shaft speed and radial load [N].
    rig : Rig
        Masses [kg] and support stiffnesses [N/m] of shaft and housing.
    settings : SimulationSettings
        Sample rate [Hz] (sets the analysis band).

    Returns
    -------
    level, reason : str
        The model level (``shaft``, ``shaft+housing`` or ``full``) and why: "requested", or
        the estimate that chose it.
    """
    if scene.level != "auto":
        return scene.level, "requested"
    bound = scene.auto_error_bound
    _, _, (ki, ko, kt) = contact_geometries(geometry)
    fr = max(operating.radial_load + (rig.shaft_mass * 9.81 if rig.gravity else 0.0), 1.0)
    st = static_load_distribution(
        geometry, fr, load_angle=operating.load_angle, stiffness_constant=kt
    )
    qmax = max(st.max_ball_load, 1.0)
    k_ball = 1.5 * (ki ** (2 / 3) + ko ** (2 / 3)) * qmax ** (1 / 3)
    f_ball = math.sqrt(k_ball / geometry.ball_mass) / (2 * math.pi)
    f_band = settings.fs / 2.56  # analysis band of an analyser sampling at 2.56 f_max
    wc = (
        2
        * math.pi
        * characteristic_frequencies(
            geometry, max(operating.shaft_frequency, 1e-9), cage_slip=operating.cage_slip
        ).ftf
    )
    centrifugal = geometry.ball_mass * wc**2 * geometry.pitch_diameter / 2
    if (f_band / f_ball) ** 2 > bound:
        return "full", f"ball mode {f_ball:.0f} Hz is close to the band f_max = {f_band:.0f} Hz"
    if centrifugal > bound * qmax:
        return (
            "full",
            f"centrifugal ball force {centrifugal:.3g} N > {bound:g} x Q_max {qmax:.3g} N",
        )
    coupling = st.radial_stiffness / (st.radial_stiffness + rig.pedestal_stiffness)
    if coupling < bound:
        return "shaft", f"housing coupling k_b/(k_b+k_h) = {coupling:.3g} < {bound:g}"
    return "shaft+housing", f"housing coupling k_b/(k_b+k_h) = {coupling:.3g} >= {bound:g}"


def _defect_record(geometry: BearingGeometry, defect: Defect) -> dict:
    record = {"kind": type(defect).__name__, **dataclasses.asdict(defect)}
    if isinstance(defect, LocalizedDefect):
        path = defect_path(geometry, defect)
        record.update(half_width_rad=path.half_width, max_sink_m=path.max_sink)
    return record


def _plain(obj):
    """``dataclasses.asdict`` without its deep copies (the parameter objects are frozen)."""
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {name: _plain(getattr(obj, name)) for name in _field_names(type(obj))}
    if isinstance(obj, (list, tuple)):
        return type(obj)(_plain(v) for v in obj)
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    return obj


@functools.cache
def _field_names(cls: type) -> tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(cls))


def params_record(
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    scene: Scene,
    level: str,
    reason: str,
    settings: SimulationSettings,
    defects: tuple[Defect, ...],
    extra: dict,
) -> dict:
    """Every parameter of a run as a JSON-serialisable dict (the result's ``parameters``).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    operating : OperatingCondition
        The operating point.
    rig : Rig
        The rig.
    scene : Scene
        The scene asked for.
    level, reason : str
        The level run and why (:func:`resolve_scene`).
    settings : SimulationSettings
        The settings.
    defects : tuple
        The defects.
    extra : dict
        Further entries (the integrator's statistics).

    Returns
    -------
    dict
    """
    clean = _plain

    return {
        "bearing": clean(geometry),
        "operating": clean(operating),
        "rig": clean(rig),
        "scene": {**clean(scene), "resolved_level": level, "reason": reason},
        "settings": clean(settings),
        "defects": [_defect_record(geometry, d) for d in defects],
        **extra,
    }


@dataclass(frozen=True)
class Prepared:
    """Everything the kernels need for one run (packed, validated, at static equilibrium)."""

    geometry: BearingGeometry
    operating: OperatingCondition
    rig: Rig
    scene: Scene
    settings: SimulationSettings
    defects: tuple
    scene_name: str  # the resolved ``Scene.level``: "shaft", "shaft+housing" or "full"
    reason: str  # why that scene (``Scene(level="auto")``)
    scene_code: int  # its kernel code (``_kernels.SCENE_*``)
    ehl: bool
    freqs: BearingFrequencies | None
    p: np.ndarray
    wav: np.ndarray
    y0: np.ndarray
    max_ball_load: float

    @property
    def film_mode(self) -> int:
        """The kernels' film mode: ``_kernels.FILM_DRY``, ``FILM_EHL`` or ``FILM_ENTRAINED``.

        Returns
        -------
        int
            ``FILM_ENTRAINED`` where the film carries its entrainment at light load
            (``Rig.film_entrainment_factor``, docs/model.md 4.6), else the film switch.
        """
        if not self.ehl:
            return K.FILM_DRY
        return K.FILM_ENTRAINED if self.p[K.P_ENTRAINMENT_SERIES] > 0.0 else K.FILM_EHL


T = TypeVar("T")


@functools.cache
def default_instance(cls: type[T]) -> T:
    """The default instance of a frozen parameter class (built and validated once).

    Parameters
    ----------
    cls : type
        A parameter class (``Scene``, ``Rig``, ``SimulationSettings``).

    Returns
    -------
    object
        ``cls()``, the same object on every call.
    """
    return cls()


def prepare(
    bearing: BearingGeometry,
    operating: OperatingCondition,
    defects: Defect | Sequence[Defect] | None = None,
    *,
    scene: Scene | None = None,
    rig: Rig | None = None,
    settings: SimulationSettings | None = None,
    random_state: int | np.random.Generator | None = None,
) -> Prepared:
    """Validate the inputs, resolve the scene, pack parameters and find the static start.

    Parameters
    ----------
    bearing, operating, defects, scene, rig, settings, random_state
        As for :func:`generators.simulate`.

    Returns
    -------
    Prepared
        The run: among its fields the packed vector ``p``, the waviness table ``wav`` and
        the initial state ``y0`` (static equilibrium, velocities zero).
    """
    if not isinstance(bearing, BearingGeometry):
        hint = ""
        if isinstance(bearing, str):
            hint = f" (generators.bearing({bearing!r}) gives the catalog's)"
        raise ParameterError(f"bearing = {bearing!r} is not a BearingGeometry{hint}")
    if not isinstance(operating, OperatingCondition):
        raise ParameterError(f"operating = {operating!r} is not an OperatingCondition")
    scene = default_instance(Scene) if scene is None else scene
    rig = default_instance(Rig) if rig is None else rig
    settings = default_instance(SimulationSettings) if settings is None else settings
    for name, obj, cls in (
        ("scene", scene, Scene),
        ("rig", rig, Rig),
        ("settings", settings, SimulationSettings),
    ):
        if not isinstance(obj, cls):
            raise ParameterError(f"{name} = {obj!r} is not a {cls.__name__}")
    defect_list = as_defects(defects)
    if random_state is not None and not isinstance(random_state, np.random.Generator):
        check_int("random_state", random_state, low=0)  # a seed: an integer of at least 0
    rng = np.random.default_rng(random_state)
    for message in operating_range_warnings(bearing, operating):
        warnings.warn(message, OperatingRangeWarning, stacklevel=3)
    freqs = None
    if operating.shaft_frequency > 0:
        freqs = characteristic_frequencies(
            bearing, operating.shaft_frequency, cage_slip=operating.cage_slip
        )
    return prepare_checked(bearing, operating, defect_list, scene, rig, settings, rng, freqs)


def prepare_checked(
    geometry: BearingGeometry,
    operating: OperatingCondition,
    defect_list: tuple[Defect, ...],
    scene: Scene,
    rig: Rig,
    settings: SimulationSettings,
    rng: np.random.Generator,
    freqs: BearingFrequencies | None,
) -> Prepared:
    """:func:`prepare` from checked inputs (the dataset generator calls this per signal).

    Parameter objects of the right types, the defects as a tuple, the phase generator, and
    the bearing's frequencies at the operating point (``characteristic_frequencies`` with its
    cage slip; None for a standing shaft).

    Parameters
    ----------
    geometry, operating : BearingGeometry, OperatingCondition
        Checked.
    defect_list : tuple
        The defects, checked.
    scene, rig, settings : Scene, Rig, SimulationSettings
        Checked.
    rng : numpy.random.Generator
        The phase generator.
    freqs : BearingFrequencies or None
        As above [Hz].

    Returns
    -------
    Prepared
    """
    z = geometry.ball_count
    level, reason = resolve_scene(scene, geometry, operating, rig, settings)
    code = SCENE_CODES[level]
    # no entrainment, no film: a bearing standing or creeping (below EHL_MIN_SHAFT_FREQUENCY)
    # runs the dry path; a film of a few nanometres adds nothing but a stiffness so high that
    # the integration crawls (1e-9 rpm took minutes per millisecond)
    ehl = bool(scene.ehl) and operating.shaft_frequency >= EHL_MIN_SHAFT_FREQUENCY
    if rig.film_entrainment_factor > 0.0 and (not scene.ehl or level == "full"):
        raise ParameterError(
            f"rig.film_entrainment_factor = {rig.film_entrainment_factor:g} needs the film and "
            f"massless balls (Scene(ehl=True), level shaft or shaft+housing); the scene is "
            f"{level} {'with' if scene.ehl else 'without'} the film: allowed 0 there"
        )
    p = pack_parameters(geometry, operating, rig, ehl, freqs)
    if ehl:
        p = with_film_tables(p)
    p[K.P_CAGE_ANGLE0] = settings.cage_angle
    wav = waviness_table(defect_list, geometry, rng, operating.radial_load)
    if (operating.random_slip or operating.ball_jitter) and np.any(
        wav[:, K.W_SURFACE] >= K.SURF_OUTER_DEFECT
    ):
        # slip only moves where balls meet local defects: no rows (and no draws) without one
        wav = np.ascontiguousarray(
            np.vstack([wav, slip_rows(operating, z, p[K.P_CAGE_SPEED], rng)])
        )
    y0, qmax = static_state(level, ehl, geometry, operating, rig, p, wav)
    # the loading anchor (docs/model.md 1.3) holds the shaft at its static position
    p[K.P_LOADING_X0] = y0[0]
    p[K.P_LOADING_Y0] = y0[1]
    scale = max(map(abs, y0[: K.n_dof(code, z)].tolist()))
    p[K.P_MAX_DISPLACEMENT] = (
        settings.max_displacement
        if settings.max_displacement is not None
        else 20.0 * scale + 0.1 * geometry.ball_diameter
    )

    return Prepared(
        geometry,
        operating,
        rig,
        scene,
        settings,
        defect_list,
        level,
        reason,
        code,
        ehl,
        freqs,
        p,
        wav,
        y0,
        qmax,
    )


@dataclass(frozen=True)
class Plan:
    """Integration schedule of a prepared run (see :func:`rk4_schedule`)."""

    oversample: int
    record_dt: float
    n_out: int
    n_record: int
    dt: float  # RK4 step [s] (NaN for DOPRI5)
    n_steps: int
    t_first: float
    error_estimate: float = math.nan  # relative line error at dt, when chosen for a bound
    fine_steps: int = 1  # steps near a local defect split into this many (1: none)
    lead: int = 0  # records before the first output sample's (the decimation filter's reach)
    tail: int = 0  # records after the last output sample's

    @property
    def record_start(self) -> float:
        """Time of the first record [s]: ``lead`` records before the first output sample."""
        return self.t_first - self.lead * self.record_dt

    def output_slice(self) -> slice:
        """The output samples of the decimated record (without its lead and tail).

        Returns
        -------
        slice
        """
        first = self.lead // self.oversample
        return slice(first, first + self.n_out)


def plan_run(prep: Prepared, halvings: int = 0) -> Plan:
    """Step, record rate and record count of a prepared run (as :func:`simulate` does).

    Parameters
    ----------
    prep : Prepared
        The run.
    halvings : int
        RK4 at its default step only: the step halved this many times and not grown onto the
        record grid (what :func:`~generators.model.integrate` retries a diverged run with);
        0, the default step as it is.

    Returns
    -------
    Plan
    """
    settings = prep.settings
    step = None
    error = math.nan
    refine = False
    longest = 1.0
    oversample = settings.oversample
    if settings.integrator == "rk4" and settings.step is None and settings.error_bound:
        from .accuracy import error_bound_step  # the pilots need the kernels' entry points

        # recorded and decimated as its pilots were: what they measured is what it returns
        oversample = oversample or DEFAULT_OVERSAMPLE
        step, error = error_bound_step(prep, settings.error_bound, oversample)
    elif settings.integrator == "rk4":
        step = settings.step
        if step is None:
            # the accuracy default (not a requested step, not a stability limit) may grow a
            # little, within the stability step, to put the records on the step grid where
            # shortening cannot (12 and 48 kHz)
            step, longest = default_step_and_growth(
                prep.scene_name, prep.scene_code, prep.film_mode, prep.p, prep.wav, prep.y0
            )
            if halvings:
                step, longest = step / 2.0**halvings, 1.0
        refine = True  # never step over a pit, whatever the step
        oversample = oversample or default_oversample(settings.fs)
    oversample = oversample or DEFAULT_OVERSAMPLE
    record_dt = 1.0 / (settings.fs * oversample)
    n_out = int(round(settings.duration * settings.fs))
    # records beyond both ends as far as the decimation filter reads (before the first
    # output sample only as far as the settling goes, in whole output intervals)
    tail = filter_reach(oversample)
    lead = min(tail, oversample * int(settings.settle_time * settings.fs * (1 + 1e-12)))
    n_record = n_out * oversample + lead + tail
    t_first = settings.settle_time
    if step is None:
        return Plan(
            oversample, record_dt, n_out, n_record, math.nan, 0, t_first, lead=lead, tail=tail
        )
    dt, n_steps, _ = rk4_schedule(
        step, record_dt, t_first - lead * record_dt, n_record, oversample, longest
    )
    fine = defect_substeps(dt, prep.p, prep.wav) if refine else 1
    return Plan(
        oversample, record_dt, n_out, n_record, dt, n_steps, t_first, error, fine, lead, tail
    )


def diverged_error(prep: Prepared, status: int, t_fail: float) -> SimulationDivergedError:
    """The error that names the scene, the time and the reason of a diverged run.

    Parameters
    ----------
    prep : Prepared
        The run.
    status : int
        The kernel's status code (why it stopped).
    t_fail : float
        When [s].

    Returns
    -------
    SimulationDivergedError
    """
    why = STATUS_REASONS.get(status, f"status {status}")
    return SimulationDivergedError(
        f"simulation diverged in scene {prep.scene_name}/{'ehl' if prep.ehl else 'dry'} at t = "
        f"{t_fail:.6g} s: {why} (integrator {prep.settings.integrator}; try a smaller step or "
        "tolerance, or check the inputs)",
        scene=prep.scene_name,
        time=t_fail,
        reason=why,
    )
