"""The dynamic model: validate, pack, find the static start, integrate, decimate, wrap.

``simulate`` is the public entry point; the numba kernels (:mod:`generators._kernels`, the
right-hand sides; :mod:`generators._integrators`, the time stepping) work on plain arrays.
Model (docs/model.md sections 1-5):

* contact: Hertz Q = K delta^1.5 with stiffness-proportional damping c = tau dQ/d delta (D1),
  optional EHL film in series (Hamrock-Dowson central film, docs/model.md 4.3) and squeeze-film
  damping (D2, times ``Rig.film_damping_factor``);
* scenes ``shaft`` (2 DOF + one-way housing estimate), ``shaft+housing`` (4 DOF, massless
  balls, series contact constant), ``full`` (4 + Z DOF, one radial DOF per ball);
* waviness on the outer race, inner race and balls (docs/model.md 5), any harmonics;
* start at the static equilibrium (loads, gravity, film and waviness at t = 0), settle, record at
  ``oversample * fs`` and decimate with a zero-phase FIR anti-alias filter.
"""

from __future__ import annotations

import dataclasses
import logging
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import _integrators
from . import _kernels as K
from ._validate import SimulationDivergedError, StepShortenedWarning
from .batches import lanes_supported, simulate_lanes
from .decimation import decimate, record_columns
from .kinematics import BearingFrequencies
from .packing import Defect, slip_line_factor, slip_rows
from .params import (
    CHANNELS,
    BearingGeometry,
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
)
from .prepared import (
    Plan,
    Prepared,
    diverged_error,
    params_record,
    plan_run,
    prepare,
    resolve_scene,
)
from .steps import (
    DEFECT_STEPS,
    default_step,
    defect_step,
    jacobian,
    rk4_schedule,
    rk4_stability_radius,
)

if TYPE_CHECKING:
    import pandas as pd

#: How often :func:`integrate` halves a diverged RK4 run's default step before it reports the
#: divergence (the step down to an eighth).
MAX_STEP_HALVINGS = 3

__all__ = [
    "Prepared",
    "prepare",
    "SimulationResult",
    "simulate",
    "integrate",
    "resolve_scene",
    "default_step",
    "CHANNELS",
    "natural_frequencies",
    "lanes_supported",
    "rk4_schedule",
    "simulate_lanes",
    "rk4_stability_radius",
    "slip_rows",
    "slip_line_factor",
]

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class SimulationResult:
    """Signals and the full parameter record of one simulation.

    Attributes
    ----------
    time : ndarray, shape (n,)
        Sample times after settling [s] (start at 0).
    fs : float
        Sample rate [Hz].
    signals : dict of str to ndarray
        Channels named ``<body>_<quantity>_<axis>`` (see ``CHANNELS``) in m, m/s, m/s^2.
    frequencies : BearingFrequencies
        Characteristic frequencies of the run [Hz].
    parameters : dict
        Every parameter of the run (bearing, operating point, rig, scene, settings, defects,
        integrator statistics), JSON-serialisable.
    contact_loads : ndarray or None, shape (n, 2, Z)
        Inner [:, 0] and outer [:, 1] contact load of every ball [N], when requested (in
        scene ``full`` with the film, also the film's push between a ball and a race apart,
        docs/model.md 4.4: count a contact as loaded over a threshold, e.g. 0.1 N).
    """

    time: np.ndarray
    fs: float
    signals: dict[str, np.ndarray]
    frequencies: BearingFrequencies
    parameters: dict
    contact_loads: np.ndarray | None = None

    def __getitem__(self, channel: str) -> np.ndarray:
        """Return one channel by name, e.g. ``result["housing_velocity_y"]``."""
        return self.signals[channel]

    def to_frame(self) -> pd.DataFrame:
        """Return the signals as a pandas DataFrame with a ``time`` column [s].

        Returns
        -------
        pandas.DataFrame
            ``time`` [s] and one column per recorded channel, in SI units.
        """
        import pandas as pd

        data = {"time": self.time}
        data.update({name: self.signals[name] for name in CHANNELS if name in self.signals})
        return pd.DataFrame(data)


def simulate(
    bearing: BearingGeometry,
    operating: OperatingCondition,
    defects: Defect | Sequence[Defect] | None = None,
    *,
    scene: Scene | None = None,
    rig: Rig | None = None,
    settings: SimulationSettings | None = None,
    random_state: int | np.random.Generator | None = None,
) -> SimulationResult:
    """Simulate the housing and shaft vibration of a deep groove ball bearing.

    Convenience wrapper around the numba kernels ``_rk4`` / ``_dopri5``: validates, packs the
    parameters, starts from the static equilibrium, integrates, checks for divergence and
    decimates to ``settings.fs`` with a zero-phase FIR anti-alias filter.

    Parameters
    ----------
    bearing : BearingGeometry
        Bearing geometry (e.g. ``generators.bearing("6205")``).
    operating : OperatingCondition
        Shaft speed [Hz] and radial load [N].
    defects : Waviness, LocalizedDefect or a sequence of them, optional
        Surface waviness harmonics and local defects (pits, spalls) on the outer race, inner
        race and balls.
    scene : Scene, optional
        Model level and EHL switch; default ``Scene()`` (``shaft+housing`` with EHL).
    rig : Rig, optional
        Masses, pedestal, damping, lubricant; default ``Rig()`` (docs/model.md 6.3).
    settings : SimulationSettings, optional
        Sample rate [Hz], duration [s], settling [s], integrator and step.
    random_state : int or numpy Generator, optional
        Seeds the random waviness phases (``phase=None``, ball waviness).

    Returns
    -------
    SimulationResult
        Signals ``<body>_<quantity>_<axis>`` [m, m/s, m/s^2], time [s], frequencies [Hz] and
        the full parameter record.

    Raises
    ------
    ParameterError
        An input is outside its valid range.
    SimulationDivergedError
        The integration produced a non-finite or runaway state, or the adaptive step
        collapsed; the message names the scene and the time. At RK4's default step the run
        is first integrated again at up to an eighth of it (:func:`integrate`).

    Warns
    -----
    StepShortenedWarning
        The default RK4 step diverged and a shorter one ran through (:func:`integrate`).

    Examples
    --------
    >>> from generators import OperatingCondition, SimulationSettings, Waviness, bearing
    >>> from generators import simulate
    >>> r = simulate(bearing("6205"), OperatingCondition.from_rpm(1800, 500.0),
    ...              Waviness(surface="outer", order=9, amplitude=1e-6),
    ...              settings=SimulationSettings(duration=0.05, settle_time=0.02))
    >>> r["housing_velocity_y"].shape
    (1280,)
    """
    prep = prepare(
        bearing,
        operating,
        defects,
        scene=scene,
        rig=rig,
        settings=settings,
        random_state=random_state,
    )
    return integrate(prep)


def integrate(prep: Prepared) -> SimulationResult:
    """Integrate a prepared run (:func:`prepare`): the second half of :func:`simulate`.

    Named stages, each a function of the run and what the earlier stages made: the schedule
    (:func:`~generators.prepared.plan_run`), the record buffers (:class:`_Record`), the
    integration (:func:`_run_rk4` or :func:`_run_dopri5`), the divergence check, and the
    result (:func:`_result`: decimated signals and the parameter record).

    Parameters
    ----------
    prep : Prepared
        The prepared run.

    Returns
    -------
    SimulationResult
        As :func:`simulate`.

    Raises
    ------
    SimulationDivergedError
        As :func:`simulate`.

    Warns
    -----
    StepShortenedWarning
        RK4 at its default step diverged and the run was integrated again at half, a quarter
        or an eighth of it (``MAX_STEP_HALVINGS``), which ran through; the result's
        ``integrator_stats`` hold the step used and ``step_halvings``. With a step given, or an
        error bound, a diverged run is reported at once.
    """
    plan = plan_run(prep)
    record = _Record.allocate(prep, plan)
    run = _run_rk4 if prep.settings.integrator == "rk4" else _run_dopri5
    status, t_fail, stats = run(prep, plan, record)
    settings = prep.settings
    # RK4 at its default step: the step is the stability limit at the static start, and a run
    # that goes far from it (a ball knocked into firm contact by a pit in a dry, lightly
    # loaded `full` scene: docs/model.md 7.2) can leave RK4's region; halved and run again
    retry = settings.integrator == "rk4" and settings.step is None and not settings.error_bound
    halvings = 0
    failed_at, failed_step = t_fail, plan.dt
    while status != K.STATUS_OK and retry and halvings < MAX_STEP_HALVINGS:
        halvings += 1
        plan = plan_run(prep, halvings)
        record = _Record.allocate(prep, plan)
        status, t_fail, stats = run(prep, plan, record)
        if status == K.STATUS_OK:
            stats["step_halvings"] = halvings
            scene = f"{prep.scene_name}/{'ehl' if prep.ehl else 'dry'}"
            warnings.warn(step_shortened(failed_step, failed_at, scene, plan.dt), stacklevel=2)
    if status != K.STATUS_OK:
        error = diverged_error(prep, int(status), float(t_fail))
        if halvings:
            error = SimulationDivergedError(
                f"{error} (and at the default step, {failed_step:.3g} s, at t = "
                f"{failed_at:.6g} s, and every halving of it down to {plan.dt:.3g} s)",
                scene=error.scene,
                time=error.time,
                reason=error.reason,
            )
        raise error
    return _result(prep, plan, record, stats)


def step_shortened(
    default_step: float, failed_at: float, scene: str, step: float
) -> StepShortenedWarning:
    """The warning of a run made again at ``step`` [s] after its default step diverged.

    Parameters
    ----------
    default_step : float
        The default RK4 step [s].
    failed_at : float
        When the run at it diverged [s].
    scene : str
        The scene (its level, and its film where known).
    step : float
        The step the run went through at [s].

    Returns
    -------
    StepShortenedWarning
    """
    return StepShortenedWarning(
        f"the run diverged at its default RK4 step, {default_step:.3g} s, at t = "
        f"{failed_at:.6g} s (scene {scene}): integrated again at {step:.3g} s"
    )


@dataclass(frozen=True)
class _Record:
    """The integration record the kernels fill: states, accelerations, contact loads."""

    state: np.ndarray  # (n_record, K.N_OUT_STATE)
    accel: np.ndarray  # (n_record, K.N_OUT_ACCEL)
    loads: np.ndarray  # (n_record, 2, Z), or (1, 2, Z) when not recorded
    with_loads: bool

    @classmethod
    def allocate(cls, prep: Prepared, plan: Plan) -> _Record:
        with_loads = bool(prep.settings.record_contact_loads)
        z = prep.geometry.ball_count
        return cls(
            np.zeros((plan.n_record, K.N_OUT_STATE)),
            np.zeros((plan.n_record, K.N_OUT_ACCEL)),
            np.zeros((plan.n_record if with_loads else 1, 2, z)),
            with_loads,
        )


def _run_rk4(prep: Prepared, plan: Plan, record: _Record) -> tuple[int, float, dict]:
    """Fixed-step RK4 over the plan's grid: (status, time reached, integrator statistics)."""
    status, t_fail, _ = _integrators._rk4(
        prep.scene_code,
        prep.film_mode,
        prep.y0,
        prep.p,
        prep.wav,
        0.0,
        plan.dt,
        plan.n_steps,
        plan.record_start,
        plan.record_dt,
        plan.n_record,
        record.state,
        record.accel,
        record.loads,
        record.with_loads,
        plan.fine_steps,
        record_columns(prep.settings.channels or CHANNELS, plan.oversample),
    )
    stats = {"step_s": plan.dt, "steps": plan.n_steps}
    if plan.fine_steps > 1:
        stats["defect_step_s"] = plan.dt / plan.fine_steps  # near a local defect
    if prep.settings.error_bound and prep.settings.step is None:
        stats["error_bound"] = prep.settings.error_bound
        stats["line_error_estimate"] = plan.error_estimate
    return status, t_fail, stats


def _run_dopri5(prep: Prepared, plan: Plan, record: _Record) -> tuple[int, float, dict]:
    """Adaptive DOPRI5 with dense output: (status, time reached, integrator statistics)."""
    settings = prep.settings
    nd = K.n_dof(prep.scene_code, prep.geometry.ball_count)
    atol = np.empty(2 * nd)
    atol[:nd] = settings.atol_displacement
    atol[nd:] = settings.atol_displacement * 1e3
    stats = np.zeros(4)
    # never step over a local defect: at most half a passage per step
    h_max = min(plan.record_dt * 4, 0.5 * DEFECT_STEPS * defect_step(prep.p, prep.wav))
    span = plan.record_start + plan.n_record * plan.record_dt
    max_steps = int(settings.max_steps_per_second * span) + 1000
    status, t_fail, _ = _integrators._dopri5(
        prep.scene_code,
        prep.film_mode,
        prep.y0,
        prep.p,
        prep.wav,
        0.0,
        plan.record_start,
        plan.record_dt,
        plan.n_record,
        settings.rtol,
        atol,
        min(1e-7, plan.record_dt),
        h_max,
        max_steps,
        record.state,
        record.accel,
        record.loads,
        record.with_loads,
        stats,
    )
    return (
        status,
        t_fail,
        {
            "accepted_steps": int(stats[0]),
            "rejected_steps": int(stats[1]),
            "min_step_s": float(stats[2]),
            "max_step_s": float(stats[3]),
        },
    )


def _result(prep: Prepared, plan: Plan, record: _Record, stats: dict) -> SimulationResult:
    """Decimated signals, contact loads and the parameter record of an integrated run."""
    settings = prep.settings
    oversample = plan.oversample
    signals = decimate(
        record.state, record.accel, oversample, settings.channels or CHANNELS, plan.record_dt
    )
    kept = plan.output_slice()  # the output samples, without the filter's lead and tail
    signals = {name: np.ascontiguousarray(x[kept]) for name, x in signals.items()}
    time = np.arange(plan.n_out) / settings.fs
    loads = None
    if record.with_loads:
        loads = record.loads[plan.lead :: oversample][: plan.n_out].copy()
    extra = {
        "integrator_stats": stats,
        "oversample": oversample,
        "first_sample_time_s": plan.t_first,
        "max_static_ball_load_n": prep.max_ball_load,
    }
    params = params_record(
        prep.geometry,
        prep.operating,
        prep.rig,
        prep.scene,
        prep.scene_name,
        prep.reason,
        settings,
        prep.defects,
        extra,
    )
    freqs = prep.freqs
    if freqs is None:
        freqs = BearingFrequencies(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    return SimulationResult(
        time=time,
        fs=settings.fs,
        signals=signals,
        frequencies=freqs,
        parameters=params,
        contact_loads=loads,
    )


def natural_frequencies(
    bearing: BearingGeometry,
    operating: OperatingCondition,
    *,
    scene: Scene | None = None,
    rig: Rig | None = None,
) -> np.ndarray:
    """Natural frequencies of the model linearised about its static equilibrium [Hz].

    docs/model.md 7.5: the cage is frozen (no rotation, no centrifugal force), the Jacobian of the
    first-order right-hand side is built by central differences (displacements perturbed by
    1e-11 m, velocities by 1e-7 m/s) and its eigenvalues are taken. Returns the damped
    frequencies |Im lambda| / 2 pi of the oscillatory modes, highest first (balls out of contact
    give zero eigenvalues and are left out).

    Parameters
    ----------
    bearing : BearingGeometry
        Bearing geometry.
    operating : OperatingCondition
        Radial load [N] (the speed is ignored: the cage is frozen).
    scene : Scene, optional
        Model level and EHL switch (``auto`` is resolved as in :func:`simulate`).
    rig : Rig, optional
        Masses, pedestal and damping.

    Returns
    -------
    ndarray
        Damped natural frequencies [Hz], descending.
    """
    frozen = dataclasses.replace(operating, shaft_frequency=0.0)
    prep = prepare(bearing, frozen, scene=scene, rig=rig)
    nd = prep.y0.size // 2
    jac = jacobian(prep.scene_code, prep.film_mode, prep.p, prep.wav, prep.y0)
    if prep.scene_name == "shaft":
        # the one-way housing estimate is not part of the shaft scene's dynamics
        keep = [0, 1, nd, nd + 1]
        jac = jac[np.ix_(keep, keep)]
    lam = np.linalg.eigvals(jac)
    freqs = np.abs(lam.imag[lam.imag > 1e-6]) / (2 * np.pi)
    return np.sort(freqs)[::-1]
