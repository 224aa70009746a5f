"""Numba kernels of the bearing dynamic model: plain float64 arrays in, plain arrays out.

Conventions (the Python side, :mod:`generators.model`, packs and unpacks):

* ``p``: float64 parameter vector, indexed by the ``P_*`` constants below, SI units.
* ``wav``: float64 table, one row per waviness harmonic and surface, columns ``W_*``:
  surface code (``SURF_OUTER``, ``SURF_INNER``, ``SURF_BALL``), ball index (ball rows only),
  order k, amplitude [m], phase [rad]. A ball row's phase already contains the ball's initial
  spin angle times k.
* State ``y``: displacements first, then velocities. Bodies: shaft (x_s, y_s), housing (x_h,
  y_h), then for the ``full`` scene one radial coordinate rho_j per ball.
* ``scene`` and ``ehl`` are passed through :func:`numba.literally` by the integrators
  (:mod:`generators._integrators`, with the compiled entry points) and by
  :func:`generators._rhs._rhs`, so every combination is compiled (and cached) on its own and
  the branches that pick the scene are constants removed at compile time: a scene without
  ball masses or without a film never executes their code. The right-hand side
  (:func:`generators._rhs._rhs_inline`, in a module of its own since stop 56) and the small
  helpers that take arrays are inlined (``inline="always"``: no call and no reference
  counting of the array arguments per evaluation) at RK4's one call site; DOPRI5 and single
  evaluations call one compiled copy per scene (:func:`generators._rhs._rhs`).
* Time-only terms (cage angle, waviness per ball) are computed once per distinct stage time
  (:func:`_time_terms`), outside the right-hand side.

Scenes (docs/model.md 1.3-1.5): ``SCENE_SHAFT`` 2-DOF shaft on massless balls with a rigid housing
(the housing is integrated one-way, driven by the transmitted bearing force, as an output
estimate); ``SCENE_SHAFT_HOUSING`` 4 DOF; ``SCENE_FULL`` 4 + Z DOF.
Only numpy, numba and math are imported here (checked by import-linter).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from generators import kernel_cache

# ------------------------------------------------------------------- parameter vector layout
(
    P_BALL_COUNT,
    P_SHAFT_MASS,
    P_HOUSING_MASS,
    P_BALL_MASS,
    P_PEDESTAL_STIFFNESS,
    P_PEDESTAL_DAMPING,
    P_SHAFT_DAMPING,
    P_K_INNER,
    P_K_OUTER,
    P_K_SERIES,
    P_GAP,
    P_SHAFT_SPEED,
    P_CAGE_SPEED,
    P_BALL_SPIN_SPEED,
    P_CAGE_ANGLE0,
    P_SHAFT_ANGLE0,
    P_LOAD_X,
    P_LOAD_Y,
    P_GRAVITY,
    P_LOADING_STIFFNESS,
    P_LOADING_X0,
    P_LOADING_Y0,
    P_CONTACT_DAMPING_TIME,
    P_FILM_INNER,
    P_FILM_OUTER,
    P_FILM_LOAD_FLOOR,
    P_FILM_REFERENCE_LOAD,
    P_FILM_INNER_REF,
    P_FILM_OUTER_REF,
    P_FILM_INNER_MAX,
    P_FILM_OUTER_MAX,
    P_SQUEEZE_INNER,
    P_SQUEEZE_OUTER,
    P_SQUEEZE_SERIES,
    P_PITCH_RADIUS,
    P_UNBALANCE,
    P_MAX_DISPLACEMENT,
    P_PITCH_COS,
    P_PITCH_SIN,
    P_TABLE_NODES,
    P_TABLE_STEP_INNER,
    P_TABLE_STEP_OUTER,
    P_TABLE_STEP_SERIES,
    P_TABLE_INV_STEP_INNER,
    P_TABLE_INV_STEP_OUTER,
    P_TABLE_INV_STEP_SERIES,
    P_GAP_FLOOR_INNER,
    P_GAP_FLOOR_OUTER,
    P_ENTRAINMENT_INNER,
    P_ENTRAINMENT_OUTER,
    P_ENTRAINMENT_SERIES,
    P_ENTRAINED_NODES,
    P_ENTRAINED_ORIGIN,
    P_ENTRAINED_STEP,
    P_ENTRAINED_INV_STEP,
    P_SIZE,
) = range(56)
# Film tables (EHL scenes): from P_SIZE on, three tables (inner, outer, series contact) of
# P_TABLE_NODES nodes each, every node [Q, dQ/ds, C, dC/ds]: the static force Q = K d^1.5 and
# the damping coefficient C, d solving d = delta + h(K d^1.5), on a grid uniform in
# s = sqrt(delta + h_max) (delta >= -h_max; packing._film_tables).
TABLE_INNER, TABLE_OUTER, TABLE_SERIES = 0, 1, 2
# With the film's entrainment (FILM_ENTRAINED), a fourth table follows them, from
# P_SIZE + 12 * P_TABLE_NODES on: the series contact's composite law (``_entrained_film``),
# P_ENTRAINED_NODES nodes [Q, dQ/ds, C, dC/ds] uniform (P_ENTRAINED_STEP apart) in the signed
# s = sign(x) sqrt(|x|), x = delta + h_max, node P_ENTRAINED_ORIGIN at s = 0: the law has no
# onset, so the table reaches into the gap (x < 0) as well (packing._entrained_table).
# P_FILM_*: h_c = P_FILM_* * (Q + floor)^FILM_EXPONENT [m] (Hamrock-Dowson, docs/model.md 4.2).
# P_SQUEEZE_*: squeeze-film damping c = P_SQUEEZE_* * (Q + floor)^-FILM_EXPONENT [N s/m]
# (docs/model.md 4.5 with h_c inserted); P_SQUEEZE_SERIES is the series combination for
# massless balls. P_GAP_FLOOR_*: the Hertz approach at the film's load floor, (floor / K)^(2/3)
# [m], over which the film between a ball and a race apart fades at onset (``_gap_squeeze``).
# P_ENTRAINMENT_* (inner, outer, series in TABLE_* order): the square of the rigid-isoviscous
# entrainment coefficient C [N^2 m] of a flooded contact at light load, w = C / sqrt(h)
# (docs/model.md 4.6; 0: not modelled, the film carries nothing before the EHL contact).

FILM_EXPONENT = -0.067
FILM_ITERATIONS = 2  # Newton steps on d = delta + h(K d^1.5): error 1e-5 (tests/reference.py)
ENTRAINMENT_ITERATIONS = 100  # at most (safeguarded Newton on ln Q; 5-10 typical)

SCENE_SHAFT = 0
SCENE_SHAFT_HOUSING = 1
SCENE_FULL = 2
#: Scene codes and the names their compiled entry points carry.
SCENE_NAMES = {SCENE_SHAFT: "shaft", SCENE_SHAFT_HOUSING: "shaft_housing", SCENE_FULL: "full"}
FILM_DRY = 0
FILM_EHL = 1
#: The film with its entrainment at light load (:func:`_entrained_film`, read from its table by
#: :func:`_entrained_table`; docs/model.md 4.6): massless-ball scenes only. A mode of its own,
#: compiled apart, so that the film's default path is the same machine code as without it.
FILM_ENTRAINED = 2
FILM_NAMES = {FILM_DRY: "dry", FILM_EHL: "ehl", FILM_ENTRAINED: "entrained"}

SURF_OUTER = 0
SURF_INNER = 1
SURF_BALL = 2
# Localized defects (rows of the same table, columns named W_HALF_WIDTH, W_DEPTH, W_POSITION,
# W_SURFACE_RADIUS, W_BRIDGE_RADIUS below): the half width [rad], the depth [m], the centre
# position [rad] on the defective surface, the radius of that surface [m] (arc length per
# radian), the bridging radius [m] (the reduced radius of the contact in the rolling direction),
# W_BALL the ball (ball defects). A ball defect is two rows: the contact with the outer race
# and, diametrically opposite, with the inner race.
SURF_OUTER_DEFECT = 3
SURF_INNER_DEFECT = 4
SURF_BALL_DEFECT_OUTER = 5
SURF_BALL_DEFECT_INNER = 6
# Random slip (rows of the same table, after the defects): one sinusoidal component of the
# angle by which the balls lag their nominal, evenly spaced cage positions where they meet a
# local defect, phi_j(t) = sum over rows of angle * sin(rate t + phase) [rad]. W_BALL is the
# ball (-1: every ball, the cage's own speed fluctuation), W_SLIP_RATE the component's angular
# frequency [rad/s], W_SLIP_ANGLE its amplitude [rad], W_PHASE its phase. A ball's spin angle
# lags with it (rolling: by phi_j times ball spin / cage speed), so a ball pit's impacts jitter
# too. The varying-compliance geometry keeps the nominal spacing (docs/realism.md 1).
SURF_SLIP = 7
# rows of the time-terms work array (:func:`_scratch`) that hold each ball's slip angle and rate
SLIP_LAG = 9
#: What :func:`_waviness` evaluates of the local defects: nothing, the slip angles only (a
#: step's end away from any pit: the next step's :func:`_defect_near` reads them), or the slip
#: angles and the pits' rows.
DEFECTS_NONE, DEFECTS_SLIP, DEFECTS_ALL = 0, 1, 2
(
    W_SURFACE,
    W_BALL,
    W_ORDER,
    W_AMPLITUDE,
    W_PHASE,
    W_STEP_COS,
    W_STEP_SIN,
    W_LATITUDE,
    W_DRIFT,
    W_TRACK,
    W_SIZE,
) = range(11)
W_SLIP_RATE = W_ORDER  # slip rows: angular frequency [rad/s]
W_SLIP_ANGLE = W_AMPLITUDE  # slip rows: amplitude [rad]
W_HALF_WIDTH = W_ORDER  # local defect rows: half width [rad]
W_DEPTH = W_AMPLITUDE  # local defect rows: depth [m]
W_POSITION = W_PHASE  # local defect rows: centre position [rad]
W_SURFACE_RADIUS = W_STEP_COS  # local defect rows: radius of the defective surface [m]
W_BRIDGE_RADIUS = W_STEP_SIN  # local defect rows: bridging radius [m]
# Ball defects only: W_LATITUDE the pit's angle from the ball's rolling circle at t = 0 [rad],
# W_DRIFT the rate at which the spin axis turns that angle [rad/s], W_TRACK the half width of
# the band around the rolling circle in which the pit meets the races, over the ball radius [-].
# W_STEP_COS/SIN: cos and sin of k times the ball pitch 2 pi / Z (race rows).

# RK4 advances the cos/sin of the time-dependent arguments by rotation (two per step) and
# recomputes them exactly every PHASE_ANCHOR steps: the rotation's rounding (~1e-16 per step)
# never accumulates beyond ~1e-14.
PHASE_ANCHOR = 64

# integration status codes
STATUS_OK = 0
STATUS_NONFINITE = 1
STATUS_RUNAWAY = 2
STATUS_STEP_COLLAPSE = 3
STATUS_TOO_MANY_STEPS = 4

N_OUT_STATE = 8  # x_s, y_s, x_h, y_h, vx_s, vy_s, vx_h, vy_h
N_OUT_ACCEL = 4  # ax_s, ay_s, ax_h, ay_h

# error_model="numpy": a division by zero gives inf/NaN (caught by the divergence check) instead
# of raising inside the kernel.
# fastmath: contraction to fused multiply-add, reciprocals, no signed zeros (6 % faster on the
# full/EHL scene). Never "reassoc": with it the rounding depends on how LLVM vectorises each
# compiled specialisation, and datasets written by worker processes that compiled on their
# own were no longer byte-identical (tests_cmtool/test_datasets.py, cold numba cache). Never
# "nnan"/"ninf": the divergence check must see NaN and inf.
_FASTMATH = {"nsz", "arcp", "contract"}
_JIT = {"cache": True, "fastmath": _FASTMATH, "nogil": True, "error_model": "numpy"}
_JIT_INLINE = {**_JIT, "inline": "always"}


def n_dof(scene: int, ball_count: int) -> int:
    """Number of displacement coordinates of a scene (the state has twice as many)."""
    return 4 + ball_count if scene == SCENE_FULL else 4


# ------------------------------------------------------------------------------ contact laws


@numba.njit(**_JIT)
def _hertz_dry(delta, delta_rate, k_hertz, damping_time):
    """Q = [K d^1.5 + tau * 1.5 K d^0.5 * d']_+ (damping vanishes at onset, docs/model.md 1.2)."""
    if delta <= 0.0:
        return 0.0
    root = math.sqrt(delta)
    q = k_hertz * delta * root + damping_time * 1.5 * k_hertz * root * delta_rate
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT)
def _hertz_ehl(delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, h_ref, h_max):
    """Hertz contact in series with the EHL film (docs/model.md 4.3-4.4).

    Solves d = delta + h(K d^1.5) for the elastic approach d, with the film
    h(Q) = film * (Q + floor)^-0.067: a smooth form of docs/model.md's floor max(Q, floor) (0.013 %
    thinner at 500 N with a 1 N floor), smooth so that RK4 keeps its order. ``FILM_ITERATIONS``
    Newton steps from d = delta + h_ref (the film at the reference load); dh/dd =
    -0.1005 h/d Q/(Q + floor). Then adds the dry (stiffness-proportional) and squeeze-film
    damping; the squeeze term is weighted by Q / (Q + floor) so that Q is continuous at onset.
    ``h_max`` = film * floor^-0.067 is the film at zero load: no contact while
    delta + h_max <= 0. (With the film's entrainment, :func:`_entrained_film` instead.)
    """
    if delta + h_max <= 0.0:
        return 0.0
    d = delta + h_ref
    h = h_ref
    for _ in range(FILM_ITERATIONS):
        if d > 0.0:
            q = k_hertz * d * math.sqrt(d)
            h = film * math.exp(FILM_EXPONENT * math.log(q + floor))
            slope = -1.5 * FILM_EXPONENT * h / d * q / (q + floor)
        else:
            h = h_max
            slope = 0.0
        d = d - (d - delta - h) / (1.0 + slope)
    if d <= 0.0:
        return 0.0
    root = math.sqrt(d)
    q = k_hertz * d * root
    # squeeze * (Q + floor)^0.067 == squeeze * film / h (h of the last Newton iterate)
    c = damping_time * 1.5 * k_hertz * root + q / (q + floor) * squeeze * film / h
    q = q + c * delta_rate
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT)
def _entrained_film(delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, entrainment):
    """A flooded lubricated contact from the rigid-isoviscous to the EHL regime (docs/model.md 4.6).

    The film carries the load Q at the gap h(Q) = film (Q + floor)^-0.067 + C^2 / Q^2: the
    EHL film of :func:`_hertz_ehl` under load and, at light load, the rigid-isoviscous film of a
    rolling point contact (Hamrock and Dowson), Q = C / sqrt(h). The approach solves
    (Q / K)^(2/3) - h(Q) = delta for Q > 0 (strictly increasing in Q: one root) by Newton's
    method on ln Q, kept inside a bisection bracket; Q is smooth in delta, with no onset: a
    contact the rigid approach leaves g apart carries C / sqrt(g) and more as it closes. Then
    the dry and the squeeze-film damping of :func:`_hertz_ehl`, the squeeze term at the
    composite gap.
    """
    lo = -40.0  # ln Q [ln N]: the root lies between 4e-18 N and 5e21 N
    hi = 50.0
    log_k = math.log(k_hertz)
    q_guess = k_hertz * max(delta, 0.0) ** 1.5 + math.sqrt(entrainment / max(abs(delta), 1e-12))
    v = min(max(math.log(q_guess), lo + 1.0), hi - 1.0)
    for _ in range(ENTRAINMENT_ITERATIONS):
        q = math.exp(v)
        elastic = math.exp((2.0 / 3.0) * (v - log_k))
        ehl = film * math.exp(FILM_EXPONENT * math.log(q + floor))
        rigid = entrainment / (q * q)
        residual = elastic - ehl - rigid - delta
        if residual > 0.0:
            hi = v
        else:
            lo = v
        slope = (2.0 / 3.0) * elastic - FILM_EXPONENT * ehl * q / (q + floor) + 2.0 * rigid
        step = v - residual / slope
        if not lo < step < hi:
            step = 0.5 * (lo + hi)
        if abs(step - v) <= 1e-14 * max(abs(v), 1.0):
            v = step
            break
        v = step
    q = math.exp(v)
    d = math.exp((2.0 / 3.0) * (v - log_k))
    h = film * math.exp(FILM_EXPONENT * math.log(q + floor)) + entrainment / (q * q)
    c = damping_time * 1.5 * k_hertz * math.sqrt(d) + q / (q + floor) * squeeze * film / h
    q = q + c * delta_rate
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT_INLINE)
def _gap_squeeze(delta, delta_rate, film, squeeze, h_max, gap_floor):
    """Squeeze-film force [N] of a lubricated pair of surfaces apart (docs/model.md 4.4).

    Out of contact (delta + h_max < 0) the surfaces are -delta apart and a flooded film
    between them resists their approach by c_sq = squeeze * film / (-delta), (4.5) at that
    separation (Reynolds' 6 pi eta R^2 / h for a sphere); as they separate it gives nothing
    (Guembel's cavitation condition: no pressure under ambient). The weight g / (g +
    gap_floor), g = -(delta + h_max) the gap beyond the film at zero load and ``gap_floor``
    = (floor / K)^(2/3) the Hertz approach at the film's load floor (``P_GAP_FLOOR_*``),
    takes it to zero at onset as Q / (Q + floor) takes the contact's squeeze term there, so
    the force is continuous. Only scene ``full`` uses it: its balls have masses that the film
    holds back; massless balls have no motion of their own between the races.
    """
    gap = -(delta + h_max)
    if gap <= 0.0 or delta_rate <= 0.0:
        return 0.0
    return squeeze * film * gap * delta_rate / (-delta * (gap + gap_floor))


@numba.njit(**_JIT_INLINE)
def _hertz_ehl_table(
    delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, h_ref, h_max, p, table
):
    """:func:`_hertz_ehl` with the film equation's solution read from the table ``table``.

    The nodes are uniform in s = sqrt(delta + h_max), dense near contact onset where the
    force bends most, and hold the static force Q and the damping coefficient C with their
    slopes in s (``packing._film_tables``); cubic Hermite interpolation (C1, O(step^4)) gives
    Q + C delta', clipped at zero. Outside the table the Newton solution of :func:`_hertz_ehl`
    is used.
    """
    x = delta + h_max
    if x <= 0.0:
        return 0.0
    nodes = int(p[P_TABLE_NODES])
    x = math.sqrt(x) * p[P_TABLE_INV_STEP_INNER + table]
    i = int(x)
    if i >= nodes - 1:
        return _hertz_ehl(
            delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, h_ref, h_max
        )
    base = P_SIZE + 4 * (table * nodes + i)
    q = _film_force(
        x - i,
        p[P_TABLE_STEP_INNER + table],
        delta_rate,
        p[base],
        p[base + 1],
        p[base + 2],
        p[base + 3],
        p[base + 4],
        p[base + 5],
        p[base + 6],
        p[base + 7],
    )
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT_INLINE)
def _entrained_table(
    delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, entrainment, h_max, p
):
    """:func:`_entrained_film` (the series contact) read from its table in ``p``.

    The nodes are uniform in the signed s = sign(x) sqrt(|x|), x = delta + h_max, from inside
    the gap (x < 0, where the entrainment alone carries the load) to the table's top, and hold
    Q and C with their slopes in s (``packing._entrained_table``); cubic Hermite interpolation
    as :func:`_hertz_ehl_table`. Outside the table, the Newton solution of
    :func:`_entrained_film`.
    """
    x = delta + h_max
    s = math.sqrt(x) if x >= 0.0 else -math.sqrt(-x)
    u = s * p[P_ENTRAINED_INV_STEP] + p[P_ENTRAINED_ORIGIN]
    nodes = int(p[P_ENTRAINED_NODES])
    if not (0.0 <= u < nodes - 1):
        return _entrained_film(
            delta, delta_rate, k_hertz, damping_time, film, squeeze, floor, entrainment
        )
    i = int(u)
    base = P_SIZE + 12 * int(p[P_TABLE_NODES]) + 4 * i
    q = _film_force(
        u - i,
        p[P_ENTRAINED_STEP],
        delta_rate,
        p[base],
        p[base + 1],
        p[base + 2],
        p[base + 3],
        p[base + 4],
        p[base + 5],
        p[base + 6],
        p[base + 7],
    )
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT_INLINE)
def _film_force(u, step, delta_rate, q0, q0_s, c0, c0_s, q1, q1_s, c1, c1_s):
    """The film contact's force Q + C delta' [N] between two table nodes (u in [0, 1)).

    Cubic Hermite interpolation of the static force Q and the damping coefficient C from
    their values and slopes at the two nodes (``step`` the node spacing in s); not clipped.
    """
    u2 = u * u
    u3 = u2 * u
    w00 = 2.0 * u3 - 3.0 * u2 + 1.0
    w10 = (u3 - 2.0 * u2 + u) * step
    w01 = -2.0 * u3 + 3.0 * u2
    w11 = (u3 - u2) * step
    q = w00 * q0 + w10 * q0_s + w01 * q1 + w11 * q1_s
    c = w00 * c0 + w10 * c0_s + w01 * c1 + w11 * c1_s
    return q + c * delta_rate


# --------------------------------------------------------------------------------- waviness


@numba.njit(**_JIT)
def _wrap(angle):
    """Angle wrapped to [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


@numba.njit(**_JIT)
def _pit(delta, half_width, depth, radius, bridge, rate, scale, scale_rate, out, row, j):
    """Subtract the path of a ball over a pit from ``out[row, j]`` (and its rate from row + 1).

    ``delta`` is the angle of the contact point from the pit centre [rad] and ``rate`` its time
    derivative [rad/s]; the pit spans |delta| < half_width on a surface of radius ``radius``
    [m]. The ball (reduced radius ``bridge`` [m] in the rolling direction) pivots over the
    nearer edge, at a distance e = (half_width - |delta|) radius from it, and sinks by the
    sagitta bridge - sqrt(bridge^2 - e^2) until it reaches the floor at ``depth`` [m]: a narrow
    pit is bridged, a wide one is followed to its floor (the kinks are the impacts). The sink is
    multiplied by ``scale`` (rate ``scale_rate`` [1/s]): 1 for race pits.
    """
    u = abs(delta)
    if u >= half_width:
        return
    e = (half_width - u) * radius
    root2 = bridge * bridge - e * e
    sag = depth
    sag_rate = 0.0
    if root2 > 0.0:
        root = math.sqrt(root2)
        if bridge - root < depth:
            sag = bridge - root
            # d(sag)/dt = e / root * de/dt, de/dt = -sign(delta) * rate * radius
            sign = 1.0 if delta >= 0.0 else -1.0
            sag_rate = -e / root * sign * rate * radius
    out[row, j] -= scale * sag
    out[row + 1, j] -= scale * sag_rate + scale_rate * sag


@numba.njit(**_JIT)
def _track_factor(wav, r, t):
    """How much of a ball pit the races meet: (factor, its rate [1/s]).

    The pit sits at latitude lat(t) = lat0 + drift t from the ball's rolling circle; the races
    meet it fully on the circle and not at all outside the band |sin lat| < track, with a
    cos^2 taper between (C1: no jump in the contact force when the axis turns).
    """
    lat = wav[r, W_LATITUDE] + wav[r, W_DRIFT] * t
    track = wav[r, W_TRACK]
    y = math.sin(lat)
    u = abs(y) / track
    if u >= 1.0:
        return 0.0, 0.0
    c = math.cos(0.5 * math.pi * u)
    sign = 1.0 if y >= 0.0 else -1.0
    du = sign * math.cos(lat) * wav[r, W_DRIFT] / track
    return c * c, -0.5 * math.pi * math.sin(math.pi * u) * du


@numba.njit(**_JIT)
def _slip_lags(wav, trig, z, out):
    """Each ball's slip angle [rad] into ``out[SLIP_LAG, j]``, its rate [rad/s] into the next row.

    The sum of the slip rows (``SURF_SLIP``, the last rows of the table) for ball j and for
    every ball (-1), from the cos/sin of their arguments in ``trig``.
    """
    for j in range(z):
        out[SLIP_LAG, j] = 0.0
        out[SLIP_LAG + 1, j] = 0.0
    for r in range(wav.shape[0] - 1, -1, -1):
        if int(wav[r, W_SURFACE]) != SURF_SLIP:
            break
        a = wav[r, W_SLIP_ANGLE]
        angle = a * trig[r + 1, 1]
        rate = a * wav[r, W_SLIP_RATE] * trig[r + 1, 0]
        ball = int(wav[r, W_BALL])
        if ball >= 0:
            out[SLIP_LAG, ball] += angle
            out[SLIP_LAG + 1, ball] += rate
        else:
            for j in range(z):
                out[SLIP_LAG, j] += angle
                out[SLIP_LAG + 1, j] += rate


@numba.njit(**_JIT)
def _defect(wav, r, surface, z, theta0, shaft_angle, t, wc, ws, wb, slipping, out):
    """Localized defect rows of the waviness table (outer, inner race, or one ball).

    ``slipping``: the table has slip rows (:data:`SURF_SLIP`); ball j then meets the defect at
    its nominal position minus its slip angle ``out[SLIP_LAG, j]`` (:func:`_slip_lags`).
    """
    half = wav[r, W_HALF_WIDTH]
    depth = wav[r, W_DEPTH]
    pos = wav[r, W_POSITION]
    radius = wav[r, W_SURFACE_RADIUS]
    bridge = wav[r, W_BRIDGE_RADIUS]
    if surface == SURF_BALL_DEFECT_OUTER or surface == SURF_BALL_DEFECT_INNER:
        j = int(wav[r, W_BALL])
        scale, scale_rate = _track_factor(wav, r, t)
        if scale == 0.0:
            return
        # spin angle of the outer contact point on the ball; the inner one is opposite
        chi = wb * t if surface == SURF_BALL_DEFECT_OUTER else wb * t + math.pi
        spin = wb
        if slipping:
            # a ball that lags by phi has rolled phi * wb / wc less
            lag, lag_rate = out[SLIP_LAG, j], out[SLIP_LAG + 1, j]
            chi -= lag * wb / wc
            spin -= lag_rate * wb / wc
        row = 4 if surface == SURF_BALL_DEFECT_OUTER else 6
        _pit(_wrap(chi - pos), half, depth, radius, bridge, spin, scale, scale_rate, out, row, j)
        return
    pitch = 2.0 * math.pi / z
    for j in range(z):
        theta = theta0 + j * pitch
        rate = wc
        if slipping:
            lag, lag_rate = out[SLIP_LAG, j], out[SLIP_LAG + 1, j]
            theta -= lag
            rate -= lag_rate
        if surface == SURF_OUTER_DEFECT:
            _pit(_wrap(theta - pos), half, depth, radius, bridge, rate, 1.0, 0.0, out, 0, j)
        else:
            delta = _wrap(theta - shaft_angle - pos)
            _pit(delta, half, depth, radius, bridge, rate - ws, 1.0, 0.0, out, 2, j)


@numba.njit(**_JIT)
def _defect_near(wav, p, t, horizon, scratch):
    """Whether a contact is over a local defect at ``t`` or can reach one within ``horizon`` [s].

    The contact angles of :func:`_defect` at ``t`` (slip angles and rates from ``scratch``,
    which must hold the time terms of ``t``): a contact at angle delta from a pit of half width
    w moving at rate r is near when |delta| < w + |r| horizon. The RK4 loop subdivides the steps
    in which one is (``fine_steps``): the pit's path is resolved where it acts, and the step
    elsewhere is the scene's.
    """
    slip_rate = _slip_rate_bound(wav, int(p[P_BALL_COUNT]))
    return _defect_clear_steps(wav, p, t, horizon, scratch, 1.0, slip_rate) < 0


@numba.njit(**_JIT)
def _slip_rate_bound(wav, z):
    """The fastest any ball's slip angle can change [rad/s]: sum |a_m w_m| of its slip rows."""
    common_rate = 0.0  # rows of every ball (-1), then the largest of a ball's own rows
    own_rate = 0.0
    for j in range(-1, z):
        rate_sum = 0.0
        for r in range(wav.shape[0] - 1, -1, -1):
            if int(wav[r, W_SURFACE]) != SURF_SLIP:
                break
            if int(wav[r, W_BALL]) == j:
                rate_sum += abs(wav[r, W_SLIP_ANGLE] * wav[r, W_SLIP_RATE])
        if j < 0:
            common_rate = rate_sum
        else:
            own_rate = max(own_rate, rate_sum)
    return common_rate + own_rate


@numba.njit(**_JIT)
def _defect_clear_steps(wav, p, t, horizon, scratch, dt, slip_rate):
    """-1 if a contact is within reach of a local defect at ``t``, else steps none can reach.

    The steps are those of ``dt`` [s] after ``t``. Reach (:func:`_defect_near`): a contact at
    angle delta from a pit of half width w moving at rate r is within reach when
    |delta| < w + |r| ``horizon`` (a ball pit only while on its track). Otherwise its distance
    from reach, |delta| - w - r_max ``horizon``, over the fastest its angle can move, r_max:
    the nominal rate plus the largest rate of any ball's slip rows (its own and the common
    ones), sum |a_m w_m| (for a ball pit scaled as the spin is); an angle moves by at most
    r_max s in s seconds (``slip_rate``: :func:`_slip_rate_bound`, once per run). The RK4 loop
    skips the test (and the slip angles it reads) for that many steps. A ball pit off its track
    counts as on it for the bound (it turns slowly; that only makes the answer smaller).
    """
    z = int(p[P_BALL_COUNT])
    wc, ws, wb = p[P_CAGE_SPEED], p[P_SHAFT_SPEED], p[P_BALL_SPIN_SPEED]
    theta0 = p[P_CAGE_ANGLE0] + wc * t
    shaft_angle = p[P_SHAFT_ANGLE0] + ws * t
    slipping = wav.shape[0] > 0 and int(wav[wav.shape[0] - 1, W_SURFACE]) == SURF_SLIP
    pitch = 2.0 * math.pi / z
    clear = 1e9  # in steps
    for r in range(wav.shape[0]):
        surface = int(wav[r, W_SURFACE])
        if surface < SURF_OUTER_DEFECT or surface == SURF_SLIP:
            continue
        half, pos = wav[r, W_HALF_WIDTH], wav[r, W_POSITION]
        if surface == SURF_BALL_DEFECT_OUTER or surface == SURF_BALL_DEFECT_INNER:
            j = int(wav[r, W_BALL])
            chi = wb * t if surface == SURF_BALL_DEFECT_OUTER else wb * t + math.pi
            spin = wb
            fastest = abs(wb)
            if slipping:
                chi -= scratch[SLIP_LAG, j] * wb / wc
                spin -= scratch[SLIP_LAG + 1, j] * wb / wc
                fastest += slip_rate * abs(wb / wc)
            distance = abs(_wrap(chi - pos))
            on_track = _track_factor(wav, r, t)[0] != 0.0
            if on_track and distance < half + abs(spin) * horizon:
                return -1
            gap = distance - half - fastest * horizon
            if fastest > 0.0:
                clear = min(clear, gap / (fastest * dt))
            continue
        fastest = abs(wc - ws) if surface == SURF_INNER_DEFECT else abs(wc)
        fastest += slip_rate
        for j in range(z):
            theta = theta0 + j * pitch
            rate = wc
            if slipping:
                theta -= scratch[SLIP_LAG, j]
                rate -= scratch[SLIP_LAG + 1, j]
            if surface == SURF_INNER_DEFECT:
                theta -= shaft_angle
                rate -= ws
            distance = abs(_wrap(theta - pos))
            if distance < half + abs(rate) * horizon:
                return -1
            gap = distance - half - fastest * horizon
            if fastest > 0.0:
                clear = min(clear, gap / (fastest * dt))
    # a margin for rounding: one step fewer than the bound, and a thousandth off it
    return max(int(0.999 * clear) - 1, 0)


@numba.njit(**_JIT_INLINE)
def _waviness(wav, z, theta0, shaft_angle, t, p, trig, out, defects):
    """Waviness seen by ball j: ``out[:, j] = [w_o, dw_o, w_i, dw_i, wb_o, dwb_o, wb_i, dwb_i]``.

    Values in m, rates in m/s. ``trig[r + 1]`` holds cos and sin of row r's argument at time
    ``t`` (:func:`_phases`). Race harmonics are evaluated for ball 0 and rotated by k times the
    ball pitch for the others (no cos/sin per ball). ``defects`` (``DEFECTS_*``): whether the
    local defects' rows and the slip angles they use are evaluated. Where no contact can be over
    a local defect (:func:`_defect_near` said so for the step) the rows add nothing
    (:func:`_pit` writes only inside a pit) and are skipped; the slip angles are then needed
    only at the step's end, for the next step's :func:`_defect_near`.
    """
    for i in range(8):
        for j in range(z):
            out[i, j] = 0.0
    wc = p[P_CAGE_SPEED]
    ws = p[P_SHAFT_SPEED]
    wb = p[P_BALL_SPIN_SPEED]
    # slip rows come last in the table
    slipping = wav.shape[0] > 0 and int(wav[wav.shape[0] - 1, W_SURFACE]) == SURF_SLIP
    if slipping and defects != DEFECTS_NONE:
        _slip_lags(wav, trig, z, out)
    for r in range(wav.shape[0]):
        surface = int(wav[r, W_SURFACE])
        k = wav[r, W_ORDER]
        a = wav[r, W_AMPLITUDE]
        if surface == SURF_SLIP:
            break
        if surface >= SURF_OUTER_DEFECT:
            if defects == DEFECTS_ALL:
                _defect(wav, r, surface, z, theta0, shaft_angle, t, wc, ws, wb, slipping, out)
            continue
        if surface == SURF_BALL:
            j = int(wav[r, W_BALL])
            ca = a * trig[r + 1, 0]
            sa = a * k * wb * trig[r + 1, 1]
            out[4, j] += ca
            out[5, j] -= sa
            # the inner contact point is diametrically opposite: chi + pi -> factor (-1)^k
            sign = 1.0 if int(k) % 2 == 0 else -1.0
            out[6, j] += sign * ca
            out[7, j] -= sign * sa
            continue
        if surface == SURF_OUTER:
            rate = wc
            row = 0
        else:
            rate = wc - ws
            row = 2
        c, s = trig[r + 1, 0], trig[r + 1, 1]
        cd, sd = wav[r, W_STEP_COS], wav[r, W_STEP_SIN]
        for j in range(z):
            if j > 0:
                c, s = c * cd - s * sd, s * cd + c * sd
            out[row, j] += a * c
            out[row + 1, j] -= a * k * rate * s


# ------------------------------------------------------------------------ right-hand sides


@numba.njit(**_JIT)
def _scratch(z):
    """Work array of :func:`generators._rhs._rhs`: waviness per ball, time-only terms (time NaN)."""
    scratch = np.zeros((11, max(z, 4)))
    scratch[8, 0] = np.nan
    return scratch


@numba.njit(**_JIT_INLINE)
def _phase_rate(p, wav, r):
    """Rate [rad/s] of the argument of trig row r (0: the cage angle; r + 1: table row r)."""
    if r == 0:
        return p[P_CAGE_SPEED]
    surface = int(wav[r - 1, W_SURFACE])
    k = wav[r - 1, W_ORDER]
    if surface == SURF_OUTER:
        return k * p[P_CAGE_SPEED]
    if surface == SURF_INNER:
        return k * (p[P_CAGE_SPEED] - p[P_SHAFT_SPEED])
    if surface == SURF_BALL:
        return k * p[P_BALL_SPIN_SPEED]
    if surface == SURF_SLIP:
        return wav[r - 1, W_SLIP_RATE]
    return 0.0  # localized defects: no harmonic argument


@numba.njit(**_JIT)
def _trig(wav):
    """cos/sin table of the time-dependent arguments: row 0 the cage angle, r + 1 table row r."""
    return np.zeros((wav.shape[0] + 1, 2))


@numba.njit(**_JIT)
def _start_waviness(p, wav, z, out):
    """:func:`_waviness` at t = 0 into ``out`` (11, z): one call for the static start."""
    trig = _trig(wav)
    _phases(0.0, p, wav, trig)
    _waviness(wav, z, p[P_CAGE_ANGLE0], p[P_SHAFT_ANGLE0], 0.0, p, trig, out, DEFECTS_ALL)


@numba.njit(**_JIT)
def _phases(t, p, wav, trig):
    """Fill ``trig`` with cos and sin of every argument at time ``t`` [s] (exactly)."""
    theta0 = p[P_CAGE_ANGLE0] + p[P_CAGE_SPEED] * t
    shaft_angle = p[P_SHAFT_ANGLE0] + p[P_SHAFT_SPEED] * t
    trig[0, 0] = math.cos(theta0)
    trig[0, 1] = math.sin(theta0)
    for r in range(wav.shape[0]):
        surface = int(wav[r, W_SURFACE])
        k = wav[r, W_ORDER]
        ph = wav[r, W_PHASE]
        if surface == SURF_OUTER:
            arg = k * theta0 + ph
        elif surface == SURF_INNER:
            arg = k * (theta0 - shaft_angle) + ph
        elif surface == SURF_BALL:
            arg = k * p[P_BALL_SPIN_SPEED] * t + ph
        elif surface == SURF_SLIP:
            arg = wav[r, W_SLIP_RATE] * t + ph
        else:
            continue
        trig[r + 1, 0] = math.cos(arg)
        trig[r + 1, 1] = math.sin(arg)


@numba.njit(**_JIT)
def _phase_steps(p, wav, dt):
    """The cos and sin of every argument's advance over ``dt`` [s] (rows as :func:`_trig`)."""
    inc = np.empty((wav.shape[0] + 1, 2))
    for r in range(wav.shape[0] + 1):
        a = _phase_rate(p, wav, r) * dt
        inc[r, 0] = math.cos(a)
        inc[r, 1] = math.sin(a)
    return inc


@numba.njit(**_JIT_INLINE)
def _advance(trig, inc, rows):
    """Rotate the first ``rows`` (cos, sin) pairs of ``trig`` by the matching pairs of ``inc``."""
    for r in range(rows):
        c, s = trig[r, 0], trig[r, 1]
        trig[r, 0] = c * inc[r, 0] - s * inc[r, 1]
        trig[r, 1] = s * inc[r, 0] + c * inc[r, 1]


@numba.njit(**_JIT)
def _time_terms(t, p, wav, trig, scratch, defects):
    """Fill ``scratch`` with the terms of the right-hand side that depend on time only.

    ``trig`` must hold the cos/sin of the arguments at ``t`` (:func:`_phases`, or rotated to
    ``t`` by the RK4 loop). Rows 0-7: the waviness seen by each ball (:func:`_waviness`);
    row 8: the time ``t`` [s], cos and sin of the cage angle, and the shaft angle [rad]; rows
    9-10: each ball's slip angle and rate (local defects with random slip only).
    Called once per distinct stage time by the integrators (RK stages that share a time share
    them). ``defects``: which local-defect terms to evaluate (``DEFECTS_*``, :func:`_waviness`).
    Not inlined: the waviness code would otherwise sit in the right-hand side's hot loop and
    slow it down (measured: 62 ns against 33 ns per shaft-scene evaluation).
    """
    z = int(p[P_BALL_COUNT])
    theta0 = p[P_CAGE_ANGLE0] + p[P_CAGE_SPEED] * t
    if wav.shape[0] > 0:
        shaft_angle = p[P_SHAFT_ANGLE0] + p[P_SHAFT_SPEED] * t
        _waviness(wav, z, theta0, shaft_angle, t, p, trig, scratch, defects)
    _clock_terms(t, p, trig, scratch)


@numba.njit(**_JIT_INLINE)
def _clock_terms(t, p, trig, scratch):
    """Row 8 of the time terms (:func:`_time_terms`): the clock of a stage time ``t``.

    ``t``, the cage angle's cos and sin (``trig``) and the shaft angle: all a stage needs when
    the table holds only local defects (and slip), zeroed, and no contact is near one.
    """
    scratch[8, 0] = t
    scratch[8, 1] = trig[0, 0]
    scratch[8, 2] = trig[0, 1]
    scratch[8, 3] = p[P_SHAFT_ANGLE0] + p[P_SHAFT_SPEED] * t


@numba.njit(**_JIT)
def _time_terms_at(t, p, wav, trig, scratch):
    """:func:`_phases` then :func:`_time_terms`: the time terms at ``t``, computed directly."""
    _phases(t, p, wav, trig)
    _time_terms(t, p, wav, trig, scratch, DEFECTS_ALL)


# The cached machine code of every kernel module inlines functions of this one: drop it when
# any kernel source changed since it was written (generators/kernel_cache.py).
kernel_cache.guard(_hertz_dry)
