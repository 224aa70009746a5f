"""Speed of the dynamic model against scipy's solve_ivp at equal accuracy (prints figures).

Run: ``make bench`` or ``.venv/bin/python benchmarks/bench_model.py [--quick]``.

Scene: 6205, 1800 rpm, 500 N, outer-race waviness N_w = 9, A = 1 um, docs/model.md 6.3 rig, output
25.6 kHz. Accuracy measure: the BPFO amplitude of the housing velocity (y).

1. Every compiled scene (shaft, shaft+housing, full; dry and EHL) at its default RK4 step:
   wall seconds per simulated second (one core, after compilation) and the BPFO amplitude
   error against the full/EHL model at a 1 us step.
2. The ``shaft`` scene (dry) against scipy.integrate.solve_ivp (RK45 and LSODA) on the same
   right-hand side written in vectorised numpy: each integrator at the loosest setting whose
   BPFO amplitude is within 1 % of the converged shaft-scene value; the ratio of wall times.
   Then the same at equal accuracy in the octave bands from 500 Hz to 0.45 fs
   (``generators.accuracy.band_error`` within 1 %, what the default step is chosen for).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time

import numpy as np
from scipy import integrate

import features as F
from generators import (
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)
from generators.accuracy import band_error
from generators.model import prepare

GEOMETRY = bearing("6205")
OPERATING = OperatingCondition.from_rpm(1800, 500.0)
DEFECT = Waviness(surface="outer", order=9, amplitude=1e-6)
CHANNEL = "housing_velocity_y"


def bpfo_amplitude(x, fs, bpfo):
    f, a = F.amplitude_spectrum(x, fs)
    return F.band_amplitude(f, a, bpfo, half_width=1.5)


def timed(fn, repeat=3):
    best = math.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


class NumpyShaftModel:
    """Scene ``shaft`` (dry) in vectorised numpy: the same equations as the kernel."""

    def __init__(self, prep):
        p = prep.p
        from generators import _kernels as K

        self.z = GEOMETRY.ball_count
        self.kt, self.gap = p[K.P_K_SERIES], p[K.P_GAP]
        self.tau = p[K.P_CONTACT_DAMPING_TIME]
        self.ms, self.mh = p[K.P_SHAFT_MASS], p[K.P_HOUSING_MASS]
        self.cs, self.kh, self.ch = (
            p[K.P_SHAFT_DAMPING],
            p[K.P_PEDESTAL_STIFFNESS],
            p[K.P_PEDESTAL_DAMPING],
        )
        self.wc, self.g = p[K.P_CAGE_SPEED], p[K.P_GRAVITY]
        self.load = np.array([p[K.P_LOAD_X], p[K.P_LOAD_Y]])
        self.offsets = 2 * np.pi * np.arange(self.z) / self.z
        w = prep.wav[0]
        self.k, self.a, self.ph = w[2], w[3], w[4]

    def __call__(self, t, y):
        theta = self.wc * t + self.offsets
        c, s = np.cos(theta), np.sin(theta)
        xs, ys, xh, yh, vxs, vys, vxh, vyh = y
        wav = self.a * np.cos(self.k * theta + self.ph)
        dwav = -self.a * self.k * self.wc * np.sin(self.k * theta + self.ph)
        d = xs * c + ys * s - self.gap + wav
        dd = vxs * c + vys * s + self.wc * (-xs * s + ys * c) + dwav
        dp = np.maximum(d, 0.0)
        root = np.sqrt(dp)
        q = np.maximum(self.kt * dp * root + self.tau * 1.5 * self.kt * root * dd, 0.0)
        fx, fy = q @ c, q @ s
        return np.array(
            [
                vxs,
                vys,
                vxh,
                vyh,
                (-fx + self.load[0] - self.cs * vxs) / self.ms,
                (-fy + self.load[1] - self.cs * vys) / self.ms - self.g,
                (fx - self.ch * vxh - self.kh * xh) / self.mh,
                (fy - self.ch * vyh - self.kh * yh) / self.mh - self.g,
            ]
        )


def run_solve_ivp(method, rtol, settings, prep):
    model = NumpyShaftModel(prep)
    t_first = settings.settle_time
    n = int(round(settings.duration * settings.fs))
    t_eval = t_first + np.arange(n) / settings.fs
    atol = np.r_[np.full(4, 1e-12), np.full(4, 1e-9)]
    sol = integrate.solve_ivp(
        model, (0.0, t_eval[-1]), prep.y0, method=method, t_eval=t_eval, rtol=rtol, atol=atol
    )
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol.y[7], sol.nfev


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="0.5 s records, fewer settings")
    args = parser.parse_args(argv)
    duration = 0.5 if args.quick else 1.0
    settings = SimulationSettings(
        fs=25600.0, duration=duration, settle_time=0.1, channels=(CHANNEL,)
    )
    simulated = duration + settings.settle_time
    print(
        f"# dynamic model benchmark: 6205, 1800 rpm, 500 N, outer N_w = 9, 1 um; "
        f"{duration:g} s record + {settings.settle_time:g} s settling; one core"
    )

    ref = simulate(
        GEOMETRY,
        OPERATING,
        DEFECT,
        scene=Scene(level="full", ehl=True),
        settings=dataclasses.replace(settings, step=1e-6),
    )
    bpfo = ref.frequencies.bpfo
    a_ref = bpfo_amplitude(ref[CHANNEL], ref.fs, bpfo)
    print(f"reference full/ehl, RK4 1 us: BPFO amplitude {a_ref * 1e3:.5f} mm/s\n")
    print(f"{'scene':<22s} {'step [us]':>10s} {'wall/sim s':>11s} {'BPFO err %':>11s}")
    compiled = {}
    for level in ("shaft", "shaft+housing", "full"):
        for ehl in (False, True):
            scene = Scene(level=level, ehl=ehl)
            simulate(
                GEOMETRY,
                OPERATING,
                DEFECT,
                scene=scene,  # compile/load the cache
                settings=dataclasses.replace(settings, duration=0.01, settle_time=0.0),
            )
            wall, r = timed(
                lambda scene=scene: simulate(
                    GEOMETRY, OPERATING, DEFECT, scene=scene, settings=settings
                )
            )
            err = abs(bpfo_amplitude(r[CHANNEL], r.fs, bpfo) / a_ref - 1) * 100
            step = r.parameters["integrator_stats"]["step_s"] * 1e6
            compiled[scene.label] = wall / simulated
            print(f"{scene.label:<22s} {step:10.2f} {wall / simulated:11.4f} {err:11.3f}")

    # -------- shaft scene (dry) vs solve_ivp at equal accuracy
    scene = Scene(level="shaft", ehl=False)
    conv = simulate(
        GEOMETRY, OPERATING, DEFECT, scene=scene, settings=dataclasses.replace(settings, step=2e-6)
    )
    a_conv = bpfo_amplitude(conv[CHANNEL], conv.fs, bpfo)
    print(f"\nshaft/dry converged (RK4 2 us): BPFO {a_conv * 1e3:.5f} mm/s; target: within 1 %")
    prep = prepare(GEOMETRY, OPERATING, DEFECT, scene=scene, settings=settings)
    # the loosest setting of each integrator within 1 % in the BPFO line and in the bands
    best: dict[str, dict[str, float]] = {"line": {}, "band": {}}

    def keep(name: str, seconds: float, line_err: float, band_err: float) -> None:
        for key, err in (("line", line_err), ("band", band_err)):
            if err <= 0.01 and name not in best[key]:
                best[key][name] = seconds

    for step in (1e-4, 5e-5, 4e-5, 2e-5):
        st = dataclasses.replace(settings, step=step)
        wall, r = timed(
            lambda st=st: simulate(GEOMETRY, OPERATING, DEFECT, scene=scene, settings=st), repeat=5
        )
        err = abs(bpfo_amplitude(r[CHANNEL], r.fs, bpfo) / a_conv - 1)
        band = band_error(conv[CHANNEL], r[CHANNEL], settings.fs)
        print(
            f"  compiled RK4 step {step * 1e6:6.1f} us: {wall / simulated:9.5f} s/s, "
            f"error {err * 100:.3f} %, bands {band * 100:.2f} %"
        )
        keep("compiled", wall / simulated, err, band)
    for method in ("RK45", "LSODA"):
        for rtol in (1e-3, 1e-4, 1e-5, 1e-6) if not args.quick else (1e-4, 1e-5):
            t0 = time.perf_counter()
            try:
                x, nfev = run_solve_ivp(method, rtol, settings, prep)
            except RuntimeError as exc:
                print(f"  solve_ivp {method} rtol {rtol:g}: failed ({exc})")
                continue
            wall = time.perf_counter() - t0
            err = abs(bpfo_amplitude(x, settings.fs, bpfo) / a_conv - 1)
            band = band_error(conv[CHANNEL], x, settings.fs)
            print(
                f"  solve_ivp {method:5s} rtol {rtol:6.0e}: {wall / simulated:9.3f} s/s, "
                f"{nfev} evaluations, error {err * 100:.3f} %, bands {band * 100:.2f} %"
            )
            keep(method, wall / simulated, err, band)
            if method in best["line"] and method in best["band"]:
                break
    print()
    for key, what in (("line", "the BPFO line"), ("band", "the octave bands")):
        if "compiled" not in best[key]:
            continue
        for method in ("RK45", "LSODA"):
            if method in best[key]:
                print(
                    f"shaft scene speed-up over solve_ivp {method} at <= 1 % error in {what}: "
                    f"{best[key][method] / best[key]['compiled']:.0f}x"
                )
    print(
        f"full scene with EHL: {compiled.get('full/ehl', float('nan')):.3f} s per simulated "
        "second (issue 22: 0.12 s or less)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
