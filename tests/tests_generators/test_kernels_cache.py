"""The compiled entry points: one per (scene, film) pair, each cached under its own name.

``generators._integrators`` and ``generators._lanes`` build their entry points with one factory
per integrator (a closure over the scene and film codes). numba keys its cache on the
closure's values, so each pair must be compiled once and then loaded by any later process:
the session's kernel warmer (tests/kernel_warmer.py, started by tests/conftest.py) calls every
entry point in a process of its own; a second process must find every one in the cache.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from generators import _integrators
from generators import _kernels as K
from generators import _lanes as L

REPO = Path(__file__).resolve().parents[2]

WARMER = REPO / "tests" / "kernel_warmer.py"


def _child() -> dict:
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    out = subprocess.run(
        [sys.executable, str(WARMER)],
        capture_output=True,
        text=True,
        cwd=REPO,
        env=env,
        timeout=900,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_entry_points_cover_every_pair_with_named_codes():
    assert (
        set(_integrators.RK4)
        == set(_integrators.DOPRI5)
        == set(_integrators.RHS)
        == {(scene, film) for scene in K.SCENE_NAMES for film in K.FILM_NAMES}
        - {(K.SCENE_FULL, K.FILM_ENTRAINED)}  # the film's entrainment: massless balls only
    )
    assert set(L.RK4) == {(scene, film) for scene in L.LANE_SCENES for film in L.LANE_FILMS} - {
        (K.SCENE_SHAFT, K.FILM_ENTRAINED)  # the entrainment's table: in shaft+housing's lanes
    }
    assert set(L.LANE_FILMS) == set(K.FILM_NAMES)
    assert _integrators.RK4[K.SCENE_SHAFT_HOUSING, K.FILM_EHL].__name__ == "_rk4_shaft_housing_ehl"
    names = [
        entry.__name__
        for table in (_integrators.RK4, _integrators.DOPRI5, _integrators.RHS, L.RK4)
        for entry in table.values()
    ]
    assert len(set(names)) == len(names) == 29


@pytest.mark.validation
def test_a_second_process_loads_every_specialisation_from_the_cache(kernel_warmer):
    """The session's kernel warmer (tests/conftest.py) called every entry point in a process
    of its own, compiling what the cache lacked; a second process must load every one."""
    code, stdout, stderr = kernel_warmer.result()
    assert code == 0, stderr
    first = json.loads(stdout.strip().splitlines()[-1])
    assert len(first) == 29 and all(hits + misses == 1 for _, hits, misses in first.values())
    second = _child()
    missed = {key: value for key, value in second.items() if value[1:] != [1, 0]}
    assert not missed, missed


def test_a_changed_kernel_source_drops_the_cached_code_of_every_kernel_module(tmp_path):
    """numba keys a cached function on its own file; the kernel modules inline each other's
    functions, so a change of any kernel source must remove all their cache files (and only
    theirs), once (generators/kernel_cache.py)."""
    from generators import kernel_cache as guard

    names = [
        "_kernels._hertz_dry-195.py311.1.nbc",
        "_kernels._hertz_dry-195.py311.nbi",
        "_lanes._rk4_impl-542.py311.nbi",
        "_integrators._rk4_full_ehl-439.py311.2.nbc",
        "_static_kernels._static_newton-57.py311.nbi",
        "model.something-1.py311.nbi",  # another module's: kept
        "_kernels.cpython-311.pyc",  # bytecode: kept
    ]
    for name in names:
        (tmp_path / name).write_bytes(b"x")
    assert guard.clear_stale(tmp_path, "a" * 64) == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["model.something-1.py311.nbi", "_kernels.cpython-311.pyc", guard.STAMP]
    )
    (tmp_path / names[0]).write_bytes(b"x")  # compiled again under the same sources
    assert guard.clear_stale(tmp_path, "a" * 64) == 0 and (tmp_path / names[0]).exists()
    assert guard.clear_stale(tmp_path, "b" * 64) == 1  # another source change


def test_the_kernel_sources_digest_is_recorded_beside_the_live_cache():
    """After the kernels are imported, their cache directory records the current sources."""
    from generators import kernel_cache as guard

    cache = Path(K._hertz_dry._cache._cache_path)
    package = Path(K.__file__).parent
    assert (cache / guard.STAMP).read_text().strip() == guard.sources_digest(package)
