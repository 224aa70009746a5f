"""Shared fixtures: seeded rng, location of the measured recordings in ../shared/data."""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import tempfile
from typing import IO

import numpy as np
import pytest
from hypothesis import settings as hypothesis_settings

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED_DATA = REPO.parent / "shared" / "data"
#: Thread pools (OpenBLAS, OpenMP) capped at this session's share of the cores.
_THREAD_LIMITS: list = []

#: Under CI (``.ci/run`` runs with CI=true) the property tests draw the same examples in every
#: run, so that a landing is judged on the code and not on a draw; elsewhere they keep drawing
#: new ones (stop 80: a random draw of test_force_balance failed a suite run, on a tolerance of
#: the test's own). Loaded here, before the test modules build their own settings on it.
hypothesis_settings.register_profile("ci", derandomize=True)
if os.environ.get("CI"):
    hypothesis_settings.load_profile("ci")


def pytest_configure(config: pytest.Config) -> None:
    """Give each pytest-xdist worker its share of the cores for BLAS and OpenMP threads.

    Every worker's OpenBLAS and OpenMP (scikit-learn's gradient boosting) start as many
    threads as the machine has cores, and their threads spin while they wait: two workers on
    two cores then wait for each other's spinning threads (``tests/tests_cmtool/
    test_diagnosis.py`` on two workers: 159 s, 68 s with one thread each). The environment
    variables carry the limit into the processes the tests start (the CLI, process pools).
    """
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    if workers <= 1:
        return
    from threadpoolctl import threadpool_limits

    share = max(1, (os.cpu_count() or 1) // workers)
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(name, str(share))
    _THREAD_LIMITS.append(threadpool_limits(limits=share))


class KernelWarmer:
    """The background process that compiles every kernel specialisation (kernel_warmer.py).

    Started when the session starts in the test process that warms (the only one, or the
    first pytest-xdist worker: ``make test`` runs two), otherwise when a test first asks for
    its result (by then the cache holds what it compiles: it only loads).
    """

    def __init__(self, out: IO[str], err: IO[str], start: bool) -> None:
        self.stdout = out
        self.stderr = err
        self.proc: subprocess.Popen | None = None
        if start:
            self.start()

    def start(self) -> None:
        env = {**os.environ, "PYTHONPATH": str(REPO)}
        self.proc = subprocess.Popen(
            [sys.executable, str(REPO / "tests" / "kernel_warmer.py")],
            cwd=REPO,
            env=env,
            stdout=self.stdout,
            stderr=self.stderr,
            text=True,
        )

    def result(self, timeout: float = 900.0) -> tuple[int, str, str]:
        """Wait for it: (exit code, its stdout, the end of its stderr)."""
        if self.proc is None:
            self.start()
        code = self.proc.wait(timeout=timeout)
        self.stdout.seek(0)
        self.stderr.seek(0)
        return code, self.stdout.read(), self.stderr.read()[-4000:]

    def stop(self) -> None:
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait()


@pytest.fixture(scope="session", autouse=True)
def kernel_warmer():
    """Compile the kernels in a process of their own while the tests run (numba's disk cache is
    shared: a test that needs a specialisation the warmer has built loads it). Under
    pytest-xdist only the first worker starts it with the session: two warmers would compile
    the same kernels twice on the same two cores."""
    warms = os.environ.get("PYTEST_XDIST_WORKER", "gw0") == "gw0"
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        warmer = KernelWarmer(out, err, start=warms)
        yield warmer
        warmer.stop()


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(440)


@pytest.fixture
def shared_data() -> pathlib.Path:
    if not (SHARED_DATA / "MANIFEST.csv").is_file():
        pytest.skip("../shared/data is absent (a fresh clone alone has no measured recordings)")
    return SHARED_DATA


@pytest.fixture(scope="session")
def small_dataset():
    """The committed ``datasets/small`` (read once per session)."""
    from cmtool.datasets import read_dataset

    return read_dataset(pathlib.Path(__file__).resolve().parents[1] / "datasets" / "small")


@pytest.fixture(scope="session")
def small_bundle(small_dataset, tmp_path_factory):
    """``cmtool train``'s defaults on ``datasets/small`` (trained once per test run: the
    diagnosis tests and the small target share it).

    Under pytest-xdist the first worker to ask trains it and pickles it into the run's
    temporary folder, under a file lock; the other loads it (the same bundle: training is
    seeded and a pickle round trip is exact) instead of training it again (about 20 s).
    """
    import pickle

    from filelock import FileLock

    from cmtool.classifier import train

    recipe = pathlib.Path(__file__).resolve().parents[1] / "datasets" / "small" / "recipe.toml"
    if "PYTEST_XDIST_WORKER" not in os.environ:
        return train(small_dataset, recipe=recipe.read_text())
    shared = tmp_path_factory.getbasetemp().parent / "small_bundle.pickle"
    with FileLock(f"{shared}.lock"):
        if shared.is_file():
            return pickle.loads(shared.read_bytes())
        # two processes: the other test worker waits for this bundle meanwhile, and the
        # bundle is the same for any count (test_diagnosis.py, train on two workers)
        bundle = train(small_dataset, recipe=recipe.read_text(), workers=2)
        shared.write_bytes(pickle.dumps(bundle))
        return bundle
