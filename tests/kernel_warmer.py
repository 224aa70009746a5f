"""Call every compiled entry point once and print each one's cache hits and misses (JSON).

Run as a script (``python tests/kernel_warmer.py``). The suite starts it in the background at
the beginning of a session (tests/conftest.py): numba compiles one specialisation per (scene,
film) pair and integrator, about 2.5 minutes on one core from an empty cache, and a second
core can do that while the first runs tests (each loads what is already cached instead of
compiling it). ``tests_generators/test_kernels_cache.py`` reads its report and then checks
that a second process finds every specialisation in the cache. Specialisations are compiled
in the order the suite first needs them.
"""

from __future__ import annotations

import json


def warm() -> dict[str, list]:
    """Call every entry point once; return name, cache hits and misses per entry point."""
    from generators import _integrators as integrators
    from generators import _lanes as lanes
    from generators import bearing, simulate
    from generators.model import prepare, simulate_lanes
    from generators.params import OperatingCondition, Scene, SimulationSettings

    b = bearing("6205")
    op = OperatingCondition.from_rpm(1800, 500)
    for level in ("shaft+housing", "shaft", "full"):
        for ehl in (True, False):
            scene = Scene(level=level, ehl=ehl)
            settings = SimulationSettings(fs=12000, duration=0.002, settle_time=0.0)
            simulate(b, op, scene=scene, settings=settings)
            if level != "full":
                simulate_lanes(
                    [prepare(b, op, scene=scene, settings=settings)], "housing_acceleration_y"
                )
    for level in ("shaft+housing", "shaft", "full"):
        for ehl in (True, False):
            settings = SimulationSettings(
                fs=12000, duration=0.002, settle_time=0.0, integrator="dopri5"
            )
            simulate(b, op, scene=Scene(level=level, ehl=ehl), settings=settings)
    tables = (
        ("rk4", integrators.RK4),
        ("dopri5", integrators.DOPRI5),
        ("rhs", integrators.RHS),
        ("lanes", lanes.RK4),
    )
    return {
        f"{kind} {pair}": [
            entry.__name__,
            sum(entry.stats.cache_hits.values()),
            sum(entry.stats.cache_misses.values()),
        ]
        for kind, table in tables
        for pair, entry in table.items()
    }


if __name__ == "__main__":
    print(json.dumps(warm()))
