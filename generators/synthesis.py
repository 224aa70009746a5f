"""Synthesis of a recipe's cases: one labelled signal per case (:mod:`generators.recipe`).

Each case is simulated (batches of healthy and waviness runs in SIMD lanes, local defects one
by one), passed through the recipe's measurement chain (docs/realism.md) and returned as one
row: the case's columns, the signal and an error message where it could not be made.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from scipy import signal as sp_signal

from . import _kernels as K
from ._validate import ParameterError, SimulationDivergedError
from .batches import lanes_supported, simulate_lanes
from .cases import DAMPING_RATIO_KEYS, RIG_KEYS, Case
from .catalog import bearing
from .form import form_waviness
from .kinematics import characteristic_frequencies, passage_lines
from .measurement import (
    MachineBackground,
    StructuralMode,
    SupportStructure,
    anti_alias_filter,
    digitise,
    electronic_noise,
    fault_band_powers,
    machine_background,
    overall_velocity_band,
    overall_velocity_rms,
    sensor_noise,
    sensor_response,
    transfer_path,
)
from .model import integrate
from .params import (
    GRAVITY,
    BearingGeometry,
    LocalizedDefect,
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
    Waviness,
)
from .prepared import Prepared, default_instance, prepare_checked
from .static import static_load_distribution
from .steps import DEFAULT_OVERSAMPLE

__all__ = [
    "bearing_stiffness",
    "case_rig",
    "generate_case",
    "generate_cases",
    "bound_steps",
    "step_group",
    "GENERATOR_REVISION",
    "MAX_FAULT_GAIN",
]

#: Raised whenever the same case gives other signals (a dataset's files record it, and
#: ``cmtool generate --resume`` refuses to top up files of another revision: the signals
#: would mix two generators). 1: until stop 46 (no record in the files). 2: accelerations
#: are the velocity record's derivative and runs record beyond their ends (stop 46). 3: records
#: between step starts are the quintic Hermite interpolant through position, velocity and
#: acceleration (stop 47).
GENERATOR_REVISION = 3


def _resonance(x: np.ndarray, fs: float, f0: float, zeta: float) -> np.ndarray:
    """Sensor/structure resonance: a second-order band-pass (unit gain at f0), bilinear."""
    w0 = 2 * np.pi * f0
    # H(s) = 2 zeta w0 s / (s^2 + 2 zeta w0 s + w0^2): |H(j w0)| = 1
    b, a = sp_signal.bilinear([2 * zeta * w0, 0.0], [1.0, 2 * zeta * w0, w0 * w0], fs)
    return sp_signal.lfilter(b, a, x)


@dataclass
class _Job:
    """One case on its way through :func:`generate_cases`."""

    case: Case
    meta: dict
    rng: np.random.Generator
    run: Prepared | None = None  # the case's simulation
    healthy: Prepared | None = None  # its healthy twin (background noise), if needed
    error: str | None = None
    untouched: bool = False  # a local defect the run never meets: simulated as healthy


def _setup(recipe: dict, case: Case, channel: str, shared: dict) -> _Job:
    """Metadata of a case and its prepared simulation(s) (phases drawn from the case seed).

    ``shared``: the validated parameter objects that cases of one call have in common
    (geometry per bearing and clearance, settings per sample rate, the scene), built once.
    """
    r = recipe
    sensor, model = r["sensor"], r["model"]
    geometry = shared.get(("bearing", case.bearing, case.clearance_m))
    if geometry is None:
        overrides = (
            {} if case.clearance_m is None else {"radial_internal_clearance": case.clearance_m}
        )
        geometry = bearing(case.bearing, **overrides)
        shared["bearing", case.bearing, case.clearance_m] = geometry
    operating = OperatingCondition.from_rpm(
        case.rpm,
        case.radial_load_n,
        random_slip=case.random_slip,
        ball_jitter=case.ball_jitter_rad,
        load_angle=case.load_angle_rad,
        cage_slip=case.cage_slip,
    )
    # the bearing's own form errors come first: a case and its healthy twin draw the same
    # phases for them (generators.form)
    form = form_waviness(
        geometry.ball_count,
        case.inner_form_waviness_m,
        case.outer_form_waviness_m,
        case.ball_form_waviness_m,
    )
    defects: list = []
    if case.defect_kind == "localized":
        defects.append(
            LocalizedDefect(
                surface=case.surface,
                length=case.defect_length_m,
                depth=case.defect_depth_m,
                position=None if math.isnan(case.defect_position_rad) else case.defect_position_rad,
                # a ball pit lies anywhere on the ball: its latitude is drawn per case
                **(
                    {"latitude": None, "axis_drift": case.defect_axis_drift_rad_s}
                    if case.surface == "ball"
                    else {}
                ),
            )
        )
    elif case.surface is not None:
        defects.append(
            Waviness(
                surface=case.surface,
                order=case.waviness_order,
                amplitude=case.waviness_amplitude_m,
                phase=None,
            )
        )
    # the recipe's step, or the one found for this bearing, rate and condition (bound_steps)
    step = model.get("group_steps", {}).get(step_group(case), (model.get("step_s"), None))[0]
    settings = shared.get(("settings", case.fs_hz, step))
    if settings is None:
        settings = SimulationSettings(
            fs=case.fs_hz,
            duration=float(sensor["duration_s"]),
            settle_time=float(sensor["settle_s"]),
            integrator=model["integrator"],
            step=step,
            rtol=model.get("rtol", 1e-6),
            channels=(channel,),
            # a bound's step records as its pilots did (generators.accuracy)
            oversample=None if model.get("error_bound") is None else DEFAULT_OVERSAMPLE,
        )
        shared["settings", case.fs_hz, step] = settings
    freqs = characteristic_frequencies(
        geometry, operating.shaft_frequency, cage_slip=operating.cage_slip
    )
    # the rate columns are the kinematic rates an analyst computes from the speed (what a
    # detector is given); the run's cage lags them by cage_slip
    nominal = characteristic_frequencies(geometry, operating.shaft_frequency)
    wpf = math.nan
    if case.defect_kind == "waviness":
        # waviness_passage_frequencies from the frequencies at hand (order checked by the recipe)
        lines = passage_lines(nominal, geometry.ball_count, case.surface, case.waviness_order, 2)
        strong = [ln.frequency for ln in lines if ln.strength == "strong"]
        wpf = strong[0] if strong else (lines[0].frequency if lines else math.nan)
    meta = {
        "id": f"{r['name']}-{case.index:06d}",
        "index": case.index,
        "label": case.label,
        "condition": case.condition,
        "bearing": case.bearing,
        "operating_point_id": case.operating_point_id,
        "rpm": case.rpm,
        "shaft_frequency_hz": operating.shaft_frequency,
        "radial_load_n": case.radial_load_n,
        "load_angle_rad": case.load_angle_rad,
        **{key: getattr(case, key) for key in RIG_KEYS},
        "film_entrainment_factor": case.film_entrainment_factor,
        **{key: getattr(case, key) for key in DAMPING_RATIO_KEYS},
        "radial_internal_clearance_m": geometry.radial_internal_clearance,
        "surface": case.surface or "none",
        "waviness_order": case.waviness_order,
        "waviness_amplitude_m": case.waviness_amplitude_m,
        "defect_kind": case.defect_kind,
        "defect_length_m": case.defect_length_m,
        "defect_depth_m": case.defect_depth_m,
        "defect_position_rad": case.defect_position_rad,
        "defect_axis_drift_rad_s": case.defect_axis_drift_rad_s,
        "seed": case.seed,
        "scene": model["scene"],
        "ehl": model["ehl"],
        "integrator": model["integrator"],
        "step_s": float(step or math.nan),
        "quantity": sensor["quantity"],
        "body": sensor["body"],
        "direction": sensor["direction"],
        "fs_hz": case.fs_hz,
        "duration_s": float(sensor["duration_s"]),
        "snr_db": math.nan if case.snr_db is None else case.snr_db,
        "background_db": case.background_db,
        "fault_snr_db": case.fault_snr_db,
        "noise_rms": 0.0,
        "resonance_hz": case.resonance_hz,
        "ftf_hz": nominal.ftf,
        "bpfo_hz": nominal.bpfo,
        "bpfi_hz": nominal.bpfi,
        "bsf_hz": nominal.bsf,
        "two_bsf_hz": nominal.two_bsf,
        "wpf_hz": wpf,
        "random_slip": case.random_slip,
        "ball_jitter_rad": case.ball_jitter_rad,
        "cage_slip": case.cage_slip,
        "inner_form_waviness_m": case.inner_form_waviness_m,
        "outer_form_waviness_m": case.outer_form_waviness_m,
        "ball_form_waviness_m": case.ball_form_waviness_m,
        "fault_band_low_hz": math.nan,
        "fault_band_high_hz": math.nan,
        "chain": "",
    }
    job = _Job(case=case, meta=meta, rng=np.random.default_rng(case.seed))
    scene = shared.get("scene")
    if scene is None:
        scene = shared["scene"] = Scene(level=model["scene"], ehl=model["ehl"])

    def healthy() -> Prepared:
        # the same case without its defects (prepare() without re-checking these objects)
        rng = np.random.default_rng(case.seed)
        return prepare_checked(geometry, operating, form, scene, rig, settings, rng, freqs)

    try:
        rig = case_rig(case, geometry)
        job.run = prepare_checked(
            geometry, operating, form + tuple(defects), scene, rig, settings, job.rng, freqs
        )
        if not math.isnan(case.background_db) and defects:
            job.healthy = healthy()
        if case.defect_kind == "localized" and _untouched(job.run, settings):
            # a ball pit that stays off the contact track for the whole run changes nothing:
            # the run is its healthy twin (integrated with the others, in SIMD lanes)
            job.untouched = True
            job.run = job.healthy or healthy()
    except ParameterError as err:  # e.g. no static equilibrium for this case's geometry
        job.error = f"not simulated: {err}"
    return job


def case_rig(case: Case, geometry: BearingGeometry) -> Rig:
    """The rig of a case: the default ``Rig`` with what the recipe drew for it.

    ``RIG_KEYS`` columns replace their ``Rig`` fields; ``DAMPING_RATIO_KEYS`` columns set the
    dashpots from modal damping ratios: the pedestal damping 2 zeta_h sqrt(k_h M_h) (the
    housing on its support), the shaft damping 2 zeta_s sqrt(k_r M_s), k_r the bearing's
    static radial stiffness at the case's load and clearance (:func:`bearing_stiffness`); the
    ``film_entrainment_factor`` column (the recipe's ``[model]`` key, drawn per case;
    docs/model.md 4.6) sets ``Rig.film_entrainment_factor``. NaN columns keep the default's
    values.

    Parameters
    ----------
    case : Case
        A drawn case.
    geometry : BearingGeometry
        The case's bearing (with its clearance).

    Returns
    -------
    Rig
        Validated (a value out of ``Rig``'s ranges raises ``ParameterError`` naming it).
    """
    rig = default_instance(Rig)
    drawn = {
        field: getattr(case, key)
        for key, field in RIG_KEYS.items()
        if not math.isnan(getattr(case, key))
    }
    if case.film_entrainment_factor > 0.0:  # NaN (not drawn) and 0: none
        drawn["film_entrainment_factor"] = case.film_entrainment_factor
    if drawn:
        rig = dataclasses.replace(rig, **drawn)
    zeta_h, zeta_s = case.housing_damping_ratio, case.shaft_damping_ratio
    dashpots = {}
    if not math.isnan(zeta_h):
        dashpots["pedestal_damping"] = (
            2.0 * zeta_h * math.sqrt(rig.pedestal_stiffness * rig.housing_mass)
        )
    if not math.isnan(zeta_s):
        k_r = bearing_stiffness(geometry, case.radial_load_n, rig)
        dashpots["shaft_damping"] = 2.0 * zeta_s * math.sqrt(k_r * rig.shaft_mass)
    return dataclasses.replace(rig, **dashpots) if dashpots else rig


def bearing_stiffness(geometry: BearingGeometry, radial_load: float, rig: Rig) -> float:
    """The bearing's static radial stiffness k_r [N/m] at a case's load (dry Hertz).

    Where ``radial_load`` leaves a bearing with clearance unloaded (no load), at the shaft's
    weight, which the model applies (``Rig.gravity``); 0 if neither loads it.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    radial_load : float
        The case's load [N].
    rig : Rig
        The rig (the shaft's mass [kg] and gravity).

    Returns
    -------
    float
        k_r [N/m].
    """
    k_r = _radial_stiffness(geometry, radial_load)
    if k_r <= 0.0 and rig.gravity:
        k_r = _radial_stiffness(geometry, rig.shaft_mass * GRAVITY)
    return k_r


@functools.lru_cache(maxsize=256)
def _radial_stiffness(geometry: BearingGeometry, radial_load: float) -> float:
    """``static_load_distribution``'s radial stiffness [N/m], solved once per bearing and load.

    A case asks for it twice: its shaft dashpot (:func:`case_rig`) and its machine noise's
    structure (``_finish_realistic``).
    """
    return static_load_distribution(geometry, radial_load).radial_stiffness


def _untouched(prep: Prepared, settings: SimulationSettings) -> bool:
    """Whether every local defect of a run is a ball pit the races never meet.

    A ball pit at latitude lat(t) = lat0 + drift t meets the races only while |sin lat| is
    under the contact track's half width (``_kernels._track_factor``); over the run, from 0 to
    the settling plus the record, lat(t) sweeps one interval, and the pit stays untouched when
    that interval comes nowhere within asin(track) of a multiple of pi.
    """
    rows = prep.wav[prep.wav[:, K.W_SURFACE] >= K.SURF_OUTER_DEFECT]
    rows = rows[rows[:, K.W_SURFACE] != K.SURF_SLIP]
    if not rows.size:
        return False
    end = settings.settle_time + settings.duration + 1e-3  # and the last step
    for row in rows:
        if row[K.W_SURFACE] not in (K.SURF_BALL_DEFECT_OUTER, K.SURF_BALL_DEFECT_INNER):
            return False
        reach = math.asin(min(row[K.W_TRACK], 1.0))
        start, stop = sorted((row[K.W_LATITUDE], row[K.W_LATITUDE] + row[K.W_DRIFT] * end))
        # distance from the swept interval to the nearest multiple of pi (the rolling circle)
        gap = min(
            max(start - math.pi * k, math.pi * k - stop, 0.0)
            for k in range(math.floor(start / math.pi), math.ceil(stop / math.pi) + 1)
        )
        if gap < reach:
            return False
    return True


def _measured(recipe: dict, case: Case, x: np.ndarray) -> np.ndarray:
    """The sensor's view of a simulated channel: mean removed (displacement), resonance."""
    sensor = recipe["sensor"]
    x = x - x.mean() if sensor["quantity"] == "displacement" else x
    if not math.isnan(case.resonance_hz):
        x = _resonance(x, case.fs_hz, case.resonance_hz, float(sensor["resonance_damping"]))
    return x


#: Largest factor by which the realistic chain scales a fault's simulated signature to reach
#: the drawn fault SNR (40 dB).
MAX_FAULT_GAIN = 100.0


def _pick(spec: dict | None, rng: np.random.Generator, default, *, integer: bool = False):
    """One value of a recipe grid (chosen at random) or range (uniform), or ``default``."""
    if spec is None:
        return default
    if "grid" in spec:
        v = spec["grid"][int(rng.integers(len(spec["grid"])))]
    else:
        lo, hi = spec["range"]
        v = rng.integers(int(lo), int(hi) + 1) if integer else rng.uniform(lo, hi)
    return int(v) if integer else float(v)


def _realistic(recipe: dict) -> bool:
    """Whether a validated recipe asks for the realistic measurement chain."""
    return "background" in recipe or "modes" in recipe["sensor"]


#: The lines of a healthy bearing's own form errors in the plain spectrum, relative to the
#: drawn level of their family [dB]: the inner race's orders Z - 1, Z, Z + 1 at BPFI - fs,
#: BPFI, BPFI + fs, and the balls' order 2 at 2 BSF - FTF, 2 BSF, 2 BSF + FTF; the pattern the
#: dynamic model gives (a 6205 at 1730-1797 rpm, 300 and 1000 N, form errors of 0.01-0.2 um
#: from ``form_waviness``: docs/realism.md 9).
FORM_LINE_PATTERN_DB = {
    "form_inner_db": (
        (("bpfi", "shaft", -1.0), -7.0),
        (("bpfi", None, 0.0), 0.0),
        (("bpfi", "shaft", 1.0), 4.0),
    ),
    "form_ball_db": (
        (("two_bsf", "ftf", -1.0), 0.0),
        (("two_bsf", None, 0.0), 0.0),
        (("two_bsf", "ftf", 1.0), 0.0),
    ),
}


def _form_lines(
    background: dict, rng: np.random.Generator, reference: float, geometry, rpm: float
) -> tuple[tuple[tuple[float, float], ...], dict]:
    """The test bearing's own form-error lines (frequency [Hz], amplitude) and their levels.

    Each family present in ``background`` (``form_inner_db``, ``form_ball_db``) has its level
    drawn in dB over ``reference`` (the healthy bearing's RMS at the sensor) and its lines at
    the kinematic rates (:data:`FORM_LINE_PATTERN_DB`); none drawn without the keys.
    """
    lines: list[tuple[float, float]] = []
    drawn: dict[str, float] = {}
    freqs = None
    for key, pattern in FORM_LINE_PATTERN_DB.items():
        db = _pick(background.get(key), rng, None)
        if db is None:
            continue
        if freqs is None:
            freqs = characteristic_frequencies(geometry, rpm / 60.0).as_dict()
        drawn[key] = db
        for (rate, spacing, sign), offset_db in pattern:
            f = freqs[rate] + (sign * freqs[spacing] if spacing else 0.0)
            lines.append((f, reference * 10.0 ** ((db + offset_db) / 20.0)))
    return tuple(lines), drawn


def _finish_realistic(
    recipe: dict, job: _Job, x: np.ndarray, healthy: np.ndarray, signal_dtype: type
) -> dict:
    """The realistic chain (docs/realism.md): structure, background, fault SNR, sensor, ADC.

    Every random choice of the chain comes from its own generator seeded by the case's seed,
    so the simulation's draws are those of the same case without the chain.
    """
    case, meta, sensor = job.case, job.meta, recipe["sensor"]
    background = recipe.get("background", {})
    rng = np.random.default_rng([case.seed, 7])
    fs = case.fs_hz
    modes = tuple(
        StructuralMode(
            frequency=_pick(sensor.get("mode_hz"), rng, 3000.0),
            damping=_pick(sensor.get("mode_damping"), rng, 0.05),
            gain=10.0 ** (_pick(sensor.get("mode_gain_db"), rng, 0.0) / 20.0),
        )
        for _ in range(_pick(sensor.get("modes"), rng, 0, integer=True))
    )
    if healthy is x:
        at_sensor = healthy_at_sensor = transfer_path(x, fs, modes)
    else:  # both records through the structure in one pass
        at_sensor, healthy_at_sensor = transfer_path(np.stack([x, healthy]), fs, modes)
    reference = float(np.sqrt(np.mean(healthy_at_sensor**2))) or 1e-12

    def level(key: str, default_db: float | None) -> float:
        db = _pick(background.get(key), rng, default_db)
        return 0.0 if db is None else reference * 10.0 ** (db / 20.0)

    shaft_1x = level("shaft_db", None)
    decay = _pick(background.get("shaft_decay_db"), rng, 6.0)
    shaft = tuple(
        shaft_1x * 10.0 ** ((-decay * h + rng.uniform(-3.0, 3.0)) / 20.0)
        for h in range(_pick(background.get("shaft_harmonics"), rng, 3, integer=True))
    )
    line_hz = _pick(background.get("line_hz"), rng, 60.0)
    line_2x = level("line_db", None)
    other = level("other_bearing_db", None)
    other_lines: tuple = ()
    if "other_bearing" in background and other > 0.0:
        f = characteristic_frequencies(bearing(background["other_bearing"]), case.rpm / 60.0)
        other_lines = ((f.bpfo, other), (2.0 * f.bpfo, other / 2.0), (f.bpfi, other / 2.0))
    floor = level("floor_db", None)
    # the rotor's own broadband excitation (electromagnetic pull, coupling, the other
    # bearing) over the frame's, drawn last so that recipes without it keep their draws
    rotor_db = _pick(background.get("rotor_force_db"), rng, None)
    machine = MachineBackground(
        broadband_rms=reference * 10.0 ** (case.background_db / 20.0),
        shaft_harmonics=shaft,
        line_frequency=line_hz,
        line_harmonics=(line_2x / 2.0, line_2x),
        other_lines=other_lines,
        floor_rms=floor,
        rotor_force_ratio=0.0 if rotor_db is None else 10.0 ** (rotor_db / 20.0),
    )
    rig, geometry = job.run.rig, job.run.geometry
    support = SupportStructure(
        shaft_mass=rig.shaft_mass,
        housing_mass=rig.housing_mass,
        bearing_stiffness=bearing_stiffness(geometry, case.radial_load_n, rig),
        pedestal_stiffness=rig.pedestal_stiffness,
        shaft_damping=rig.shaft_damping,
        pedestal_damping=rig.pedestal_damping,
    )
    noise = machine_background(x.size, fs, case.rpm / 60.0, machine, modes, rng, support)
    # the bearing's own form errors (docs/realism.md 9): levels and phases from a generator of
    # their own, so that every other draw of the case is the same with the keys as without
    form_rng = np.random.default_rng([case.seed, 7, 9])
    form_lines, form_db = _form_lines(background, form_rng, reference, job.run.geometry, case.rpm)
    if form_lines:
        own = MachineBackground(other_lines=form_lines)
        noise = noise + machine_background(x.size, fs, case.rpm / 60.0, own, (), form_rng)
    chain: dict = {
        "modes": [[m.frequency, m.damping, m.gain] for m in modes],
        "shaft_amplitudes": list(shaft),
        "line_hz": line_hz,
        "line_2x_amplitude": line_2x,
        "other_lines": [list(pair) for pair in other_lines],
        "floor_rms": machine.floor_rms,
    }
    if rotor_db is not None:
        chain["rotor_force_db"] = rotor_db
    if form_lines:
        chain.update(form_db, form_lines=[list(pair) for pair in form_lines])
    y = healthy_at_sensor + noise
    level_scale = _level_scale(recipe, case, y, chain)
    if healthy is not x:
        signature = at_sensor - healthy_at_sensor
        gain = 1.0
        if not math.isnan(case.fault_snr_db) and np.any(signature):
            # the fault's visibility where it stands out most: the band SNR is the label. How
            # loud a pit of a given size is on a machine is not known, so the signature is
            # scaled to the drawn SNR, by at most MAX_FAULT_GAIN: a pit the balls barely
            # touch (outside the load zone) stays as faint as the model makes it, and the
            # SNR recorded is the one reached.
            band, own, rest = fault_band_powers(signature, y, fs)
            meta["fault_band_low_hz"], meta["fault_band_high_hz"] = band
            own = max(own, 1e-300)
            wanted = rest * 10.0 ** (case.fault_snr_db / 10.0)
            gain = min(math.sqrt(wanted / own), MAX_FAULT_GAIN)
            meta["fault_snr_db"] = 10.0 * math.log10(max(gain * gain * own, 1e-300) / rest)
        chain["fault_gain"] = gain
        y = y + gain * signature
    y = level_scale * y
    if job.untouched and not math.isnan(case.fault_snr_db):
        meta["fault_snr_db"] = -math.inf  # nothing of the fault reaches the sensor
    resonance = _pick(sensor.get("sensor_resonance_hz"), rng, None)
    if resonance is not None:
        zeta = _pick(sensor.get("sensor_damping"), rng, 0.03)
        y = sensor_response(y, fs, resonance, zeta)
        chain["sensor_resonance_hz"], chain["sensor_damping"] = resonance, zeta
    if "sensor_noise_density" in sensor:
        # the accelerometer's own noise, absolute (it does not follow the vibration), after
        # its resonance; from a generator of its own, as the electronics' below
        noise_rng = np.random.default_rng([case.seed, 7, 17])
        density = _pick(sensor["sensor_noise_density"], noise_rng, None)
        y, own_noise = sensor_noise(y, fs, density, noise_rng)
        chain["sensor_noise_density"], chain["sensor_noise_rms"] = density, own_noise
    if "electronic_floor_db" in sensor:
        # the sensor's preamplifier and the recorder's front end: white after the mounted
        # resonance, low-passed by the anti-alias filter (docs/realism.md 2), from a generator
        # of its own so that every other draw of the case is the same with the key as without
        floor_rng = np.random.default_rng([case.seed, 7, 11])
        floor_db = _pick(sensor["electronic_floor_db"], floor_rng, None)
        y, electronic = electronic_noise(y, floor_db, floor_rng)
        chain["electronic_floor_db"], chain["electronic_floor_rms"] = floor_db, electronic
    cutoff = _pick(sensor.get("anti_alias"), rng, None)
    if cutoff is not None:
        order = _pick(sensor.get("anti_alias_order"), rng, 8, integer=True)
        y = anti_alias_filter(y, fs, cutoff, order)
        chain["anti_alias"], chain["anti_alias_order"] = cutoff, order
    bits = _pick(sensor.get("adc_bits"), rng, None, integer=True)
    if bits is not None:
        headroom = _pick(sensor.get("adc_headroom_db"), rng, 6.0)
        full_scale = float(np.max(np.abs(y))) * 10.0 ** (headroom / 20.0)
        y, clipped = digitise(y, bits, max(full_scale, 1e-300))
        chain.update(adc_bits=bits, adc_full_scale=full_scale, clipped_fraction=clipped)
    if not np.all(np.isfinite(y)):
        return {**meta, "error": "non-finite samples after the measurement chain"}
    meta["noise_rms"] = level_scale * machine.broadband_rms
    meta["chain"] = json.dumps(chain, separators=(",", ":"))
    return {**meta, "signal": y.astype(signal_dtype), "error": None}


def _level_scale(recipe: dict, case: Case, machine: np.ndarray, chain: dict) -> float:
    """The factor that gives a record its absolute level (``[sensor] machine_velocity_mm_s``).

    The healthy machine (``machine``: the bearing's healthy record and the background at the
    sensor's place, before the sensor) is scaled so that its overall velocity in ISO 10816's
    band is the drawn value; the same factor scales the fault's signature, so a fault raises
    the record over it. Drawn from a generator of its own (the case's seed, 7, 13), so that
    every other draw of the case is the same with the key as without it; 1 without the key.
    """
    spec = recipe["sensor"].get("machine_velocity_mm_s")
    if spec is None:
        return 1.0
    target = _pick(spec, np.random.default_rng([case.seed, 7, 13]), None)
    band = overall_velocity_band(case.rpm, case.fs_hz)
    now = overall_velocity_rms(machine, case.fs_hz, recipe["sensor"]["quantity"], band)
    scale = 1e-3 * target / now if now > 0.0 else 1.0
    chain.update(machine_velocity_mm_s=target, level_scale=scale)
    return scale


def _finish(
    recipe: dict, job: _Job, x: np.ndarray, healthy: np.ndarray, signal_dtype: type
) -> dict:
    """Add measurement noise (SNR, background or absolute) and build the row of a case."""
    if _realistic(recipe):
        return _finish_realistic(recipe, job, x, healthy, signal_dtype)
    case, meta, rng, sensor = job.case, job.meta, job.rng, recipe["sensor"]
    noise_rms = 0.0
    if case.snr_db is not None:
        noise_rms = float(np.sqrt(np.mean(x * x))) * 10.0 ** (-case.snr_db / 20.0)
    elif not math.isnan(case.background_db):
        # machine background: relative to the healthy bearing at this operating point, the
        # same for a healthy and a faulty bearing (a fault adds to it, it does not scale it)
        noise_rms = float(np.sqrt(np.mean(healthy * healthy))) * 10.0 ** (case.background_db / 20.0)
        if not math.isnan(case.fault_snr_db):
            # at least the level that puts the fault's own signature (faulty minus healthy
            # bearing) fault_snr_db above it
            signature = x - healthy
            noise_rms = max(
                noise_rms,
                float(np.sqrt(np.mean(signature * signature)))
                * 10.0 ** (-case.fault_snr_db / 20.0),
            )
    elif "noise_rms" in sensor:
        noise_rms = float(sensor["noise_rms"])
    if noise_rms > 0:
        x = x + rng.normal(0.0, noise_rms, x.size)
    if not np.all(np.isfinite(x)):
        return {**meta, "error": "non-finite samples after the sensor model"}
    meta["noise_rms"] = noise_rms
    return {**meta, "signal": x.astype(signal_dtype, copy=False), "error": None}


def generate_cases(
    recipe: dict,
    cases: list[Case],
    *,
    signal_dtype: type = np.float32,
    workspace: list[np.ndarray] | None = None,
) -> list[dict]:
    """Simulate cases: per case its metadata (``CASE_COLUMNS``) plus ``signal`` or ``error``.

    Runs that :func:`generators.model.simulate_lanes` supports (RK4, massless-ball scenes,
    waviness) are integrated together, several per SIMD lane block; the others one by one
    (:func:`generators.model.integrate`). A case's row depends only on the recipe and the
    case, never on the other cases in the call. A diverged simulation returns the metadata
    with ``error`` set and no signal. ``signal_dtype``: the samples' type in the rows,
    float32 as stored; ``np.float64`` leaves the rounding to float32 to the writer (one copy
    fewer per signal when the rows go straight into a file). ``workspace``: output buffers
    reused from call to call (:func:`generators.model.simulate_lanes`); float64 signals are
    then views into them, valid until the next call with the same workspace.

    Parameters
    ----------
    recipe : dict
        The recipe, validated.
    cases : list of Case
        The cases.
    signal_dtype : type
        See above.
    workspace : list of ndarray, optional
        See above.

    Returns
    -------
    list of dict
        A row per case, in order.
    """
    sensor = recipe["sensor"]
    channel = f"{sensor['body']}_{sensor['quantity']}_{sensor['direction']}"
    shared: dict = {}
    jobs = [_setup(recipe, case, channel, shared) for case in cases]
    # each run once: an untouched pit's run is its healthy twin (the same object)
    preps = list(
        {
            id(prep): prep for job in jobs for prep in (job.run, job.healthy) if prep is not None
        }.values()
    )
    lanes = [prep for prep in preps if lanes_supported(prep)]
    simulated: dict[int, np.ndarray | Exception] = {}
    results = simulate_lanes(lanes, channel, workspace=workspace)
    for prep, result in zip(lanes, results, strict=True):
        simulated[id(prep)] = result
    for prep in preps:
        if id(prep) not in simulated:
            try:
                simulated[id(prep)] = integrate(prep)[channel]
            except (SimulationDivergedError, ParameterError) as err:
                simulated[id(prep)] = err
    rows = []
    for job in jobs:
        if job.error is not None:
            rows.append({**job.meta, "error": job.error})
            continue
        x = simulated[id(job.run)]
        healthy = x if job.healthy is None else simulated[id(job.healthy)]
        failed = next((r for r in (x, healthy) if isinstance(r, Exception)), None)
        if failed is not None:
            why = str(failed)
            if isinstance(failed, ParameterError):
                why = f"not simulated: {why}"
            rows.append({**job.meta, "error": why})
            continue
        x = _measured(recipe, job.case, x)
        healthy = x if job.healthy is None else _measured(recipe, job.case, healthy)
        rows.append(_finish(recipe, job, x, healthy, signal_dtype))
    return rows


def generate_case(recipe: dict, case: Case) -> dict:
    """Simulate one case: :func:`generate_cases` of that case alone (the same row).

    Parameters
    ----------
    recipe : dict
        The recipe, validated.
    case : Case
        The case.

    Returns
    -------
    dict
        Its row.
    """
    return generate_cases(recipe, [case])[0]


#: Cases of each group whose stability step is compared to choose the group's pilot case.
BOUND_SAMPLE = 32


def step_group(case: Case) -> tuple:
    """The cases that share one error-bound step: same bearing, sample rate and label.

    Parameters
    ----------
    case : Case
        A case.

    Returns
    -------
    tuple
        Its group's key.
    """
    return (case.bearing, case.fs_hz, case.label)


def bound_steps(recipe: dict, cases: Iterable[Case]) -> dict[tuple, tuple[float, float]]:
    """The RK4 step of each case group for the recipe's ``model.error_bound``.

    Per group (:func:`step_group`), the extremes of its first ``BOUND_SAMPLE`` cases are run
    as pilots (:func:`generators.accuracy.error_bound_step`: the characteristic lines and the
    octave bands above 500 Hz, Richardson's estimate): the stiffest (shortest RK4 stability
    step), the fastest and slowest shaft, the highest and lowest load; the group takes the
    shortest of their steps (no one of them bounds the others: at 12 kHz a 6205 group's
    stiffest case allowed a step that missed a 2 % bound by 1.2 times at 3600 rpm). Local
    defects are left out of the pilots: near a pit every run splits its steps to a tenth of a
    passage (``steps.defect_substeps``), so the bound is that of the dynamics between the
    crossings. The step depends on the recipe alone (its cases in order), never on a chunk.

    Parameters
    ----------
    recipe : dict
        The recipe, validated.
    cases : iterable of Case
        Its cases, in order.

    Returns
    -------
    dict
        ``step_group(case) -> (step [s], estimated relative error [-])``: the step and the
        largest estimate of the pilots at it.
    """
    from .accuracy import error_bound_step  # the pilots need the kernels' entry points
    from .steps import stability_step

    bound = recipe["model"]["error_bound"]
    sensor = recipe["sensor"]
    channel = f"{sensor['body']}_{sensor['quantity']}_{sensor['direction']}"
    shared: dict = {}
    sampled: dict[tuple, list[tuple[tuple, Prepared]]] = {}
    for case in cases:
        group = step_group(case)
        members = sampled.setdefault(group, [])
        if len(members) >= BOUND_SAMPLE:
            continue
        job = _setup(recipe, case, channel, shared)
        prep = job.healthy or job.run
        if prep is None:
            continue
        if job.healthy is None and case.defect_kind == "localized":
            # the form errors' rows stay (they come before any local defect's)
            waviness = prep.wav[prep.wav[:, K.W_SURFACE] <= K.SURF_BALL]
            prep = dataclasses.replace(prep, wav=np.ascontiguousarray(waviness), defects=())
        limit = stability_step(prep.scene_code, prep.film_mode, prep.p, prep.wav, prep.y0)
        members.append(
            ((limit, -case.rpm, case.rpm, -case.radial_load_n, case.radial_load_n), prep)
        )
    steps = {}
    for group, members in sampled.items():
        if not members:
            continue
        extremes = {id(min(members, key=lambda m, k=k: m[0][k])[1]) for k in range(5)}
        found = [
            error_bound_step(prep, bound, DEFAULT_OVERSAMPLE)
            for _, prep in members
            if id(prep) in extremes
        ]
        step = min(h for h, _ in found)
        steps[group] = (step, max(e for h, e in found if h == step))
    return steps
