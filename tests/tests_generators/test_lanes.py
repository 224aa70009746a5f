"""The SIMD-lane RK4 (``generators._lanes`` via ``simulate_lanes``), the dataset generator's path.

Checked against the one-signal path (``simulate``): the same RK4, schedule and dense output
with the operations grouped differently, so the signals agree to rounding (relative 1e-9 is
a million times looser than the 1e-15 of a float64 operation and a million times tighter than
any modelling error). A lane's bytes must not depend on its neighbours or on the width of its
block (datasets are byte-identical whatever the chunking and the number of workers).
"""

import dataclasses

import numpy as np
import pytest

from generators import (
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    Scene,
    SimulationSettings,
    Waviness,
    _lanes,
    bearing,
    simulate,
)
from generators.batches import _row_padding
from generators.model import lanes_supported, prepare, simulate_lanes

G = bearing("6205")
CHANNEL = "housing_acceleration_y"


def _settings(**kw):
    base = dict(fs=6400.0, duration=0.05, settle_time=0.02, integrator="rk4", channels=(CHANNEL,))
    return SimulationSettings(**{**base, **kw})


def _defects(surface):
    if surface is None:
        return []
    order = {"outer": 9, "inner": 10, "ball": 4}[surface]
    return [Waviness(surface=surface, order=order, amplitude=1e-6)]


def _preps(level, ehl, surface, n, settings=None):
    settings = settings or _settings()
    return [
        prepare(
            G,
            OperatingCondition.from_rpm(1200 + 61 * i, 300 + 23 * i),
            _defects(surface),
            scene=Scene(level=level, ehl=ehl),
            settings=settings,
            random_state=i,
        )
        for i in range(n)
    ]


@pytest.mark.parametrize("level", ["shaft", "shaft+housing"])
@pytest.mark.parametrize("ehl", [False, True])
@pytest.mark.parametrize("surface", [None, "outer", "inner", "ball"])
def test_lanes_agree_with_simulate(level, ehl, surface):
    preps = _preps(level, ehl, surface, 3)
    lanes = simulate_lanes(preps, CHANNEL)
    for i, prep in enumerate(preps):
        ref = simulate(
            G,
            prep.operating,
            _defects(surface),
            scene=Scene(level=level, ehl=ehl),
            settings=_settings(),
            random_state=i,
        )[CHANNEL]
        assert lanes[i].shape == ref.shape
        scale = np.max(np.abs(ref))
        assert scale > 0
        assert np.max(np.abs(lanes[i] - ref)) <= 1e-9 * scale


def test_lanes_agree_without_decimation_and_with_dense_output():
    # 25.6 kHz with a 100 us step: one record per step is interpolated (Hermite), no FIR
    channel = "shaft_displacement_y"
    settings = _settings(fs=25600.0, step=1e-4, settle_time=0.0, channels=(channel,))
    preps = _preps("shaft", False, "outer", 2, settings)
    lanes = simulate_lanes(preps, channel)
    for i, prep in enumerate(preps):
        ref = simulate(
            G,
            prep.operating,
            _defects("outer"),
            scene=Scene(level="shaft", ehl=False),
            settings=settings,
            random_state=i,
        )[channel]
        assert np.max(np.abs(lanes[i] - ref)) <= 1e-9 * np.max(np.abs(ref))


@pytest.mark.parametrize(("level", "ehl"), [("shaft", False), ("shaft+housing", True)])
def test_a_lane_does_not_depend_on_its_block(level, ehl):
    preps = _preps(level, ehl, "outer", 17)
    target = preps[5]
    others = [p for p in preps if p is not target]
    alone = simulate_lanes([target], CHANNEL)[0]
    for width, position in ((3, 2), (8, 0), (8, 7), (13, 6), (17, 16)):
        block = others[: width - 1]
        block.insert(position, target)
        got = simulate_lanes(block, CHANNEL)[position]
        assert np.array_equal(got, alone), (width, position)


def test_a_diverging_lane_is_reported_and_leaves_the_others_alone():
    preps = _preps("shaft", False, "outer", 4)
    # the same run with a runaway limit below its static displacement: diverges at once
    bad = prepare(
        G,
        preps[2].operating,
        _defects("outer"),
        scene=Scene(level="shaft", ehl=False),
        settings=dataclasses.replace(_settings(), max_displacement=1e-9),
        random_state=2,
    )
    mixed = simulate_lanes([preps[0], bad, preps[1]], CHANNEL)
    clean = simulate_lanes([preps[0], preps[1]], CHANNEL)
    assert isinstance(mixed[1], Exception) and "runaway" in str(mixed[1])
    assert np.array_equal(mixed[0], clean[0]) and np.array_equal(mixed[2], clean[1])


def test_groups_with_different_layouts_in_one_call():
    preps = _preps("shaft", False, None, 2) + _preps("shaft", False, "ball", 2)
    preps += _preps("shaft+housing", False, "inner", 2)
    out = simulate_lanes(preps, CHANNEL)
    for prep, got in zip(preps, out, strict=True):
        assert np.array_equal(got, simulate_lanes([prep], CHANNEL)[0])


def test_what_the_lanes_do_not_take():
    defect = LocalizedDefect(surface="outer", length=0.5e-3, depth=1e-5, position=0.0)
    pit = prepare(G, OperatingCondition.from_rpm(1800, 500), defect, settings=_settings())
    full = _preps("full", False, None, 1)[0]
    dopri = _preps("shaft", False, None, 1, _settings(integrator="dopri5"))[0]
    # more waviness rows than the stack tables hold (8 ball harmonics x 9 balls = 72 rows)
    many = prepare(
        G,
        OperatingCondition.from_rpm(1800, 500),
        [Waviness(surface="ball", order=2 * (h + 1), amplitude=1e-7) for h in range(8)],
        scene=Scene(level="shaft", ehl=False),
        settings=_settings(),
    )
    assert many.wav.shape[0] >= _lanes.MAX_ROWS
    for prep in (pit, full, dopri, many):
        assert not lanes_supported(prep)
    assert lanes_supported(_preps("shaft+housing", True, "ball", 1)[0])
    with pytest.raises(ParameterError, match="cannot run in lanes"):
        simulate_lanes([full], CHANNEL)
    with pytest.raises(ParameterError, match="channel = 'housing_jerk_y'"):
        simulate_lanes(_preps("shaft", False, None, 1), "housing_jerk_y")


@pytest.mark.parametrize("n_record", [1, 512, 6400, 25600, 25601, 102400])
def test_output_rows_are_padded_off_the_4k_stride(n_record):
    # every lane's record k is stored in the same pass: rows a multiple of 4 KiB apart would
    # all land in one L1 set; padded rows start one cache line apart (mod 4 KiB)
    pad = _row_padding(n_record)
    assert 0 <= pad < 512
    assert ((n_record + pad) * 8) % 4096 == 64


def test_a_workspace_is_reused_and_changes_nothing():
    # records at the output rate (no decimation): the results are views of the buffers
    settings = _settings(fs=25600.0, step=1e-4, oversample=1)
    preps = _preps("shaft", False, "outer", 40, settings=settings)  # blocks of 32 and 8 lanes
    fresh = simulate_lanes(preps, CHANNEL)
    workspace: list = []
    first = simulate_lanes(preps, CHANNEL, workspace=workspace)
    assert len(workspace) == 2
    assert all(np.array_equal(a, b) for a, b in zip(first, fresh, strict=True))
    assert np.shares_memory(first[0], workspace[0]) and np.shares_memory(first[35], workspace[1])
    buffers = [b.ctypes.data for b in workspace]
    # a narrower call into the same buffers (views of the previous call are overwritten)
    second = simulate_lanes(preps[:3], CHANNEL, workspace=workspace)
    assert [b.ctypes.data for b in workspace] == buffers
    assert all(np.array_equal(a, b) for a, b in zip(second, fresh[:3], strict=True))
    # records of another length: the buffer is replaced
    longer = _preps("shaft", False, "outer", 2, settings=_settings(duration=0.08, step=1e-4))
    third = simulate_lanes(longer, CHANNEL, workspace=workspace)
    assert workspace[0].ctypes.data != buffers[0]
    assert all(
        np.array_equal(a, simulate_lanes([p], CHANNEL)[0])
        for a, p in zip(third, longer, strict=True)
    )
