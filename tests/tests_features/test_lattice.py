"""features.lattice: a wavy inner race's slices of the line lattice, found and fitted out."""

import numpy as np
import pytest

import features
from features import FeatureError, held_offsets, inner_race_lattice_offsets, separate_discrete

FS = 12000.0
SHAFT, BPFO, BPFI = 29.95, 107.36, 162.19  # a 6205 at 1797 rpm


def _comb(offset: float, spacing: float, lines: range, n: int, seed: int = 0) -> np.ndarray:
    """Lines at offset + k spacing, off the record's bins, with drawn amplitudes and phases."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / FS
    return sum(
        rng.uniform(0.5, 1.0) * np.cos(2 * np.pi * (offset + k * spacing) * t + rng.uniform(0, 6))
        for k in lines
    )


def test_inner_race_lattice_offsets_are_k_bpfi_modulo_bpfo_both_ways():
    offsets = inner_race_lattice_offsets(BPFO, BPFI, orders=3)
    expected = [(s * k * BPFI) % BPFO for k in (1, 2, 3) for s in (1, -1)]
    assert offsets == pytest.approx(expected, abs=1e-12)
    assert all(0.0 <= o < BPFO for o in offsets)
    assert len(inner_race_lattice_offsets(BPFO, BPFI)) == 2 * features.lattice.LATTICE_ORDERS
    assert features.inner_race_lattice_orders(3) == (1, -1, 2, -2, 3, -3)
    with pytest.raises(FeatureError, match="ball_pass_inner"):
        inner_race_lattice_offsets(BPFO, -1.0)
    with pytest.raises(FeatureError, match="orders = 0"):
        inner_race_lattice_offsets(BPFO, BPFI, orders=0)


def test_a_comb_is_held_and_noise_holds_none():
    rng = np.random.default_rng(72)
    n = 12000
    offset = BPFI % BPFO
    comb = _comb(offset, BPFO, range(5, 50), n)
    noise = rng.standard_normal(n)
    others = [o for o in inner_race_lattice_offsets(BPFO, BPFI) if abs(o - offset) > 2.0]
    # a comb 10 dB under the noise's RMS in all (0.05 of it per line): held; the others not
    scale = 0.3 * np.std(noise) / np.std(comb)
    assert held_offsets(noise + scale * comb, FS, BPFO, (offset, *others)) == (offset,)
    # noise alone, 40 records: no candidate held in any (the gate's false alarms are rare)
    held = [held_offsets(rng.standard_normal(n), FS, BPFO, others) for _ in range(40)]
    assert sum(map(len, held)) == 0
    # an offset within a bin of the series itself is never a slice of its own
    assert held_offsets(noise + _comb(0.5, BPFO, range(5, 50), n), FS, BPFO, (0.5,)) == ()
    # too few periods of the spacing in the record: nothing to read
    assert held_offsets(noise[:300], FS, BPFO, (offset,)) == ()


def test_nothing_held_leaves_the_separation_as_it_was_to_the_bit():
    rng = np.random.default_rng(3)
    n = 12000
    x = rng.standard_normal(n) + 3 * _comb(0.0, BPFO, range(1, 40), n) + np.sin(SHAFT * 2e-3)
    lattice = inner_race_lattice_offsets(BPFO, BPFI)
    assert (
        held_offsets(features.separation.remove_harmonics(x, FS, (SHAFT, BPFO)), FS, BPFO, lattice)
        == ()
    )
    with_lattice = separate_discrete(x, FS, fundamentals=(SHAFT, BPFO), lattice=lattice)
    assert np.array_equal(with_lattice, separate_discrete(x, FS, fundamentals=(SHAFT, BPFO)))


def _skirts(random_part: np.ndarray, noise_part: np.ndarray, offsets: tuple[float, ...]) -> float:
    """What ``random_part`` differs from ``noise_part`` by, in the bins 3 or more from every
    line o + k BPFO (the lines' leakage, not the lines), over ``noise_part``'s power there."""
    n = random_part.size
    f = np.fft.rfftfreq(n, 1 / FS)
    lines = np.concatenate([o + BPFO * np.arange(8, 50) for o in offsets])
    away = np.min(np.abs(f[:, None] - lines[None, :]), axis=1) >= 3 * FS / n
    away &= (f > 8 * BPFO) & (f < 50 * BPFO)
    difference = np.fft.rfft(random_part - noise_part)[away]
    return float(
        np.sum(np.abs(difference) ** 2) / np.sum(np.abs(np.fft.rfft(noise_part)[away]) ** 2)
    )


def test_a_held_slice_is_fitted_out_of_the_random_part():
    # the lines k BPFI + n BPFO (k = 1, 2) of a wavy inner race of Z lobes, off the bins, as a
    # wavy bearing's stand over its noise: the line editing takes their bins, not their
    # leakage, which then stays in the random part beside them; fitted as slices, it goes
    rng = np.random.default_rng(5)
    n = 12000
    noise = rng.standard_normal(n)
    offsets = ((BPFI % BPFO), (2 * BPFI) % BPFO)
    lattice_lines = sum(_comb(o, BPFO, range(8, 50), n, seed=i) for i, o in enumerate(offsets))
    x = noise + 0.3 * lattice_lines
    periodic = (SHAFT, BPFO)
    alone = separate_discrete(noise, FS, fundamentals=periodic)
    without = separate_discrete(x, FS, fundamentals=periodic)
    lattice = inner_race_lattice_offsets(BPFO, BPFI)
    fitted, held = separate_discrete(
        x, FS, fundamentals=periodic, lattice=lattice, return_held=True
    )
    assert set(offsets) <= set(held)  # what the separation says it fitted
    left_without, left_fitted = _skirts(without, alone, offsets), _skirts(fitted, alone, offsets)
    assert left_without > 0.1
    assert left_fitted < 0.2 * left_without
