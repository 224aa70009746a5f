"""The model's right-hand side, and the record and divergence check of the integrators.

:func:`_rhs_inline` evaluates the equations of motion of every scene (docs/model.md 1.3-1.5)
from the state, the parameter vector and the time terms of :mod:`generators._kernels` (whose
conventions it follows: ``p`` indexed by ``P_*``, the state displacements first, then
velocities); :func:`_rhs` is the same as one compiled call per scene; :func:`_record` writes a
record's columns and :func:`_check` a state's status. Moved out of :mod:`generators._kernels`
unchanged in stop 56 (the same arithmetic, the same bytes); the integrators
(:mod:`generators._integrators`) inline them. Only numba and math are imported here
(checked by import-linter); the kernel cache's guard covers this file
(:mod:`generators.kernel_cache`).
"""

from __future__ import annotations

import math

import numba

from generators._kernels import (
    _JIT,
    _JIT_INLINE,
    FILM_ENTRAINED,
    P_BALL_COUNT,
    P_BALL_MASS,
    P_CAGE_SPEED,
    P_CONTACT_DAMPING_TIME,
    P_ENTRAINMENT_SERIES,
    P_FILM_INNER,
    P_FILM_INNER_MAX,
    P_FILM_INNER_REF,
    P_FILM_LOAD_FLOOR,
    P_FILM_OUTER,
    P_FILM_OUTER_MAX,
    P_FILM_OUTER_REF,
    P_GAP,
    P_GAP_FLOOR_INNER,
    P_GAP_FLOOR_OUTER,
    P_GRAVITY,
    P_HOUSING_MASS,
    P_K_INNER,
    P_K_OUTER,
    P_K_SERIES,
    P_LOAD_X,
    P_LOAD_Y,
    P_LOADING_STIFFNESS,
    P_LOADING_X0,
    P_LOADING_Y0,
    P_PEDESTAL_DAMPING,
    P_PEDESTAL_STIFFNESS,
    P_PITCH_COS,
    P_PITCH_RADIUS,
    P_PITCH_SIN,
    P_SHAFT_DAMPING,
    P_SHAFT_MASS,
    P_SHAFT_SPEED,
    P_SQUEEZE_INNER,
    P_SQUEEZE_OUTER,
    P_SQUEEZE_SERIES,
    P_UNBALANCE,
    SCENE_FULL,
    SCENE_SHAFT_HOUSING,
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_RUNAWAY,
    TABLE_INNER,
    TABLE_OUTER,
    TABLE_SERIES,
    _entrained_table,
    _gap_squeeze,
    _hertz_dry,
    _hertz_ehl_table,
)


@numba.njit(**_JIT_INLINE)
def _rhs_inline(scene, ehl, y, p, wav, dydt, loads, scratch):
    """First-order right-hand side dy/dt of a scene; fills ``loads[0/1, j]`` (inner/outer).

    ``scratch`` (shape (11, max(Z, 4)), from :func:`_scratch`) must hold the time terms of the
    evaluation time (:func:`_time_terms`): the waviness seen by each ball (rows 0-7) and, in
    row 8, the time, the cage-angle cosine/sine and the shaft angle.
    """
    z = int(p[P_BALL_COUNT])
    nd = 4 + z if scene == SCENE_FULL else 4
    xs, ys, xh, yh = y[0], y[1], y[2], y[3]
    vxs, vys, vxh, vyh = y[nd], y[nd + 1], y[nd + 2], y[nd + 3]
    wc = p[P_CAGE_SPEED]
    has_waviness = wav.shape[0] > 0
    c0, s0 = scratch[8, 1], scratch[8, 2]
    shaft_angle = scratch[8, 3]
    cd, sd = p[P_PITCH_COS], p[P_PITCH_SIN]
    gap = p[P_GAP]
    tau = p[P_CONTACT_DAMPING_TIME]
    floor = p[P_FILM_LOAD_FLOOR]
    # parameters read once: the compiler cannot hoist them out of the ball loop itself (the
    # loop's stores to dydt and loads might alias p)
    k_inner, k_outer, k_series = p[P_K_INNER], p[P_K_OUTER], p[P_K_SERIES]
    film_inner, film_outer = p[P_FILM_INNER], p[P_FILM_OUTER]
    squeeze_inner, squeeze_outer = p[P_SQUEEZE_INNER], p[P_SQUEEZE_OUTER]
    ref_inner, ref_outer = p[P_FILM_INNER_REF], p[P_FILM_OUTER_REF]
    max_inner, max_outer = p[P_FILM_INNER_MAX], p[P_FILM_OUTER_MAX]
    squeeze_series = p[P_SQUEEZE_SERIES]
    entrainment = p[P_ENTRAINMENT_SERIES] if ehl == FILM_ENTRAINED else 0.0
    inv_ball_mass = 1.0 / p[P_BALL_MASS] if scene == SCENE_FULL else 0.0
    floor_inner, floor_outer = p[P_GAP_FLOOR_INNER], p[P_GAP_FLOOR_OUTER]
    centripetal = wc * wc
    pitch_radius = p[P_PITCH_RADIUS]
    gravity = p[P_GRAVITY]
    fxs = 0.0
    fys = 0.0
    fxh = 0.0
    fyh = 0.0
    ux, uy, vx, vy = xs, ys, vxs, vys  # massless balls: the shaft-to-housing displacement
    if scene == SCENE_SHAFT_HOUSING:
        ux, uy, vx, vy = xs - xh, ys - yh, vxs - vxh, vys - vyh
    cj, sj = c0, s0
    for j in range(z):
        if j > 0:  # rotate by the ball pitch instead of calling cos/sin per ball
            cj, sj = cj * cd - sj * sd, sj * cd + cj * sd
        us = ux * cj + uy * sj
        dus = vx * cj + vy * sj + wc * (-ux * sj + uy * cj)
        if scene == SCENE_FULL:
            uh = xh * cj + yh * sj
            duh = vxh * cj + vyh * sj + wc * (-xh * sj + yh * cj)
            rho = y[4 + j]
            drho = y[nd + 4 + j]
            di = us - rho - 0.5 * gap
            ddi = dus - drho
            do = rho - uh - 0.5 * gap
            ddo = drho - duh
            if has_waviness:
                di += scratch[2, j] + scratch[6, j]
                ddi += scratch[3, j] + scratch[7, j]
                do += scratch[0, j] + scratch[4, j]
                ddo += scratch[1, j] + scratch[5, j]
            if ehl:
                qi = _hertz_ehl_table(
                    di,
                    ddi,
                    k_inner,
                    tau,
                    film_inner,
                    squeeze_inner,
                    floor,
                    ref_inner,
                    max_inner,
                    p,
                    TABLE_INNER,
                )
                qo = _hertz_ehl_table(
                    do,
                    ddo,
                    k_outer,
                    tau,
                    film_outer,
                    squeeze_outer,
                    floor,
                    ref_outer,
                    max_outer,
                    p,
                    TABLE_OUTER,
                )
                if qi == 0.0:  # apart: the film between ball and race (docs/model.md 4.4)
                    qi = _gap_squeeze(di, ddi, film_inner, squeeze_inner, max_inner, floor_inner)
                if qo == 0.0:
                    qo = _gap_squeeze(do, ddo, film_outer, squeeze_outer, max_outer, floor_outer)
            else:
                qi = _hertz_dry(di, ddi, k_inner, tau)
                qo = _hertz_dry(do, ddo, k_outer, tau)
            dydt[4 + j] = drho
            dydt[nd + 4 + j] = (
                (qi - qo) * inv_ball_mass + centripetal * (pitch_radius + rho) - gravity * sj
            )
        else:
            d = us - gap
            dd = dus
            if has_waviness:
                d += scratch[0, j] + scratch[2, j] + scratch[4, j] + scratch[6, j]
                dd += scratch[1, j] + scratch[3, j] + scratch[5, j] + scratch[7, j]
            if ehl == FILM_ENTRAINED:  # docs/model.md 4.6: no onset
                qi = _entrained_table(
                    d,
                    dd,
                    k_series,
                    tau,
                    film_inner + film_outer,
                    squeeze_series,
                    floor,
                    entrainment,
                    max_inner + max_outer,
                    p,
                )
            elif ehl:
                qi = _hertz_ehl_table(
                    d,
                    dd,
                    k_series,
                    tau,
                    film_inner + film_outer,
                    squeeze_series,
                    floor,
                    ref_inner + ref_outer,
                    max_inner + max_outer,
                    p,
                    TABLE_SERIES,
                )
            else:
                qi = _hertz_dry(d, dd, k_series, tau)
            qo = qi
        loads[0, j] = qi
        loads[1, j] = qo
        fxs -= qi * cj
        fys -= qi * sj
        fxh += qo * cj
        fyh += qo * sj
    # external loads on the shaft: constant force, or a loading spring preloaded to it
    kl = p[P_LOADING_STIFFNESS]
    fxs += p[P_LOAD_X] - kl * (xs - p[P_LOADING_X0])
    fys += p[P_LOAD_Y] - kl * (ys - p[P_LOADING_Y0])
    mu = p[P_UNBALANCE]
    if mu != 0.0:
        ws = p[P_SHAFT_SPEED]
        fxs += mu * ws * ws * math.cos(shaft_angle)
        fys += mu * ws * ws * math.sin(shaft_angle)
    ms = p[P_SHAFT_MASS]
    mh = p[P_HOUSING_MASS]
    g = p[P_GRAVITY]
    dydt[0] = vxs
    dydt[1] = vys
    dydt[2] = vxh
    dydt[3] = vyh
    dydt[nd] = (fxs - p[P_SHAFT_DAMPING] * vxs) / ms
    dydt[nd + 1] = (fys - p[P_SHAFT_DAMPING] * vys) / ms - g
    kh = p[P_PEDESTAL_STIFFNESS]
    ch = p[P_PEDESTAL_DAMPING]
    dydt[nd + 2] = (fxh - ch * vxh - kh * xh) / mh
    dydt[nd + 3] = (fyh - ch * vyh - kh * yh) / mh - g


@numba.njit(**_JIT)
def _rhs(scene, ehl, y, p, wav, dydt, loads, scratch):
    """:func:`_rhs_inline` as an ordinary call.

    One compiled copy per scene, shared by every call site (DOPRI5's stages, single
    evaluations); RK4 inlines the body at its one call site instead.
    """
    numba.literally(scene)
    numba.literally(ehl)
    _rhs_inline(scene, ehl, y, p, wav, dydt, loads, scratch)


@numba.njit(**_JIT_INLINE)
def _record(y, dydt, nd, k, out_state, out_accel):
    out_state[k, 0] = y[0]
    out_state[k, 1] = y[1]
    out_state[k, 2] = y[2]
    out_state[k, 3] = y[3]
    out_state[k, 4] = y[nd]
    out_state[k, 5] = y[nd + 1]
    out_state[k, 6] = y[nd + 2]
    out_state[k, 7] = y[nd + 3]
    out_accel[k, 0] = dydt[nd]
    out_accel[k, 1] = dydt[nd + 1]
    out_accel[k, 2] = dydt[nd + 2]
    out_accel[k, 3] = dydt[nd + 3]


@numba.njit(**_JIT_INLINE)
def _check(y, nd, limit):
    """Return a status code for the body displacements of ``y``."""
    for i in range(y.shape[0]):
        if not math.isfinite(y[i]):
            return STATUS_NONFINITE
    for i in range(nd):
        if abs(y[i]) > limit:
            return STATUS_RUNAWAY
    return STATUS_OK
