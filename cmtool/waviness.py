"""Race waviness from the plain spectrum, judged against the healthy lines the model predicts.

Waviness of order k on a race makes discrete lines whose frequencies the order fixes
(docs/model.md 2.1): on the inner race k = qZ + m gives q BPFI + m f_s (m = -3..3 here), on the
outer race k = qZ (and qZ +/- 1) gives q BPFO. A loaded healthy bearing also makes lines at q
BPFO, its varying compliance, so a line there says nothing by its height alone. Each candidate
line is therefore read against a reference that the same recording carries: the geometric mean
of the ball-pass lines (BPFO, 2 BPFO, 3 BPFO) other than itself. The same ratio is computed on
healthy simulations of this bearing at this speed over a range of loads (the model's
``shaft+housing`` scene with its EHL film, ``Rig()`` defaults; the range
``ASSUMED_LOAD_FACTORS`` or ``GIVEN_LOAD_FACTORS`` around the load), and the line's excess over
the largest ratio predicted is what tells waviness from a healthy bearing. Ratios of lines at a
few hundred hertz in one recording do not depend on the sensor's unit or gain, and hardly on the
structure below its first resonances: measured on simulations through rigs of 0.8 to 6 kg
housings (docs/diagnosis.md), the healthy pattern moved by less than 1 dB, the load by up to 25
dB for the 3 BPFI - 2 f_s line between 0.4 and 4 times the one assumed, hence the range.

A candidate line within two bins (the Hann window's main lobe) or 0.3 % of a harmonic of the
mains (50 or 60 Hz) is not read when the spectrum peaks nearer the mains harmonic than the
line: a machine's electrical components put lines there (the MFPT bearing's BPFI at a 25 Hz
shaft, 118.88 Hz, is 1.1 bins from 120 Hz in a 1 s record, and the mains line was read as
inner-race waviness of order 8).

Thresholds, fixed before any recording was read: a line must stand ``WAVINESS_SNR_DB`` (the rule
detector's one-band threshold) over its local floor, or over a good chain's
(:func:`chain_floor`) where that is higher (a noise-free simulation has no floor of its own;
stop 69), so high that Gaussian noise makes one of the candidates as high in at most
``WAVINESS_FALSE_ALARM`` of records (stop 48), and ``MODEL_EXCESS_DB`` over the model's healthy
prediction (a factor of about three for what the model leaves out: the structure, the clearance,
the film).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.signal

import features
from generators import BearingGeometry
from generators.kinematics import BearingFrequencies

__all__ = [
    "MAINS_HZ",
    "MODEL_EXCESS_DB",
    "WAVINESS_SNR_DB",
    "WAVINESS_FALSE_ALARM",
    "DEFAULT_LOAD_N",
    "ASSUMED_LOAD_FACTORS",
    "GIVEN_LOAD_FACTORS",
    "chain_floor",
    "check_load_n",
    "WavinessLine",
    "candidate_lines",
    "comparison_text",
    "healthy_model_spectrum",
    "line_bins",
    "line_false_alarm",
    "mains_harmonic_near",
    "race_waviness",
]

#: A waviness line stands this far over its local floor [dB].
WAVINESS_SNR_DB = 12.0
#: ... with at most this probability per record that Gaussian noise makes a candidate as high
#: (each line's own probability times the number of candidates; 12 dB alone let 3-5 % of 1 s
#: noise records through: benchmarks/waviness_noise.py).
WAVINESS_FALSE_ALARM = 1e-3
#: ... and this far over the healthy model's prediction of its ratio to the ball-pass lines [dB].
MODEL_EXCESS_DB = 10.0
#: Radial load of the healthy prediction when none is given [N] (docs/model.md 6.3 scene).
DEFAULT_LOAD_N = 500.0
#: Loads of the healthy prediction, as multiples of the load assumed (none given: a bearing's
#: load is seldom known to better than a factor of four) or given (a measured load, +/- 40 %):
#: each line is judged against the largest ratio any of them predicts.
ASSUMED_LOAD_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)
GIVEN_LOAD_FACTORS = (0.7, 1.0, 1.4)


def check_load_n(load_n: object, name: str = "load_n") -> float:
    """A given radial load [N], checked against (0, MAX_RADIAL_LOAD_N / 1.4] N.

    The healthy model runs at up to ``GIVEN_LOAD_FACTORS`` times the load.

    Parameters
    ----------
    load_n : object
        The load given [N].
    name : str
        The parameter's name in the message.

    Returns
    -------
    float
        The load [N].

    Raises
    ------
    generators.ParameterError
        Naming ``load_n``, its value and the allowed range.
    """
    from generators import ParameterError
    from generators.params import MAX_RADIAL_LOAD_N

    high = MAX_RADIAL_LOAD_N / max(GIVEN_LOAD_FACTORS)
    try:
        value = float(load_n)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and 0.0 < value <= high):
        shown = f"{value:g}" if math.isfinite(value) else repr(load_n)
        raise ParameterError(f"{name} = {shown} N is outside the allowed range (0, {high:g}] N")
    return value


#: Mains frequencies whose harmonics a machine's electrical components put into a record [Hz].
MAINS_HZ = features.speed.MAINS_HZ
#: Ball-pass harmonics whose lines are the reference.
_REFERENCE_HARMONICS = (1, 2, 3)


@dataclass(frozen=True)
class WavinessLine:
    """One candidate waviness line (docs/model.md 2.1).

    Attributes
    ----------
    surface : str
        ``inner`` or ``outer``.
    order : int
        Waviness order k.
    frequency : float
        Line [Hz].
    harmonic : int
        q, the ball-pass harmonic it belongs to.
    """

    surface: str
    order: int
    frequency: float
    harmonic: int


def candidate_lines(freqs: BearingFrequencies, ball_count: int) -> list[WavinessLine]:
    """Race waviness lines of orders qZ + m (inner, m = -3..3) and qZ (outer), q = 1..3.

    Parameters
    ----------
    freqs : BearingFrequencies
        The characteristic frequencies [Hz].
    ball_count : int
        Z.

    Returns
    -------
    list of WavinessLine
        Each line's surface, order, frequency [Hz] and harmonic q.
    """
    out = []
    for q in (1, 2, 3):
        for m in range(-3, 4):
            out.append(
                WavinessLine("inner", q * ball_count + m, q * freqs.bpfi + m * freqs.shaft, q)
            )
        out.append(WavinessLine("outer", q * ball_count, q * freqs.bpfo, q))
    return out


#: The guard of a line's floor, in half widths of its search band (features.line_snr).
_GUARD = 3.0


def _half_width(df: float, line: float) -> float:
    """Half width of a waviness line's search band [Hz]: 1.5 bins or 0.3 % of the line."""
    return max(1.5 * df, 0.003 * line)


def _line(f: np.ndarray, a: np.ndarray, line: float, floor: float = 0.0) -> tuple[float, float]:
    """(SNR [dB], peak [U]) of a line of a plain spectrum.

    The SNR is over the local floor, or over ``floor`` where that is higher.
    """
    df = f[1] - f[0]
    snr, peak, local = features.line_snr(f, a, line, half_width=_half_width(df, line), guard=_GUARD)
    if floor > local:
        snr = 20.0 * math.log10(max(peak, 1e-300) / floor)
    return snr, peak


def chain_floor(rms: float, n: int) -> float:
    """The median a good measurement chain's white floor has in a record's plain spectrum [U].

    ``features.instrument_floor.INSTRUMENT_FLOOR_DB`` under the record's RMS, white, read as
    :func:`features.amplitude_spectrum` reads it (Hann window, peak scaling): a Rayleigh median
    (``features.instrument_floor.instrument_floor_median``) scaled as the spectrum is, 2 / sum w. A
    waviness line is read over this floor where the record's own is lower (a noise-free
    simulation has none), as the separation and the 1x-line search read theirs.

    Parameters
    ----------
    rms : float
        The record's RMS [U].
    n : int
        Its length [samples].

    Returns
    -------
    float
        The floor's median amplitude [U].

    Raises
    ------
    features.FeatureError
        ``rms`` negative or not finite, or ``n`` not an integer of 4 or more, named with the
        allowed range.
    """
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 4:
        raise features.FeatureError(f"n = {n!r} is outside the allowed range: integers >= 4")
    window = scipy.signal.get_window("hann", int(n))  # features.amplitude_spectrum's
    floor = features.instrument_floor.instrument_floor_median(rms, window)
    return floor * 2.0 / float(window.sum())


def line_false_alarm(f: np.ndarray, line: float, snr_db: float) -> float:
    """Probability that Gaussian noise alone makes a candidate line ``snr_db`` over its floor.

    :func:`features.separation.plain_line_false_alarm` with the bins :func:`features.line_snr`
    searches and takes the floor from for this line.

    Parameters
    ----------
    f : ndarray
        The spectrum's frequencies [Hz].
    line : float
        The candidate line [Hz].
    snr_db : float
        Its height over its floor [dB].

    Returns
    -------
    float
        The probability, in [0, 1].
    """
    return features.separation.plain_line_false_alarm(snr_db, *line_bins(f, line))


def line_bins(f: np.ndarray, line: float) -> tuple[int, int]:
    """Bins :func:`features.line_snr` searches for a candidate line, and bins of its floor.

    Parameters
    ----------
    f : ndarray
        The spectrum's frequencies [Hz].
    line : float
        The candidate line [Hz].

    Returns
    -------
    searched, floor : int
        The counts of bins.
    """
    df = float(f[1] - f[0])
    hw = max(_half_width(df, line), df)
    reach = max(features.bands.FLOOR_WINDOW * line, 10.0 * df)
    near = np.abs(np.asarray(f, dtype=float) - line)
    searched = int(np.count_nonzero(near <= hw))
    floor = int(np.count_nonzero((near <= reach) & ~(near <= _GUARD * hw)))
    return searched, floor


def _peak_frequency(f: np.ndarray, a: np.ndarray, line: float) -> float:
    """Where the largest bin within a line's search width peaks, interpolated [Hz].

    A parabola through the log amplitudes of the largest bin and its two neighbours
    (:func:`features.peak_offset_bins`).
    """
    df = f[1] - f[0]
    half_width = max(1.5 * df, 0.003 * line)
    lo = max(1, int(math.floor((line - half_width - f[0]) / df)))
    hi = min(f.size - 1, int(math.ceil((line + half_width - f[0]) / df)) + 1)
    if hi - lo < 1:
        return line
    k = lo + int(np.argmax(a[lo:hi]))
    if k <= 0 or k >= f.size - 1:
        return float(f[k])
    return float(f[k] + features.peak_offset_bins(a, k) * df)


def _ratio_db(f: np.ndarray, a: np.ndarray, line: WavinessLine, freqs: BearingFrequencies) -> float:
    """The line over the geometric mean of the ball-pass lines other than itself [dB]."""
    _, peak = _line(f, a, line.frequency)
    others = [
        _line(f, a, q * freqs.bpfo)[1]
        for q in _REFERENCE_HARMONICS
        if not (line.surface == "outer" and q == line.harmonic)
    ]
    reference = float(np.exp(np.mean(np.log(np.maximum(others, 1e-300)))))
    if peak <= 0 or reference <= 0:
        return -math.inf
    return 20.0 * math.log10(peak / reference)


@functools.lru_cache(maxsize=128)
def healthy_model_spectrum(
    geometry: BearingGeometry, rpm: float, load_n: float, fs: float, duration: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """Amplitude spectrum of the housing acceleration of this bearing, healthy, in the model.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    rpm : float
        Shaft speed [rev/min].
    load_n : float
        Radial load [N].
    fs : float
        Sample rate of the simulated record [Hz].
    duration : float
        Record length [s].

    Returns
    -------
    frequencies, amplitude : ndarray
        [Hz], [m/s^2] (cached per arguments: the same bearing, speed and load recur).

    Raises
    ------
    generators.ParameterError, generators.SimulationDivergedError
        The model cannot run this case.
    """
    import warnings

    from generators import OperatingCondition, OperatingRangeWarning, SimulationSettings, simulate

    settings = SimulationSettings(fs=fs, duration=duration, channels=("housing_acceleration_y",))
    with warnings.catch_warnings():  # the diagnosis says it of the speed and the load itself
        warnings.simplefilter("ignore", OperatingRangeWarning)
        x = simulate(geometry, OperatingCondition.from_rpm(rpm, load_n), None, settings=settings)
    return features.amplitude_spectrum(x["housing_acceleration_y"], fs)


def race_waviness(
    f: np.ndarray,
    a: np.ndarray,
    freqs: BearingFrequencies,
    geometry: BearingGeometry,
    model: list[tuple[np.ndarray, np.ndarray]] | None,
    floor: float = 0.0,
) -> dict | None:
    """The waviness line that stands out most against the model's healthy lines, if one does.

    Parameters
    ----------
    f, a : ndarray
        Plain amplitude spectrum of the recording [Hz], [U].
    freqs : BearingFrequencies
        The bearing's frequencies at this speed.
    geometry : BearingGeometry
        The bearing.
    model : list of (ndarray, ndarray), or None
        The healthy references: :func:`healthy_model_spectrum` at each load of the range
        (a line is judged against the largest ratio any of them predicts), or a healthy
        recording's spectrum of the same machine; None reads lines by their height alone (a
        loaded healthy bearing's ball-pass lines then look like outer-race waviness).
    floor : float
        The lowest floor a line's height is read over [U] (:func:`chain_floor` of the
        record; 0: the local floor alone).

    Returns
    -------
    dict or None
        ``surface``, ``order``, ``line_hz``, ``snr_db``, ``over_model_db`` (99 where the
        healthy reference has no such line; None without a reference) and
        ``healthy_model_has_line`` of the strongest flagged line.
    """
    flagged = []
    resolution = float(f[1] - f[0])
    lines = [
        line for line in candidate_lines(freqs, geometry.ball_count) if 0 < line.frequency < f[-1]
    ]
    for line in lines:
        mains = mains_harmonic_near(line.frequency, resolution)
        if mains is not None:
            peak = _peak_frequency(f, a, line.frequency)
            if abs(peak - mains) < abs(peak - line.frequency):
                continue  # the peak is the mains harmonic's
        snr, _ = _line(f, a, line.frequency, floor)
        if snr < WAVINESS_SNR_DB:
            continue
        if line_false_alarm(f, line.frequency, snr) * len(lines) > WAVINESS_FALSE_ALARM:
            continue  # noise makes a line this high among this many candidates too often
        excess = None
        if model is not None:
            predicted = max(_ratio_db(mf, ma, line, freqs) for mf, ma in model)
            excess = _ratio_db(f, a, line, freqs) - predicted
            if not math.isfinite(excess):
                excess = 99.0  # the healthy reference has no line there at all
            if excess < MODEL_EXCESS_DB:
                continue
        flagged.append((line, snr, excess))
    if not flagged:
        return None
    key = (lambda item: item[2]) if model is not None else (lambda item: item[1])
    line, snr, excess = max(flagged, key=key)
    return {
        "surface": line.surface,
        "order": int(line.order),
        "line_hz": round(line.frequency, 3),
        "snr_db": round(snr, 2),
        "over_model_db": None if excess is None else round(min(excess, 99.0), 2),
        "healthy_model_has_line": None if excess is None else bool(excess < 99.0),
        "note": (
            "a discrete line consistent with waviness of this order (docs/model.md 2.1; "
            + (
                "orders qZ and qZ +/- 1 share the line"
                if line.surface == "outer"
                else "order k from the line k f_s - qZ f_c"
            )
            + ")"
            + ("" if model is None else ", above its healthy prediction")
            + "; a machine component at the same frequency looks the same: compare with a "
            "baseline before acting"
        ),
    }


def mains_harmonic_near(line_hz: float, resolution_hz: float) -> float | None:
    """The harmonic of 50 or 60 Hz that a spectrum cannot tell from a line, if any [Hz].

    Parameters
    ----------
    line_hz : float
        The line [Hz].
    resolution_hz : float
        The spectrum's bin spacing [Hz] (1 / record length).

    Returns
    -------
    float or None
        The mains harmonic within two bins (a Hann window's main lobe) or 0.3 % of the line
        (the line search's width), or None.

    Examples
    --------
    >>> mains_harmonic_near(118.876, 1.0)  # MFPT BPFI at 25 Hz, a 1 s record: 120 Hz is near
    120.0
    >>> mains_harmonic_near(118.876, 0.2) is None  # a 5 s record tells them apart
    True
    """
    width = max(2.0 * resolution_hz, 0.003 * line_hz)
    for mains in MAINS_HZ:
        k = max(round(line_hz / mains), 1)
        if abs(line_hz - k * mains) <= width:
            return float(k * mains)
    return None


def comparison_text(waviness: dict) -> str:
    """How a reported waviness line compares with its healthy reference, in words.

    Parameters
    ----------
    waviness : dict
        ``Diagnosis.waviness``.

    Returns
    -------
    str
        A clause to append to the line's description (empty without a reference).
    """
    if waviness.get("over_model_db") is None:
        return ""
    if not waviness.get("healthy_model_has_line", True):
        return ", where the healthy reference has no line"
    return f", {waviness['over_model_db']} dB over its healthy share"
