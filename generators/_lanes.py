"""Numba kernels that integrate several signals at once, one per SIMD lane (dataset generation).

The ``shaft`` and ``shaft+housing`` scenes with RK4 (:mod:`generators._kernels` for the
conventions): a block of up to ``LANES`` simulations that share the bearing (ball count), the
integration schedule and the layout of the waviness table, and differ in every value (speed,
load, clearance, waviness order, amplitude and phase, film). Every array holds the lanes in
its last, contiguous axis and every inner loop runs over the lanes, so the compiler turns the
right-hand side into vector instructions (four float64 lanes per AVX2 instruction) instead of
one signal's short ball loop with its serial chains. Two things make the loops vectorise:

* the work arrays live on the stack (:func:`_stack`), each in its own allocation: the
  compiler then knows they do not overlap (numba's heap arrays would need a run-time overlap
  check per pair of arrays, more than the vectoriser allows; swapping two of them between
  steps instead of copying loses that knowledge and was measured 18 % slower);
* the lane count is a run-time value (the arrays' shape), not a constant: a constant count
  of eight would be unrolled before the vectoriser sees the loops (numba does not run the
  straight-line SLP vectoriser).

A lane's arithmetic is the same in the vector body of a loop and in its scalar remainder, so a
signal's bytes do not depend on its position in the block or on the block's width (checked
by ``tests/tests_generators/test_lanes.py``).

Arrays (``L`` lanes): ``y0`` (2 * 4, L) initial states; ``p`` (parameter rows, L) the packed
parameter vectors; ``wav`` (rows, W_SIZE, L) the waviness tables (row layout shared: surface
and ball of each row are read from lane 0). Only waviness rows (``SURF_OUTER``,
``SURF_INNER``, ``SURF_BALL``) are allowed; local defects run on :mod:`generators._kernels`.
One output column per call: ``which`` 0 a state column (``N_OUT_STATE`` order), 1 an
acceleration (``N_OUT_ACCEL`` order), recorded at ``t_first + k * record_dt`` by the same quintic
Hermite dense output as the one-signal RK4.
Only numpy, numba, math, :mod:`generators._kernels` and :mod:`generators._integrators` are
imported here (import-linter).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from generators._integrators import _hermite_weights
from generators._kernels import (
    _JIT,
    _JIT_INLINE,
    FILM_DRY,
    FILM_EHL,
    FILM_ENTRAINED,
    FILM_NAMES,
    P_BALL_COUNT,
    P_BALL_SPIN_SPEED,
    P_CAGE_ANGLE0,
    P_CAGE_SPEED,
    P_CONTACT_DAMPING_TIME,
    P_ENTRAINED_NODES,
    P_ENTRAINED_ORIGIN,
    P_ENTRAINMENT_SERIES,
    P_FILM_INNER,
    P_FILM_INNER_MAX,
    P_FILM_INNER_REF,
    P_FILM_LOAD_FLOOR,
    P_FILM_OUTER,
    P_FILM_OUTER_MAX,
    P_FILM_OUTER_REF,
    P_GAP,
    P_GRAVITY,
    P_HOUSING_MASS,
    P_K_SERIES,
    P_LOAD_X,
    P_LOAD_Y,
    P_LOADING_STIFFNESS,
    P_LOADING_X0,
    P_LOADING_Y0,
    P_MAX_DISPLACEMENT,
    P_PEDESTAL_DAMPING,
    P_PEDESTAL_STIFFNESS,
    P_SHAFT_ANGLE0,
    P_SHAFT_DAMPING,
    P_SHAFT_MASS,
    P_SHAFT_SPEED,
    P_SIZE,
    P_SQUEEZE_SERIES,
    P_TABLE_INV_STEP_SERIES,
    P_TABLE_NODES,
    P_TABLE_STEP_SERIES,
    P_UNBALANCE,
    PHASE_ANCHOR,
    SCENE_NAMES,
    SCENE_SHAFT,
    SCENE_SHAFT_HOUSING,
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_RUNAWAY,
    SURF_BALL,
    SURF_INNER,
    SURF_OUTER,
    TABLE_SERIES,
    W_AMPLITUDE,
    W_BALL,
    W_ORDER,
    W_PHASE,
    W_STEP_COS,
    W_STEP_SIN,
    W_SURFACE,
    _entrained_film,
    _film_force,
    _hertz_ehl,
)

LANES = 32  # largest number of signals per block (more lanes, less loop overhead per signal)
MAX_BALLS = 32  # largest ball count the lane kernels take (work arrays live on the stack)
MAX_ROWS = 64  # largest number of waviness table rows

N_STATE = 8  # x_s, y_s, x_h, y_h, vx_s, vy_s, vx_h, vy_h (both scenes)

# per-lane constants read once per block (rows of ``c`` in the implementation)
(
    C_GAP,
    C_TAU,
    C_TAU15,
    C_K,
    C_WC,
    C_WS,
    C_WB,
    C_FLOOR,
    C_FILM,
    C_SQUEEZE,
    C_REF,
    C_MAX,
    C_INV_MS,
    C_INV_MH,
    C_CS,
    C_KH,
    C_CH,
    C_G,
    C_FX,
    C_FY,
    C_KL,
    C_X0,
    C_Y0,
    C_UNB,
    C_LIMIT,
    C_TABLE_STEP,
    C_TABLE_INV_STEP,
    C_ORIGIN,
    C_ENTRAINMENT,
    C_SIZE,
) = range(30)

# sizes of the stack work arrays, in float64 per lane
_SIZE_KS = 5 * N_STATE * LANES
_SIZE_STATE = N_STATE * LANES
_SIZE_FORCES = 6 * LANES
_SIZE_ROTATION = 3 * LANES
_SIZE_CONSTANTS = C_SIZE * LANES
_SIZE_TIME_TERMS = (2 * MAX_BALLS + 4) * LANES
_SIZE_PITCH = 2 * MAX_BALLS
_SIZE_TRIG = (MAX_ROWS + 2) * 2 * LANES


@intrinsic
def _stack(typingctx, size):
    """Pointer to ``size`` (a literal int) float64 on the stack of the calling function.

    The lane loops only vectorise when the compiler can prove that the arrays they read and
    write do not overlap: distinct stack allocations never do (heap arrays from numba's
    allocator would need a run-time overlap check per pair, too many for the vectoriser).
    """
    if not isinstance(size, types.IntegerLiteral):
        return None
    count = size.literal_value

    def codegen(context, builder, signature, args):
        return cgutils.alloca_once(builder, context.get_data_type(types.float64), size=count)

    return types.CPointer(types.float64)(size), codegen


@numba.njit(**_JIT_INLINE)
def _constants(p, c, nl):
    """Per-lane constants of the right-hand side (rows ``C_*`` of ``c``)."""
    for b in range(nl):
        c[C_GAP, b] = p[P_GAP, b]
        c[C_TAU, b] = p[P_CONTACT_DAMPING_TIME, b]
        c[C_TAU15, b] = 1.5 * p[P_CONTACT_DAMPING_TIME, b]  # the dry law's factor
        c[C_K, b] = p[P_K_SERIES, b]
        c[C_WC, b] = p[P_CAGE_SPEED, b]
        c[C_WS, b] = p[P_SHAFT_SPEED, b]
        c[C_WB, b] = p[P_BALL_SPIN_SPEED, b]
        c[C_FLOOR, b] = p[P_FILM_LOAD_FLOOR, b]
        c[C_FILM, b] = p[P_FILM_INNER, b] + p[P_FILM_OUTER, b]
        c[C_SQUEEZE, b] = p[P_SQUEEZE_SERIES, b]
        c[C_REF, b] = p[P_FILM_INNER_REF, b] + p[P_FILM_OUTER_REF, b]
        c[C_MAX, b] = p[P_FILM_INNER_MAX, b] + p[P_FILM_OUTER_MAX, b]
        c[C_INV_MS, b] = 1.0 / p[P_SHAFT_MASS, b]
        c[C_INV_MH, b] = 1.0 / p[P_HOUSING_MASS, b]
        c[C_CS, b] = p[P_SHAFT_DAMPING, b]
        c[C_KH, b] = p[P_PEDESTAL_STIFFNESS, b]
        c[C_CH, b] = p[P_PEDESTAL_DAMPING, b]
        c[C_G, b] = p[P_GRAVITY, b]
        c[C_FX, b] = p[P_LOAD_X, b]
        c[C_FY, b] = p[P_LOAD_Y, b]
        c[C_KL, b] = p[P_LOADING_STIFFNESS, b]
        c[C_X0, b] = p[P_LOADING_X0, b]
        c[C_Y0, b] = p[P_LOADING_Y0, b]
        c[C_UNB, b] = p[P_UNBALANCE, b]
        c[C_LIMIT, b] = p[P_MAX_DISPLACEMENT, b]
        c[C_TABLE_STEP, b] = p[P_TABLE_STEP_SERIES, b]
        c[C_TABLE_INV_STEP, b] = p[P_TABLE_INV_STEP_SERIES, b]
        c[C_ORIGIN, b] = p[P_ENTRAINED_ORIGIN, b]  # the entrained table (its step: the series')
        c[C_ENTRAINMENT, b] = p[P_ENTRAINMENT_SERIES, b]


@numba.njit(**_JIT_INLINE)
def _rate(p, wav, r, b):
    """Rate [rad/s] of the argument of trig row r (as :func:`_phases`) in lane b."""
    rows = wav.shape[0]
    if r == 0:
        return p[P_CAGE_SPEED, b]
    if r == rows + 1:
        return p[P_SHAFT_SPEED, b]
    surface = int(wav[r - 1, W_SURFACE, 0])
    k = wav[r - 1, W_ORDER, b]
    if surface == SURF_OUTER:
        return k * p[P_CAGE_SPEED, b]
    if surface == SURF_INNER:
        return k * (p[P_CAGE_SPEED, b] - p[P_SHAFT_SPEED, b])
    return k * p[P_BALL_SPIN_SPEED, b]


@numba.njit(**_JIT_INLINE)
def _phases(t, p, wav, trig, nl):
    """``trig[r, 0/1, b]``: cos/sin of every argument at ``t`` [s], exactly.

    Row 0 the cage angle, r + 1 table row r, ``rows + 1`` the shaft angle.
    """
    rows = wav.shape[0]
    for b in range(nl):
        theta0 = p[P_CAGE_ANGLE0, b] + p[P_CAGE_SPEED, b] * t
        shaft_angle = p[P_SHAFT_ANGLE0, b] + p[P_SHAFT_SPEED, b] * t
        trig[0, 0, b] = math.cos(theta0)
        trig[0, 1, b] = math.sin(theta0)
        trig[rows + 1, 0, b] = math.cos(shaft_angle)
        trig[rows + 1, 1, b] = math.sin(shaft_angle)
        for r in range(rows):
            surface = int(wav[r, W_SURFACE, 0])
            k = wav[r, W_ORDER, b]
            ph = wav[r, W_PHASE, b]
            if surface == SURF_OUTER:
                arg = k * theta0 + ph
            elif surface == SURF_INNER:
                arg = k * (theta0 - shaft_angle) + ph
            else:
                arg = k * p[P_BALL_SPIN_SPEED, b] * t + ph
            trig[r + 1, 0, b] = math.cos(arg)
            trig[r + 1, 1, b] = math.sin(arg)


@numba.njit(**_JIT_INLINE)
def _advance(trig, inc, rows, nl):
    """Rotate the (cos, sin) pairs of ``trig`` (``rows + 2`` rows) by those of ``inc``."""
    for r in range(rows + 2):
        for b in range(nl):
            c = trig[r, 0, b]
            s = trig[r, 1, b]
            trig[r, 0, b] = c * inc[r, 0, b] - s * inc[r, 1, b]
            trig[r, 1, b] = s * inc[r, 0, b] + c * inc[r, 1, b]


@numba.njit(**_JIT_INLINE)
def _time_terms(c, wav, trig, z, tt, rot, nl):
    """Time-only terms of the right-hand side at the time ``trig`` holds.

    ``tt[j]``: the waviness seen by ball j (sum over the surfaces: the series contact of the
    massless ball) minus the diametral gap over two [m]; ``tt[z + j]``: its rate [m/s];
    ``tt[2z]``, ``tt[2z + 1]``: cos/sin of the shaft angle; ``tt[2z + 2]``, ``tt[2z + 3]``:
    cos/sin of the cage angle (ball 0's). ``rot`` is a (3, lanes) work array.
    """
    rows = wav.shape[0]
    for b in range(nl):
        tt[2 * z, b] = trig[rows + 1, 0, b]
        tt[2 * z + 1, b] = trig[rows + 1, 1, b]
        tt[2 * z + 2, b] = trig[0, 0, b]
        tt[2 * z + 3, b] = trig[0, 1, b]
    for j in range(z):
        for b in range(nl):
            tt[j, b] = -c[C_GAP, b]
            tt[z + j, b] = 0.0
    for r in range(rows):
        surface = int(wav[r, W_SURFACE, 0])
        if surface == SURF_BALL:
            j = int(wav[r, W_BALL, 0])
            for b in range(nl):
                k = wav[r, W_ORDER, b]
                a = wav[r, W_AMPLITUDE, b]
                ca = a * trig[r + 1, 0, b]
                sa = a * k * c[C_WB, b] * trig[r + 1, 1, b]
                # outer contact, and the inner one diametrically opposite: (-1)^k
                sign = 1.0 if int(k) % 2 == 0 else -1.0
                tt[j, b] += ca + sign * ca
                tt[z + j, b] -= sa + sign * sa
            continue
        # race harmonic: ball j sees it rotated by k times the ball pitch from ball j - 1
        outer = surface == SURF_OUTER
        for b in range(nl):
            rate = c[C_WC, b] if outer else c[C_WC, b] - c[C_WS, b]
            rot[0, b] = trig[r + 1, 0, b]
            rot[1, b] = trig[r + 1, 1, b]
            rot[2, b] = wav[r, W_AMPLITUDE, b] * wav[r, W_ORDER, b] * rate
        j0 = 0
        while j0 + 3 <= z:
            for b in range(nl):
                _race_balls(tt, wav, rot, r, z, j0, 3, b)
            j0 += 3
        for j in range(j0, z):
            for b in range(nl):
                _race_balls(tt, wav, rot, r, z, j, 1, b)


@numba.njit(**_JIT_INLINE)
def _race_balls(tt, wav, rot, r, z, j0, count, b):
    """Add race harmonic r to balls j0 .. j0 + count - 1 of lane b (``count`` a constant).

    ``rot[0:2, b]`` holds cos/sin of the harmonic's phase at ball j0 and is left at the next
    ball's; ``rot[2, b]`` the amplitude times the phase rate.
    """
    a = wav[r, W_AMPLITUDE, b]
    cd = wav[r, W_STEP_COS, b]
    sd = wav[r, W_STEP_SIN, b]
    cw = rot[0, b]
    sw = rot[1, b]
    for u in range(count):
        tt[j0 + u, b] += a * cw
        tt[z + j0 + u, b] -= rot[2, b] * sw
        cn = cw * cd - sw * sd
        sw = sw * cd + cw * sd
        cw = cn
    rot[0, b] = cw
    rot[1, b] = sw


@numba.njit(**_JIT_INLINE)
def _series_film(delta, delta_rate, c, b, tab, nodes):
    """The series contact's film law of lane b, the table read from ``tab[b]``.

    The same arithmetic as :func:`generators._kernels._hertz_ehl_table` (the same bytes), but
    the lane's table is one contiguous row (an evaluation's eight values lie side by side,
    where in ``p``, rows of parameters with lanes across, they lie rows apart). The early
    return for an unloaded contact stays: without it (the table read at s = 0 gives exactly
    zero) the loop runs the same instructions in every lane but is slower (docs/performance.md,
    stop 37).
    """
    x = delta + c[C_MAX, b]
    if x <= 0.0:
        return 0.0
    x = math.sqrt(x) * c[C_TABLE_INV_STEP, b]
    i = int(x)
    if i >= nodes - 1:
        return _hertz_ehl(
            delta,
            delta_rate,
            c[C_K, b],
            c[C_TAU, b],
            c[C_FILM, b],
            c[C_SQUEEZE, b],
            c[C_FLOOR, b],
            c[C_REF, b],
            c[C_MAX, b],
        )
    base = 4 * i
    q = _film_force(
        x - i,
        c[C_TABLE_STEP, b],
        delta_rate,
        tab[b, base],
        tab[b, base + 1],
        tab[b, base + 2],
        tab[b, base + 3],
        tab[b, base + 4],
        tab[b, base + 5],
        tab[b, base + 6],
        tab[b, base + 7],
    )
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT_INLINE)
def _series_entrained(delta, delta_rate, c, b, tab, nodes):
    """The series contact's entrained film law of lane b, the table read from ``tab[b]``.

    The same arithmetic as :func:`generators._kernels._entrained_table` (the same bytes), the
    lane's table one contiguous row as in :func:`_series_film`.
    """
    x = delta + c[C_MAX, b]
    s = math.sqrt(x) if x >= 0.0 else -math.sqrt(-x)
    u = s * c[C_TABLE_INV_STEP, b] + c[C_ORIGIN, b]
    if not (0.0 <= u < nodes - 1):
        return _entrained_film(
            delta,
            delta_rate,
            c[C_K, b],
            c[C_TAU, b],
            c[C_FILM, b],
            c[C_SQUEEZE, b],
            c[C_FLOOR, b],
            c[C_ENTRAINMENT, b],
        )
    i = int(u)
    base = 4 * i
    q = _film_force(
        u - i,
        c[C_TABLE_STEP, b],
        delta_rate,
        tab[b, base],
        tab[b, base + 1],
        tab[b, base + 2],
        tab[b, base + 3],
        tab[b, base + 4],
        tab[b, base + 5],
        tab[b, base + 6],
        tab[b, base + 7],
    )
    return q if q > 0.0 else 0.0


@numba.njit(**_JIT_INLINE)
def _contact(ehl, j, b, f, tt, c, tab, nodes, z, pc, ps):
    """Contact force of ball j in lane b [N].

    ``f[2:6, b]`` the displacement and its rate in the cage frame (:func:`_kinematics`),
    ``pc``, ``ps`` the cosine and sine of ball j's angle in that frame (j times the pitch).
    """
    d = f[2, b] * pc + f[3, b] * ps + tt[j, b]
    dd = f[4, b] * pc + f[5, b] * ps + tt[z + j, b]
    if ehl == FILM_ENTRAINED:
        q = _series_entrained(d, dd, c, b, tab, nodes)
    elif ehl:
        q = _series_film(d, dd, c, b, tab, nodes)
    else:
        # dry Hertz contact without a branch (docs/model.md 1.2): K d^1.5 + 1.5 tau K
        # d^0.5 d', zero when d <= 0 and clipped at zero (no tension)
        dp = d if d > 0.0 else 0.0
        q = c[C_K, b] * math.sqrt(dp) * (dp + c[C_TAU15, b] * dd)
        q = q if q > 0.0 else 0.0
    return q


@numba.njit(**_JIT_INLINE)
def _kinematics(scene, c, f, tt, z, b, s0, s1, s2, s3, s4, s5, s6, s7):
    """Contact kinematics of lane b in ``f[0:6, b]`` from its state ``s0..s7``.

    Force sums zeroed, then the shaft-to-housing displacement u and the rate of u . e_j
    without the e_j terms (massless balls), both turned into the cage frame (ball 0 on its
    x axis): u . e_j = u_c . (cos j pitch, sin j pitch), the same pitch terms in every lane.
    """
    wc = c[C_WC, b]
    rx = s0
    ry = s1
    vx = s4
    vy = s5
    if scene == SCENE_SHAFT_HOUSING:
        rx -= s2
        ry -= s3
        vx -= s6
        vy -= s7
    # d/dt (u . e_j) = (v + wc ez x u) . e_j
    ux = vx + wc * ry
    uy = vy - wc * rx
    cc = tt[2 * z + 2, b]
    sc = tt[2 * z + 3, b]
    f[0, b] = 0.0
    f[1, b] = 0.0
    f[2, b] = rx * cc + ry * sc
    f[3, b] = ry * cc - rx * sc
    f[4, b] = ux * cc + uy * sc
    f[5, b] = uy * cc - ux * sc


@numba.njit(**_JIT_INLINE)
def _rhs(scene, ehl, y, c, tab, nodes, tt, z, pitch, f, dydt, nl):
    """Right-hand side of every lane: ``dydt`` from the states ``y`` (both (8, lanes)).

    ``tt`` the time terms (:func:`_time_terms`), ``pitch`` (2, z) cos/sin of j times the ball
    pitch, ``f`` a (6, lanes) work array, ``tab`` (lanes, 4 ``nodes``) each lane's series film
    table (EHL scenes, :func:`_series_film`). The balls are
    massless, so the housing carries the opposite of the shaft's contact force and each
    contact sees the shaft-to-housing displacement u: approach d = u . e_j + waviness - gap/2,
    its rate from the velocity relative to the rotating ball direction e_j.
    """
    for b in range(nl):
        _kinematics(
            scene,
            c,
            f,
            tt,
            z,
            b,
            y[0, b],
            y[1, b],
            y[2, b],
            y[3, b],
            y[4, b],
            y[5, b],
            y[6, b],
            y[7, b],
        )
    _forces(ehl, y, c, tab, nodes, tt, z, pitch, f, dydt, nl)


@numba.njit(**_JIT_INLINE)
def _stage_rhs(scene, ehl, stage, h, dt, y, ks, tmp, c, tab, nodes, tt, z, pitch, f, nl):
    """One RK4 stage: ``tmp`` the stage's state, ``ks[stage + 1]`` the right-hand side there.

    The state update runs in the same lane loop as the contact kinematics.
    """
    if stage < 3:
        for b in range(nl):
            s = _stage_state(y, ks, stage, h, b)
            _store_state(tmp, b, s)
            _kinematics(scene, c, f, tt, z, b, s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7])
    else:
        w = dt / 6.0
        for b in range(nl):
            s = _rk4_sum(y, ks, w, b)
            _store_state(tmp, b, s)
            _kinematics(scene, c, f, tt, z, b, s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7])
    _forces(ehl, tmp, c, tab, nodes, tt, z, pitch, f, ks[stage + 1], nl)


@numba.njit(**_JIT_INLINE)
def _stage_state(y, ks, stage, h, b):
    """The state of stage ``stage`` < 3 in lane b: y + h k_stage."""
    return (
        y[0, b] + h * ks[stage, 0, b],
        y[1, b] + h * ks[stage, 1, b],
        y[2, b] + h * ks[stage, 2, b],
        y[3, b] + h * ks[stage, 3, b],
        y[4, b] + h * ks[stage, 4, b],
        y[5, b] + h * ks[stage, 5, b],
        y[6, b] + h * ks[stage, 6, b],
        y[7, b] + h * ks[stage, 7, b],
    )


@numba.njit(**_JIT_INLINE)
def _store_state(state, b, s):
    """Write the 8-tuple ``s`` into lane b of ``state`` (8, lanes)."""
    state[0, b] = s[0]
    state[1, b] = s[1]
    state[2, b] = s[2]
    state[3, b] = s[3]
    state[4, b] = s[4]
    state[5, b] = s[5]
    state[6, b] = s[6]
    state[7, b] = s[7]


@numba.njit(**_JIT_INLINE)
def _rk4_sum(y, ks, w, b):
    """The state at the step's end in lane b: y + w (k0 + 2 k1 + 2 k2 + k3), w = dt / 6."""
    return (
        y[0, b] + w * (ks[0, 0, b] + 2.0 * ks[1, 0, b] + 2.0 * ks[2, 0, b] + ks[3, 0, b]),
        y[1, b] + w * (ks[0, 1, b] + 2.0 * ks[1, 1, b] + 2.0 * ks[2, 1, b] + ks[3, 1, b]),
        y[2, b] + w * (ks[0, 2, b] + 2.0 * ks[1, 2, b] + 2.0 * ks[2, 2, b] + ks[3, 2, b]),
        y[3, b] + w * (ks[0, 3, b] + 2.0 * ks[1, 3, b] + 2.0 * ks[2, 3, b] + ks[3, 3, b]),
        y[4, b] + w * (ks[0, 4, b] + 2.0 * ks[1, 4, b] + 2.0 * ks[2, 4, b] + ks[3, 4, b]),
        y[5, b] + w * (ks[0, 5, b] + 2.0 * ks[1, 5, b] + 2.0 * ks[2, 5, b] + ks[3, 5, b]),
        y[6, b] + w * (ks[0, 6, b] + 2.0 * ks[1, 6, b] + 2.0 * ks[2, 6, b] + ks[3, 6, b]),
        y[7, b] + w * (ks[0, 7, b] + 2.0 * ks[1, 7, b] + 2.0 * ks[2, 7, b] + ks[3, 7, b]),
    )


@numba.njit(**_JIT_INLINE)
def _forces(ehl, y, c, tab, nodes, tt, z, pitch, f, dydt, nl):
    """Contact force sums from the kinematics in ``f``, then ``dydt`` from the states ``y``."""
    # the sums in the cage frame, three balls per lane loop (they stay in registers)
    j0 = 0
    while j0 + 3 <= z:
        for b in range(nl):
            fa = f[0, b]
            fb = f[1, b]
            for u in range(3):
                q = _contact(
                    ehl, j0 + u, b, f, tt, c, tab, nodes, z, pitch[0, j0 + u], pitch[1, j0 + u]
                )
                fa += q * pitch[0, j0 + u]
                fb += q * pitch[1, j0 + u]
            f[0, b] = fa
            f[1, b] = fb
        j0 += 3
    for j in range(j0, z):
        for b in range(nl):
            q = _contact(ehl, j, b, f, tt, c, tab, nodes, z, pitch[0, j], pitch[1, j])
            f[0, b] += q * pitch[0, j]
            f[1, b] += q * pitch[1, j]
    for b in range(nl):
        # back to the fixed frame: the contact force on the shaft is minus the sum
        cc = tt[2 * z + 2, b]
        sc = tt[2 * z + 3, b]
        fx = sc * f[1, b] - cc * f[0, b]
        fy = -(sc * f[0, b] + cc * f[1, b])
        kl = c[C_KL, b]
        unbalance = c[C_UNB, b] * c[C_WS, b] * c[C_WS, b]
        fxs = fx + c[C_FX, b] - kl * (y[0, b] - c[C_X0, b]) + unbalance * tt[2 * z, b]
        fys = fy + c[C_FY, b] - kl * (y[1, b] - c[C_Y0, b]) + unbalance * tt[2 * z + 1, b]
        g = c[C_G, b]
        dydt[0, b] = y[4, b]
        dydt[1, b] = y[5, b]
        dydt[2, b] = y[6, b]
        dydt[3, b] = y[7, b]
        dydt[4, b] = (fxs - c[C_CS, b] * y[4, b]) * c[C_INV_MS, b]
        dydt[5, b] = (fys - c[C_CS, b] * y[5, b]) * c[C_INV_MS, b] - g
        kh = c[C_KH, b]
        ch = c[C_CH, b]
        dydt[6, b] = (-fx - ch * y[6, b] - kh * y[2, b]) * c[C_INV_MH, b]
        dydt[7, b] = (-fy - ch * y[7, b] - kh * y[3, b]) * c[C_INV_MH, b] - g


@numba.njit(**_JIT_INLINE)
def _check(y, c, status, t_status, t, nl):
    """Mark lanes whose state is non-finite or ran away (first failure and its time kept)."""
    for b in range(nl):
        if status[b] != STATUS_OK:
            continue
        bad = STATUS_OK
        for i in range(N_STATE):
            if not math.isfinite(y[i, b]):
                bad = STATUS_NONFINITE
        if bad == STATUS_OK:
            for i in range(4):
                if abs(y[i, b]) > c[C_LIMIT, b]:
                    bad = STATUS_RUNAWAY
        if bad != STATUS_OK:
            status[b] = bad
            t_status[b] = t


@numba.njit(**_JIT)
def _rk4_impl(
    scene,
    ehl,
    y0,
    p,
    wav,
    t0,
    dt,
    n_steps,
    t_first,
    record_dt,
    n_record,
    which,
    column,
    out,
    status,
    t_status,
):
    """Classical RK4 (fixed step) of ``y0.shape[1]`` lanes with quintic Hermite dense output.

    The same schedule, stage order, phase rotation (exact every ``PHASE_ANCHOR`` steps) and
    dense output as the one-signal ``generators._integrators._rk4_impl``. Writes ``out[b, k]``
    (lane b, record k < n_record) and, per lane, ``status`` and the time of the first failure
    ``t_status``.
    The lane count is read from the arrays (at most ``LANES``), not a compile-time constant:
    a constant eight would be unrolled before the loop vectoriser sees the loops.
    """
    numba.literally(scene)
    numba.literally(ehl)
    nl = y0.shape[1]
    z = int(p[P_BALL_COUNT, 0])
    rows = wav.shape[0]
    c = numba.carray(_stack(_SIZE_CONSTANTS), (C_SIZE, nl))
    y = numba.carray(_stack(_SIZE_STATE), (N_STATE, nl))
    tmp = numba.carray(_stack(_SIZE_STATE), (N_STATE, nl))
    ks = numba.carray(_stack(_SIZE_KS), (5, N_STATE, nl))
    f = numba.carray(_stack(_SIZE_FORCES), (6, nl))
    rot = numba.carray(_stack(_SIZE_ROTATION), (3, nl))
    tt = numba.carray(_stack(_SIZE_TIME_TERMS), (2 * z + 4, nl))
    pitch = numba.carray(_stack(_SIZE_PITCH), (2, z))
    trig = numba.carray(_stack(_SIZE_TRIG), (MAX_ROWS + 2, 2, nl))
    inc = numba.carray(_stack(_SIZE_TRIG), (MAX_ROWS + 2, 2, nl))
    _constants(p, c, nl)
    nodes = 0
    if ehl == FILM_ENTRAINED:  # the fourth table (generators._kernels)
        nodes = int(p[P_ENTRAINED_NODES, 0])
        tab = np.empty((nl, 4 * nodes))
        first = P_SIZE + 12 * int(p[P_TABLE_NODES, 0])
        for b in range(nl):
            for k in range(4 * nodes):
                tab[b, k] = p[first + k, b]
    elif ehl:
        nodes = int(p[P_TABLE_NODES, 0])
        tab = np.empty((nl, 4 * nodes))
        first = P_SIZE + 4 * TABLE_SERIES * nodes
        for b in range(nl):
            for k in range(4 * nodes):
                tab[b, k] = p[first + k, b]
    else:
        tab = np.empty((1, 1))
    for j in range(z):
        pitch[0, j] = math.cos(2.0 * math.pi * j / z)
        pitch[1, j] = math.sin(2.0 * math.pi * j / z)
    half = 0.5 * dt
    for r in range(rows + 2):
        for b in range(nl):
            a = _rate(p, wav, r, b) * half
            inc[r, 0, b] = math.cos(a)
            inc[r, 1, b] = math.sin(a)
    for i in range(N_STATE):
        for b in range(nl):
            y[i, b] = y0[i, b]
    for b in range(nl):
        status[b] = STATUS_OK
        t_status[b] = math.nan
    k1 = ks[0]
    f1 = ks[4]
    _phases(t0, p, wav, trig, nl)
    _time_terms(c, wav, trig, z, tt, rot, nl)
    _rhs(scene, ehl, y, c, tab, nodes, tt, z, pitch, f, k1, nl)
    # the recorded coordinate j (x_s, y_s, x_h, y_h) and its derivative order: position,
    # velocity or acceleration of the one quintic interpolant (_hermite_weights)
    j = column % 4
    order = 2 if which != 0 else (0 if column < 4 else 1)
    next_rec = 0
    t = t0
    for step in range(n_steps):
        t = t0 + step * dt
        if step % PHASE_ANCHOR == 0:
            _phases(t, p, wav, trig, nl)
        for stage in range(4):
            if stage == 0 or stage == 2:
                _advance(trig, inc, rows, nl)
                _time_terms(c, wav, trig, z, tt, rot, nl)
            h = half if stage < 2 else dt
            _stage_rhs(scene, ehl, stage, h, dt, y, ks, tmp, c, tab, nodes, tt, z, pitch, f, nl)
        y1 = tmp  # the step's end state (not written again before the next step's stage 0)
        while next_rec < n_record:
            theta = (t_first + next_rec * record_dt - t) / dt
            if theta >= 1.0 - 1e-9:
                break
            if theta < 0.0:
                theta = 0.0
            w0, w1, w2, w3, w4, w5 = _hermite_weights(theta, dt, order)
            for b in range(nl):
                out[b, next_rec] = (
                    w0 * y[j, b]
                    + w1 * y[4 + j, b]
                    + w2 * k1[4 + j, b]
                    + w3 * y1[j, b]
                    + w4 * y1[4 + j, b]
                    + w5 * f1[4 + j, b]
                )
            next_rec += 1
        for i in range(N_STATE):
            for b in range(nl):
                y[i, b] = y1[i, b]
                k1[i, b] = f1[i, b]
        if step % 64 == 0 or next_rec >= n_record:
            _check(y, c, status, t_status, t + dt, nl)
        if next_rec >= n_record:
            return t + dt
    _check(y, c, status, t_status, t0 + n_steps * dt, nl)
    return t0 + n_steps * dt


# One entry point per (scene, film) pair, as in generators._integrators: the pair reaches the
# implementation as literal types (each pair compiled and cached on its own, under its name).


def _rk4_entry(scene: int, ehl: int):
    """The lanes' RK4 entry point of one (scene, film) pair (arguments: :func:`_rk4_impl`)."""

    def entry(
        y0,
        p,
        wav,
        t0,
        dt,
        n_steps,
        t_first,
        record_dt,
        n_record,
        which,
        column,
        out,
        status,
        t_status,
    ):
        return _rk4_impl(
            scene,
            ehl,
            y0,
            p,
            wav,
            t0,
            dt,
            n_steps,
            t_first,
            record_dt,
            n_record,
            which,
            column,
            out,
            status,
            t_status,
        )

    entry.__name__ = entry.__qualname__ = f"_rk4_lanes_{SCENE_NAMES[scene]}_{FILM_NAMES[ehl]}"
    return numba.njit(**_JIT)(entry)


#: The scenes the lanes integrate (massless balls).
LANE_SCENES = (SCENE_SHAFT, SCENE_SHAFT_HOUSING)
#: The film modes the lanes run (each one's law as the one-signal kernels', the same bytes).
LANE_FILMS = (FILM_DRY, FILM_EHL, FILM_ENTRAINED)
#: The (scene, film) pairs compiled: the film's entrainment in ``shaft+housing`` only, the
#: scene of the recipes (a lane kernel takes 30-80 s of compilation from an empty cache;
#: ``shaft`` with the entrainment runs one signal at a time).
LANE_PAIRS = tuple(
    (scene, film)
    for scene in LANE_SCENES
    for film in LANE_FILMS
    if film != FILM_ENTRAINED or scene == SCENE_SHAFT_HOUSING
)
RK4 = {(scene, film): _rk4_entry(scene, film) for scene, film in LANE_PAIRS}
