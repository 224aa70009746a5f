"""The longest RK4 step that meets an error bound, from the measured convergence of the run.

``SimulationSettings(error_bound=e)`` (recipes: ``model.error_bound``) asks for the longest
fixed RK4 step whose error stays under ``e`` (relative) in the amplitudes of the bearing's
characteristic lines and in the spectrum's octave bands above ``BAND_LOW``. The error is
measured, not assumed: three pilot runs of the prepared scene (same parameters, film,
defects, speed, record rate and settling), at steps h, h / 2 and h / 4, over the window the
run records (at most ``PILOT_MAX_DURATION``, at least ``PILOT_PERIODS`` periods of the
slowest characteristic rate).

* Lines (:func:`line_error`): the complex amplitudes of k f for f in (shaft, BPFO, BPFI,
  2 x BSF), k = 1..3, fitted by least squares on the housing acceleration (y); the largest
  change of a line as a fraction of the strongest line's amplitude (issue 22: "1 % of the
  fault-line amplitude"; each weak line's change relative to itself made the bound chase
  the fit's noise).
* Bands (:func:`band_error`): the relative change of the spectrum in each octave from
  ``BAND_LOW`` to 0.45 fs, the band an envelope analyst demodulates. The lines alone are not
  enough: a healthy 6205 at 1200 rpm and 25.6 kHz has its lines within 0.1 % at a 6e-5 s step
  while its 3-11.5 kHz band is off by 5 % (RK4's error on the contact's fast terms), which the
  rule detector reads as an outer-race fault (26 dB; at 2e-5 s: healthy; docs/performance.md).

For each, the changes from h to h / 2 (d1) and from h / 2 to h / 4 (d2) give the order the run
converges at, p = log2(d1 / d2) (RK4's 4 where the right-hand side is smooth; about 2 where a
contact opens and closes, as in the dry ``shaft`` scene), and Richardson's estimate of the
error at h, d1 2^p / (2^p - 1); the step must meet the bound in both. The first candidate is
the longest step the scene allows (its RK4 stability radius with ``steps.STABILITY_SAFETY``,
and the local-defect limit ``steps.defect_step``); where it misses the bound the step is
scaled by (bound / error)^(1/p) with a margin and measured again, until the bound holds
(``MAX_TRIALS`` rescalings, then halvings). The pilots cost seven times the window at the
first candidate step and three times it at each further candidate; the choice is cached per
run configuration (parameters, defects, start, rate, window, bound), so repeated runs and long
runs gain most.

Where halving the step does not shrink a measure over the bound (``NOT_CONVERGING``), the
response does not converge pointwise: a preloaded bearing's band converges at order 0.7, a
chaotic one not at all. The band is then judged by its octaves' levels (``band_error(...,
levels=True)``), and if that too stalls, or the step reaches ``SHORTEST_FRACTION`` of the
first candidate (or of the default step), the search stops with a ``RuntimeWarning``
(before this, a CWRU-rig recipe with the bound halved its pilots' step to 1e-8 s and ran for
hours).

The chosen step and its error estimate are recorded in the result's parameter record
(``integrator_stats``). An explicit ``SimulationSettings.step`` always wins.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import warnings
from collections import OrderedDict
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from ._validate import SimulationDivergedError
from .steps import DEFAULT_STEP_MASSLESS, defect_step, stability_step

if TYPE_CHECKING:
    from .prepared import Prepared

__all__ = [
    "PILOT_PERIODS",
    "MAX_TRIALS",
    "band_error",
    "error_bound_step",
    "line_error",
]

#: Shortest pilot in periods of the slowest characteristic rate (the shaft's): the least-squares
#: fit resolves lines a few times the record's inverse apart (the closest here, 3 f_s and BPFO
#: of a 6205, are 0.6 f_s apart: 1.8 line spacings over three periods).
PILOT_PERIODS = 3
#: Longest pilot [s]: the run's own window (after its settling) up to this long. The line
#: error at a step depends on the window by up to a factor 3 where a contact opens and closes
#: (the dry ``shaft`` scene), so the pilots integrate the window the run records.
PILOT_MAX_DURATION = 1.0
#: Pilot pairs at most; then the last step is halved until it holds, as measured.
MAX_TRIALS = 4
#: Margin on the extrapolated step.
MARGIN = 0.9
#: Lowest band edge of :func:`band_error` [Hz] (envelope analysis demodulates above it).
BAND_LOW = 500.0
#: Octave bands weaker than this fraction of the strongest one's power are left out (a record's
#: dynamic range: numerically empty bands would have a relative error of 1 at any step).
BAND_RANGE = 1e-6
#: A measure that halving the step does not shrink to this fraction is not converging: the
#: band's waveform then is judged by its octave levels (a preloaded 6205's band converges at
#: order 0.7; a chaotic response's trajectories part whatever the step).
NOT_CONVERGING = 0.7
#: Shortest pilot step as a fraction of the first candidate or the massless scenes' default
#: step, whichever is shorter: the search stops there (with a warning and the estimate it
#: reached) rather than chase an error the step cannot reduce.
SHORTEST_FRACTION = 1.0 / 16.0
#: The channel the pilots compare.
PILOT_CHANNEL = "housing_acceleration_y"
#: Longest step considered [s] (the settings' own upper limit).
LONGEST_STEP = 1e-3

_CACHE: OrderedDict[str, tuple[float, float]] = OrderedDict()


def _lines(prep) -> np.ndarray:
    """The characteristic line frequencies [Hz] (k = 1..3 of shaft, BPFO, BPFI, 2 x BSF)."""
    f = prep.freqs
    if f is None:
        return np.zeros(0)
    base = [f.shaft, f.bpfo, f.bpfi, f.two_bsf]
    return np.array([k * r for r in base for k in (1, 2, 3) if r > 0])


def line_error(reference: np.ndarray, other: np.ndarray, fs: float, lines: np.ndarray) -> float:
    """Largest relative difference of the fitted line amplitudes of two signals.

    Parameters
    ----------
    reference, other : ndarray
        The same record computed two ways [U].
    fs : float
        Sample rate [Hz].
    lines : ndarray
        Line frequencies [Hz]; those closer than 1.5 / the record length to a lower one are
        merged with it; none (or none under fs / 2): the relative RMS difference.

    Returns
    -------
    float
        max over the lines of |A_o - A_r| / max |A_r| (the change of each line as a fraction
        of the strongest).
    """
    lines = np.sort(lines[(lines > 0) & (lines < 0.5 * fs)])
    # lines closer than 1.5 / the record's length cannot be told apart by the fit (their sum
    # is well determined, each alone is not): keep the first of each such group
    if lines.size:
        resolution = 1.5 * fs / reference.size
        lines = lines[np.concatenate([[True], np.diff(lines) > resolution])]
    scale = float(np.sqrt(np.mean(reference**2)))
    if lines.size == 0:
        return float(np.sqrt(np.mean((other - reference) ** 2))) / (scale or 1.0)
    t = np.arange(reference.size) / fs
    basis = np.concatenate(
        [
            np.ones((t.size, 1)),
            np.cos(2 * np.pi * np.outer(t, lines)),
            np.sin(2 * np.pi * np.outer(t, lines)),
        ],
        axis=1,
    )
    coef, *_ = np.linalg.lstsq(basis, np.stack([reference, other], axis=1), rcond=None)
    m = lines.size
    amp = coef[1 : 1 + m] + 1j * coef[1 + m :]  # (lines, 2)
    strongest = float(np.abs(amp[:, 0]).max())
    if strongest <= 0.0:
        return float(np.sqrt(np.mean((other - reference) ** 2))) / (scale or 1.0)
    return float(np.max(np.abs(amp[:, 1] - amp[:, 0])) / strongest)


def band_error(
    reference: np.ndarray, other: np.ndarray, fs: float, *, levels: bool = False
) -> float:
    """Largest relative spectral difference of two records over octave bands above BAND_LOW.

    Parameters
    ----------
    reference, other : ndarray
        The same record computed two ways [U].
    fs : float
        Sample rate [Hz].
    levels : bool
        Compare the octaves' RMS levels instead of their spectra (below).

    Returns
    -------
    float
        max over the octaves [0.45 fs / 2^(k+1), 0.45 fs / 2^k] above ``BAND_LOW`` Hz of
        ||X_o - X_r|| / ||X_r|| (Hann-windowed spectra), octaves weaker than ``BAND_RANGE``
        of the strongest left out; 0 when none lies above ``BAND_LOW``. With ``levels``,
        the octaves' RMS levels are compared instead, |(P_o / P_r)^(1/2) - 1|: what can be
        bounded where the waveform itself does not converge (a chaotic response).
    """
    window = np.hanning(reference.size)
    ref = np.fft.rfft(reference * window)
    diff = np.fft.rfft((other - reference) * window)
    f = np.fft.rfftfreq(reference.size, 1.0 / fs)
    power, change = [], []
    high = 0.45 * fs
    while high / 2.0 >= BAND_LOW:
        band = (f >= high / 2.0) & (f < high)
        power.append(float(np.sum(np.abs(ref[band]) ** 2)))
        if levels:
            moved = float(np.sum(np.abs(ref[band] + diff[band]) ** 2))
            change.append((math.sqrt(moved) - math.sqrt(power[-1])) ** 2)
        else:
            change.append(float(np.sum(np.abs(diff[band]) ** 2)))
        high /= 2.0
    if not power or max(power) <= 0.0:
        return 0.0
    floor = BAND_RANGE * max(power)
    return float(max(math.sqrt(c / p) for p, c in zip(power, change, strict=True) if p >= floor))


def _pilot(prep, step: float, oversample: int, n_out: int) -> np.ndarray | None:
    """Housing acceleration (y) of ``prep`` run at ``step``, as the run itself is made.

    ``n_out`` output samples after its settling, recorded and decimated by
    :func:`generators.model.integrate` (None: it diverged).
    """
    from .model import integrate  # model -> prepared -> here: imported when a pilot runs

    settings = dataclasses.replace(
        prep.settings,
        step=step,
        error_bound=None,
        duration=n_out / prep.settings.fs,
        oversample=oversample,
        channels=(PILOT_CHANNEL,),
        record_contact_loads=False,
    )
    try:
        return integrate(dataclasses.replace(prep, settings=settings))[PILOT_CHANNEL]
    except SimulationDivergedError:
        return None


def _key(prep, bound: float, oversample: int) -> str:
    digest = hashlib.sha256()
    for array in (prep.p, prep.wav, prep.y0):
        digest.update(np.ascontiguousarray(array).tobytes())
    settings = prep.settings
    window = (settings.fs, settings.settle_time, min(settings.duration, PILOT_MAX_DURATION))
    digest.update(repr((prep.scene_code, prep.ehl, window, oversample, bound)).encode())
    return digest.hexdigest()


def on_record_grid(step: float, record_dt: float, oversample: int) -> float:
    """The longest ``record_dt`` x 2^m [s] not above ``step`` and at most an output interval.

    On that grid a pilot's step and its halves all record on the same pattern of their step
    grids (:func:`generators.steps.rk4_schedule` keeps them): a record between steps samples
    the step's interpolant (cubic until stop 47, quintic since), whose error does not fall as
    RK4's does with the step, and pilots recorded partly on and partly off the grid gave
    Richardson's estimate 3-6 times under the true error (stop 36: the bound missed in 3 of
    the 9 cases of ``benchmarks/bench_error_bound.py``).

    Parameters
    ----------
    step : float
        The step wanted [s].
    record_dt : float
        The record interval [s] (the output interval over ``oversample``).
    oversample : int
        Records per output sample.

    Returns
    -------
    float
        The step on the record grid [s].
    """
    top = math.floor(math.log2(oversample) + 1e-9)
    power = min(top, math.floor(math.log2(step / record_dt) + 1e-9))
    return record_dt * 2.0**power


def error_bound_step(prep: Prepared, bound: float, oversample: int) -> tuple[float, float]:
    """The longest RK4 step meeting ``bound`` for a prepared run, and its error estimate.

    Parameters
    ----------
    prep : Prepared
        The run (:func:`generators.prepare`).
    bound : float
        Largest relative error of the characteristic line amplitudes [-].
    oversample : int
        Record samples per output sample of the run.

    Returns
    -------
    (float, float)
        Step [s] and the estimated relative error at it [-]: the larger of the line and the
        band error (Richardson's estimates from the last pilots, at the orders they showed).
    """
    key = _key(prep, bound, oversample)
    if key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    fs = prep.settings.fs
    lines = _lines(prep)
    slowest = float(lines.min()) if lines.size else 10.0
    window = max(min(prep.settings.duration, PILOT_MAX_DURATION), PILOT_PERIODS / slowest)
    n_out = int(math.ceil(window * fs))
    stable = stability_step(prep.scene_code, prep.film_mode, prep.p, prep.wav, prep.y0)
    step = min(LONGEST_STEP, stable, defect_step(prep.p, prep.wav))
    record_dt = 1.0 / (fs * oversample)
    shortest = min(step, DEFAULT_STEP_MASSLESS) * SHORTEST_FRACTION
    measures = [partial(line_error, fs=fs, lines=lines), partial(band_error, fs=fs)]
    levels = False
    error, order = math.inf, 4.0
    for trial in range(MAX_TRIALS + 8):
        step = on_record_grid(step, record_dt, oversample)
        runs = [_pilot(prep, step / 2**k, oversample, n_out) for k in range(3)]
        if any(r is None for r in runs):
            step *= 0.5
            continue
        estimates, halves, stalled = [], [], []
        for index, measure in enumerate(measures):
            first, second = measure(runs[1], runs[0]), measure(runs[2], runs[1])
            if index == 1 and not levels and first > bound and second > NOT_CONVERGING * first:
                # the waveform parts whatever the step: bound the octaves' levels instead
                levels = True
                measure = measures[1] = partial(band_error, fs=fs, levels=True)
                first, second = measure(runs[1], runs[0]), measure(runs[2], runs[1])
            # a measure over the bound that halving the step does not shrink
            stalled.append(second > NOT_CONVERGING * first if first > bound else None)
            # the order the run shows (a contact that opens, a pit's edges: less than RK4's 4)
            p = 4.0
            if second > 0.0 and first > 0.0:
                p = min(4.5, max(1.0, math.log2(first / second)))
            estimates.append((first * 2.0**p / (2.0**p - 1.0), p))  # Richardson at this step
            halves.append(second * 2.0**p / (2.0**p - 1.0))  # and at half of it, same order
        error, order = max(estimates)
        if error <= bound:
            break
        if max(halves) <= bound and not any(stalled):
            # the same pilots say half the step meets the bound: the longest grid step below
            # this one, which a rescaled step could overshoot
            step, error = step / 2.0, max(halves)
            break
        blocking = [x for x in stalled if x is not None]
        if (blocking and all(blocking)) or step / 2.0 < shortest:
            # no step would do: keep the scene's own default and say so
            step = min(step, DEFAULT_STEP_MASSLESS, stable)
            warnings.warn(
                f"error_bound = {bound:g} not met: the error estimate is {error:.3g}, and "
                + (
                    "halving the step does not shrink the pilots' differences (a response "
                    "that does not converge pointwise: a preloaded or chaotic bearing)"
                    if blocking and all(blocking)
                    else f"the step reached {step:.3g} s, where the search stops"
                )
                + f"; the run uses {step:.3g} s",
                RuntimeWarning,
                stacklevel=2,
            )
            break
        if trial < MAX_TRIALS:
            step *= max(0.125, min(0.95, MARGIN * (bound / error) ** (1.0 / order)))
        else:
            step *= 0.5
        step = max(step, shortest)
    _CACHE[key] = (step, error)
    while len(_CACHE) > 64:
        _CACHE.popitem(last=False)
    return step, error
