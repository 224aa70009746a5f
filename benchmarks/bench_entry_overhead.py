"""Call overhead of the compiled entry points (issue 21: below a microsecond).

Each (scene, film) entry point is a numba dispatcher built by a factory
(``generators._kernels._rk4_entry`` and friends). The figure printed is the whole cost of one
Python call of the one-evaluation right-hand-side entry ``RHS[pair]`` (argument typing and
dispatch, the scratch arrays, one right-hand-side evaluation), and of an RK4 entry asked for
zero steps (dispatch, set-up and the first evaluation): upper bounds of the dispatch alone.

Run: .venv/bin/python benchmarks/bench_entry_overhead.py
"""

import time

import numpy as np

from generators import _integrators, bearing
from generators import _kernels as K
from generators.model import prepare
from generators.params import OperatingCondition, Scene, SimulationSettings

CALLS = 200_000


def per_call(fn, *args) -> float:
    fn(*args)  # compile or load
    start = time.perf_counter()
    for _ in range(CALLS):
        fn(*args)
    return (time.perf_counter() - start) / CALLS


def main() -> None:
    b = bearing("6205")
    op = OperatingCondition.from_rpm(1800, 500)
    for level, code in (("shaft", K.SCENE_SHAFT), ("shaft+housing", K.SCENE_SHAFT_HOUSING)):
        for film in K.FILM_NAMES:
            prep = prepare(
                b,
                op,
                scene=Scene(level=level, ehl=bool(film)),
                settings=SimulationSettings(duration=0.01),
            )
            y = prep.y0.copy()
            dydt = np.zeros_like(y)
            loads = np.zeros((2, b.ball_count))
            rhs = per_call(_integrators.RHS[code, film], 0.0, y, prep.p, prep.wav, dydt, loads)
            out_state = np.zeros((1, K.N_OUT_STATE))
            out_accel = np.zeros((1, K.N_OUT_ACCEL))
            out_loads = np.zeros((1, 2, b.ball_count))
            rk4 = per_call(
                _integrators.RK4[code, film],
                y,
                prep.p,
                prep.wav,
                0.0,
                1e-5,
                0,
                0.0,
                1e-5,
                0,
                out_state,
                out_accel,
                out_loads,
                False,
            )
            name = _integrators.RK4[code, film].__name__
            print(
                f"{name:26s} RHS entry {rhs * 1e9:6.0f} ns per call, "
                f"RK4 entry (0 steps) {rk4 * 1e9:6.0f} ns per call"
            )


if __name__ == "__main__":
    main()
