"""The compiled entry points: one per (scene, film) pair, each cached under its own name.

``generators._integrators`` and ``generators._lanes`` build their entry points with one factory
per integrator (a closure over the scene and film codes). numba keys its cache on the
closure's values, so each pair must be compiled once and then loaded by any later process:
a child process calls every entry point, a second child must find every one in the cache.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from generators import _integrators
from generators import _kernels as K
from generators import _lanes as L

REPO = Path(__file__).resolve().parents[2]

CALL_EVERY_ENTRY = textwrap.dedent(
    """
    import json
    from generators import bearing, simulate
    from generators import _integrators, _lanes as L
    from generators.model import prepare, simulate_lanes
    from generators.params import OperatingCondition, Scene, SimulationSettings

    b = bearing("6205")
    op = OperatingCondition.from_rpm(1800, 500)
    for level in ("shaft", "shaft+housing", "full"):
        for ehl in (False, True):
            for integrator in ("rk4", "dopri5"):
                settings = SimulationSettings(
                    fs=12000, duration=0.002, settle_time=0.0, integrator=integrator
                )
                simulate(b, op, scene=Scene(level=level, ehl=ehl), settings=settings)
            if level != "full":
                settings = SimulationSettings(fs=12000, duration=0.002, settle_time=0.0)
                prep = prepare(b, op, scene=Scene(level=level, ehl=ehl), settings=settings)
                simulate_lanes([prep], "housing_acceleration_y")
    stats = {}
    tables = (
        ("rk4", _integrators.RK4),
        ("dopri5", _integrators.DOPRI5),
        ("rhs", _integrators.RHS),
        ("lanes", L.RK4),
    )
    for kind, table in tables:
        for pair, entry in table.items():
            stats[f"{kind} {pair}"] = [
                entry.__name__,
                sum(entry.stats.cache_hits.values()),
                sum(entry.stats.cache_misses.values()),
            ]
    print(json.dumps(stats))
    """
)


def _child() -> dict:
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    out = subprocess.run(
        [sys.executable, "-c", CALL_EVERY_ENTRY],
        capture_output=True,
        text=True,
        cwd=REPO,
        env=env,
        timeout=600,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_entry_points_cover_every_pair_with_named_codes():
    assert (
        set(_integrators.RK4)
        == set(_integrators.DOPRI5)
        == set(_integrators.RHS)
        == {(scene, film) for scene in K.SCENE_NAMES for film in K.FILM_NAMES}
    )
    assert set(L.RK4) == {(scene, film) for scene in L.LANE_SCENES for film in K.FILM_NAMES}
    assert _integrators.RK4[K.SCENE_SHAFT_HOUSING, K.FILM_EHL].__name__ == "_rk4_shaft_housing_ehl"
    names = [
        entry.__name__
        for table in (_integrators.RK4, _integrators.DOPRI5, _integrators.RHS, L.RK4)
        for entry in table.values()
    ]
    assert len(set(names)) == len(names) == 22


@pytest.mark.validation
def test_a_second_process_loads_every_specialisation_from_the_cache():
    first = _child()  # compiles whatever the cache lacks
    assert len(first) == 22 and all(hits + misses == 1 for _, hits, misses in first.values())
    second = _child()
    missed = {key: value for key, value in second.items() if value[1:] != [1, 0]}
    assert not missed, missed
