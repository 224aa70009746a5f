"""The evidence an analyst weighs for a local fault, as numbers: one row per signal.

The random part of the signal (:func:`features.separate_discrete`, the shaft's and the ball
pass's harmonics removed), demodulated in the band where a fault rate shows most clearly
(:func:`features.select_band` through :func:`features.band_selection.fault_band`: the fault
rates and the cage rate, in bands from 3 x the fastest fault rate up); then for each fault
(``bpfo``, ``bpfi``, ``two_bsf``):

* ``evidence_<fault>_h<k>_snr`` [dB], k = 1, 2, 3: the envelope line at k x the rate,
  searched from ``SLIP_SEARCH[0]`` below to ``SLIP_SEARCH[1]`` above it (real bearings slip:
  their fault rates run up to 2 % under the kinematic ones), over the median of its
  neighbourhood (+/- 10 %, at least ``FLOOR_BINS`` bins each side);
* ``evidence_<fault>_sideband_snr`` [dB]: the mean of the first sidebands of the fundamental
  (inner race: +/- the shaft rate, the pit turning through the load zone; ball: +/- the cage
  rate; outer race: none, 0);
* ``evidence_<fault>_best_band_db`` [dB]: the clearest line of this rate over every candidate
  band;
* ``evidence_<fault>_weighed_db`` [dB]: the fault's weighed evidence (``evidence_db`` of
  :attr:`Evidence.combined`, below) over the detection threshold, what the rule's verdict on
  that fault rests on: its line family with the lines another fault accounts for left out
  (since stop 78: on the MFPT bearing a ball pit's 2 x BSF - FTF line lies 1.1 % under BPFI,
  inside BPFI's slip window, and raises ``evidence_bpfi_h1_snr``; docs/realism.md 6);

and ``evidence_margin_db`` [dB], the chosen band's best line over the detection threshold for
that many bands and bins (:func:`features.detection_threshold_db`). Every feature is a ratio at
the bearing's own rates: independent of the sensor's unit and gain, the transfer path and the
machine's periodic components, and the same for any bearing and speed, which is what lets one
model serve every machine given its bearing and speed.

Beyond the row, :attr:`Evidence.combined` weighs each fault's line family as an analyst
does: the fundamental, its second and third harmonics and its first sidebands (inner race:
shaft rate; ball: cage rate about 2 x BSF), and for the ball the cage rate and its second
harmonic (a ball pit strikes in bursts, once per cage revolution; in records holding at least
``MIN_CAGE_REVOLUTIONS`` cage revolutions, :func:`cage_lines_weighed`). Each line's false-alarm
probability under Gaussian noise (:func:`features.separation.line_false_alarm`; the
fundamental's counted over every band searched) is combined by Fisher's method (-2 sum ln p
is chi-square with 2 m degrees of freedom under noise), and the fault's probability is twice
the smaller of the fundamental's and the family's (Bonferroni over the two tests: one clear
fundamental keeps its weight, a family of moderate lines adds up). Where the families of K
bands are weighed and the strongest kept (``EVIDENCE_BANDS``), the fundamental's union bound
already covers every band but the family's test was made K times: the factor is 1 + K
(:func:`combine_lines`), 2 for the one band. ``evidence_db`` is that
probability on the dB scale of the detection threshold
(:func:`features.separation.ratio_for_false_alarm`), so that a fault is detected when
``evidence_db`` reaches it, at the same false-alarm probability per fault. A line that lies
on a stronger detected fault's harmonics or their sidebands counts for that fault only
(:func:`explain_shared_lines`); the row's line ratios are as found, its ``weighed_db``
after that.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ._validate import FeatureError, check_fs, check_positive, check_record
from .band_selection import ANALYSER_RATIO, BAND_FLOOR_FACTOR, BandSelection, fault_band
from .envelope import envelope
from .lattice import inner_race_lattice_offsets, inner_race_lattice_orders
from .separation import (
    FALSE_ALARM,
    FLOOR_BINS,
    detection_threshold_db,
    line_false_alarm,
    ratio_for_false_alarm,
    separate_discrete,
)
from .spectra import amplitude_spectrum

__all__ = [
    "EVIDENCE_FAULTS",
    "EVIDENCE_NAMES",
    "MIN_CAGE_REVOLUTIONS",
    "SLIP_SEARCH",
    "Evidence",
    "cage_lines_weighed",
    "combine_lines",
    "explain_shared_lines",
    "fault_evidence",
    "slip_line",
]

#: Fault rates weighed (context keys).
EVIDENCE_FAULTS = ("bpfo", "bpfi", "two_bsf")
#: Sideband spacing of each fault's fundamental (context key), where the physics gives one.
_SIDEBANDS = {"bpfi": "shaft", "two_bsf": "ftf"}
#: A fault line is searched from 2 % below its kinematic rate (slip) to 0.5 % above (the
#: speed's own uncertainty).
SLIP_SEARCH = (0.02, 0.005)
#: Bands weighed per record: of the candidate bands, those whose envelope shows a fault rate's
#: line most clearly; every fault's lines are weighed in each, and the band where the weighed
#: evidence stands furthest over its threshold is kept (the threshold counts every candidate
#: band for the fundamental; the family's test, made in each band weighed, is counted K times:
#: :func:`combine_lines`). 1, as shipped: the band the line ranks highest alone. 6 was measured
#: in stops 56 and 68, with and without that count, and not adopted (docs/diagnosis.md, "The
#: band chosen by the weighed evidence").
EVIDENCE_BANDS = 1

EVIDENCE_NAMES = tuple(
    [
        name
        for fault in EVIDENCE_FAULTS
        for name in (
            *(f"evidence_{fault}_h{k}_snr" for k in (1, 2, 3)),
            f"evidence_{fault}_sideband_snr",
            f"evidence_{fault}_best_band_db",
            f"evidence_{fault}_weighed_db",
        )
    ]
    + ["evidence_margin_db"]
)


def slip_line(
    freqs: np.ndarray, amp: np.ndarray, line: float, search: tuple[float, float] = SLIP_SEARCH
) -> tuple[float, float, int, int]:
    """A spectral line searched within the slip, against the median of its neighbourhood.

    Parameters
    ----------
    freqs, amp : ndarray
        A spectrum [Hz], [U].
    line : float
        Expected frequency [Hz].
    search : (float, float)
        Searched from ``line * (1 - search[0])`` to ``line * (1 + search[1])``.

    Returns
    -------
    ratio_db : float
        Peak over the floor [dB] (0 when the line is beyond the spectrum).
    found : float
        Where the peak is [Hz].
    searched_bins, floor_bins : int
        Bins searched and bins of the floor's median (for :func:`detection_threshold_db`).
    """
    line = check_positive("line", line, unit="Hz")
    below, above = (float(v) for v in search)
    if not (0.0 <= below < 1.0 and 0.0 <= above < 1.0):
        raise FeatureError(
            f"search = {tuple(search)!r} is outside the allowed range: each share of the line "
            "in [0, 1)"
        )
    df = freqs[1] - freqs[0]
    low, high = line * (1 - below) - df, line * (1 + above) + df
    inside = (freqs >= low) & (freqs <= high)
    reach = max(0.1 * line, FLOOR_BINS * df)
    window = (np.abs(freqs - line) <= reach) & ~inside
    if not inside.any() or window.sum() < 3 or high > freqs[-1]:
        return 0.0, float(line), 1, 3
    i = int(np.argmax(np.where(inside, amp, -np.inf)))
    floor = float(np.median(amp[window]))
    ratio = 20 * math.log10(amp[i] / floor) if amp[i] > 0 and floor > 0 else 0.0
    return ratio, float(freqs[i]), int(inside.sum()), int(window.sum())


@dataclass(frozen=True)
class Evidence:
    """What :func:`fault_evidence` found in one signal.

    Attributes
    ----------
    features : dict of str to float
        The row (``EVIDENCE_NAMES``).
    selection : BandSelection
        The band choice and every candidate's scores.
    threshold_db : float
        Detection threshold of the fundamentals [dB] (false alarm ``FALSE_ALARM`` per fault).
    lines : dict of str to list of (float, float)
        Per fault, (ratio [dB], found [Hz]) of harmonics 1-3.
    random_part : ndarray
        The separated signal.
    envelope_frequencies, envelope_amplitude : ndarray
        Its envelope spectrum in the chosen band [Hz], [U].
    combined : dict of str to dict
        Per fault, the weighed line family (module docstring): ``evidence_db`` [dB, the
        threshold's scale], ``false_alarm`` (its probability under noise), ``family_p``
        (Fisher's combination alone), ``lines`` (name, ratio [dB], probability) and
        ``explained`` (the lines another fault's harmonics account for, which count as
        absent: :func:`explain_shared_lines`).
    families : dict of str to list
        Per fault, each line weighed: (name, (ratio [dB], found [Hz], bins searched, floor
        bins)), before any is explained.
    lattice_orders : tuple of int
        The series k BPFI + n BPFO the separation found held and fitted (``features.lattice``),
        by their signed k; empty where none was.
    instrument_floor_rms : float
        The white floor the separation added to a record without one of its own [U]; 0 where
        the record had its own (``features.separate_discrete``, step 2).
    """

    features: dict[str, float]
    selection: BandSelection
    threshold_db: float
    lines: dict[str, list[tuple[float, float]]]
    random_part: np.ndarray
    envelope_frequencies: np.ndarray
    envelope_amplitude: np.ndarray
    combined: dict[str, dict] = field(default_factory=dict)
    families: dict[str, list] = field(default_factory=dict)
    lattice_orders: tuple[int, ...] = ()
    instrument_floor_rms: float = 0.0


def combine_lines(
    probabilities: list[float], fundamental: float, bands_weighed: int = 1
) -> tuple[float, float]:
    """A fault's false-alarm probability from its lines' (module docstring).

    Parameters
    ----------
    probabilities : list of float
        Each line's probability under noise, the fundamental's first (over every band).
    fundamental : float
        The fundamental's probability (the first of ``probabilities``).
    bands_weighed : int
        Bands whose families were weighed, the strongest kept (K): the fundamental's
        probability already counts every band, the family's test is made K times, so the
        two tests together cost 1 + K (Bonferroni); 1 gives the factor 2.

    Returns
    -------
    (float, float)
        The fault's probability, min(1, (1 + K) min(fundamental, Fisher)), and Fisher's alone.

    Raises
    ------
    FeatureError
        ``bands_weighed`` not an integer of at least 1.

    Examples
    --------
    >>> p, fisher = combine_lines([1e-3, 1e-2, 1e-2], 1e-3)
    >>> bool(fisher < 1e-3 and p == 2 * fisher)  # three moderate lines outweigh one
    True
    >>> p6, _ = combine_lines([1e-3, 1e-2, 1e-2], 1e-3, bands_weighed=6)
    >>> bool(p6 == 7 * fisher)  # the family's test made in six bands, the fundamental's once
    True
    >>> combine_lines([1e-3], 1e-3, bands_weighed=0)
    Traceback (most recent call last):
    ...
    features._validate.FeatureError: bands_weighed = 0 is outside the allowed range [1, inf)
    """
    from scipy.stats import chi2

    if not isinstance(bands_weighed, (int, np.integer)) or bands_weighed < 1:
        raise FeatureError(
            f"bands_weighed = {bands_weighed!r} is outside the allowed range [1, inf)"
        )
    logs = np.log(np.clip(probabilities, 1e-300, 1.0))
    fisher = float(chi2.sf(-2.0 * float(logs.sum()), 2 * len(probabilities)))
    return min(1.0, (1.0 + bands_weighed) * min(fundamental, fisher)), fisher


def fault_evidence(x: np.ndarray, fs: float, fault_frequencies: Mapping[str, float]) -> Evidence:
    """The analyst's evidence for each local fault (module docstring), and what it rests on.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fault_frequencies : mapping of str to float
        ``bpfo``, ``bpfi``, ``two_bsf``, ``shaft`` and ``ftf`` [Hz].

    Returns
    -------
    Evidence
        Features, band, threshold, the lines found and the spectra.

    Raises
    ------
    FeatureError
        A rate missing or not a positive number, the shaft or cage rate at or above fs / 2,
        or the fastest fault rate too high for the bands (``BAND_FLOOR_FACTOR`` times it must
        lie under fs / ``ANALYSER_RATIO``), each named by its key.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 12000.0; rng = np.random.default_rng(0)
    >>> ctx = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2, "shaft": 29.95, "ftf": 11.9}
    >>> e = fault_evidence(rng.standard_normal(12000), fs, ctx)
    >>> bool(e.features["evidence_margin_db"] < 0)  # noise: nothing above the threshold
    True
    """
    x = check_record(x, function="fault_evidence", min_length=64)
    fs = check_fs(fs)
    missing = [k for k in (*EVIDENCE_FAULTS, "shaft", "ftf") if k not in fault_frequencies]
    if missing:
        raise FeatureError(f"fault_frequencies has no {missing}; it needs those rates in Hz")
    checked = {
        name: check_positive(f"fault_frequencies[{name!r}]", fault_frequencies[name], unit="Hz")
        for name in (*EVIDENCE_FAULTS, "shaft", "ftf")
    }
    ctx = {**{k: float(v) for k, v in fault_frequencies.items()}, **checked}
    for name in ("shaft", "ftf"):
        if ctx[name] >= fs / 2:
            raise FeatureError(
                f"fault_frequencies[{name!r}] = {ctx[name]:g} Hz is outside the allowed range "
                f"(0, {fs / 2:g}) Hz (below fs / 2)"
            )
    fastest = max(EVIDENCE_FAULTS, key=ctx.__getitem__)
    top = fs / ANALYSER_RATIO  # the bands start at BAND_FLOOR_FACTOR x the fastest fault rate
    if BAND_FLOOR_FACTOR * ctx[fastest] >= top:
        raise FeatureError(
            f"fault_frequencies[{fastest!r}] = {ctx[fastest]:g} Hz is too high for fs = {fs:g} "
            f"Hz: the demodulation bands start at {BAND_FLOOR_FACTOR:g} x the fastest fault "
            f"rate, under fs / {ANALYSER_RATIO:g} = {top:g} Hz (fault rates below "
            f"{top / BAND_FLOOR_FACTOR:g} Hz)"
        )
    rates = {k: ctx[k] for k in EVIDENCE_FAULTS}
    lattice = inner_race_lattice_offsets(ctx["bpfo"], ctx["bpfi"])
    random_part, held, floor_rms = separate_discrete(
        x,
        fs,
        fundamentals=(ctx["shaft"], ctx["bpfo"]),
        lattice=lattice,
        return_held=True,
        return_floor=True,
    )
    selection = fault_band(random_part, fs, rates, ctx["ftf"])
    orders = tuple(
        k for k, o in zip(inner_race_lattice_orders(), lattice, strict=True) if o in held
    )
    evidence = best_band_evidence(random_part, fs, ctx, selection)
    return replace(evidence, lattice_orders=orders, instrument_floor_rms=floor_rms)


def best_band_evidence(
    random_part: np.ndarray, fs: float, ctx: Mapping[str, float], selection: BandSelection
) -> Evidence:
    """The evidence in the band where it stands furthest over its threshold.

    A band is chosen by one line (a fault rate's fundamental over its floor), the verdict by
    the weighed lines (fundamental, harmonics, sidebands): near-tied bands can weigh the same
    fault very differently. So each of the ``EVIDENCE_BANDS`` candidate bands the line ranks
    highest is weighed, and the strongest kept. The threshold counts every candidate band (a
    union bound over them), so keeping the maximum over some of them keeps the false-alarm
    probability.

    Parameters
    ----------
    random_part : ndarray
        The record's random part [U] (:func:`features.separate_discrete`).
    fs : float
        Sample rate [Hz].
    ctx : mapping of str to float
        ``bpfo``, ``bpfi``, ``two_bsf``, ``shaft`` and ``ftf`` [Hz].
    selection : BandSelection
        The candidate bands and their scores (:func:`features.band_selection.fault_band`).

    Returns
    -------
    Evidence
        As :func:`fault_evidence`; its ``selection.band`` is the band kept.
    """
    ctx = {k: float(v) for k, v in ctx.items()}
    rows = np.argsort(-selection.scores_db.max(axis=1), kind="stable")[:EVIDENCE_BANDS]
    best, best_margin = None, -math.inf
    for i in rows:
        j = int(np.argmax(selection.scores_db[i]))
        chosen = replace(
            selection,
            band=(float(selection.bands[i][0]), float(selection.bands[i][1])),
            score_db=float(selection.scores_db[i, j]),
            rate=selection.rates[j],
        )
        evidence = _evidence_in_band(random_part, fs, ctx, chosen, len(rows))
        weighed = max(v["evidence_db"] for v in evidence.combined.values())
        if best is None or weighed - evidence.threshold_db > best_margin:
            best, best_margin = evidence, weighed - evidence.threshold_db
    if best is None:
        raise FeatureError("the band selection holds no band")
    return best


def _evidence_in_band(
    random_part: np.ndarray,
    fs: float,
    ctx: dict[str, float],
    selection: BandSelection,
    bands_weighed: int = 1,
) -> Evidence:
    """:func:`fault_evidence` once the random part and the band are known.

    The band is one of ``bands_weighed`` whose families are weighed (:func:`combine_lines`).
    """
    rates = {k: ctx[k] for k in EVIDENCE_FAULTS}
    env = envelope(random_part, fs, band=selection.band)
    ef, ea = amplitude_spectrum(env, fs)
    out: dict[str, float] = {}
    lines: dict[str, list[tuple[float, float]]] = {}
    found_all: dict[str, list[tuple[str, tuple[float, float, int, int]]]] = {}
    searched, floor = 1, None
    for j, fault in enumerate(EVIDENCE_FAULTS):
        found = [slip_line(ef, ea, k * rates[fault]) for k in (1, 2, 3)]
        lines[fault] = [(r[0], r[1]) for r in found]
        searched = max(searched, found[0][2])
        floor = found[0][3] if floor is None else min(floor, found[0][3])
        for k, r in enumerate(found, 1):
            out[f"evidence_{fault}_h{k}_snr"] = r[0]
        family = [(f"{k}x", r) for k, r in enumerate(found, 1)]
        spacing = ctx.get(_SIDEBANDS.get(fault, ""), 0.0)
        sidebands = 0.0
        if spacing > 0:
            pair = [slip_line(ef, ea, rates[fault] + s * spacing) for s in (-1, 1)]
            sidebands = float(np.mean([r[0] for r in pair]))
            family += [("1x-", pair[0]), ("1x+", pair[1])]
        found_all[fault] = family
        out[f"evidence_{fault}_sideband_snr"] = sidebands
        out[f"evidence_{fault}_best_band_db"] = float(selection.scores_db[:, j].max())
    threshold = detection_threshold_db(
        len(selection.bands), searched_bins=searched, floor_bins=floor
    )
    best = max(out[f"evidence_{fault}_h1_snr"] for fault in EVIDENCE_FAULTS)
    out["evidence_margin_db"] = best - threshold
    spacings = {fault: ctx.get(_SIDEBANDS.get(fault, ""), 0.0) for fault in EVIDENCE_FAULTS}
    combined = explain_shared_lines(
        found_all,
        len(selection.bands),
        searched,
        floor,
        float(ef[1] - ef[0]),
        spacings,
        bands_weighed=bands_weighed,
    )
    cage = [
        (f"cage {k}x", slip_line(ef, ea, k * ctx["ftf"]))
        for k in (CAGE_HARMONICS if cage_lines_weighed(random_part.size / fs, ctx["ftf"]) else ())
    ]
    combined["two_bsf"] = _with_cage_lines(
        combined["two_bsf"],
        found_all["two_bsf"],
        cage,
        len(selection.bands),
        searched,
        floor,
        bands_weighed,
    )
    for fault in EVIDENCE_FAULTS:  # what the verdict rests on, shared lines explained
        out[f"evidence_{fault}_weighed_db"] = combined[fault]["evidence_db"] - threshold
    return Evidence(out, selection, threshold, lines, random_part, ef, ea, combined, found_all)


#: A fault's line lies on another fault's harmonic k when it is within this many envelope bins
#: of k times that fault's found fundamental, plus k times ``SHARED_LINE_SLIP`` of it: random
#: slip (1-2 % in real bearings, Ho and Randall 2000; 0.5-2 % in the rig recipes) smears the
#: k-th harmonic over about k times the slip, and its peak or its slip sidebands can stand
#: anywhere in that width.
SHARED_LINE_BINS = 1.0
SHARED_LINE_SLIP = 0.015
#: Harmonics of the cage rate weighed into the ball's family (docs/diagnosis.md, "The cage
#: rate chooses the ball's band").
CAGE_HARMONICS = (1, 2)
#: The cage-rate lines are weighed only in records holding at least this many cage
#: revolutions: the fewest at which the rule's threshold has been checked on healthy records
#: (the rig recipes' 1 s records hold 10.1-11.9). In shorter ones the cage line lies a few
#: bins from 0 Hz, where a healthy bearing's slow envelope changes stand. Measured in stop 57
#: on fresh rig-recipe draws: healthy records cut to 0.25 s were called faulty 26 and 11
#: times in 100 with the cage lines, 3 and 2 without (docs/diagnosis.md, "Cage lines in
#: short records").
MIN_CAGE_REVOLUTIONS = 10.0
#: Harmonics of a stronger fault that can account for another fault's line.
SHARED_LINE_ORDERS = 10


def explain_shared_lines(
    families: Mapping[str, list],
    n_bands: int,
    searched: int,
    floor: int,
    bin_width: float,
    spacings: Mapping[str, float] | None = None,
    *,
    bands_weighed: int = 1,
) -> dict[str, dict]:
    """Each fault's line family weighed, the lines another fault accounts for left out.

    A bearing's fault rates are not commensurate, but their harmonics can fall within a line's
    width of each other (a 6205: 3 x BPFO and 2 x BPFI are 0.7 % apart, 4 x BPFO and 3 x (2 x
    BSF) 1.4 %), and each fault's lines are searched within the slip: one fault's harmonic
    then also counts as another fault's. An analyst gives a shared line to the fault whose
    series it continues. Here the faults are taken in order of their weighed evidence (ties:
    the fundamental); a fault that is detected (false-alarm probability at most
    ``FALSE_ALARM``) accounts for every line of a fault ranked below it that lies on its own
    harmonic series or on its harmonics' first and second sidebands (within
    ``SHARED_LINE_BINS`` envelope bins plus ``SHARED_LINE_SLIP`` per order of k f + m s, f its
    found fundamental, k up to ``SHARED_LINE_ORDERS``, s its sideband spacing: an inner-race
    fault's lines stand at k BPFI -/+ m f_shaft, the pit turning through the load zone);
    such lines count as absent (0 dB over the floor) in the lower fault's weighing, which is
    then repeated. The strongest fault's weighing is never changed, so neither is the
    ranking's head.

    Parameters
    ----------
    families : mapping of str to list
        Per fault (``EVIDENCE_FAULTS`` order), (name, (ratio [dB], found [Hz], bins searched,
        floor bins)) of each line, the fundamental (``"1x"``) first.
    n_bands, searched, floor : int
        Bands the fundamental was looked for in, bins searched per line, floor bins.
    bin_width : float
        The envelope spectrum's bin width [Hz].
    spacings : mapping of str to float, optional
        Per fault, the spacing of its sidebands [Hz] (0 or absent: none).
    bands_weighed : int
        Bands whose families are weighed, the strongest kept (:func:`combine_lines`).

    Returns
    -------
    dict of str to dict
        As :attr:`Evidence.combined`, each with ``explained``: a list of (line, fault, k).
    """
    counts = (n_bands, searched, floor, bands_weighed)
    raw = {fault: _weigh(family, *counts) for fault, family in families.items()}
    order = sorted(raw, key=lambda f: (raw[f]["evidence_db"], families[f][0][1][0]), reverse=True)
    combined: dict[str, dict] = {}
    spacings = spacings or {}
    # detected faults: (name, found fundamental, sideband spacing)
    explainers: list[tuple[str, float, float]] = []
    for fault in order:
        family = list(families[fault])
        explained = []
        for i, (name, line) in enumerate(family):
            source = _on_series(line[1], explainers, bin_width)
            if source is not None:
                explained.append((name, *source))
                family[i] = (name, (0.0, *line[1:]))
        weighed = _weigh(family, *counts) if explained else raw[fault]
        combined[fault] = {**weighed, "explained": explained}
        if weighed["detected"]:
            explainers.append((fault, families[fault][0][1][1], spacings.get(fault, 0.0)))
    return {fault: combined[fault] for fault in families}


def cage_lines_weighed(duration: float, cage_rate: float) -> bool:
    """Whether a record this long weighs the ball's cage-rate lines (``MIN_CAGE_REVOLUTIONS``).

    Parameters
    ----------
    duration : float
        The record's length [s].
    cage_rate : float
        The cage rate (FTF) [Hz].

    Returns
    -------
    bool
        True when the record holds at least ``MIN_CAGE_REVOLUTIONS`` cage revolutions.
    """
    return duration * cage_rate >= MIN_CAGE_REVOLUTIONS


def _with_cage_lines(
    weighed: dict,
    family,
    cage,
    n_bands: int,
    searched: int,
    floor: int,
    bands_weighed: int = 1,
):
    """The ball's weighing with its cage-rate lines added to its family.

    A ball pit strikes only while its ball crosses the load zone, once per cage revolution,
    so its impacts come in bursts and its envelope shows the cage rate and its harmonics
    (Randall and Antoni 2011); the lines another fault accounts for stay out, as in
    :func:`explain_shared_lines`, whose ranking is left as it was.
    """
    explained = weighed.get("explained", [])
    names = {name for name, *_ in explained}
    family = [(name, (0.0, *line[1:]) if name in names else line) for name, line in family]
    counts = (n_bands, searched, floor, bands_weighed)
    return {**_weigh(family + list(cage), *counts), "explained": explained}


def _on_series(
    found: float, explainers: list[tuple[str, float, float]], bin_width: float
) -> tuple[str, int] | None:
    """(fault, k) of the first explainer whose line k f + m s (|m| <= 2) ``found`` lies on."""
    for other, fundamental, spacing in explainers:
        if fundamental <= 0:
            continue
        for m in (0, -1, 1, -2, 2) if spacing > 0 else (0,):
            k = round((found - m * spacing) / fundamental)
            if not 1 <= k <= SHARED_LINE_ORDERS:
                continue
            tolerance = SHARED_LINE_BINS * bin_width + SHARED_LINE_SLIP * k * fundamental
            if abs(found - k * fundamental - m * spacing) <= tolerance:
                return other, k
    return None


def _weigh(family, n_bands: int, searched: int, floor: int, bands_weighed: int = 1) -> dict:
    """One fault's line family weighed into one probability and its dB equivalent.

    The family is one of ``bands_weighed`` bands', the strongest kept (:func:`combine_lines`).
    """
    named = []
    fundamental = 1.0
    for index, (name, (ratio, _, bins, floor_bins)) in enumerate(family):
        p = line_false_alarm(ratio, bins, floor_bins)
        if index == 0:  # the fundamental was looked for in every band
            fundamental = n_bands * p  # the union bound, uncapped: a score below 1 too
            p = min(1.0, fundamental)
        named.append((name, round(ratio, 2), p))
    probability, fisher = combine_lines([p for _, _, p in named], named[0][2], bands_weighed)
    # the dB figure from the uncapped bound, so that weak evidence still ranks (ROC)
    tests = 1.0 + bands_weighed
    evidence_db = ratio_for_false_alarm(tests * min(fundamental, fisher), n_bands, searched, floor)
    if probability <= 1e-299:  # beyond the tabulated curve: the fundamental speaks for itself
        evidence_db = max(evidence_db, family[0][1][0])
    return {
        "evidence_db": evidence_db,
        "false_alarm": probability,
        "family_p": fisher,
        "lines": named,
        "detected": probability <= FALSE_ALARM,
    }
