"""Discrete/random separation for envelope analysis.

A loaded bearing's varying compliance, the shaft's harmonics, gear meshes and the mains are
periodic: their spectra are lines, sharp at every harmonic. A local fault's impacts arrive with
random jitter (ball-pocket play, slip: 1-2 %, Randall and Antoni 2011), so at the resonances
where they ring their spectrum is continuous. :func:`separate_discrete` removes every bin that
stands far above the local median of the amplitude spectrum, and its leakage (``NEIGHBOURS``
bins each side): the discrete part goes, the random part stays, and the envelope of what
remains shows a fault's rate but not a periodic machine's (Antoni and Randall 2004 separate
the same two parts with a delayed-correlation filter).

Threshold, fixed from noise statistics: the bins of a Gaussian noise's spectrum are Rayleigh
distributed, P(|X| > k median) = exp(-(1.177 k)^2 / 2); ``LINE_DB = 10`` (k = 3.16) takes one
noise bin in a thousand (with its two neighbours each side, 0.5 % of a noise's bins).

:func:`select_band` and :func:`fault_band` (the demodulation band) live in
:mod:`features.band_selection` since stop 78; this module still exports them.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from collections.abc import Sequence

import numpy as np
from scipy import ndimage, sparse
from scipy.sparse import linalg as sparse_linalg

from ._validate import FeatureError, check_band, check_fs, check_positive, check_record
from .band_selection import (  # noqa: F401 (moved in stop 78, still exported here)
    ANALYSER_RATIO,
    BAND_FLOOR_FACTOR,
    BandSelection,
    candidate_bands,
    fault_band,
    select_band,
)
from .chirp_z import ChirpZ, unit_phasor
from .false_alarm import (  # noqa: F401 (moved in stop 56, still exported here)
    CALIBRATION_DB,
    FALSE_ALARM,
    FLOOR_BINS,
    SEARCHED_BINS,
    detection_threshold_db,
    line_false_alarm,
    plain_line_false_alarm,
    ratio_for_false_alarm,
)
from .instrument_floor import (  # noqa: F401 (moved in stop 77, still exported here)
    FLOOR_SKIP_DB,
    INSTRUMENT_FLOOR_DB,
    add_instrument_floor,
    instrument_floor_median,
)
from .lattice import held_offsets

__all__ = [
    "remove_harmonics",
    "remove_periodic",
    "separate_discrete",
    "discrete_over_random_db",
    "select_band",
    "BandSelection",
    "candidate_bands",
    "detection_threshold_db",
    "line_false_alarm",
    "plain_line_false_alarm",
    "ratio_for_false_alarm",
    "LINE_DB",
    "FALSE_ALARM",
    "instrument_floor_median",
]

#: A spectral bin this far above its local median is a discrete line [dB].
LINE_DB = 10.0
#: Width of the local median [Hz] (wider than a line's leakage, narrower than a resonance).
LINE_WINDOW_HZ = 20.0
#: Bins on each side of a line removed with it (its leakage: a tone between two bins puts
#: 64 % of its amplitude in the nearest bins, 21 % and 13 % two and three bins away).
NEIGHBOURS = 2
#: Lines of the harmonic families closer than this many bins are fitted jointly: their Hann
#: windows' overlap (the Gram matrix of the fit) is solved exactly. Farther apart it is under
#: 5e-5 (the Hann side lobes fall as the cube of the distance), and refinement passes take it
#: out. Harmonics closer than this to fs/2 are not fitted (their mirror images would overlap).
COUPLED_BINS = 20.0
#: Refinement passes of the joint fit (each leaves about 1e-4 of what the last one did).
MAX_PASSES = 6
#: Ridge on the Gram matrix: lines closer than about a hundredth of a bin are one line to a
#: record this long (their difference is a function of almost no weight), and they are fitted
#: as one; the ridge keeps their split, which the record cannot tell, finite.
RIDGE = 1e-4
#: The joint fit has settled when a refinement pass moved it by less than this fraction of the
#: record's Hann-weighted RMS (far below the instrument floor of ``separate_discrete``).
SETTLED = 1e-6
#: Bytes of harmonic-family transforms kept for the next record of the same length, rate and
#: fundamental (a dataset's operating points repeat, and setting a family's transforms up costs
#: about four times as much as the passes that use them; one holds about 80 bytes a sample:
#: 4 MB for 1 s at 48 kHz).
TRANSFORM_CACHE_BYTES = 64 * 2**20


def remove_harmonics(
    x: np.ndarray, fs: float, fundamentals: Sequence[float], offsets: Sequence[float] = ()
) -> np.ndarray:
    """Subtract every harmonic of each fundamental: the synchronous part of the signal.

    The harmonics k f0 below fs/2 of every fundamental are fitted to the record together by
    Hann-weighted least squares (the Hann weight keeps the leakage of other, stronger
    components out of weak bands: it falls as the cube of the frequency distance): the
    weighted projections on every line come from a chirp-z transform per family, and the
    overlap of lines closer than ``COUPLED_BINS`` bins, which the projections alone would
    count twice or miss, is solved for exactly (a sparse Gram matrix of the window's transform
    at the lines' differences, :func:`_hann_gram`). Two families whose lines fall within a
    bin of each other (a shaft harmonic and a ball-pass harmonic: on a 6205 at 1797 rpm
    harmonic 43 of the shaft is 0.5 Hz from harmonic 12 of BPFO) are fitted as well as one:
    fitting them in turn instead converges as the square of their windows' overlap (0.85 at
    half a bin), and four such passes left 6.6 % of a simulated healthy bearing's RMS, whose
    envelope then showed BPFO. A periodic component at an exactly known period (a simulated
    bearing's varying compliance at the ball-pass rate, a shaft's harmonics) leaves nothing
    but rounding; at a period known to 0.1 % the low harmonics go and the rest is left to
    :func:`separate_discrete`'s line editing.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fundamentals : sequence of float
        Fundamental frequencies [Hz] (each at least two periods in the record).
    offsets : sequence of float
        Further series of the last fundamental f0, the lines o + k f0 [Hz] for each offset
        o in (0, f0) (slices of a lattice, ``features.lattice``), fitted with the rest;
        none without fundamentals.

    Returns
    -------
    ndarray
        ``x`` minus its mean and the harmonic series.
    """
    x = check_record(x, function="remove_harmonics", min_length=64)
    fs = check_fs(fs)
    y = x - x.mean()
    n = y.size
    duration = n / fs
    families = []
    for i, f0 in enumerate(fundamentals):
        f0 = check_positive(f"fundamentals[{i}]", f0, unit="Hz")
        if f0 * duration < 4:  # fewer than four periods: the harmonics cannot be resolved
            continue
        count = int((0.5 * fs - COUPLED_BINS / duration) // f0)
        if count >= 1:  # none below fs / 2: nothing of it in the record to remove
            families.append((f0, 0.0, 1, count))
    if families and offsets and families[-1][0] == fundamentals[-1]:
        f0 = families[-1][0]
        for offset in offsets:  # o + k f0 from a coupling width over 0 Hz to one under fs/2
            first = math.floor((COUPLED_BINS / duration - offset) / f0) + 1
            last = math.floor((0.5 * fs - COUPLED_BINS / duration - offset) / f0)
            if last >= first:
                families.append((f0, float(offset), first, last - first + 1))
    if not families:
        return y
    weights = np.hanning(n)
    weights = weights / weights.sum()
    transforms = [_harmonic_transforms(n, *family, fs) for family in families]
    lines = np.concatenate([o + f0 * np.arange(k, k + c) for f0, o, k, c in families])
    solve = sparse_linalg.splu(_hann_gram(lines / fs, n)).solve
    splits = np.cumsum([c for *_, c in families])[:-1]
    total = np.zeros(n)
    scale = float(np.sqrt(np.sum(weights * y * y))) or 1.0
    moved = math.inf
    for _ in range(MAX_PASSES):
        projections = np.concatenate([t.analyse(y - total, weights) for t in transforms])
        amplitudes = np.split(2.0 * solve(projections), splits)
        fit = sum(t.synthesise(a) for t, a in zip(transforms, amplitudes, strict=True))
        step = float(np.sqrt(np.sum(weights * fit * fit))) / scale
        if step >= moved:  # a refinement that grows would not converge: keep the last fit
            break
        total += fit
        moved = step
        if step < SETTLED:
            break
    return y - total


def remove_periodic(
    x: np.ndarray,
    fs: float,
    fundamentals: Sequence[float],
    lattice: Sequence[float] = (),
    *,
    return_held: bool = False,
) -> np.ndarray | tuple[np.ndarray, tuple[float, ...]]:
    """:func:`remove_harmonics`, and the lattice slices the record holds fitted jointly.

    The last fundamental's series offset by each ``lattice`` offset that the record holds
    (``features.lattice.held_offsets``) are fitted with the harmonic series: step 1 of
    :func:`separate_discrete`. Where none is held, :func:`remove_harmonics`'s result itself.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fundamentals : sequence of float
        Fundamental frequencies [Hz].
    lattice : sequence of float
        Candidate offsets [Hz] in [0, f0) of the last fundamental f0's further series.
    return_held : bool
        Also return the offsets held [Hz].

    Returns
    -------
    ndarray
        ``x`` minus its mean, the harmonic series and the series held.
    held : tuple of float
        Only with ``return_held=True``.
    """
    y = remove_harmonics(x, fs, fundamentals)
    held: tuple[float, ...] = ()
    if lattice and fundamentals:
        held = held_offsets(y, fs, fundamentals[-1], lattice)
        if held:  # fitted again with the slices held, jointly (their lines couple)
            y = remove_harmonics(x, fs, fundamentals, held)
    return (y, held) if return_held else y


def _hann_gram(lines: np.ndarray, n: int) -> sparse.csc_matrix:
    """Gram matrix of the Hann-weighted fit of complex sinusoids at ``lines`` [cycles/sample].

    Entry (k, j) is W(lines[k] - lines[j]), W the transform of the unit-sum Hann window of
    ``n`` samples (``np.hanning``), kept for pairs closer than ``COUPLED_BINS`` bins (1/n
    each), with ``RIDGE`` on the diagonal. Hermitian; W(0) = 1.
    """
    order = np.argsort(lines)
    ordered = lines[order]
    reach = COUPLED_BINS / n
    ends = np.searchsorted(ordered, ordered + reach, side="right")
    # row k pairs line k with lines k .. ends[k] - 1: the rows one after the other
    counts = ends - np.arange(ordered.size)
    r = np.repeat(np.arange(ordered.size), counts)
    c = r + np.arange(r.size) - np.repeat(np.cumsum(counts) - counts, counts)
    values = _hann_transform(ordered[r] - ordered[c], n)
    upper = r != c
    r, c, values = (
        np.concatenate([r, c[upper]]),
        np.concatenate([c, r[upper]]),
        np.concatenate([values, np.conj(values[upper])]),
    )
    values = np.where(r == c, values + RIDGE, values)
    size = lines.size
    return sparse.csc_matrix((values, (order[r], order[c])), shape=(size, size))


def _hann_transform(nu: np.ndarray, n: int) -> np.ndarray:
    """Sum over t of w_t exp(-2 pi i nu t), w the unit-sum ``np.hanning(n)`` [nu: cycles/sample].

    The window is 1/2 - 1/2 cos(2 pi t / (n - 1)): three geometric sums (Dirichlet kernels)
    at nu and nu -/+ 1 / (n - 1), over the window's sum (n - 1) / 2.
    """

    def dirichlet(v: np.ndarray) -> np.ndarray:
        s = np.sin(np.pi * v)
        small = np.abs(s) < 1e-12
        ratio = np.sin(np.pi * v * n) / np.where(small, 1.0, s)
        return np.exp(-1j * np.pi * v * (n - 1)) * np.where(small, n, ratio)

    shift = 1.0 / (n - 1)
    total = 0.5 * dirichlet(nu) - 0.25 * (dirichlet(nu - shift) + dirichlet(nu + shift))
    return total / (0.5 * (n - 1))


class _HarmonicTransforms:
    """The two chirp-z transforms of one harmonic family, set up once for every pass.

    :meth:`analyse` gives the Hann-weighted projections of y on harmonics 1 .. count of f0,
    :meth:`synthesise` a series' sum in time: the analysis evaluates the weighted signal's
    transform at k f0 (k = 1 .. count), the synthesis the harmonic series at every sample, each in
    O((n + count) log(n + count)). Setting a transform up (its chirp and the filter's FFT)
    costs more than applying it, so the passes of :func:`remove_harmonics` share them,
    and so do records of the same length, rate and fundamental (:func:`_harmonic_transforms`).
    """

    def __init__(self, n: int, f0: float, offset: float, first: int, count: int, fs: float) -> None:
        step = f0 / fs  # turns per sample between neighbouring lines
        start = (offset + first * f0) / fs  # the series' first line
        self.analysis = ChirpZ(n, count, -step, start)
        self.synthesis = ChirpZ(count, n, step, 0.0)
        self.ramp = unit_phasor(start * np.arange(n, dtype=float))
        arrays = [self.ramp]
        for transform in (self.analysis, self.synthesis):
            arrays += [v for v in vars(transform).values() if isinstance(v, np.ndarray)]
        #: Memory held by the two transforms and the ramp [bytes] (counted once: the cache
        #: sums it over every kept family at each insert).
        self.nbytes = sum(a.nbytes for a in arrays)

    def analyse(self, y: np.ndarray, weights: np.ndarray) -> np.ndarray:
        """Hann-weighted projections of ``y`` on harmonics 1 .. count (``weights``: unit sum)."""
        return self.analysis(weights * y)

    def synthesise(self, amplitudes: np.ndarray) -> np.ndarray:
        """The real series sum of Re(a_k exp(2 pi i k f0 t)) at every sample."""
        return np.real(self.synthesis(amplitudes) * self.ramp)


_transform_cache: OrderedDict[tuple[int, float, float, int, int, float], _HarmonicTransforms] = (
    OrderedDict()
)
_transform_cache_lock = threading.Lock()


def _harmonic_transforms(
    n: int, f0: float, offset: float, first: int, count: int, fs: float
) -> _HarmonicTransforms:
    """:class:`_HarmonicTransforms` of one family, kept for the next record alike.

    The least recently used are dropped once the kept ones hold more than
    ``TRANSFORM_CACHE_BYTES``. The same transforms as made anew: the results are the same bits.
    """
    key = (n, f0, offset, first, count, fs)
    with _transform_cache_lock:
        if key in _transform_cache:
            _transform_cache.move_to_end(key)
            return _transform_cache[key]
    transforms = _HarmonicTransforms(n, f0, offset, first, count, fs)
    with _transform_cache_lock:
        _transform_cache[key] = transforms
        held = sum(t.nbytes for t in _transform_cache.values())
        while held > TRANSFORM_CACHE_BYTES and len(_transform_cache) > 1:
            held -= _transform_cache.popitem(last=False)[1].nbytes
    return transforms


def separate_discrete(
    x: np.ndarray,
    fs: float,
    *,
    fundamentals: Sequence[float] = (),
    line_db: float = LINE_DB,
    window_hz: float = LINE_WINDOW_HZ,
    lattice: Sequence[float] = (),
    return_held: bool = False,
    return_floor: bool = False,
) -> np.ndarray | tuple:
    """The random part of a signal: periodic components and discrete spectral lines removed.

    1. the harmonic series of each known ``fundamentals`` (:func:`remove_harmonics`), with
       the series of the last one offset by each ``lattice`` offset that the record holds
       (:func:`remove_periodic`: a wavy inner race's slices of the line lattice);
    2. a white floor ``INSTRUMENT_FLOOR_DB`` below the record's RMS is added, the floor of a
       good measurement chain, so that a noise-free simulated signal is judged as a recording
       of it would be; only where the record's own broadband floor lies less than
       ``FLOOR_SKIP_DB`` above it (a recording has a higher floor already and gets none), and
       drawn once per record length (``features.instrument_floor.FLOOR_SEED``) and scaled to
       the record, so that the random part is the same in any unit of the record
       (:func:`features.instrument_floor.add_instrument_floor`);
    3. in the spectrum of the whole record, a bin more than ``line_db`` above the median of its
       +/- ``window_hz`` / 2 neighbourhood is a line: it and ``NEIGHBOURS`` bins each side
       (its leakage) are removed.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fundamentals : sequence of float
        Known periodic rates [Hz] (e.g. the shaft's and the ball pass's).
    line_db : float
        Line threshold over the local median [dB], in (0, 300].
    window_hz : float
        Width of the running median [Hz] (at least 21 bins), in (0, fs/2].
    lattice : sequence of float
        Candidate offsets [Hz] in [0, f0) of further series of the last fundamental f0
        (``features.lattice.inner_race_lattice_offsets``), each fitted only where the record
        holds it; with none held the result is the same as without.
    return_held, return_floor : bool
        Also return the ``lattice`` offsets held and fitted [Hz]; the step 2 floor's RMS [U].

    Returns
    -------
    ndarray
        The random part, same length and unit as ``x`` (mean removed).
    held : tuple of float
        Only with ``return_held=True``.
    floor_rms : float
        Only with ``return_floor=True`` (after ``held``): 0 where the record has its own.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 1000.0; t = np.arange(4000) / fs
    >>> noise = np.random.default_rng(0).standard_normal(t.size)
    >>> shaft = sum(np.sin(2 * np.pi * k * 50.3 * t + k) for k in range(1, 9))
    >>> mains = 5 * np.sin(2 * np.pi * 60.0 * t)  # on a bin: the line editing takes it
    >>> rest = separate_discrete(10 * shaft + mains + noise, fs, fundamentals=(50.3,))
    >>> bool(np.std(rest - noise) < 0.3 * np.std(noise))
    True
    """
    spec, lines, held, floor_rms = _line_editing(x, fs, fundamentals, line_db, window_hz, lattice)
    random_part = np.fft.irfft(np.where(lines, 0.0, spec), np.size(x))
    extra = ((held,) if return_held else ()) + ((floor_rms,) if return_floor else ())
    return (random_part, *extra) if extra else random_part


#: Highest ``line_db`` of :func:`separate_discrete`: a line 300 dB (a factor 1e15) over its
#: floor is already beyond what float64 resolves beside it.
MAX_LINE_DB = 300.0


def _line_editing(
    x: np.ndarray,
    fs: float,
    fundamentals: Sequence[float],
    line_db: float,
    window_hz: float,
    lattice: Sequence[float] = (),
) -> tuple[np.ndarray, np.ndarray, tuple[float, ...], float]:
    """:func:`separate_discrete`'s spectrum after steps 1-2, edited bins, offsets held, floor."""
    x = check_record(x, function="separate_discrete", min_length=64)
    fs = check_fs(fs)
    if not 0.0 < check_positive("line_db", line_db, unit="dB") <= MAX_LINE_DB:
        raise FeatureError(
            f"line_db = {line_db!r} dB is outside the allowed range (0, {MAX_LINE_DB:g}] dB"
        )
    if not check_positive("window_hz", window_hz, unit="Hz") <= fs / 2:
        raise FeatureError(
            f"window_hz = {window_hz!r} Hz is outside the allowed range (0, fs/2 = {fs / 2:g}] Hz"
        )
    n = x.size
    y, held = remove_periodic(x, fs, fundamentals, lattice, return_held=True)
    y, spec, floor_rms = add_instrument_floor(x, y)
    mag = np.abs(spec)
    bins = max(21, int(round(window_hz * n / fs))) | 1
    floor = ndimage.median_filter(mag, size=bins, mode="nearest")
    lines = mag > 10.0 ** (line_db / 20.0) * floor
    for _ in range(NEIGHBOURS):
        lines[1:] |= lines[:-1].copy()
        lines[:-1] |= lines[1:].copy()
    lines[0] = True  # the mean
    return spec, lines, held, floor_rms


def discrete_over_random_db(
    x: np.ndarray,
    fs: float,
    band: tuple[float, float],
    fundamentals: Sequence[float] = (),
    *,
    line_db: float = LINE_DB,
    window_hz: float = LINE_WINDOW_HZ,
) -> float:
    """How discrete a band is: the lines :func:`separate_discrete` edits out over what it leaves.

    After the harmonic series of ``fundamentals`` are fitted and removed (they count for
    neither side), the power in ``band`` of the bins the line editing takes (lines over
    ``line_db`` above their local median, with their neighbours) over the power of the rest,
    the random part the envelope analysis reads.

    Parameters
    ----------
    x : ndarray
        Signal [U].
    fs : float
        Sample rate [Hz].
    band : (float, float)
        Band [Hz].
    fundamentals : sequence of float
        Fundamentals [Hz] whose harmonic series are removed first.
    line_db, window_hz : float
        As :func:`separate_discrete` [dB], [Hz].

    Returns
    -------
    float
        10 log10(P_lines / P_random) [dB]; inf when nothing random is left in the band.

    Examples
    --------
    >>> t = np.arange(12000) / 12000.0
    >>> noise = np.random.default_rng(0).normal(0.0, 0.1, t.size)
    >>> x = noise + sum(np.sin(2 * np.pi * f * t) for f in (1013.0, 1171.0, 1329.0))
    >>> round(discrete_over_random_db(x, 12000.0, (1000.0, 1400.0)), 1) > 20  # lines
    True
    >>> round(discrete_over_random_db(noise, 12000.0, (1000.0, 1400.0)), 1) < -10  # noise
    True
    """
    x = check_record(x, function="discrete_over_random_db", min_length=64)
    fs = check_fs(fs)
    low, high = check_band(band, fs)
    spec, lines, *_ = _line_editing(x, fs, fundamentals, line_db, window_hz)
    f = np.fft.rfftfreq(np.asarray(x).size, 1.0 / fs)
    inside = (f >= low) & (f <= high)
    inside[0] = False
    power = np.abs(spec) ** 2
    taken, left = float(np.sum(power[inside & lines])), float(np.sum(power[inside & ~lines]))
    return math.inf if left <= 0.0 else 10.0 * math.log10(max(taken, 1e-300) / left)
