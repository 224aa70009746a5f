"""The time integrators of the dynamic model and their compiled entry points.

Classical RK4 with a fixed step and quintic Hermite dense output, Dormand-Prince 5(4) with
Hairer's dense output, and the one-evaluation right-hand side, each compiled per (scene, film)
pair from one factory (:func:`_rk4_entry`, :func:`_dopri5_entry`, :func:`_rhs_entry`).
The right-hand sides they integrate are in :mod:`generators._kernels`. Only numpy, numba, math
and :mod:`generators._kernels` are imported here (import-linter).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from generators._kernels import (
    _JIT,
    _JIT_INLINE,
    DEFECTS_ALL,
    DEFECTS_NONE,
    DEFECTS_SLIP,
    FILM_ENTRAINED,
    FILM_NAMES,
    N_OUT_ACCEL,
    N_OUT_STATE,
    P_BALL_COUNT,
    P_MAX_DISPLACEMENT,
    PHASE_ANCHOR,
    SCENE_FULL,
    SCENE_NAMES,
    STATUS_OK,
    STATUS_STEP_COLLAPSE,
    STATUS_TOO_MANY_STEPS,
    SURF_OUTER_DEFECT,
    SURF_SLIP,
    W_PHASE,
    W_SLIP_RATE,
    W_SURFACE,
    _advance,
    _clock_terms,
    _defect_clear_steps,
    _phase_steps,
    _phases,
    _scratch,
    _slip_rate_bound,
    _time_terms,
    _time_terms_at,
    _trig,
)
from generators._rhs import _check, _record, _rhs, _rhs_inline

# ---------------------------------------------------------------------------------- RK4


@numba.njit(**_JIT_INLINE)
def _hermite_weights(theta, dt, order):
    """Weights of (x0, v0, a0, x1, v1, a1) in the quintic Hermite interpolant of a position.

    x a position, v = dx/dt and a = dv/dt its velocity and acceleration at the two ends of a
    step ``dt`` [s]; the weights give, at fraction ``theta`` of the step, the interpolant
    (``order`` 0), its first (1: the velocity) or its second time derivative (2: the
    acceleration). The errors at mid-step are O(dt^6), O(dt^5) and O(dt^4) (a line of angular
    frequency w: velocity 3e-6 of its amplitude at w dt = 1, 8.6e-4 at w dt = 2.6, where the
    cubic interpolant of the velocity alone is 2.6e-3 and 0.10 off). At theta = 0 the weights
    are those of x0, v0 and a0 exactly.
    """
    t = theta
    t2 = t * t
    t3 = t2 * t
    if order == 0:
        t4 = t3 * t
        t5 = t4 * t
        return (
            1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5,
            (t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5) * dt,
            0.5 * (t2 - 3.0 * t3 + 3.0 * t4 - t5) * dt * dt,
            10.0 * t3 - 15.0 * t4 + 6.0 * t5,
            (-4.0 * t3 + 7.0 * t4 - 3.0 * t5) * dt,
            0.5 * (t3 - 2.0 * t4 + t5) * dt * dt,
        )
    if order == 1:
        t4 = t3 * t
        return (
            (-30.0 * t2 + 60.0 * t3 - 30.0 * t4) / dt,
            1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4,
            (t - 4.5 * t2 + 6.0 * t3 - 2.5 * t4) * dt,
            (30.0 * t2 - 60.0 * t3 + 30.0 * t4) / dt,
            -12.0 * t2 + 28.0 * t3 - 15.0 * t4,
            (1.5 * t2 - 4.0 * t3 + 2.5 * t4) * dt,
        )
    return (
        (-60.0 * t + 180.0 * t2 - 120.0 * t3) / (dt * dt),
        (-36.0 * t + 96.0 * t2 - 60.0 * t3) / dt,
        1.0 - 9.0 * t + 18.0 * t2 - 10.0 * t3,
        (60.0 * t - 180.0 * t2 + 120.0 * t3) / (dt * dt),
        (-24.0 * t + 84.0 * t2 - 60.0 * t3) / dt,
        3.0 * t - 12.0 * t2 + 10.0 * t3,
    )


@numba.njit(**_JIT_INLINE)
def _hermite_record(y0, f0, y1, f1, dt, theta, nd, k, out_state, out_accel, wanted):
    """Record the quintic Hermite interpolant between two RK4 steps at fraction ``theta``.

    Each recorded body coordinate is interpolated from its position, velocity and acceleration
    at both ends of the step (:func:`_hermite_weights`): positions O(dt^6), velocities (its
    derivative) O(dt^5), accelerations (its second derivative) O(dt^4) between the step's
    ends; RK4's own error at the ends is O(dt^4). At theta = 0 the record is exactly the
    step-start state and its right-hand side. ``wanted`` (``N_OUT_STATE + N_OUT_ACCEL``
    flags, the columns of :func:`generators._rhs._record`): only those columns are
    written (a call that decimates one channel interpolates one).
    """
    for c in range(N_OUT_STATE + N_OUT_ACCEL):
        if not wanted[c]:
            continue
        if c < N_OUT_STATE:
            order = 0 if c < 4 else 1
            j = c % 4
        else:
            order = 2
            j = c - N_OUT_STATE
        w0, w1, w2, w3, w4, w5 = _hermite_weights(theta, dt, order)
        value = (
            w0 * y0[j]
            + w1 * y0[nd + j]
            + w2 * f0[nd + j]
            + w3 * y1[j]
            + w4 * y1[nd + j]
            + w5 * f1[nd + j]
        )
        if c < N_OUT_STATE:
            out_state[k, c] = value
        else:
            out_accel[k, j] = value


@numba.njit(**_JIT_INLINE)
def _slip_phases(t, wav, trig, first):
    """The slip rows' cos and sin (table rows ``first`` on) at ``t`` [s], computed exactly.

    The same arguments as :func:`generators._kernels._phases` gives them.
    """
    for r in range(first, wav.shape[0]):
        arg = wav[r, W_SLIP_RATE] * t + wav[r, W_PHASE]
        trig[r + 1, 0] = math.cos(arg)
        trig[r + 1, 1] = math.sin(arg)


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
    out_state,
    out_accel,
    out_loads,
    record_loads,
    fine_steps,
    wanted,
):
    """Classical RK4 with a fixed step and quintic Hermite dense output.

    Records at ``t_first + k * record_dt`` (k < n_record), interpolating inside the step that
    contains each record time, so the step may be longer or shorter than the record interval.
    A step in which a contact meets a local defect (:func:`_defect_near`) is taken as
    ``fine_steps`` shorter ones (1: never). ``wanted``: the record columns written
    (:func:`_hermite_record`).
    The right-hand side at the end of a step is the first stage of the next (computed once).
    Returns (status, time, state): the state at that time (a later call continues from it).
    """
    numba.literally(scene)
    numba.literally(ehl)
    n = y0.shape[0]
    z = int(p[P_BALL_COUNT])
    nd = n // 2
    limit = p[P_MAX_DISPLACEMENT]
    y = y0.copy()
    # stages: ks[0] = f(y_n) (the previous step's last evaluation), ks[1..3] = k2..k4,
    # ks[4] = f(y_{n+1}); one call site of the inlined right-hand side (compile time)
    ks = np.empty((5, n))
    k1 = ks[0]
    f1 = ks[4]
    # the stages' rows as views made once: a view made per stage costs 7-10 ns (measured)
    k2 = ks[1]
    k3 = ks[2]
    k4 = ks[3]
    y1 = np.empty(n)
    tmp = np.empty(n)
    loads = np.zeros((2, z))
    loads_start = np.zeros((2, z))
    scratch = _scratch(z)
    next_rec = 0
    trig = _trig(wav)
    inc = _phase_steps(p, wav, 0.5 * dt)
    # steps in which a contact meets a local defect are taken as fine_steps shorter ones
    inc_fine = _phase_steps(p, wav, 0.5 * dt / fine_steps) if fine_steps > 1 else inc
    anchor = False
    next_check = 0
    slip_rate = _slip_rate_bound(wav, z)  # the reach test's bound, once per run
    # a table of local defects (and slip) only: away from the pits its rows add nothing, and
    # once zeroed (a step's terms without the pits' rows) they need not be evaluated again
    # until a step near a pit writes them (only the clock terms change)
    defects_only = wav.shape[0] > 0
    local_defects = False  # a pit anywhere: the reach test decides where its rows are read
    for r in range(wav.shape[0]):
        surface = int(wav[r, W_SURFACE])
        if surface < SURF_OUTER_DEFECT:
            defects_only = False
        elif surface != SURF_SLIP:
            local_defects = True
    zeroed = False
    # no table rows: a stage's time terms are its clock alone (the call costs 20-30 ns)
    clock_only = wav.shape[0] == 0
    # the slip rows (last in the table) are read only in the steps that evaluate the slip
    # angles (near a pit, or before a reach test); in the others they are not rotated, and the
    # next step that reads them first computes them afresh (_slip_phases)
    first_slip = wav.shape[0]
    while first_slip > 0 and int(wav[first_slip - 1, W_SURFACE]) == SURF_SLIP:
        first_slip -= 1
    every_row = trig.shape[0]
    stale = False
    _time_terms_at(t0, p, wav, trig, scratch)
    _rhs(scene, ehl, y, p, wav, k1, loads, scratch)
    if record_loads:
        loads_start[:, :] = loads
    t = t0
    for step in range(n_steps):
        t = t0 + step * dt
        if step % PHASE_ANCHOR == 0 or anchor:
            _phases(t, p, wav, trig)  # exact every PHASE_ANCHOR steps, rotated between
            stale = False
        # a contact near a local defect: the step is split (into fine_steps, 1 for a pit
        # whose passage the step already resolves) and the pit's rows evaluated; elsewhere
        # they add nothing and are skipped. After a step with no contact in reach, the test is
        # skipped for as many steps as no contact can come within reach (the same answers:
        # _defect_clear_steps)
        if not local_defects:
            near = True
        elif step < next_check:
            near = False
        else:
            clear = _defect_clear_steps(wav, p, t, 1.5 * dt, scratch, dt, slip_rate)
            near = clear < 0
            next_check = step + 1 + clear
        subs = fine_steps if near else 1
        at_half = DEFECTS_ALL if near else DEFECTS_NONE
        # the slip angles at the step's end only for a test at the next step
        at_end = DEFECTS_ALL if near else (DEFECTS_SLIP if step + 1 >= next_check else DEFECTS_NONE)
        anchor = subs > 1
        rotated = every_row
        if near or at_end != DEFECTS_NONE:
            if stale:
                _slip_phases(t, wav, trig, first_slip)
                stale = False
        elif first_slip < wav.shape[0]:
            rotated = first_slip + 1
            stale = True
        h = dt / subs
        half = 0.5 * h
        step_inc = inc_fine if subs > 1 else inc
        for sub in range(subs):
            ts = t + sub * h
            for stage in range(4):
                # the two time-terms blocks below stay written out: one inline helper for both
                # made every run 15 % slower (benchmarks/bench_pit_runs.py, stop 34)
                if stage == 0:
                    _advance(trig, step_inc, rotated)
                    if clock_only or (zeroed and at_half == DEFECTS_NONE):
                        _clock_terms(ts + half, p, trig, scratch)
                    else:
                        _time_terms(ts + half, p, wav, trig, scratch, at_half)
                        zeroed = defects_only and at_half != DEFECTS_ALL
                    for i in range(n):
                        tmp[i] = y[i] + half * ks[0, i]
                elif stage == 1:
                    for i in range(n):
                        tmp[i] = y[i] + half * ks[1, i]
                elif stage == 2:
                    _advance(trig, step_inc, rotated)
                    if clock_only or (zeroed and at_end == DEFECTS_NONE):
                        _clock_terms(ts + h, p, trig, scratch)
                    else:
                        _time_terms(ts + h, p, wav, trig, scratch, at_end)
                        zeroed = defects_only and at_end != DEFECTS_ALL
                    for i in range(n):
                        tmp[i] = y[i] + h * ks[2, i]
                else:
                    for i in range(n):
                        tmp[i] = y[i] + h / 6.0 * (
                            ks[0, i] + 2.0 * ks[1, i] + 2.0 * ks[2, i] + ks[3, i]
                        )
                dst = k2 if stage == 0 else (k3 if stage == 1 else (k4 if stage == 2 else f1))
                _rhs_inline(scene, ehl, tmp, p, wav, dst, loads, scratch)
            for i in range(n):
                y1[i] = tmp[i]
            while next_rec < n_record:
                theta = (t_first + next_rec * record_dt - ts) / h
                if theta >= 1.0 - 1e-9:
                    break
                if theta < 0.0:
                    theta = 0.0
                _hermite_record(y, k1, y1, f1, h, theta, nd, next_rec, out_state, out_accel, wanted)
                if record_loads:
                    for j in range(z):  # loads at the nearer end of the step
                        src = loads_start if theta < 0.5 else loads
                        out_loads[next_rec, 0, j] = src[0, j]
                        out_loads[next_rec, 1, j] = src[1, j]
                next_rec += 1
            for i in range(n):
                y[i] = y1[i]
                k1[i] = f1[i]
            if record_loads:
                loads_start[:, :] = loads
        if step % 64 == 0 or next_rec >= n_record:
            status = _check(y, nd, limit)
            if status != STATUS_OK:
                return status, t + dt, y
        if next_rec >= n_record:
            return STATUS_OK, t + dt, y
    return _check(y, nd, limit), t0 + n_steps * dt, y


# --------------------------------------------------------------------- Dormand-Prince 5(4)

# Butcher tableau (Dormand & Prince 1980) and the dense-output coefficients of Hairer's DOPRI5.
_A21 = 1.0 / 5.0
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0
_A64, _A65 = 49.0 / 176.0, -5103.0 / 18656.0
_A71, _A73, _A74 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0
_A75, _A76 = -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4 = 71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0
_E5, _E6, _E7 = -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0
_D1, _D3 = -12715105075.0 / 11282082432.0, 87487479700.0 / 32700410799.0
_D4, _D5 = -10690763975.0 / 1880347072.0, 701980252875.0 / 199316789632.0
_D6, _D7 = -1453857185.0 / 822651844.0, 69997945.0 / 29380423.0


@numba.njit(**_JIT)
def _dopri5_impl(
    scene,
    ehl,
    y0,
    p,
    wav,
    t0,
    t_first,
    record_dt,
    n_record,
    rtol,
    atol,
    h0,
    h_max,
    max_steps,
    out_state,
    out_accel,
    out_loads,
    record_loads,
    step_stats,
):
    """Adaptive Dormand-Prince 5(4) with error control and dense output at the record times.

    Records at ``t_first + k * record_dt``; each record evaluates the right-hand side once at
    the interpolated state (accelerations, loads). ``step_stats`` receives [accepted steps,
    rejected steps, smallest step, largest step]. Returns (status, time, state at that time).
    """
    numba.literally(scene)
    numba.literally(ehl)
    n = y0.shape[0]
    z = int(p[P_BALL_COUNT])
    nd = n // 2
    limit = p[P_MAX_DISPLACEMENT]
    y = y0.copy()
    y1 = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    tmp = np.empty(n)
    r1 = np.empty(n)
    r2 = np.empty(n)
    r3 = np.empty(n)
    r4 = np.empty(n)
    acc = np.empty(n)
    loads = np.zeros((2, z))
    scratch = _scratch(z)
    trig = _trig(wav)
    t = t0
    t_end = t_first + (n_record - 1) * record_dt
    h = h0
    h_min_seen = 1e300
    h_max_seen = 0.0
    accepted = 0
    rejected = 0
    next_rec = 0
    _time_terms_at(t, p, wav, trig, scratch)
    _rhs(scene, ehl, y, p, wav, k1, loads, scratch)
    err_old = 1e-4
    while next_rec < n_record:
        if accepted + rejected >= max_steps:
            step_stats[0], step_stats[1] = accepted, rejected
            step_stats[2], step_stats[3] = h_min_seen, h_max_seen
            return STATUS_TOO_MANY_STEPS, t, y
        if h < 1e-13 * max(abs(t), record_dt):
            step_stats[0], step_stats[1] = accepted, rejected
            step_stats[2], step_stats[3] = h_min_seen, h_max_seen
            return STATUS_STEP_COLLAPSE, t, y
        if h > h_max:
            h = h_max
        if t + h > t_end and t_end > t:
            h = t_end - t
        for i in range(n):
            tmp[i] = y[i] + h * _A21 * k1[i]
        _time_terms_at(t + 0.2 * h, p, wav, trig, scratch)
        _rhs(scene, ehl, tmp, p, wav, k2, loads, scratch)
        for i in range(n):
            tmp[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        _time_terms_at(t + 0.3 * h, p, wav, trig, scratch)
        _rhs(scene, ehl, tmp, p, wav, k3, loads, scratch)
        for i in range(n):
            tmp[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        _time_terms_at(t + 0.8 * h, p, wav, trig, scratch)
        _rhs(scene, ehl, tmp, p, wav, k4, loads, scratch)
        for i in range(n):
            tmp[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        _time_terms_at(t + 8.0 / 9.0 * h, p, wav, trig, scratch)
        _rhs(scene, ehl, tmp, p, wav, k5, loads, scratch)
        for i in range(n):
            tmp[i] = y[i] + h * (
                _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
            )
        _time_terms_at(t + h, p, wav, trig, scratch)
        _rhs(scene, ehl, tmp, p, wav, k6, loads, scratch)
        for i in range(n):
            y1[i] = y[i] + h * (
                _A71 * k1[i] + _A73 * k3[i] + _A74 * k4[i] + _A75 * k5[i] + _A76 * k6[i]
            )
        _rhs(scene, ehl, y1, p, wav, k7, loads, scratch)
        err = 0.0
        finite = True
        for i in range(n):
            e = h * (
                _E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i]
            )
            sc = atol[i] + rtol * max(abs(y[i]), abs(y1[i]))
            err += (e / sc) ** 2
            if not math.isfinite(y1[i]):
                finite = False
        err = math.sqrt(err / n)
        if not finite or not math.isfinite(err):
            rejected += 1
            h *= 0.2
            continue
        if err <= 1.0:
            # dense output (Hairer's CONTD5) for every record time inside (t, t + h]
            while next_rec < n_record and t_first + next_rec * record_dt <= t + h * (1 + 1e-12):
                tr = t_first + next_rec * record_dt
                if tr < t:
                    next_rec += 1
                    continue
                th = (tr - t) / h
                th1 = 1.0 - th
                for i in range(n):
                    ydiff = y1[i] - y[i]
                    bspl = h * k1[i] - ydiff
                    r1[i] = ydiff
                    r2[i] = bspl
                    r3[i] = ydiff - h * k7[i] - bspl
                    r4[i] = h * (
                        _D1 * k1[i]
                        + _D3 * k3[i]
                        + _D4 * k4[i]
                        + _D5 * k5[i]
                        + _D6 * k6[i]
                        + _D7 * k7[i]
                    )
                    tmp[i] = y[i] + th * (r1[i] + th1 * (r2[i] + th * (r3[i] + th1 * r4[i])))
                status = _check(tmp, nd, limit)
                if status != STATUS_OK:
                    return status, tr, y
                _time_terms_at(tr, p, wav, trig, scratch)
                _rhs(scene, ehl, tmp, p, wav, acc, loads, scratch)
                _record(tmp, acc, nd, next_rec, out_state, out_accel)
                if record_loads:
                    for j in range(z):
                        out_loads[next_rec, 0, j] = loads[0, j]
                        out_loads[next_rec, 1, j] = loads[1, j]
                next_rec += 1
            t = t + h
            for i in range(n):
                y[i] = y1[i]
                k1[i] = k7[i]  # first same as last
            accepted += 1
            if h < h_min_seen:
                h_min_seen = h
            if h > h_max_seen:
                h_max_seen = h
            status = _check(y, nd, limit)
            if status != STATUS_OK:
                step_stats[0], step_stats[1] = accepted, rejected
                step_stats[2], step_stats[3] = h_min_seen, h_max_seen
                return status, t, y
            # PI step control (Hairer: beta = 0.04)
            fac = 0.9 * err ** (-0.2 + 0.04 * 0.75) * err_old**0.04 if err > 0 else 5.0
            fac = min(5.0, max(0.2, fac))
            err_old = max(err, 1e-4)
            h *= fac
        else:
            rejected += 1
            h *= max(0.2, 0.9 * err**-0.2)
    step_stats[0], step_stats[1] = accepted, rejected
    step_stats[2], step_stats[3] = h_min_seen, h_max_seen
    return STATUS_OK, t, y


# ------------------------------------------------------------------ compiled entry points
# One entry point per (scene, film) pair: the pair reaches the implementations as literal
# types, so each pair is compiled (and cached, under its own name) on its own with the other
# scenes' branches removed; Python picks the entry from ``RK4``, ``DOPRI5`` and ``RHS`` by
# (scene, ehl). Each factory spells its integrator's arguments once; the closure's two
# integers are part of numba's cache key (tests_generators/test_kernels_cache.py).


@numba.njit(**_JIT)
def _rhs_once_impl(scene, ehl, t, y, p, wav, dydt, loads):
    numba.literally(scene)
    numba.literally(ehl)
    scratch = _scratch(int(p[P_BALL_COUNT]))
    trig = _trig(wav)
    _time_terms_at(t, p, wav, trig, scratch)
    _rhs(scene, ehl, y, p, wav, dydt, loads, scratch)


def _specialised(entry, kind: str, scene: int, ehl: int):
    """Compile ``entry`` (a closure over ``scene`` and ``ehl``) under a name of its own."""
    entry.__name__ = entry.__qualname__ = f"_{kind}_{SCENE_NAMES[scene]}_{FILM_NAMES[ehl]}"
    return numba.njit(**_JIT)(entry)


def _rk4_entry(scene: int, ehl: int):
    """The RK4 entry point of one (scene, film) pair (arguments: :func:`_rk4_impl`)."""

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
        out_state,
        out_accel,
        out_loads,
        record_loads,
        fine_steps,
        wanted,
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
            out_state,
            out_accel,
            out_loads,
            record_loads,
            fine_steps,
            wanted,
        )

    return _specialised(entry, "rk4", scene, ehl)


def _dopri5_entry(scene: int, ehl: int):
    """The DOPRI5 entry point of one (scene, film) pair (arguments: :func:`_dopri5_impl`)."""

    def entry(
        y0,
        p,
        wav,
        t0,
        t_first,
        record_dt,
        n_record,
        rtol,
        atol,
        h0,
        h_max,
        max_steps,
        out_state,
        out_accel,
        out_loads,
        record_loads,
        step_stats,
    ):
        return _dopri5_impl(
            scene,
            ehl,
            y0,
            p,
            wav,
            t0,
            t_first,
            record_dt,
            n_record,
            rtol,
            atol,
            h0,
            h_max,
            max_steps,
            out_state,
            out_accel,
            out_loads,
            record_loads,
            step_stats,
        )

    return _specialised(entry, "dopri5", scene, ehl)


def _rhs_entry(scene: int, ehl: int):
    """One right-hand-side evaluation of one (scene, film) pair (:func:`_rhs_once_impl`)."""

    def entry(t, y, p, wav, dydt, loads):
        _rhs_once_impl(scene, ehl, t, y, p, wav, dydt, loads)

    return _specialised(entry, "rhs", scene, ehl)


#: Every (scene, film mode) compiled: the film's entrainment with massless balls only.
PAIRS = tuple(
    (scene, ehl)
    for scene in SCENE_NAMES
    for ehl in FILM_NAMES
    if not (scene == SCENE_FULL and ehl == FILM_ENTRAINED)
)
RK4 = {pair: _rk4_entry(*pair) for pair in PAIRS}
DOPRI5 = {pair: _dopri5_entry(*pair) for pair in PAIRS}
RHS = {pair: _rhs_entry(*pair) for pair in PAIRS}


def _rk4(scene, ehl, *args):
    """RK4 for a (scene, ehl) pair (Python-side dispatch to the compiled entry point)."""
    return RK4[int(scene), int(ehl)](*args)


def _dopri5(scene, ehl, *args):
    """DOPRI5 for a (scene, ehl) pair."""
    return DOPRI5[int(scene), int(ehl)](*args)


def _rhs_once(scene, ehl, t, y, p, wav, dydt, loads):
    """One right-hand-side evaluation (static checks, linearisation, reference tests)."""
    RHS[int(scene), int(ehl)](float(t), y, p, wav, dydt, loads)
