"""Call every compiled entry point once and print each one's cache hits and misses (JSON).

Run as a script (``python tests/kernel_warmer.py``; ``PART/PARTS`` for a share of the runs,
``--processes N`` for N such shares side by side, as ``make test`` does before pytest). The
suite also starts it in the background at the beginning of a session (tests/conftest.py):
numba compiles one specialisation per (scene, film) pair and integrator, about 2.5 minutes on
one core from an empty cache, and a second core can do that while the first runs tests (each
loads what is already cached instead of compiling it); after ``make test``'s pre-compilation
it only loads. ``tests_generators/test_kernels_cache.py`` reads its report and then checks
that a second process finds every specialisation in the cache. Specialisations are compiled
in the order the suite first needs them.
"""

from __future__ import annotations

import json


def warm(part: int = 0, parts: int = 1) -> dict[str, list]:
    """Call every entry point once; return name, cache hits and misses per entry point.

    ``part`` of ``parts``: only every ``parts``-th run from the ``part``-th (so that several
    processes can compile disjoint sets side by side); the report covers every entry point.
    """
    from generators import _integrators as integrators
    from generators import _lanes as lanes
    from generators import bearing, simulate
    from generators.model import prepare, simulate_lanes
    from generators.params import OperatingCondition, Rig, Scene, SimulationSettings

    b = bearing("6205")
    op = OperatingCondition.from_rpm(1800, 500)
    runs = []
    lane_runs = []  # the costly compilations (about 30-80 s each), dealt out first
    for level in ("shaft+housing", "shaft", "full"):
        for ehl in (True, False):
            scene = Scene(level=level, ehl=ehl)
            settings = SimulationSettings(fs=12000, duration=0.002, settle_time=0.0)
            runs.append(
                lambda scene=scene, settings=settings: simulate(
                    b, op, scene=scene, settings=settings
                )
            )
            if level != "full":
                lane_runs.append(
                    lambda scene=scene, settings=settings: simulate_lanes(
                        [prepare(b, op, scene=scene, settings=settings)], "housing_acceleration_y"
                    )
                )
    entrained = Rig(film_entrainment_factor=1.0)
    for level in ("shaft+housing", "shaft"):  # the film's entrainment (massless balls only)
        scene = Scene(level=level, ehl=True)
        for integrator in ("rk4", "dopri5"):
            settings = SimulationSettings(
                fs=12000, duration=0.002, settle_time=0.0, integrator=integrator
            )
            runs.append(
                lambda scene=scene, settings=settings: simulate(
                    b, op, scene=scene, rig=entrained, settings=settings
                )
            )
    settings = SimulationSettings(fs=12000, duration=0.002, settle_time=0.0)
    lane_runs.append(  # the entrainment's lanes: shaft+housing only (generators._lanes.LANE_PAIRS)
        lambda settings=settings: simulate_lanes(
            [prepare(b, op, rig=entrained, settings=settings)], "housing_acceleration_y"
        )
    )
    for level in ("shaft+housing", "shaft", "full"):
        for ehl in (True, False):
            settings = SimulationSettings(
                fs=12000, duration=0.002, settle_time=0.0, integrator="dopri5"
            )
            scene = Scene(level=level, ehl=ehl)
            runs.append(
                lambda scene=scene, settings=settings: simulate(
                    b, op, scene=scene, settings=settings
                )
            )
    runs = lane_runs + runs  # each process gets its share of the lanes
    for run in runs[part::parts]:
        run()
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


def warm_in_processes(processes: int) -> int:
    """Compile every specialisation in ``processes`` processes side by side (exit status).

    What ``make test`` runs before pytest's workers start: from an empty cache two processes
    compile everything in about 1.5 minutes where one takes about 2.5. A share that fails is
    run once more alone, after the others have finished: numba's cache is not safe against
    processes that compile the same callee side by side (its issue tracker reports such races,
    e.g. numba/numba#10128 for GUFuncs), and once in a few empty-cache runs a share stopped
    with a TypingError on the shared ``_rhs`` (stop 80, a CI run; the same commit passed on the
    next run).
    """
    import subprocess
    import sys

    def share(part: int) -> subprocess.Popen:
        command = [sys.executable, __file__, f"{part}/{processes}"]
        return subprocess.Popen(command, stdout=subprocess.DEVNULL)

    children = {part: share(part) for part in range(processes)}
    failed = [part for part, child in children.items() if child.wait() != 0]
    for part in failed:
        print(
            f"kernel_warmer: share {part}/{processes} failed; running it again alone",
            file=sys.stderr,
        )
    return max((share(part).wait() for part in failed), default=0)


if __name__ == "__main__":
    import sys

    if len(sys.argv) > 2 and sys.argv[1] == "--processes":
        sys.exit(warm_in_processes(int(sys.argv[2])))
    part, parts = (int(v) for v in sys.argv[1].split("/")) if len(sys.argv) > 1 else (0, 1)
    print(json.dumps(warm(part, parts)))
