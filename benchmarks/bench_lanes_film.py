"""What the lubricant film costs the lanes (prints figures; not a test).

256 healthy one-second 6205 signals at 12 kHz (1700-1800 rpm, 50-500 N, clearance -10 to 15
um, 0.1 s settling, the default RK4 step), generated on one worker thread, so that every run
goes through the SIMD lanes (``generators/_lanes.py``); milliseconds per signal, the whole call
(set-up, lanes, decimation, parquet) over the count, for the `shaft` and `shaft+housing` scenes
dry and the `shaft+housing` scene with EHL (the rig recipes' and the small recipe's scene).
Each setting runs ``--repeat`` times (default 2, after one warm-up call that loads the
kernels): this host's speed drifts, so compare figures of the same run.

Run: .venv/bin/python benchmarks/bench_lanes_film.py [--repeat K]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from cmtool.datasets import generate_dataset

COUNT = 256
RECIPE = """
name = "lanes-film"
seed = 1
chunk_size = 64
bearings = ["6205"]
[operating]
rpm = {{ min = 1700, max = 1800 }}
load_n = {{ min = 50, max = 500 }}
clearance_m = {{ min = -10e-6, max = 15e-6 }}
[model]
scene = "{scene}"
ehl = {ehl}
integrator = "rk4"
[sensor]
fs_hz = 12000
duration_s = 1.0
settle_s = 0.1
[[conditions]]
label = "healthy"
count = {count}
"""


def _run(scene: str, ehl: bool, count: int) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        recipe = Path(tmp) / "recipe.toml"
        text = RECIPE.format(scene=scene, ehl=str(ehl).lower(), count=count)
        recipe.write_text(text)
        start = time.perf_counter()
        generate_dataset(recipe, Path(tmp) / "out", workers=1)
        return (time.perf_counter() - start) / count


def main(repeat: int) -> None:
    for scene, ehl in (("shaft", False), ("shaft+housing", False), ("shaft+housing", True)):
        _run(scene, ehl, 8)  # the kernels loaded from numba's cache (or compiled)
        times = [_run(scene, ehl, COUNT) * 1e3 for _ in range(repeat)]
        label = f"{scene}/{'ehl' if ehl else 'dry'}"
        print(f"{label}: " + ", ".join(f"{t:.1f}" for t in times) + " ms per signal")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    main(parser.parse_args().repeat)
