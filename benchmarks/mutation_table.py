"""Mutation check of the test suite (issue 23): plant one physics error at a time and report
which test fails first. Every mutation must make at least one test fail.

Run (about 1-3 minutes per mutation on two cores): python benchmarks/mutation_table.py
Each run is ``pytest -x`` over the generators and validation tests with the plugin
``tests/mutants.py`` (``CMTOOL_MUTANT=<name>``); the table gives the first failing test.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from mutants import MUTANTS  # noqa: E402

SUITES = ["tests/tests_generators", "tests/tests_validation"]


def main() -> int:
    print("| mutation | what changes | first failing test | s |")
    print("|---|---|---|---|")
    survived = []
    for name, what in MUTANTS.items():
        start = time.perf_counter()
        env = {**os.environ, "CMTOOL_MUTANT": name, "PYTHONPATH": str(ROOT / "tests")}
        done = subprocess.run(
            [sys.executable, "-m", "pytest", "-x", "-q", "-p", "mutants", "-p", "no:cacheprovider"]
            + SUITES,
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
        )
        found = re.search(r"^FAILED (\S+)", done.stdout, re.MULTILINE)
        caught = found.group(1) if found else None
        if caught is None:
            survived.append(name)
        print(
            f"| {name} | {what} | {caught or 'NONE (survived)'} | "
            f"{time.perf_counter() - start:.0f} |",
            flush=True,
        )
    if survived:
        print(f"survived: {', '.join(survived)}")
    return 1 if survived else 0


if __name__ == "__main__":
    raise SystemExit(main())
