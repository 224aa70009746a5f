"""Shared fixtures: seeded rng, location of the measured recordings in ../shared/data."""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from typing import IO

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED_DATA = REPO.parent / "shared" / "data"


@dataclass
class KernelWarmer:
    """The background process that compiles every kernel specialisation (kernel_warmer.py)."""

    proc: subprocess.Popen
    stdout: IO[str]
    stderr: IO[str]

    def result(self, timeout: float = 900.0) -> tuple[int, str, str]:
        """Wait for it: (exit code, its stdout, the end of its stderr)."""
        code = self.proc.wait(timeout=timeout)
        self.stdout.seek(0)
        self.stderr.seek(0)
        return code, self.stdout.read(), self.stderr.read()[-4000:]


@pytest.fixture(scope="session", autouse=True)
def kernel_warmer():
    """Compile the kernels on a second core while the first runs tests (numba's disk cache is
    shared: a test that needs a specialisation the warmer has built loads it)."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        proc = subprocess.Popen(
            [sys.executable, str(REPO / "tests" / "kernel_warmer.py")],
            cwd=REPO,
            env=env,
            stdout=out,
            stderr=err,
            text=True,
        )
        yield KernelWarmer(proc, out, err)
        if proc.poll() is None:
            proc.kill()
        proc.wait()


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
def small_bundle(small_dataset):
    """``cmtool train``'s defaults on ``datasets/small`` (trained once per session: the
    diagnosis tests and the small target share it)."""
    from cmtool.classifier import train

    recipe = pathlib.Path(__file__).resolve().parents[1] / "datasets" / "small" / "recipe.toml"
    return train(small_dataset, recipe=recipe.read_text())
