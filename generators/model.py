"""The dynamic model: validate, pack, find the static start, integrate, decimate, wrap.

``simulate`` is the public entry point; the numba kernels in :mod:`generators._kernels` do the
time stepping on plain arrays. Model (docs/model.md sections 1-5):

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
import functools
import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import signal as sp_signal

from . import _kernels as K
from . import _lanes
from ._validate import ParameterError, SimulationDivergedError
from .contact import (
    entrainment_speed,
    film_thickness,
    hertz_contact,
    load_deflection_constants,
    squeeze_film_damping,
)
from .defects import defect_path
from .kinematics import BearingFrequencies, characteristic_frequencies
from .params import (
    CHANNELS,
    BearingGeometry,
    LocalizedDefect,
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
    Waviness,
)
from .static import _equilibrium, static_load_distribution

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

SCENE_CODES = {"shaft": K.SCENE_SHAFT, "shaft+housing": K.SCENE_SHAFT_HOUSING, "full": K.SCENE_FULL}

#: Default fixed RK4 step of the massless-ball scenes [s] (docs/model.md 7.2: converged to 4 digits
#: at <= 2e-5 s; 5-10 us recommended). See ``cmtool fidelity`` for the measured trade.
DEFAULT_STEP_MASSLESS = 2e-5
#: Safety factor on the RK4 stability limit of the linearised scene (dynamic overloads stiffen
#: the contacts beyond the static linearisation).
STABILITY_SAFETY = 0.8
#: Slowest shaft [Hz] (1 rpm) at which the EHL film is modelled; slower runs are dry.
EHL_MIN_SHAFT_FREQUENCY = 1.0 / 60.0
#: Default oversampling of the integration record over the output rate (anti-alias margin).
DEFAULT_OVERSAMPLE = 4

STATUS_REASONS = {
    K.STATUS_NONFINITE: "non-finite state (NaN or inf)",
    K.STATUS_RUNAWAY: "runaway displacement beyond the physical limit",
    K.STATUS_STEP_COLLAPSE: "adaptive step size collapsed",
    K.STATUS_TOO_MANY_STEPS: "adaptive integrator exceeded its step budget",
}


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
        Inner [:, 0] and outer [:, 1] contact load of every ball [N], when requested.
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

    def to_frame(self):
        """Return the signals as a pandas DataFrame with a ``time`` column [s]."""
        import pandas as pd

        data = {"time": self.time}
        data.update({name: self.signals[name] for name in CHANNELS if name in self.signals})
        return pd.DataFrame(data)


# ------------------------------------------------------------------------------- helpers


@functools.lru_cache(maxsize=64)
def _contacts(geometry: BearingGeometry):
    ci = hertz_contact(geometry, "inner")
    co = hertz_contact(geometry, "outer")
    return ci, co, load_deflection_constants(geometry)


Defect = Waviness | LocalizedDefect


def _as_defects(defects) -> tuple[Defect, ...]:
    if defects is None:
        return ()
    if isinstance(defects, (Waviness, LocalizedDefect)):
        return (defects,)
    out = tuple(defects)
    for i, d in enumerate(out):
        if not isinstance(d, (Waviness, LocalizedDefect)):
            raise ParameterError(f"defects[{i}] = {d!r} is not a Waviness or LocalizedDefect")
    return out


def _localized_rows(
    geometry: BearingGeometry,
    defect: LocalizedDefect,
    rng: np.random.Generator,
    radial_load: float,
) -> list[tuple]:
    """Kernel table rows of a local defect (columns: see ``_kernels`` SURF_*_DEFECT)."""
    if defect.surface == "ball" and defect.ball >= geometry.ball_count:
        raise ParameterError(
            f"ball = {defect.ball} is outside the allowed range [0, {geometry.ball_count - 1}]"
        )
    path = defect_path(geometry, defect)
    position = rng.uniform(-np.pi, np.pi) if defect.position is None else defect.position
    common = (path.half_width, defect.depth, position, path.surface_radius)
    if defect.surface == "outer":
        return [(K.SURF_OUTER_DEFECT, -1, *common, path.bridge_radius_outer)]
    if defect.surface == "inner":
        return [(K.SURF_INNER_DEFECT, -1, *common, path.bridge_radius_inner)]
    # the band the races sweep on the ball: the contact ellipse's half width across the
    # rolling direction at the Stribeck ball load 4.37 F_r / Z, plus half the pit
    ball_load = max(4.37 * radial_load / geometry.ball_count, 1.0)
    radius = 0.5 * geometry.ball_diameter
    # a point placed at random on a sphere is as likely at any height above its equator
    # (Archimedes' hat-box theorem): sin(latitude) is uniform, not the latitude
    latitude = np.arcsin(rng.uniform(-1.0, 1.0)) if defect.latitude is None else defect.latitude
    rows = []
    for code, race, bridge in (
        (K.SURF_BALL_DEFECT_OUTER, "outer", path.bridge_radius_outer),
        (K.SURF_BALL_DEFECT_INNER, "inner", path.bridge_radius_inner),
    ):
        half_track = hertz_contact(geometry, race).semi_axes(ball_load)[0] + 0.5 * defect.length
        track = min(half_track / radius, 1.0)
        rows.append((code, defect.ball, *common, bridge, latitude, defect.axis_drift, track))
    return rows


def _waviness_table(
    defects: Sequence[Defect],
    geometry: BearingGeometry,
    rng: np.random.Generator,
    radial_load: float,
) -> np.ndarray:
    """Expand defects into the kernel table (ball rows per ball, phases drawn).

    ``radial_load`` [N] sets the contact track width of ball pits (Stribeck load).
    """
    ball_count = geometry.ball_count
    rows = []
    code = {"outer": K.SURF_OUTER, "inner": K.SURF_INNER}
    for w in defects:
        if isinstance(w, LocalizedDefect):
            if w.depth > 0.0:
                rows.extend(_localized_rows(geometry, w, rng, radial_load))
            continue
        if w.amplitude == 0.0:
            continue
        if w.surface in code:
            phase = rng.uniform(0, 2 * np.pi) if w.phase is None else w.phase
            step = 2 * np.pi * w.order / ball_count
            rows.append(
                (code[w.surface], -1, w.order, w.amplitude, phase, np.cos(step), np.sin(step))
            )
        else:
            balls = range(ball_count) if w.ball is None else (w.ball,)
            for j in balls:
                if j >= ball_count:
                    raise ParameterError(
                        f"ball = {j} is outside the allowed range [0, {ball_count - 1}]"
                    )
                # each ball its own waviness phase and initial spin angle (docs/model.md 5, [A])
                phase = rng.uniform(0, 2 * np.pi) if w.phase is None else w.phase
                spin0 = rng.uniform(0, 2 * np.pi)
                rows.append(
                    (K.SURF_BALL, j, w.order, w.amplitude, phase + w.order * spin0, 1.0, 0.0)
                )
    rows = [tuple(row) + (0.0,) * (K.W_SIZE - len(row)) for row in rows]
    table = np.array(rows, dtype=np.float64).reshape(-1, K.W_SIZE)
    return np.ascontiguousarray(table)


#: Random slip as sums of sinusoids (docs/realism.md): components of the cage-speed
#: fluctuation, log-spaced over [SLIP_BAND[0], SLIP_BAND[1]] times the cage frequency, and of
#: each ball's pocket offset over [POCKET_BAND[0], POCKET_BAND[1]] times the cage frequency.
SLIP_COMPONENTS = 12
SLIP_BAND = (1.0 / 8.0, 2.0)
POCKET_COMPONENTS = 4
POCKET_BAND = (0.5, 4.0)


def slip_rows(
    operating: OperatingCondition, ball_count: int, cage_speed: float, rng: np.random.Generator
) -> np.ndarray:
    """Kernel table rows of the random slip (``_kernels.SURF_SLIP``), drawn from ``rng``.

    The cage-speed fluctuation eps(t) (standard deviation ``operating.random_slip``) is a sum
    of ``SLIP_COMPONENTS`` sinusoids of equal power at frequencies drawn log-uniformly, one per
    equal log-band of ``SLIP_BAND`` x f_c, with uniform random phases; the balls' common lag
    is its integral, psi(t) = w_c int eps dt, so component m has angle amplitude
    w_c eps_m / w_m [rad]. Each ball's pocket offset (standard deviation
    ``operating.ball_jitter`` [rad]) is a sum of ``POCKET_COMPONENTS`` such sinusoids over
    ``POCKET_BAND`` x f_c. For random phases the coherent part of harmonic k of a race
    defect's impact rate is multiplied by the product of J0(k Z a_m) over the rows
    (:func:`slip_line_factor`).

    Parameters
    ----------
    operating : OperatingCondition
        Supplies ``random_slip`` [-] and ``ball_jitter`` [rad].
    ball_count : int
        Z.
    cage_speed : float
        Cage angular speed w_c [rad/s].
    rng : numpy.random.Generator
        Source of the frequencies and phases.

    Returns
    -------
    ndarray, shape (rows, W_SIZE)
        Empty when both are 0 or the cage stands.
    """
    rows = []
    wc = abs(cage_speed)
    for sigma, count, band, balls in (
        (operating.random_slip, SLIP_COMPONENTS, SLIP_BAND, (-1,)),
        (operating.ball_jitter, POCKET_COMPONENTS, POCKET_BAND, tuple(range(ball_count))),
    ):
        if sigma == 0.0 or wc == 0.0:
            continue
        edges = np.linspace(np.log(band[0] * wc), np.log(band[1] * wc), count + 1)
        for ball in balls:
            rates = np.exp(rng.uniform(edges[:-1], edges[1:]))
            phases = rng.uniform(0.0, 2 * np.pi, count)
            share = sigma * np.sqrt(2.0 / count)
            # the cage's speed fluctuation integrates to an angle; a pocket offset is one
            angles = wc * share / rates if ball == -1 else np.full(count, share)
            for rate, angle, phase in zip(rates, angles, phases, strict=True):
                rows.append((K.SURF_SLIP, ball, rate, angle, phase) + (0.0,) * (K.W_SIZE - 5))
    return np.array(rows, dtype=np.float64).reshape(-1, K.W_SIZE)


def slip_line_factor(wav: np.ndarray, multiple: float, ball: int = 0) -> float:
    """Expected coherent fraction of a line whose argument is ``multiple`` x ball j's lag.

    For psi = sum a_m sin(w_m t + phi_m) with independent uniform phases,
    E[exp(i kappa psi)] = prod J0(kappa a_m): the factor by which slip shrinks the discrete
    (periodic) part of harmonic k of a race defect's impacts, ``multiple = k Z`` for the
    outer race (the rest spreads into a continuous spectrum).

    Parameters
    ----------
    wav : ndarray
        A kernel table (only its ``SURF_SLIP`` rows for ``ball`` and -1 are used).
    multiple : float
        kappa [-].
    ball : int
        The ball whose pocket rows count.

    Returns
    -------
    float
        Between 0 and 1 (1 without slip rows).
    """
    from scipy.special import j0

    rows = wav[(wav[:, K.W_SURFACE] == K.SURF_SLIP) & np.isin(wav[:, K.W_BALL], (-1, ball))]
    return float(np.prod(j0(multiple * rows[:, K.W_SLIP_ANGLE])))


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

    Returns
    -------
    level, reason : str
    """
    if scene.level != "auto":
        return scene.level, "requested"
    bound = scene.auto_error_bound
    _, _, (ki, ko, kt) = _contacts(geometry)
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


def _pack(
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    ehl: bool,
    freqs: BearingFrequencies | None,
) -> np.ndarray:
    """Pack the parameter objects into the kernel's float64 vector (indices ``K.P_*``)."""
    ci, co, (ki, ko, kt) = _contacts(geometry)
    p = np.zeros(K.P_SIZE)
    z = geometry.ball_count
    p[K.P_BALL_COUNT] = z
    p[K.P_PITCH_COS] = math.cos(2 * math.pi / z)
    p[K.P_PITCH_SIN] = math.sin(2 * math.pi / z)
    p[K.P_SHAFT_MASS] = rig.shaft_mass
    p[K.P_HOUSING_MASS] = rig.housing_mass
    p[K.P_BALL_MASS] = geometry.ball_mass
    p[K.P_PEDESTAL_STIFFNESS] = rig.pedestal_stiffness
    p[K.P_PEDESTAL_DAMPING] = rig.pedestal_damping
    p[K.P_SHAFT_DAMPING] = rig.shaft_damping
    p[K.P_K_INNER] = ki
    p[K.P_K_OUTER] = ko
    p[K.P_K_SERIES] = kt
    p[K.P_GAP] = geometry.radial_gap
    fs = operating.shaft_frequency
    if freqs is not None:
        p[K.P_SHAFT_SPEED] = 2 * math.pi * fs
        p[K.P_CAGE_SPEED] = 2 * math.pi * freqs.ftf
        p[K.P_BALL_SPIN_SPEED] = 2 * math.pi * freqs.bsf
    p[K.P_LOAD_X] = operating.radial_load * math.cos(operating.load_angle)
    p[K.P_LOAD_Y] = operating.radial_load * math.sin(operating.load_angle)
    p[K.P_GRAVITY] = 9.81 if rig.gravity else 0.0
    p[K.P_LOADING_STIFFNESS] = rig.loading_stiffness
    p[K.P_CONTACT_DAMPING_TIME] = rig.contact_damping_time
    p[K.P_PITCH_RADIUS] = 0.5 * geometry.pitch_diameter
    p[K.P_UNBALANCE] = rig.unbalance
    wc = p[K.P_CAGE_SPEED]
    centrifugal = geometry.ball_mass * wc**2 * geometry.pitch_diameter / 2
    p[K.P_FILM_LOAD_FLOOR] = max(1.0, centrifugal)  # docs/model.md 4.1: Q_floor = max(1 N, F_c)
    p[K.P_FILM_REFERENCE_LOAD] = max(operating.radial_load / max(z / 4.37, 1.0), 1.0)
    if ehl and (u := entrainment_speed(geometry, fs)) > 0.0:
        lub = rig.lubricant
        # h_c(Q) = h_c(1 N) * Q^-0.067 (Hamrock-Dowson load exponent)
        hi = film_thickness(ci, lub, u, 1.0, load_floor=1e-30)
        ho = film_thickness(co, lub, u, 1.0, load_floor=1e-30)
        p[K.P_FILM_INNER] = hi
        p[K.P_FILM_OUTER] = ho
        qref, qfloor = p[K.P_FILM_REFERENCE_LOAD], p[K.P_FILM_LOAD_FLOOR]
        p[K.P_FILM_INNER_REF] = hi * (qref + qfloor) ** K.FILM_EXPONENT
        p[K.P_FILM_OUTER_REF] = ho * (qref + qfloor) ** K.FILM_EXPONENT
        p[K.P_FILM_INNER_MAX] = hi * qfloor**K.FILM_EXPONENT
        p[K.P_FILM_OUTER_MAX] = ho * qfloor**K.FILM_EXPONENT
        csi = rig.film_damping_factor * squeeze_film_damping(ci, lub, 1.0)  # = c_sq * h_c
        cso = rig.film_damping_factor * squeeze_film_damping(co, lub, 1.0)
        p[K.P_SQUEEZE_INNER] = csi / hi
        p[K.P_SQUEEZE_OUTER] = cso / ho
        # two Kelvin-Voigt contacts in series (docs/model.md 1.4): c_eff = c_i r_o^2 + c_o r_i^2
        # with r = k / (k_i + k_o); k_i / k_o = (K_i / K_o)^(2/3) at equal load
        kri, kro = ki ** (2 / 3), ko ** (2 / 3)
        ri, ro = kri / (kri + kro), kro / (kri + kro)
        p[K.P_SQUEEZE_SERIES] = p[K.P_SQUEEZE_INNER] * ro**2 + p[K.P_SQUEEZE_OUTER] * ri**2
    return p


#: Nodes per film table (see ``_kernels``): 2048 nodes up to a 100-fold overload keep the
#: interpolation error below 1e-9 relative in the load (checked in tests_generators).
FILM_TABLE_NODES = 2048


def _film_tables(p: np.ndarray) -> np.ndarray:
    """Append the film tables d(delta) of the three contacts to ``p`` (EHL scenes)."""
    floor = p[K.P_FILM_LOAD_FLOOR]
    e = K.FILM_EXPONENT
    q_hi = 100.0 * (p[K.P_FILM_REFERENCE_LOAD] + 100.0)
    specs = (
        (p[K.P_K_INNER], p[K.P_FILM_INNER], p[K.P_FILM_INNER_MAX]),
        (p[K.P_K_OUTER], p[K.P_FILM_OUTER], p[K.P_FILM_OUTER_MAX]),
        (
            p[K.P_K_SERIES],
            p[K.P_FILM_INNER] + p[K.P_FILM_OUTER],
            p[K.P_FILM_INNER_MAX] + p[K.P_FILM_OUTER_MAX],
        ),
    )
    n = FILM_TABLE_NODES
    tables = np.zeros((3, n, 2))
    out = p.copy()
    for c, (kc, film, h_max) in enumerate(specs):
        delta_hi = (q_hi / kc) ** (2.0 / 3.0)
        step = math.sqrt(delta_hi + h_max) / (n - 1)  # uniform in s = sqrt(delta + h_max)
        s_nodes = step * np.arange(n)
        delta = s_nodes**2 - h_max
        d = np.maximum(delta + h_max, 0.0)
        for _ in range(60):  # Newton to full convergence
            pos = d > 0
            q = kc * np.where(pos, d, 0.0) ** 1.5
            h = film * (q + floor) ** e
            slope = np.where(pos, -1.5 * e * h / np.where(pos, d, 1.0) * q / (q + floor), 0.0)
            d_new = d - (d - delta - h) / (1.0 + slope)
            if np.max(np.abs(d_new - d)) <= 1e-16 * max(float(np.max(np.abs(d))), 1e-12):
                d = d_new
                break
            d = d_new
        d = np.maximum(d, 0.0)
        pos = d > 0
        q = kc * d**1.5
        h = film * (q + floor) ** e
        slope = np.where(pos, -1.5 * e * h / np.where(pos, d, 1.0) * q / (q + floor), 0.0)
        tables[c, :, 0] = d
        tables[c, :, 1] = 2.0 * s_nodes / (1.0 + slope)  # dd/ds = dd/d delta * 2 s
        out[K.P_TABLE_STEP_INNER + c] = step
        out[K.P_TABLE_INV_STEP_INNER + c] = 1.0 / step
    out[K.P_TABLE_NODES] = n
    return np.concatenate([out, tables.ravel()])


def _film_sum(p: np.ndarray, loads: np.ndarray) -> np.ndarray:
    q = loads + p[K.P_FILM_LOAD_FLOOR]  # smooth floor, as in the kernel
    return (p[K.P_FILM_INNER] + p[K.P_FILM_OUTER]) * q**K.FILM_EXPONENT


def _waviness_at_start(p: np.ndarray, wav: np.ndarray, z: int) -> np.ndarray:
    """Waviness values seen by each ball at t = 0: rows [w_o, w_i, wb_o, wb_i] [m]."""
    out = np.zeros((11, z))
    K._start_waviness(p, wav, z, out)
    return out[[0, 2, 4, 6]]


@functools.lru_cache(maxsize=64)
def _ball_directions(cage_angle: float, z: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ball angles [rad] at t = 0 and their cosines and sines (shared: never write to them)."""
    theta = cage_angle + 2.0 * np.pi * np.arange(z) / z
    return theta, np.cos(theta), np.sin(theta)


def _ball_equilibrium(
    p: np.ndarray,
    ehl: bool,
    us: float,
    uh: float,
    extra_i: float,
    extra_o: float,
    sin_theta: float,
) -> float:
    """Radial ball position rho with zero net force (bisection; the force decreases with rho)."""
    gap = p[K.P_GAP]
    mb = p[K.P_BALL_MASS]
    wc = p[K.P_CAGE_SPEED]
    tau = 0.0

    def net(rho: float) -> float:
        di = us - rho - 0.5 * gap + extra_i
        do = rho - uh - 0.5 * gap + extra_o
        if ehl:
            qi = K._hertz_ehl(
                di,
                0.0,
                p[K.P_K_INNER],
                tau,
                p[K.P_FILM_INNER],
                0.0,
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_INNER_REF],
                p[K.P_FILM_INNER_MAX],
            )
            qo = K._hertz_ehl(
                do,
                0.0,
                p[K.P_K_OUTER],
                tau,
                p[K.P_FILM_OUTER],
                0.0,
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_OUTER_REF],
                p[K.P_FILM_OUTER_MAX],
            )
        else:
            qi = K._hertz_dry(di, 0.0, p[K.P_K_INNER], tau)
            qo = K._hertz_dry(do, 0.0, p[K.P_K_OUTER], tau)
        return qi - qo + mb * wc**2 * (p[K.P_PITCH_RADIUS] + rho) - mb * p[K.P_GRAVITY] * sin_theta

    span = abs(us) + abs(uh) + abs(gap) + abs(extra_i) + abs(extra_o) + 1e-6
    lo, hi = -span, span
    for _ in range(60):
        if net(lo) > 0:
            break
        lo *= 2
    for _ in range(60):
        if net(hi) < 0:
            break
        hi *= 2
    f_lo, f_hi = net(lo), net(hi)
    if f_lo * f_hi > 0:
        return 0.5 * (us + uh)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        f = net(mid)
        if f == 0.0:
            # inside the play with no force: find the whole zero interval and take its middle
            a, b = lo, mid
            for _ in range(100):
                m = 0.5 * (a + b)
                a, b = (a, m) if net(m) == 0.0 else (m, b)
            c, d = mid, hi
            for _ in range(100):
                m = 0.5 * (c + d)
                c, d = (m, d) if net(m) == 0.0 else (c, m)
            return 0.5 * (b + c)
        if f > 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-16:
            break
    return 0.5 * (lo + hi)


def _static_state(
    level: str,
    ehl: bool,
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    p: np.ndarray,
    wav: np.ndarray,
) -> tuple[np.ndarray, float]:
    """Static equilibrium at t = 0 (velocities 0): the initial state, and the largest ball load."""
    z = geometry.ball_count
    g = p[K.P_GRAVITY]
    fx = p[K.P_LOAD_X]
    fy = p[K.P_LOAD_Y] - rig.shaft_mass * g
    fr = math.hypot(fx, fy)
    angle = math.atan2(fy, fx)
    w0 = _waviness_at_start(p, wav, z)
    waviness_sum = w0[0] + w0[1] + w0[2] + w0[3]  # as w0.sum(axis=0): row after row
    kt = p[K.P_K_SERIES]
    loads = np.full(z, p[K.P_FILM_REFERENCE_LOAD]) if ehl else None
    extra = waviness_sum
    # static_load_distribution's solver without its input checks: load, angles and
    # waviness were validated by prepare (the dataset generator solves one per signal)
    theta, cos_t, sin_t = _ball_directions(float(p[K.P_CAGE_ANGLE0]), z)
    for _ in range(4 if ehl else 1):
        if ehl:
            extra = waviness_sum + _film_sum(p, loads)
        if not math.isfinite(float(extra.sum())):
            raise ParameterError(f"static start: non-finite approach per ball {extra!r}")
        gap = geometry.radial_gap - extra
        x, y, loads, _ = _equilibrium(cos_t, sin_t, gap, kt, fr, angle)
    housing_x = fx / rig.pedestal_stiffness
    housing_y = (fy - rig.housing_mass * g) / rig.pedestal_stiffness
    nd = 4 + z if level == "full" else 4  # K.n_dof
    y0 = np.zeros(2 * nd)
    y0[2] = housing_x
    y0[3] = housing_y
    y0[0] = x if level == "shaft" else x + housing_x
    y0[1] = y if level == "shaft" else y + housing_y
    if level == "full":
        for j in range(z):
            c, s = math.cos(theta[j]), math.sin(theta[j])
            us = y0[0] * c + y0[1] * s
            uh = y0[2] * c + y0[3] * s
            y0[4 + j] = _ball_equilibrium(
                p, ehl, us, uh, w0[1, j] + w0[3, j], w0[0, j] + w0[2, j], s
            )
    p[K.P_LOADING_X0] = y0[0]
    p[K.P_LOADING_Y0] = y0[1]
    return y0, float(loads.max()) if loads.size else 0.0


def _jacobian(code: int, ehl: bool, p: np.ndarray, wav: np.ndarray, y0: np.ndarray) -> np.ndarray:
    """Jacobian of the first-order right-hand side at ``y0``, t = 0, by central differences.

    Displacements are perturbed by 1e-11 m, velocities by 1e-7 m/s (docs/model.md 7.5).
    """
    n = y0.size
    nd = n // 2
    loads = np.zeros((2, int(p[K.P_BALL_COUNT])))
    jac = np.zeros((n, n))
    fp, fm = np.zeros(n), np.zeros(n)
    for i in range(n):
        h = 1e-11 if i < nd else 1e-7
        yp, ym = y0.copy(), y0.copy()
        yp[i] += h
        ym[i] -= h
        K._rhs_once(code, int(ehl), 0.0, yp, p, wav, fp, loads)
        K._rhs_once(code, int(ehl), 0.0, ym, p, wav, fm, loads)
        jac[:, i] = (fp - fm) / (2 * h)
    return jac


#: RK4 steps per passage of a contact over a local defect (envelope line within 1 % of a step
#: 8 times shorter; tests_validation/test_local_defects.py checks 4 times shorter to 2 %).
DEFECT_STEPS = 10


def default_step(
    level: str, code: int, ehl: bool, p: np.ndarray, wav: np.ndarray, y0: np.ndarray
) -> float:
    """Default RK4 step [s] of a scene.

    The smaller of the accuracy step ``DEFAULT_STEP_MASSLESS`` (massless-ball scenes converge
    to 0.01 % in the band amplitude there, see ``cmtool fidelity``) and the stability step
    ``STABILITY_SAFETY * min_i r(arg lambda_i) / |lambda_i|``, lambda the eigenvalues of the
    right-hand side linearised at the static start and r(phi) the radius of RK4's stability
    region along the ray at angle phi (:func:`rk4_stability_radius`: 2.83 on the imaginary
    axis, 2.79 on the real axis, 2.62 at its narrowest, near 120 degrees). The fastest mode is
    the ball radial mode in the ``full`` scene (lightly damped, or well damped with the squeeze
    film), otherwise the shaft-on-bearing or a stiff pedestal's housing mode.
    """
    lam = np.linalg.eigvals(_jacobian(code, ehl, p, wav, y0))
    lam = lam[np.abs(lam) > 0.0]
    stable = math.inf
    if lam.size:
        stable = float(np.min(rk4_stability_radius(np.angle(lam)) / np.abs(lam)))
    step = min(DEFAULT_STEP_MASSLESS, STABILITY_SAFETY * stable)
    return min(step, defect_step(p, wav))


def rk4_stability_radius(angle: np.ndarray | float) -> np.ndarray:
    """Radius of the classical RK4 stability region along rays z = r exp(i angle).

    The first r > 0 where |R(z)| = 1, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 (scan on a 0.001
    grid, then bisection to 1e-9). A ray into the right half-plane (|angle| < pi/2: an
    eigenvalue whose real part is rounding noise of a finite-difference Jacobian, or a growing
    mode the divergence check reports) is given the imaginary-axis value. ``angle`` in rad;
    returns r [-] (2.7853 at pi, 2.8284 at pi/2).
    """

    def amplification(r, ray):  # |R(r ray)|, ray = exp(i angle); Horner's form
        z = r * ray
        return np.abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))))

    phi = np.maximum(np.abs(np.atleast_1d(np.asarray(angle, dtype=float))), 0.5 * np.pi)
    grid = np.arange(1, 3501) * 1e-3
    # all rays at once: the first grid point past the boundary, then bisection on every ray
    ray = np.exp(1j * phi)
    unstable = amplification(grid[None, :], ray[:, None]) > 1.0 + 1e-12
    found = unstable.any(axis=1)
    k = np.argmax(unstable, axis=1)
    lo = np.where(k > 0, grid[np.maximum(k - 1, 0)], 0.0)
    hi = grid[k]
    while np.any(hi - lo > 1e-9):
        mid = 0.5 * (lo + hi)
        stable = amplification(mid, ray) <= 1.0 + 1e-12
        lo, hi = np.where(stable, mid, lo), np.where(stable, hi, mid)
    return np.where(found, lo, grid[-1])


def defect_step(p: np.ndarray, wav: np.ndarray) -> float:
    """Step limit [s] from local defects: ``DEFECT_STEPS`` steps per passage of a contact.

    A contact crosses a pit of half width w [rad] in 2 w / |rate|, rate the angular speed of
    the contact point on the defective surface (cage for the outer race, cage minus shaft for
    the inner race, ball spin for a ball). ``inf`` without local defects.
    """
    rates = {
        K.SURF_OUTER_DEFECT: p[K.P_CAGE_SPEED],
        K.SURF_INNER_DEFECT: p[K.P_CAGE_SPEED] - p[K.P_SHAFT_SPEED],
        K.SURF_BALL_DEFECT_OUTER: p[K.P_BALL_SPIN_SPEED],
        K.SURF_BALL_DEFECT_INNER: p[K.P_BALL_SPIN_SPEED],
    }
    step = math.inf
    for row in wav:
        rate = abs(rates.get(int(row[K.W_SURFACE]), 0.0))
        if rate > 0.0:
            step = min(step, 2.0 * row[K.W_ORDER] / rate / DEFECT_STEPS)
    return step


def default_oversample(step: float | None, fs: float) -> int:
    """Record rate / output rate: ``DEFAULT_OVERSAMPLE``, less when the RK4 step is long.

    The record feeds the zero-phase FIR decimation; a record faster than the integration step
    only samples the step's cubic interpolant, whose content above 1 / (2 dt) is not resolved
    anyway, so it is capped at about one record per step (at least 1).
    """
    if step is None:
        return DEFAULT_OVERSAMPLE
    return int(min(DEFAULT_OVERSAMPLE, max(1, round(1.0 / (fs * step)))))


def rk4_schedule(
    step: float, record_dt: float, settle_time: float, n_record: int
) -> tuple[float, int, float]:
    """RK4 step, number of steps and first record time for a requested step [s].

    A step shorter than the record interval is shortened to divide it exactly when that costs
    at most 20 % more steps (records then fall on step starts, no interpolation); otherwise the
    step is kept and the records are interpolated (cubic Hermite dense output).
    """
    divisor = record_dt / max(1, int(math.ceil(record_dt / step - 1e-9)))
    if step <= record_dt * (1 + 1e-9) and divisor >= 0.8 * step:
        dt = divisor
        t_first = math.ceil(settle_time / dt - 1e-9) * dt
    else:
        dt = step
        t_first = settle_time
    t_last = t_first + (n_record - 1) * record_dt
    n_steps = int(math.floor(t_last / dt + 1e-9)) + 1
    return dt, n_steps, t_first


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


def _params_record(geometry, operating, rig, scene, level, reason, settings, defects, extra):
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


# ------------------------------------------------------------------------------- simulate


@dataclass(frozen=True)
class Prepared:
    """Everything the kernels need for one run (packed, validated, at static equilibrium)."""

    geometry: BearingGeometry
    operating: OperatingCondition
    rig: Rig
    scene: Scene
    settings: SimulationSettings
    defects: tuple
    level: str
    reason: str
    code: int
    ehl: bool
    freqs: BearingFrequencies | None
    p: np.ndarray
    wav: np.ndarray
    y0: np.ndarray
    max_ball_load: float


@functools.cache
def _default(cls: type):
    """The default instance of a frozen parameter class (built and validated once)."""
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

    Parameters are those of :func:`simulate`; returns the packed vector ``p``, the waviness
    table ``wav`` and the initial state ``y0`` (static equilibrium, velocities zero).
    """
    if not isinstance(bearing, BearingGeometry):
        raise ParameterError(f"bearing = {bearing!r} is not a BearingGeometry")
    if not isinstance(operating, OperatingCondition):
        raise ParameterError(f"operating = {operating!r} is not an OperatingCondition")
    scene = _default(Scene) if scene is None else scene
    rig = _default(Rig) if rig is None else rig
    settings = _default(SimulationSettings) if settings is None else settings
    for name, obj, cls in (
        ("scene", scene, Scene),
        ("rig", rig, Rig),
        ("settings", settings, SimulationSettings),
    ):
        if not isinstance(obj, cls):
            raise ParameterError(f"{name} = {obj!r} is not a {cls.__name__}")
    defect_list = _as_defects(defects)
    rng = np.random.default_rng(random_state)
    freqs = None
    if operating.shaft_frequency > 0:
        freqs = characteristic_frequencies(
            bearing, operating.shaft_frequency, cage_slip=operating.cage_slip
        )
    return _prepare(bearing, operating, defect_list, scene, rig, settings, rng, freqs)


def _prepare(
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
    """
    z = geometry.ball_count
    level, reason = resolve_scene(scene, geometry, operating, rig, settings)
    code = SCENE_CODES[level]
    # no entrainment, no film: a bearing standing or creeping (below EHL_MIN_SHAFT_FREQUENCY)
    # runs the dry path; a film of a few nanometres adds nothing but a stiffness so high that
    # the integration crawls (1e-9 rpm took minutes per millisecond)
    ehl = bool(scene.ehl) and operating.shaft_frequency >= EHL_MIN_SHAFT_FREQUENCY
    p = _pack(geometry, operating, rig, ehl, freqs)
    if ehl:
        p = _film_tables(p)
    p[K.P_CAGE_ANGLE0] = settings.cage_angle
    wav = _waviness_table(defect_list, geometry, rng, operating.radial_load)
    if (operating.random_slip or operating.ball_jitter) and np.any(
        wav[:, K.W_SURFACE] >= K.SURF_OUTER_DEFECT
    ):
        # slip only moves where balls meet local defects: no rows (and no draws) without one
        wav = np.ascontiguousarray(
            np.vstack([wav, slip_rows(operating, z, p[K.P_CAGE_SPEED], rng)])
        )
    y0, qmax = _static_state(level, ehl, geometry, operating, rig, p, wav)
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
class _Plan:
    """Integration schedule of a prepared run (see :func:`rk4_schedule`)."""

    oversample: int
    record_dt: float
    n_out: int
    n_record: int
    dt: float  # RK4 step [s] (NaN for DOPRI5)
    n_steps: int
    t_first: float


def _plan(prep: Prepared) -> _Plan:
    """Step, record rate and record count of a prepared run (as :func:`simulate` does)."""
    settings = prep.settings
    step = None
    if settings.integrator == "rk4":
        step = settings.step or default_step(
            prep.level, prep.code, prep.ehl, prep.p, prep.wav, prep.y0
        )
    oversample = settings.oversample or default_oversample(step, settings.fs)
    record_dt = 1.0 / (settings.fs * oversample)
    n_out = int(round(settings.duration * settings.fs))
    n_record = n_out * oversample
    if step is None:
        return _Plan(oversample, record_dt, n_out, n_record, math.nan, 0, settings.settle_time)
    dt, n_steps, t_first = rk4_schedule(step, record_dt, settings.settle_time, n_record)
    return _Plan(oversample, record_dt, n_out, n_record, dt, n_steps, t_first)


def _diverged(prep: Prepared, status: int, t_fail: float) -> SimulationDivergedError:
    why = STATUS_REASONS.get(status, f"status {status}")
    return SimulationDivergedError(
        f"simulation diverged in scene {prep.level}/{'ehl' if prep.ehl else 'dry'} at t = "
        f"{t_fail:.6g} s: {why} (integrator {prep.settings.integrator}; try a smaller step or "
        "tolerance, or check the inputs)",
        scene=prep.level,
        time=t_fail,
        reason=why,
    )


def lanes_supported(prep: Prepared) -> bool:
    """Whether :func:`simulate_lanes` can integrate this prepared run.

    RK4 in the ``shaft`` or ``shaft+housing`` scene with waviness only (no local defects, fewer
    than ``MAX_ROWS`` table rows, at most ``MAX_BALLS`` balls) and no contact-load record.
    """
    return (
        prep.settings.integrator == "rk4"
        and prep.level in ("shaft", "shaft+housing")
        and not prep.settings.record_contact_loads
        and bool(np.all(prep.wav[:, K.W_SURFACE] <= K.SURF_BALL))
        and prep.wav.shape[0] < _lanes.MAX_ROWS
        and prep.geometry.ball_count <= _lanes.MAX_BALLS
    )


def _row_padding(n_record: int) -> int:
    """Extra float64 per row of a lane block's output so rows start 64 bytes apart mod 4 KiB.

    The kernel writes one sample of every lane per record: with rows a multiple of 4 KiB
    long (25 600 samples) those stores all map to one set of the L1 cache, which holds 8
    lines, and evict each other (measured: the padded block integrates ~9 % faster).
    """
    return ((64 - (n_record * 8) % 4096) % 4096) // 8


def _block_buffer(
    workspace: list[np.ndarray] | None, index: int, width: int, n_record: int
) -> np.ndarray:
    """Output array (width, padded n_record) of lane block ``index``, from ``workspace``."""
    shape = (width, n_record + _row_padding(n_record))
    if workspace is None:
        return np.empty(shape)
    while len(workspace) <= index:
        workspace.append(np.empty((0, 0)))
    buffer = workspace[index]
    if buffer.shape[0] < width or buffer.shape[1] != shape[1]:
        buffer = workspace[index] = np.empty((max(width, _lanes.LANES), shape[1]))
    return buffer[:width]  # the first rows: C-contiguous, the kernel's array type


def simulate_lanes(
    preps: Sequence[Prepared], channel: str, *, workspace: list[np.ndarray] | None = None
) -> list[np.ndarray | SimulationDivergedError]:
    """One output channel of many prepared runs, integrated ``LANES`` at a time.

    The dataset generator's path: runs that share the scene, film switch, bearing (ball
    count), schedule and waviness layout are integrated together, one per SIMD lane
    (:mod:`generators._lanes`), by the same RK4 and dense output as :func:`simulate`, then
    decimated the same way. The result of a run does not depend on which runs share its
    block; it equals :func:`simulate`'s to rounding (the operations are grouped differently).

    Parameters
    ----------
    preps : sequence of Prepared
        Prepared runs (:func:`prepare`), each :func:`lanes_supported`.
    channel : str
        Output channel (``CHANNELS``), e.g. ``"housing_acceleration_y"``.
    workspace : list of ndarray, optional
        Output buffers kept from call to call (one per lane block, replaced when too small):
        the returned arrays are then views into them, valid until the next call with the
        same workspace. Writing into memory already touched saves ~9 % of the integration
        (page faults and cache misses of a fresh block); the dataset writer keeps one per
        worker thread.

    Returns
    -------
    list
        Per run, the channel at ``settings.fs`` [m, m/s or m/s^2], or the
        :class:`SimulationDivergedError` that says why the run diverged.
    """
    if channel not in _CHANNEL_COLUMNS:
        raise ParameterError(f"channel = {channel!r} is not one of {sorted(_CHANNEL_COLUMNS)}")
    which, column = _CHANNEL_COLUMNS[channel]
    groups: dict[tuple, list[tuple[int, Prepared, _Plan]]] = {}
    for i, prep in enumerate(preps):
        if not lanes_supported(prep):
            raise ParameterError(
                f"preps[{i}] (scene {prep.level}, integrator {prep.settings.integrator}) "
                "cannot run in lanes: RK4, shaft or shaft+housing scene, waviness only"
            )
        plan = _plan(prep)
        layout = tuple(map(tuple, prep.wav[:, [K.W_SURFACE, K.W_BALL]].tolist()))
        key = (prep.code, prep.ehl, prep.geometry.ball_count, prep.p.size, layout, plan)
        groups.setdefault(key, []).append((i, prep, plan))
    results: list = [None] * len(preps)
    lanes = _lanes.LANES
    n_blocks = 0
    for (code, ehl, *_), members in groups.items():
        kernel = _lanes.RK4[(code, int(ehl))]
        plan = members[0][2]
        for start in range(0, len(members), lanes):
            block = members[start : start + lanes]
            # no padding: a lane's bytes are the same in the vector body of the lane loops
            # and in their scalar remainder (tests_generators/test_lanes.py checks it)
            width = len(block)
            padded = [m[1] for m in block]
            y0 = np.stack([m.y0 for m in padded], axis=1)
            p = np.stack([m.p for m in padded], axis=1)
            wav = np.ascontiguousarray(np.stack([m.wav for m in padded], axis=2))
            out = _block_buffer(workspace, n_blocks, width, plan.n_record)
            n_blocks += 1
            status = np.empty(width, dtype=np.int64)
            t_status = np.empty(width)
            kernel(
                y0,
                p,
                wav,
                0.0,
                plan.dt,
                plan.n_steps,
                plan.t_first,
                plan.record_dt,
                plan.n_record,
                which,
                column,
                out,
                status,
                t_status,
            )
            records = out[:, : plan.n_record]
            if plan.oversample > 1:
                records = sp_signal.resample_poly(
                    records, 1, plan.oversample, axis=1, padtype="line"
                )
            for b, (i, prep, _) in enumerate(block):
                if status[b] != K.STATUS_OK:
                    results[i] = _diverged(prep, int(status[b]), float(t_status[b]))
                else:
                    results[i] = records[b]  # a row of the block's array
    return results


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
        collapsed; the message names the scene and the time.

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

    Raises
    ------
    SimulationDivergedError
        As :func:`simulate`.
    """
    geometry, settings, level, code, ehl = (
        prep.geometry,
        prep.settings,
        prep.level,
        prep.code,
        prep.ehl,
    )
    p, wav, y0, qmax, z = prep.p, prep.wav, prep.y0, prep.max_ball_load, geometry.ball_count
    rig, scene, operating, defect_list, reason, freqs = (
        prep.rig,
        prep.scene,
        prep.operating,
        prep.defects,
        prep.reason,
        prep.freqs,
    )

    plan = _plan(prep)
    oversample, record_dt, n_out, n_record = (
        plan.oversample,
        plan.record_dt,
        plan.n_out,
        plan.n_record,
    )
    out_state = np.zeros((n_record, K.N_OUT_STATE))
    out_accel = np.zeros((n_record, K.N_OUT_ACCEL))
    record_loads = bool(settings.record_contact_loads)
    out_loads = np.zeros((n_record if record_loads else 1, 2, z))
    extra: dict = {}
    if settings.integrator == "rk4":
        dt, n_steps, t_first = plan.dt, plan.n_steps, plan.t_first
        status, t_fail, _ = K._rk4(
            code,
            int(ehl),
            y0,
            p,
            wav,
            0.0,
            dt,
            n_steps,
            t_first,
            record_dt,
            n_record,
            out_state,
            out_accel,
            out_loads,
            record_loads,
        )
        extra["integrator_stats"] = {"step_s": dt, "steps": n_steps}
    else:
        nd = K.n_dof(code, z)
        atol = np.empty(2 * nd)
        atol[:nd] = settings.atol_displacement
        atol[nd:] = settings.atol_displacement * 1e3
        stats = np.zeros(4)
        t_first = plan.t_first
        # never step over a local defect: at most half a passage per step
        h_max = min(record_dt * 4, 0.5 * DEFECT_STEPS * defect_step(p, wav))
        max_steps = int(settings.max_steps_per_second * (t_first + settings.duration)) + 1000
        status, t_fail, _ = K._dopri5(
            code,
            int(ehl),
            y0,
            p,
            wav,
            0.0,
            t_first,
            record_dt,
            n_record,
            settings.rtol,
            atol,
            min(1e-7, record_dt),
            h_max,
            max_steps,
            out_state,
            out_accel,
            out_loads,
            record_loads,
            stats,
        )
        extra["integrator_stats"] = {
            "accepted_steps": int(stats[0]),
            "rejected_steps": int(stats[1]),
            "min_step_s": float(stats[2]),
            "max_step_s": float(stats[3]),
        }
    if status != K.STATUS_OK:
        raise _diverged(prep, int(status), float(t_fail))
    signals = _decimate(out_state, out_accel, oversample, settings.channels or CHANNELS)
    time = np.arange(n_out) / settings.fs
    loads = out_loads[::oversample].copy() if record_loads else None
    extra.update(
        {"oversample": oversample, "first_sample_time_s": t_first, "max_static_ball_load_n": qmax}
    )
    params = _params_record(
        geometry, operating, rig, scene, level, reason, settings, defect_list, extra
    )
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


#: Output channel -> (record array: 0 state, 1 acceleration; column).
_CHANNEL_COLUMNS = {
    "housing_displacement_x": (0, 2),
    "housing_displacement_y": (0, 3),
    "housing_velocity_x": (0, 6),
    "housing_velocity_y": (0, 7),
    "housing_acceleration_x": (1, 2),
    "housing_acceleration_y": (1, 3),
    "shaft_displacement_x": (0, 0),
    "shaft_displacement_y": (0, 1),
    "shaft_velocity_x": (0, 4),
    "shaft_velocity_y": (0, 5),
    "shaft_acceleration_x": (1, 0),
    "shaft_acceleration_y": (1, 1),
}


def _decimate(
    out_state: np.ndarray, out_accel: np.ndarray, factor: int, channels: Sequence[str]
) -> dict[str, np.ndarray]:
    """Anti-alias filter and downsample the integration record to the output rate.

    All requested channels in one block (one gather, one polyphase filter call): each output
    channel is a contiguous row of the result.
    """
    records = (out_state, out_accel)
    block = np.empty((len(channels), out_state.shape[0]))
    for c, name in enumerate(channels):
        which, column = _CHANNEL_COLUMNS[name]
        block[c] = records[which][:, column]
    if factor > 1:
        # polyphase FIR (Kaiser window), linear phase with its delay compensated
        block = sp_signal.resample_poly(block, 1, factor, axis=1, padtype="line")
    return {name: block[c] for c, name in enumerate(channels)}


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
    jac = _jacobian(prep.code, prep.ehl, prep.p, prep.wav, prep.y0)
    if prep.level == "shaft":
        # the one-way housing estimate is not part of the shaft scene's dynamics
        keep = [0, 1, nd, nd + 1]
        jac = jac[np.ix_(keep, keep)]
    lam = np.linalg.eigvals(jac)
    freqs = np.abs(lam.imag[lam.imag > 1e-6]) / (2 * np.pi)
    return np.sort(freqs)[::-1]
