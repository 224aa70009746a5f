"""How far issue 22's speed targets lie from this machine's floor (prints figures; not a test).

Issue 22 asks for ``simulate`` of the ``shaft`` scene at its defaults at 1,000 times scipy's
RK45 on the same physics, and for 2,000 one-second ``shaft`` signals per second from
``cmtool generate`` on two workers, at the default step (1.953e-5 s at 25.6 kHz: the longest
step on the record grid that keeps the octave bands within 1 %, docs/performance.md). Both
come down to the cost of one Hertz contact evaluation: a second of signal takes 51,200 RK4
steps x 4 stages x 9 balls = 1.84 million of them. This measures the least that evaluation
can cost here, in kernels that do nothing else (a 2-DOF shaft, nine dry Hertz contacts with
their damping, RK4; no waviness, no record, no decimation, no checks):

1. ``scalar``: one signal, the balls in a loop (what ``simulate`` runs), and the same with the
   ball loop written branch-free over arrays, the form the compiler vectorises;
2. ``lanes``: signals side by side in SIMD lanes, float64 (what ``cmtool generate`` runs);
3. ``lanes float32``: the same in single precision (twice the lanes per instruction; the
   model's signals are nanometres over micrometres of static deflection, so this would need
   the state written as a perturbation of the static equilibrium);

The lanes kernel keeps its balls at fixed angles (no cage rotation): a lower bound. It
prints each against the budget the targets leave, from RK45 measured in the same run on
``benchmarks/bench_model.py``'s numpy right-hand side (rtol 1e-3, its loosest setting within
1 % in the BPFO line: the largest baseline, so the most generous budget).

4. What single precision costs in accuracy: the scalar kernel in float32 against float64 (a
   6205-like shaft, 500 N, 2.5 um radial clearance, 1800 rpm; the shaft's acceleration), the
   difference per octave band as a fraction of the signal's amplitude there (the 1 % bound of
   docs/performance.md is on these bands).

Run: .venv/bin/python benchmarks/roofline.py
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numba
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

_JIT = {"cache": False, "fastmath": True, "nogil": True, "error_model": "numpy"}
BALLS = 9
STEP = 1.953125e-5  # the default step on the 102.4 kHz record grid at 25.6 kHz [s]
STEPS = int(round(1.0 / STEP))  # one simulated second
CONTACTS = STEPS * 4 * BALLS
K_HERTZ, DAMPING_TIME, GAP, MASS, LOAD = 8e9, 1e-5, 1e-6, 1.0, 500.0
CAGE = 2 * math.pi * 12.0


@numba.njit(**_JIT, inline="always")
def _rk4_increment(k, dt):
    """RK4's step from its four stage slopes ``k`` over ``dt``."""
    return dt / 6 * (k[0] + 2 * k[1] + 2 * k[2] + k[3])


@numba.njit(**_JIT)
def scalar(n_steps, dt, z, k, tau, gap, m, load, wc):  # noqa: D103
    x, y, vx, vy = 0.0, 1e-5, 0.0, 0.0
    cd, sd = math.cos(2 * math.pi / z), math.sin(2 * math.pi / z)
    ci, si = math.cos(wc * dt), math.sin(wc * dt)
    c0, s0 = 1.0, 0.0
    kx, ky, kvx, kvy = np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(4)
    for _ in range(n_steps):
        for st in range(4):
            h = 0.0 if st == 0 else (0.5 * dt if st < 3 else dt)
            p = st - 1 if st else 0
            xs, ys = x + h * kx[p], y + h * ky[p]
            vxs, vys = vx + h * kvx[p], vy + h * kvy[p]
            fx, fy = 0.0, 0.0
            cj, sj = c0, s0
            for j in range(z):
                if j > 0:
                    cj, sj = cj * cd - sj * sd, sj * cd + cj * sd
                d = xs * cj + ys * sj - gap
                if d > 0.0:
                    q = k * math.sqrt(d) * (d + 1.5 * tau * (vxs * cj + vys * sj))
                    if q > 0.0:
                        fx -= q * cj
                        fy -= q * sj
            kx[st], ky[st] = vxs, vys
            kvx[st], kvy[st] = fx / m, (fy + load) / m
        x, y = x + _rk4_increment(kx, dt), y + _rk4_increment(ky, dt)
        vx, vy = vx + _rk4_increment(kvx, dt), vy + _rk4_increment(kvy, dt)
        c0, s0 = c0 * ci - s0 * si, s0 * ci + c0 * si
    return x + y


@numba.njit(**_JIT)
def balls_vectorised(n_steps, dt, z, k, tau, gap, m, load, wc):  # noqa: D103
    # one signal, the ball loop branch-free over arrays (the form the compiler vectorises),
    # the ball angles rotated by the cage each step as arrays too
    x, y, vx, vy = 0.0, 1e-5, 0.0, 0.0
    cs, sn = np.empty(z), np.empty(z)
    for j in range(z):
        cs[j], sn[j] = math.cos(2 * math.pi * j / z), math.sin(2 * math.pi * j / z)
    ci, si = math.cos(wc * dt), math.sin(wc * dt)
    q = np.empty(z)
    kx, ky, kvx, kvy = np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(4)
    for _ in range(n_steps):
        for st in range(4):
            h = 0.0 if st == 0 else (0.5 * dt if st < 3 else dt)
            p = st - 1 if st else 0
            xs, ys = x + h * kx[p], y + h * ky[p]
            vxs, vys = vx + h * kvx[p], vy + h * kvy[p]
            for j in range(z):
                d = max(xs * cs[j] + ys * sn[j] - gap, 0.0)
                dd = vxs * cs[j] + vys * sn[j]
                q[j] = max(k * math.sqrt(d) * (d + 1.5 * tau * dd), 0.0)
            fx, fy = 0.0, 0.0
            for j in range(z):
                fx -= q[j] * cs[j]
                fy -= q[j] * sn[j]
            kx[st], ky[st] = vxs, vys
            kvx[st], kvy[st] = fx / m, (fy + load) / m
        x, y = x + _rk4_increment(kx, dt), y + _rk4_increment(ky, dt)
        vx, vy = vx + _rk4_increment(kvx, dt), vy + _rk4_increment(kvy, dt)
        for j in range(z):
            cs[j], sn[j] = cs[j] * ci - sn[j] * si, sn[j] * ci + cs[j] * si
    return x + y


def _lanes_kernel(dtype):
    """The lanes kernel in ``dtype`` (every loop over the lanes: the vectorised one)."""

    @numba.njit(**_JIT)
    def lanes(n_steps, dt0, z, k0, tau0, gap0, m0, load0, lanes_count):
        zero, half, two, six = dtype(0.0), dtype(0.5), dtype(2.0), dtype(6.0)
        dt, k, tau, gap = dtype(dt0), dtype(k0), dtype(tau0), dtype(gap0)
        m, load, c15 = dtype(m0), dtype(load0), dtype(1.5)
        n = lanes_count
        x, y = np.zeros(n, dtype), np.full(n, dtype(1e-5))
        vx, vy = np.zeros(n, dtype), np.zeros(n, dtype)
        xs, ys = np.empty(n, dtype), np.empty(n, dtype)
        vxs, vys = np.empty(n, dtype), np.empty(n, dtype)
        fx, fy = np.empty(n, dtype), np.empty(n, dtype)
        kx, ky = np.zeros((4, n), dtype), np.zeros((4, n), dtype)
        kvx, kvy = np.zeros((4, n), dtype), np.zeros((4, n), dtype)
        cs, sn = np.empty((z, n), dtype), np.empty((z, n), dtype)
        for j in range(z):
            for b in range(n):
                angle = 2 * math.pi * j / z + 0.01 * b
                cs[j, b], sn[j, b] = math.cos(angle), math.sin(angle)
        for _ in range(n_steps):
            for st in range(4):
                h = zero if st == 0 else (half * dt if st < 3 else dt)
                p = st - 1 if st else 0
                for b in range(n):
                    xs[b], ys[b] = x[b] + h * kx[p, b], y[b] + h * ky[p, b]
                    vxs[b], vys[b] = vx[b] + h * kvx[p, b], vy[b] + h * kvy[p, b]
                    fx[b], fy[b] = zero, zero
                for j in range(z):
                    for b in range(n):
                        cj, sj = cs[j, b], sn[j, b]
                        d = max(xs[b] * cj + ys[b] * sj - gap, zero)
                        dd = vxs[b] * cj + vys[b] * sj
                        q = max(k * np.sqrt(d) * (d + tau * c15 * dd), zero)
                        fx[b] -= q * cj
                        fy[b] -= q * sj
                for b in range(n):
                    kx[st, b], ky[st, b] = vxs[b], vys[b]
                    kvx[st, b], kvy[st, b] = fx[b] / m, (fy[b] + load) / m
            for b in range(n):
                x[b] += dt / six * (kx[0, b] + two * kx[1, b] + two * kx[2, b] + kx[3, b])
                y[b] += dt / six * (ky[0, b] + two * ky[1, b] + two * ky[2, b] + ky[3, b])
                vx[b] += dt / six * (kvx[0, b] + two * kvx[1, b] + two * kvx[2, b] + kvx[3, b])
                vy[b] += dt / six * (kvy[0, b] + two * kvy[1, b] + two * kvy[2, b] + kvy[3, b])
        return x[0] + y[0]

    return lanes


def _best(fn, repeat):
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _precision_kernel(dtype):
    """The scalar kernel in ``dtype``, recording the shaft's y acceleration at every step."""

    @numba.njit(**_JIT)
    def run(n_steps, dt0, z, k0, tau0, gap0, m0, load0, cage0, damping0):
        dt, k, tau, gap = dtype(dt0), dtype(k0), dtype(tau0), dtype(gap0)
        m, load, damping = dtype(m0), dtype(load0), dtype(damping0)
        zero, half, two, six, c15 = dtype(0.0), dtype(0.5), dtype(2.0), dtype(6.0), dtype(1.5)
        x, y, vx, vy = zero, dtype(2e-5), zero, zero
        kx, ky = np.zeros(4, dtype), np.zeros(4, dtype)
        kvx, kvy = np.zeros(4, dtype), np.zeros(4, dtype)
        out = np.empty(n_steps)
        for step in range(n_steps):
            for st in range(4):
                h = zero if st == 0 else (half * dt if st < 3 else dt)
                t = (step + (0.0 if st == 0 else (0.5 if st < 3 else 1.0))) * dt0
                p = st - 1 if st else 0
                xs, ys = x + h * kx[p], y + h * ky[p]
                vxs, vys = vx + h * kvx[p], vy + h * kvy[p]
                fx, fy = zero, zero
                for j in range(z):
                    angle = cage0 * t + 2 * math.pi * j / z
                    cj, sj = dtype(math.cos(angle)), dtype(math.sin(angle))
                    d = max(xs * cj + ys * sj - gap, zero)
                    q = max(k * np.sqrt(d) * (d + tau * c15 * (vxs * cj + vys * sj)), zero)
                    fx -= q * cj
                    fy -= q * sj
                kx[st], ky[st] = vxs, vys
                kvx[st], kvy[st] = (fx - damping * vxs) / m, (fy + load - damping * vys) / m
            x += dt / six * (kx[0] + two * kx[1] + two * kx[2] + kx[3])
            y += dt / six * (ky[0] + two * ky[1] + two * ky[2] + ky[3])
            vx += dt / six * (kvx[0] + two * kvx[1] + two * kvx[2] + kvx[3])
            vy += dt / six * (kvy[0] + two * kvy[1] + two * kvy[2] + kvy[3])
            out[step] = kvy[3]
        return out

    return run


def precision_errors() -> list[tuple[float, float, float]]:
    """Per octave band (low, high [Hz]): float32's error over float64's amplitude there."""
    from scipy.signal import welch

    args = (60000, STEP, BALLS, K_HERTZ, DAMPING_TIME, 2.5e-6, MASS, LOAD, 2 * math.pi * 0.398 * 30)
    runs = [_precision_kernel(dtype)(*args, 200.0)[10000:] for dtype in (np.float64, np.float32)]
    reference, single = (r - r.mean() for r in runs)
    f, p_ref = welch(reference, 1.0 / STEP, nperseg=8192)
    _, p_err = welch(single - reference, 1.0 / STEP, nperseg=8192)
    bands = [(0.0, 500.0), (500.0, 1000.0), (1000.0, 2000.0), (2000.0, 4000.0)]
    bands += [(4000.0, 8000.0), (8000.0, 11520.0)]
    out = []
    for low, high in bands:
        inside = (f >= low) & (f < high)
        out.append((low, high, float(np.sqrt(p_err[inside].sum() / p_ref[inside].sum()))))
    return out


def rk45_seconds_per_second() -> float:
    """RK45 on bench_model's numpy right-hand side, rtol 1e-3, wall s per simulated s."""
    import dataclasses

    from bench_model import CHANNEL, DEFECT, GEOMETRY, OPERATING, run_solve_ivp

    from generators import Scene, SimulationSettings
    from generators.model import prepare

    settings = SimulationSettings(fs=25600.0, duration=0.3, settle_time=0.1, channels=(CHANNEL,))
    scene = Scene(level="shaft", ehl=False)
    prep = prepare(GEOMETRY, OPERATING, DEFECT, scene=scene, settings=settings)
    run_solve_ivp("RK45", 1e-3, dataclasses.replace(settings, duration=0.01), prep)
    wall = _best(lambda: run_solve_ivp("RK45", 1e-3, settings, prep), 2)
    return wall / (settings.duration + settings.settle_time)


def main() -> int:
    rk45 = rk45_seconds_per_second()
    budget_simulate = rk45 / 1000.0
    # 2,000 signals/s on two cores: 1 ms of one core per signal of 1 s + 0.1 s settling
    budget_generate = 2.0 / 2000.0 / 1.1
    print(f"# roofline: {STEPS} RK4 steps x 4 stages x {BALLS} contacts a simulated second")
    print(f"RK45 (numpy right-hand side, rtol 1e-3): {rk45:.3f} s per simulated second")
    print(
        f"budgets: simulate at 1000x RK45 {budget_simulate * 1e3:.2f} ms per simulated second "
        f"({budget_simulate / CONTACTS * 1e9:.2f} ns a contact); generate at 2000/s on 2 cores "
        f"{budget_generate * 1e3:.2f} ms of a core per simulated second "
        f"({budget_generate / CONTACTS * 1e9:.2f} ns a contact), everything included\n"
    )
    args = (STEP, BALLS, K_HERTZ, DAMPING_TIME, GAP, MASS, LOAD)
    for name, kernel in (("scalar", scalar), ("balls vectorised", balls_vectorised)):
        kernel(10, *args, CAGE)
        wall = _best(lambda k=kernel: k(STEPS, *args, CAGE), 5)
        print(
            f"one signal, {name:17s}: {wall * 1e3:6.2f} ms per simulated second, "
            f"{wall / CONTACTS * 1e9:.3f} ns a contact, {rk45 / wall:5.0f}x RK45 at most"
        )
    kernels = {
        "lanes float64": _lanes_kernel(np.float64),
        "lanes float32": _lanes_kernel(np.float32),
    }
    for name, kernel in kernels.items():
        for count in (16, 64, 128):
            kernel(10, *args, count)
            wall = _best(lambda k=kernel, c=count: k(STEPS, *args, c), 3)
            per_signal = wall / count
            print(
                f"{name:25s} {count:4d} lanes: {per_signal * 1e3:6.3f} ms per signal-second, "
                f"{per_signal / CONTACTS * 1e9:.3f} ns a contact-lane, "
                f"{2.0 / (per_signal * 1.1):6.0f} signals/s on 2 cores for the kernel alone"
            )
    print("\nfloat32 against float64, the shaft's acceleration per band (error / amplitude):")
    for low, high, error in precision_errors():
        print(f"  {low:7.0f}-{high:7.0f} Hz: {error * 100:6.2f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
