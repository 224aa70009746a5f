"""Parameter packing for the kernels.

The float vector ``p``, the waviness and defect table ``wav``, random slip rows and the EHL
film tables (docs/model.md 3-5, 11-12).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np

from . import _kernels as K
from . import _static_kernels as SK
from ._validate import ParameterError
from .contact import (
    HertzContact,
    entrainment_speed,
    film_thickness,
    hertz_contact,
    load_deflection_constants,
    rigid_isoviscous_coefficient,
    squeeze_film_damping,
)
from .defects import defect_path
from .kinematics import BearingFrequencies
from .params import (
    BearingGeometry,
    LocalizedDefect,
    OperatingCondition,
    Rig,
    Waviness,
)


@functools.lru_cache(maxsize=64)
def contact_geometries(
    geometry: BearingGeometry,
) -> tuple[HertzContact, HertzContact, tuple[float, float, float]]:
    """Inner and outer contact geometry and the Hertz constants (K_i, K_o, K_series) [N/m^1.5].

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.

    Returns
    -------
    inner, outer : HertzContact
        The contacts.
    constants : (float, float, float)
        K_i, K_o and their series constant [N/m^1.5].
    """
    ci = hertz_contact(geometry, "inner")
    co = hertz_contact(geometry, "outer")
    return ci, co, load_deflection_constants(geometry)


Defect = Waviness | LocalizedDefect


def as_defects(defects: Defect | Sequence[Defect] | None) -> tuple[Defect, ...]:
    """``simulate``'s ``defects`` argument as a tuple of checked defect objects.

    Parameters
    ----------
    defects : Waviness, LocalizedDefect, sequence of them, or None
        As given to ``simulate``.

    Returns
    -------
    tuple
        The defects (empty for None).
    """
    if defects is None:
        return ()
    if isinstance(defects, (Waviness, LocalizedDefect)):
        return (defects,)
    if isinstance(defects, str) or not hasattr(defects, "__iter__"):
        raise ParameterError(
            f"defects = {defects!r} is not a Waviness or LocalizedDefect, or a sequence of them"
        )
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
    """Kernel table rows of a local defect (one per race; two for a ball pit).

    Column order W_SURFACE, W_BALL, W_HALF_WIDTH, W_DEPTH, W_POSITION, W_SURFACE_RADIUS,
    W_BRIDGE_RADIUS (and for a ball pit W_LATITUDE, W_DRIFT, W_TRACK) of ``generators._kernels``.
    """
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


def waviness_table(
    defects: Sequence[Defect],
    geometry: BearingGeometry,
    rng: np.random.Generator,
    radial_load: float,
) -> np.ndarray:
    """Expand defects into the kernel table (ball rows per ball, phases drawn).

    Parameters
    ----------
    defects : sequence of Waviness or LocalizedDefect
        The run's defects, checked (:func:`as_defects`).
    geometry : BearingGeometry
        The bearing.
    rng : numpy.random.Generator
        Draws the phases and positions asked for as random.
    radial_load : float
        Sets the contact track width of ball pits (Stribeck load) [N].

    Returns
    -------
    ndarray
        The kernels' table, a row per surface term (``_kernels.W_*`` columns).
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
#: How the cage components' frequencies are spread over SLIP_BAND: "log" (equal power per
#: log band, the default) or "linear" (equal power per Hz: a white speed fluctuation, whose
#: integral wanders like a random walk; benchmarks/slip_discreteness.py compares them).
SLIP_SPACING = "log"
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
        linear = SLIP_SPACING == "linear" and balls == (-1,)
        scale = (lambda v: v) if linear else np.log
        edges = np.linspace(scale(band[0] * wc), scale(band[1] * wc), count + 1)
        for ball in balls:
            drawn = rng.uniform(edges[:-1], edges[1:])
            rates = drawn if linear else np.exp(drawn)
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


def pack_parameters(
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    ehl: bool,
    freqs: BearingFrequencies | None,
) -> np.ndarray:
    """Pack the parameter objects into the kernel's float64 vector (indices ``K.P_*``).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    operating : OperatingCondition
        Speed [Hz], load [N], its angle [rad], slip.
    rig : Rig
        Masses [kg], stiffnesses [N/m] and damping of the rig.
    ehl : bool
        With the lubricant film.
    freqs : BearingFrequencies or None
        The characteristic frequencies [Hz], when computed already.

    Returns
    -------
    ndarray
        The parameter vector (SI units).
    """
    ci, co, (ki, ko, kt) = contact_geometries(geometry)
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
        # the film between ball and race apart (scene full): the Hertz approach at the floor
        p[K.P_GAP_FLOOR_INNER] = (qfloor / ki) ** (2 / 3)
        p[K.P_GAP_FLOOR_OUTER] = (qfloor / ko) ** (2 / 3)
        if rig.film_entrainment_factor > 0.0:  # docs/model.md 4.6: C^2 of w = C / sqrt(h)
            share = rig.film_entrainment_factor**2
            p[K.P_ENTRAINMENT_INNER] = share * rigid_isoviscous_coefficient(ci, lub, u) ** 2
            p[K.P_ENTRAINMENT_OUTER] = share * rigid_isoviscous_coefficient(co, lub, u) ** 2
            # in series one load crosses both films: h_i + h_o = (C_i^2 + C_o^2) / Q^2
            p[K.P_ENTRAINMENT_SERIES] = p[K.P_ENTRAINMENT_INNER] + p[K.P_ENTRAINMENT_OUTER]
    return p


#: Nodes per film table (see ``_kernels``): 2048 nodes up to a 100-fold overload keep the
#: interpolation error of the force within 2e-8 of it (1e-9 at 500 N; checked in
#: tests_generators/test_contact.py).
FILM_TABLE_NODES = 2048
#: Values per node: the static force Q, dQ/ds, the damping coefficient C and dC/ds.
FILM_TABLE_WIDTH = 4


def with_film_tables(p: np.ndarray) -> np.ndarray:
    """Append the film tables of the three contacts to ``p`` (EHL scenes).

    Each node holds the contact's static force Q [N] and damping coefficient C [N s/m] (with
    their derivatives in s = sqrt(delta + h_max)), so that the kernels read the force
    Q + C delta' without solving the film equation (``_kernels._hertz_ehl_table``). The
    tables depend on thirteen of ``p``'s values only; a faulty case and its healthy twin share
    them, so the last few are kept
    (:func:`_film_tables`).

    Parameters
    ----------
    p : ndarray
        The parameter vector (:func:`pack_parameters`).

    Returns
    -------
    ndarray
        ``p`` with the tables appended.
    """
    keys = (
        K.P_FILM_LOAD_FLOOR,
        K.P_FILM_REFERENCE_LOAD,
        K.P_K_INNER,
        K.P_K_OUTER,
        K.P_K_SERIES,
        K.P_FILM_INNER,
        K.P_FILM_OUTER,
        K.P_FILM_INNER_MAX,
        K.P_FILM_OUTER_MAX,
        K.P_CONTACT_DAMPING_TIME,
        K.P_SQUEEZE_INNER,
        K.P_SQUEEZE_OUTER,
        K.P_SQUEEZE_SERIES,
    )
    values = tuple(float(p[k]) for k in keys)
    steps, tables = _film_tables(values)
    out = p.copy()
    for c in range(3):
        out[K.P_TABLE_STEP_INNER + c] = steps[c]
        out[K.P_TABLE_INV_STEP_INNER + c] = 1.0 / steps[c]
    out[K.P_TABLE_NODES] = FILM_TABLE_NODES
    if p[K.P_ENTRAINMENT_SERIES] <= 0.0:
        return np.concatenate([out, tables])
    extra = (float(p[K.P_ENTRAINMENT_SERIES]), steps[K.TABLE_SERIES])
    entrained = _entrained_film_table(values + extra)
    out[K.P_ENTRAINED_NODES] = ENTRAINED_GAP_NODES + FILM_TABLE_NODES
    out[K.P_ENTRAINED_ORIGIN] = ENTRAINED_GAP_NODES
    out[K.P_ENTRAINED_STEP] = steps[K.TABLE_SERIES]
    out[K.P_ENTRAINED_INV_STEP] = 1.0 / steps[K.TABLE_SERIES]
    return np.concatenate([out, tables, entrained])


#: Nodes of the entrained table inside the gap (x < 0), at the plain series table's spacing:
#: the table reaches a quarter of the Hertz approach at the plain table's top (100-fold
#: overload) into the gap, 0.1-0.2 mm, further than an unloaded ball stands from its race in
#: a clearance; beyond, the kernels solve the law by Newton (``_kernels._entrained_table``). A
#: fixed count, so that every case's table has the same length (the lanes stack them).
ENTRAINED_GAP_NODES = FILM_TABLE_NODES // 2
#: Halvings of the entrained table's bisection on ln Q in [-40, 50]: to the last bit.
ENTRAINED_PASSES = 64


@functools.lru_cache(maxsize=8)
def _entrained_film_table(values: tuple[float, ...]) -> np.ndarray:
    """The flattened entrained table of :func:`with_film_tables` (read-only).

    The series contact's composite law (``_kernels._entrained_film``, docs/model.md 4.6) on
    nodes uniform in the signed s = sign(x) sqrt(|x|), x = delta + h_max, at the plain series
    table's spacing, ``ENTRAINED_GAP_NODES`` of them inside the gap and ``FILM_TABLE_NODES``
    from s = 0 to the plain table's top. At each node the load Q solves
    (Q / K)^(2/3) - h(Q) = delta, h(Q) = film (Q + floor)^-0.067 + C^2 / Q^2, by bisection on
    ln Q to the last bit (``_static_kernels._entrained_bisection``: the halvings far from the
    root decided by its side, since stop 86; until then every one by the law, in numpy: the
    same bits on this project's hosts), then C = 1.5 tau K d^0.5 + Q / (Q + floor) squeeze film
    / h, and the slopes in s by implicit differentiation: dQ/ds = 2 |s| / (d delta / dQ).
    """
    (floor, _, _, _, k, film_inner, film_outer, _, _, tau, _, _, squeeze) = values[:13]
    max_inner, max_outer = values[7], values[8]
    entrainment, step = values[13:]
    film, h_max = film_inner + film_outer, max_inner + max_outer
    e = K.FILM_EXPONENT
    s = step * (np.arange(ENTRAINED_GAP_NODES + FILM_TABLE_NODES) - ENTRAINED_GAP_NODES)
    delta = np.sign(s) * s**2 - h_max
    # ln Q [ln N] in [-40, 50] (_kernels._entrained_film's bracket): the residual rises with Q,
    # 64 halvings take it to the last bit (90 / 2^64)
    log_q = np.empty(s.shape)
    SK._entrained_bisection(delta, k, film, floor, entrainment, e, ENTRAINED_PASSES, log_q)
    q = np.exp(log_q)
    d = (q / k) ** (2 / 3)
    ehl = film * (q + floor) ** e
    rigid = entrainment / q**2
    h = ehl + rigid
    delta_q = (2 / 3) * d / q - e * ehl / (q + floor) + 2.0 * rigid / q  # d delta / dQ
    q_s = 2.0 * np.abs(s) / delta_q
    weight = q / (q + floor)
    damping = 1.5 * tau * k * np.sqrt(d) + weight * squeeze * film / h
    damping_q = 1.5 * tau * k * (1 / 3) * np.sqrt(d) / q + squeeze * film * (
        floor / (q + floor) ** 2 / h - weight * (e * ehl / (q + floor) - 2.0 * rigid / q) / h**2
    )
    table = np.stack([q, q_s, damping, damping_q * q_s], axis=1).ravel()
    table.flags.writeable = False
    return table


@functools.lru_cache(maxsize=8)
def _film_tables(values: tuple[float, ...]) -> tuple[tuple[float, ...], np.ndarray]:
    """The node spacings and the flattened tables of :func:`with_film_tables` (read-only).

    Per contact, on nodes uniform in s = sqrt(delta + h_max): the elastic approach d solving
    d = delta + h(K d^1.5) by Newton to full convergence, then Q = K d^1.5 and
    C = 1.5 tau K d^0.5 + Q / (Q + floor) squeeze film / h (the dry and the squeeze-film
    damping of ``_kernels._hertz_ehl``), with dQ/ds and dC/ds from dd/ds. Both vanish at
    s = 0 (no contact), so a table read at s = 0 gives no force.
    """
    (
        floor,
        reference,
        k_inner,
        k_outer,
        k_series,
        film_inner,
        film_outer,
        max_inner,
        max_outer,
        tau,
        squeeze_inner,
        squeeze_outer,
        squeeze_series,
    ) = values
    e = K.FILM_EXPONENT
    q_hi = 100.0 * (reference + 100.0)
    specs = (
        (k_inner, film_inner, max_inner, squeeze_inner),
        (k_outer, film_outer, max_outer, squeeze_outer),
        (k_series, film_inner + film_outer, max_inner + max_outer, squeeze_series),
    )
    n = FILM_TABLE_NODES
    tables = np.zeros((3, n, FILM_TABLE_WIDTH))
    steps = []
    for c, (kc, film, h_max, squeeze) in enumerate(specs):
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
        safe_d = np.where(pos, d, 1.0)
        root = np.sqrt(d)
        q = kc * d * root
        h = film * (q + floor) ** e
        slope = np.where(pos, -1.5 * e * h / safe_d * q / (q + floor), 0.0)
        d_s = 2.0 * s_nodes / (1.0 + slope)  # dd/ds = dd/d delta * 2 s
        q_s = 1.5 * kc * root * d_s
        # d sqrt(d)/ds = d_s / (2 sqrt d) -> 1 at s = 0, where d = s^2 to first order
        root_s = np.where(pos, d_s / (2.0 * np.where(pos, root, 1.0)), 1.0)
        h_s = e * h * q_s / (q + floor)
        weight = q / (q + floor)
        weight_s = floor * q_s / (q + floor) ** 2
        damping = 1.5 * tau * kc * root + weight * squeeze * film / h
        damping_s = 1.5 * tau * kc * root_s + squeeze * film * (weight_s / h - weight * h_s / h**2)
        tables[c, :, 0] = q
        tables[c, :, 1] = q_s
        tables[c, :, 2] = damping
        tables[c, :, 3] = damping_s
        steps.append(step)
    flat = tables.ravel()
    flat.flags.writeable = False
    return tuple(steps), flat


def film_sum(p: np.ndarray, loads: np.ndarray) -> np.ndarray:
    """Inner plus outer central film [m] of each ball at its load [N] (docs/model.md 4.2).

    Parameters
    ----------
    p : ndarray
        The parameter vector.
    loads : ndarray
        Each ball's load [N].

    Returns
    -------
    ndarray
        Each ball's film [m].
    """
    q = loads + p[K.P_FILM_LOAD_FLOOR]  # smooth floor, as in the kernel
    return (p[K.P_FILM_INNER] + p[K.P_FILM_OUTER]) * q**K.FILM_EXPONENT


def waviness_at_start(p: np.ndarray, wav: np.ndarray, z: int) -> np.ndarray:
    """Waviness values seen by each ball at t = 0: rows [w_o, w_i, wb_o, wb_i] [m].

    Parameters
    ----------
    p : ndarray
        The parameter vector.
    wav : ndarray
        The waviness table (:func:`waviness_table`).
    z : int
        Ball count.

    Returns
    -------
    ndarray
        (4, z) [m].
    """
    out = np.zeros((11, z))
    K._start_waviness(p, wav, z, out)
    return out[[0, 2, 4, 6]]
