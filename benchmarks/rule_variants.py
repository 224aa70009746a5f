"""Variants of the rule detector tried against its two open gaps, measured and not shipped
(docs/diagnosis.md: "Form errors read as a local fault", "The ball's odd harmonics").

Modes:

``record-length``
    The four noise-free cases of ``tests/tests_cmtool/test_diagnosis.py::
    test_a_healthy_bearing_with_form_errors_is_no_local_fault`` (6205, 1797 rpm, clearance 5 um,
    100 and 400 N, 0.1 um of form errors on the inner race or on the balls) at record lengths
    of 1, 2, 4 and 8 s: does a finer resolution let the separation take the form errors' line
    lattice? Prints each verdict and the top candidate's margin over the threshold [dB].
``fitted-lines``
    The same cases and their preloaded twins (clearance -5 um), plus 0.3 mm pits with 1 %
    slip, with the shipped separation and with a variant whose line editing fits and
    subtracts each detected line as a sinusoid at its interpolated frequency (joint
    Hann-weighted least squares, three passes) instead of zeroing the bins of the record's
    spectrum, which leaves the skirts of lines between bins.
``entry-jitter``
    When do the balls enter the load zone? A 6205 with 5 um of clearance at 1797 rpm and 400
    N, dry, 48 kHz, 1 s, perfect or with 0.1 um of form errors on the inner race or the balls:
    from the outer contacts' loads (``record_contact_loads``), each ball's entries (load
    rising through 1 mN), and the spread of the intervals between successive entries of any
    ball (one ball-pass interval, 1 / BPFO, apart) and the number of load on/off transitions
    per ball and cage revolution (2: one clean entry and exit).
``ball-odd DATASET [DATASET ...]``
    The rule on a dataset's healthy signals and its faults at fault SNR >= -10 dB, with the
    ball's line family as shipped (2, 4, 6 x BSF and 2 x BSF -/+ the cage rate) and with
    BSF and 3 x BSF added to it (a ball pit strikes the two races in turn, and the two impacts
    differ). Prints the share of right verdicts per class.

``ball-cage DATASET [DATASET ...]``
    As ``ball-odd``, with the cage-rate lines of the envelope (a ball pit strikes only while
    its ball crosses the load zone, once per cage revolution, so its impacts come in bursts at
    the cage rate): ``family``, FTF and 2 x FTF weighed into the ball's Fisher family;
    ``comb``, FTF, 2 and 3 x FTF as a third test of their own, the ball's probability three
    times the least of the fundamental's, the family's and the comb's (Bonferroni).

``shifted-bands DATASET [DATASET ...]``
    As ``ball-odd``, the band tree as shipped and with each level's bands also shifted by half
    a band (a resonance on a band edge gets a band centred on it; the threshold counts the
    extra bands, as the selection does): stop 51, docs/diagnosis.md "Half-shifted bands".

``band-floor DATASET [DATASET ...]``
    As ``ball-odd``, the rule as shipped (every candidate band starting at 3 x the fastest
    fault rate, the highest envelope line weighed: ``features.band_selection.fault_band``) against
    the tree whose bands may start at 0 Hz, the cage rate in both (docs/diagnosis.md, "Bands
    from 0 Hz": measured in stop 42 without the cage rate, shipped in stop 44, B15).

``sideband-cap DATASET [DATASET ...]``
    As ``ball-odd``, with each first sideband weighed at most at its fundamental's ratio: the
    squared envelope is the fault's train times a non-negative modulation (load zone, shaft,
    cage), whose Fourier coefficients satisfy |M_1| <= M_0, so no sideband of a real fault
    stands above its fundamental (docs/diagnosis.md, "A sideband above its line").

``squared-envelope DATASET [DATASET ...]``
    As ``ball-odd``, demodulating with the squared envelope |z|^2 (the squared envelope
    spectrum of Randall and Antoni 2011) instead of its modulus |z|, in the band selection and
    in the evidence, against the shipped modulus.

``cage-band DATASET [DATASET ...]``
    As ``ball-odd``, the evidence before stop 44 (the band chosen by the fault rates alone,
    the ball's family without the cage lines) against B14's, whose band is chosen by the cage
    rate too (scored in bands from 3 x the fastest fault rate up) and whose ball family weighs
    FTF and 2 x FTF (docs/diagnosis.md, "The cage rate chooses the ball's band"), both on the
    band tree from 0 Hz. Since stop 44 the other modes' "shipped" has the cage rate and the
    band floor.

``own-band DATASET [DATASET ...]``
    As ``ball-odd``, each fault weighed in the band where its own rate shows most clearly (the
    ball's: its 2 x BSF or the cage rate) instead of all three in the one band where any rate
    does; the threshold is the same (it already counts every band for a fundamental's
    maximum). A fault whose rate did not choose the band is read where it shows best.

``whitened DATASET [DATASET ...]``
    As ``ball-odd``: the shipped evidence; the same evidence on the separation's random part
    cepstrally pre-whitened (unit magnitude spectrum, phase kept: Borghesani et al. 2013, the
    whitening of the benchmark method) before the band is chosen (``whitened only``); and
    both, each fault's false-alarm probability the lesser of the two doubled (Bonferroni over
    the two sets of bands: ``whitened union``); and the union with the bins the line editing
    emptied kept empty in the whitened part (``whitened union, emptied bins kept empty``;
    mode ``whitened-kept``: that one and the shipped evidence only). Stop 54,
    docs/diagnosis.md "Pre-whitened bands".

``cage-feature CWRU MFPT CWRU777``
    The FTF line of the envelope over its floor (in the chosen band) as a model feature added
    to ``evidence+scale-free``: extra trees (``cmtool train``'s model for the rig recipes, three
    seeds) trained on CWRU and scored on MFPT, on MFPT scored on CWRU777 (the CWRU-rig recipe
    with seed 777) and on CWRU scored on CWRU777, faulty signals below -10 dB fault SNR left
    out; balanced accuracy and recall per class, with and without the feature.

Run: .venv/bin/python benchmarks/rule_variants.py MODE [DATASET ...]
"""

from __future__ import annotations

import dataclasses
import math
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy import ndimage
from scipy.sparse import linalg as sparse_linalg

import features
import features.band_selection as band_selection
import features.evidence as evidence
import features.separation as separation
from cmtool.datasets import read_dataset
from cmtool.diagnose import diagnose_signal
from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationSettings,
    bearing,
    characteristic_frequencies,
    form_waviness,
    simulate,
)

LABELS = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}
FS = 12000.0
RPM = 1797.0


def _verdict(x: np.ndarray, geometry) -> str:
    d = diagnose_signal(x, FS, RPM, geometry, waviness=False)
    top = d.candidates[0]
    return f"{d.verdict} ({top['fault']} {top['evidence_db'] - d.threshold_db:+.1f})"


def record_length() -> None:
    g = bearing("6205", radial_internal_clearance=5e-6)
    forms = (form_waviness(9, 1e-7, 0.0, 0.0), form_waviness(9, 0.0, 0.0, 1e-7))
    for duration in (1.0, 2.0, 4.0, 8.0):
        settings = SimulationSettings(
            fs=FS, duration=duration, channels=("housing_acceleration_y",)
        )
        row = []
        for load in (100.0, 400.0):
            op = OperatingCondition.from_rpm(RPM, load)
            for form in forms:
                x = simulate(g, op, form, settings=settings, random_state=2)
                row.append(_verdict(x["housing_acceleration_y"], g))
        print(f"{duration:g} s: " + " | ".join(row))


def entry_jitter() -> None:
    g = bearing("6205", radial_internal_clearance=5e-6)
    op = OperatingCondition.from_rpm(RPM, 400.0)
    fs = 48000.0
    settings = SimulationSettings(
        fs=fs, duration=1.0, record_contact_loads=True, channels=("housing_acceleration_y",)
    )
    cases = {
        "perfect": None,
        "inner race 0.1 um": form_waviness(9, 1e-7, 0.0, 0.0),
        "balls 0.1 um": form_waviness(9, 0.0, 0.0, 1e-7),
    }
    for name, form in cases.items():
        r = simulate(g, op, form, settings=settings, scene=Scene(ehl=False), random_state=2)
        loaded = np.asarray(r.contact_loads)[:, 1, :] > 1e-3  # outer contacts (samples, balls)
        steps = np.diff(loaded.astype(int), axis=0)
        entries = np.sort(np.concatenate([np.flatnonzero(col == 1) for col in steps.T])) / fs
        gaps = np.diff(entries)
        cage_revolutions = r.frequencies.ftf * 1.0
        transitions = np.abs(steps).sum(axis=0).mean() / cage_revolutions
        print(
            f"{name}: entry interval {gaps.mean() * 1e3:.3f} ms (1 / BPFO "
            f"{1e3 / r.frequencies.bpfo:.3f}), spread {gaps.std() * 1e6:.0f} us "
            f"({100 * gaps.std() / gaps.mean():.2f} %), {transitions:.1f} transitions per ball "
            "and cage revolution"
        )


def _projections(y: np.ndarray, weights: np.ndarray, nu: np.ndarray) -> np.ndarray:
    t = np.arange(y.size)
    wy = weights * y
    return np.concatenate(
        [np.exp(-2j * np.pi * np.outer(nu[i : i + 256], t)) @ wy for i in range(0, nu.size, 256)]
    )


def _synthesis(amplitudes: np.ndarray, nu: np.ndarray, n: int) -> np.ndarray:
    t = np.arange(n)
    out = np.zeros(n)
    for i in range(0, nu.size, 256):
        out += np.real(amplitudes[i : i + 256] @ np.exp(2j * np.pi * np.outer(nu[i : i + 256], t)))
    return out


def separate_fitted_lines(
    x: np.ndarray,
    fs: float,
    *,
    fundamentals=(),
    line_db: float = separation.LINE_DB,
    window_hz: float = separation.LINE_WINDOW_HZ,
    lattice=(),
) -> np.ndarray:
    """``features.separate_discrete`` with lines fitted and subtracted instead of zeroed."""
    x = np.asarray(x, dtype=float)
    n = x.size
    y = separation.remove_periodic(x, fs, fundamentals, lattice)
    rms = float(np.std(x))
    seed = np.frombuffer(np.ascontiguousarray(x[:64], dtype=float).tobytes(), np.uint32)
    floor_rms = rms * 10.0 ** (-separation.INSTRUMENT_FLOOR_DB / 20.0)
    y = y + np.random.default_rng(seed).normal(0.0, floor_rms, n)
    weights = np.hanning(n)
    weights /= weights.sum()
    bins = max(21, int(round(window_hz * n / fs))) | 1
    for _ in range(3):
        mag = np.abs(np.fft.rfft(y * weights))
        floor = ndimage.median_filter(mag, size=bins, mode="nearest")
        k = np.arange(2, mag.size - 2)
        peak = (mag[k] > 10.0 ** (line_db / 20.0) * floor[k]) & (mag[k] >= mag[k - 1])
        k = k[peak & (mag[k] >= mag[k + 1])]
        if k.size == 0:
            break
        a, b, c = np.log(mag[k - 1]), np.log(mag[k]), np.log(mag[k + 1])
        nu = (k + np.clip(0.5 * (a - c) / (a - 2.0 * b + c), -0.5, 0.5)) / n
        solve = sparse_linalg.splu(separation._hann_gram(nu, n)).solve
        y = y - _synthesis(2.0 * solve(_projections(y, weights, nu)), nu, n)
    return y - y.mean()


def fitted_lines() -> None:
    cases = {
        "inner form": form_waviness(9, 1e-7, 0.0, 0.0),
        "ball form": form_waviness(9, 0.0, 0.0, 1e-7),
        "outer pit": LocalizedDefect(surface="outer", length=0.3e-3, depth=0.1e-3),
        "inner pit": LocalizedDefect(surface="inner", length=0.3e-3, depth=0.1e-3),
    }
    settings = SimulationSettings(fs=FS, duration=1.0, channels=("housing_acceleration_y",))
    shipped = evidence.separate_discrete
    for variant in ("shipped", "fitted lines"):
        evidence.separate_discrete = shipped if variant == "shipped" else separate_fitted_lines
        for clearance in (5e-6, -5e-6):
            g = bearing("6205", radial_internal_clearance=clearance)
            row = []
            for load in (100.0, 400.0):
                for name, defect in cases.items():
                    slip = 0.01 if "pit" in name else 0.0
                    op = OperatingCondition.from_rpm(RPM, load, random_slip=slip)
                    x = simulate(g, op, defect, settings=settings, random_state=2)
                    row.append(f"{name} {load:.0f} N: {_verdict(x['housing_acceleration_y'], g)}")
            print(f"{variant}, {clearance * 1e6:+.0f} um: " + "; ".join(row))
    evidence.separate_discrete = shipped


def ball_odd(paths: list[str], variants=None) -> None:
    variants = variants or {"shipped": _SHIPPED_EVIDENCE, "with BSF and 3 x BSF": None}
    for variant, function in variants.items():
        for path in paths:
            frame = read_dataset(path)
            frame = frame[(frame["label"] == "healthy") | (frame["fault_snr_db"] >= -10)]

            def one(r) -> str:
                x = np.asarray(r.signal, dtype=float)
                d = diagnose_signal(x, r.fs_hz, r.rpm, r.bearing, waviness=False)
                return d.rule_verdict["label"]

            features.fault_evidence = function or _with_odd_ball_lines
            start = time.perf_counter()
            with ThreadPoolExecutor(2) as pool:
                verdicts = np.array(list(pool.map(one, frame.itertuples())))
            right = verdicts == frame["label"].map(LABELS).to_numpy()
            frame = frame.assign(right=right)
            alarms = int((frame["label"].eq("healthy") & ~frame["right"]).sum())
            print(
                f"{variant}, {path} ({len(frame)} signals, {time.perf_counter() - start:.0f} s; "
                f"right {int(frame['right'].sum())}, healthy false alarms {alarms})"
            )
            print(frame.groupby("label")["right"].mean().round(3).to_string())
    features.fault_evidence = _SHIPPED_EVIDENCE


_SHIPPED_EVIDENCE = evidence.fault_evidence
_SHIPPED_CANDIDATE_BANDS = band_selection.candidate_bands


def _shifted_candidate_bands(
    fs, n, *, min_bandwidth, nlevel=6, max_frequency=None, min_frequency=0.0
):
    """The shipped tree's bands and each level's bands shifted by half a band (stop 51)."""
    out = _SHIPPED_CANDIDATE_BANDS(
        fs,
        n,
        min_bandwidth=min_bandwidth,
        nlevel=nlevel,
        max_frequency=max_frequency,
        min_frequency=min_frequency,
    )
    top = fs / band_selection.ANALYSER_RATIO if max_frequency is None else max_frequency
    splits = {1}
    for k in range(1, int(nlevel) + 1):
        splits |= {2**k, 3 * 2 ** (k - 1)}
    for nb in sorted(splits):
        bw = fs / 2 / nb
        if bw < min_bandwidth or bw * n / fs < 64:
            continue
        for b in range(nb - 1):
            low, high = max((b + 0.5) * bw, min_frequency), min((b + 1.5) * bw, top)
            if high - low >= min_bandwidth and (low, high) not in out:
                out.append((low, high))
    return out


def _with_shifted_bands(x, fs, fault_frequencies):
    """The shipped evidence over the tree with half-shifted bands: a resonance on a band edge
    then gets a band centred on it (every thread of a variant sets the same tree)."""
    band_selection.candidate_bands = _shifted_candidate_bands
    return _SHIPPED_EVIDENCE(x, fs, fault_frequencies)


def _with_shipped_bands(x, fs, fault_frequencies):
    """The shipped evidence, the shipped tree put back."""
    band_selection.candidate_bands = _SHIPPED_CANDIDATE_BANDS
    return _SHIPPED_EVIDENCE(x, fs, fault_frequencies)


def _with_odd_ball_lines(x, fs, fault_frequencies):
    """The shipped evidence, with BSF and 3 x BSF weighed into the ball's family."""
    result = _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    ef, ea = result.envelope_frequencies, result.envelope_amplitude
    rates = {k: float(fault_frequencies[k]) for k in evidence.EVIDENCE_FAULTS}
    # the bins searched and the floor's bins as the shipped weighing counts them
    firsts = [evidence.slip_line(ef, ea, rate) for rate in rates.values()]
    searched = max(1, *(r[2] for r in firsts))
    floor = min(r[3] for r in firsts)
    rate, ftf = rates["two_bsf"], float(fault_frequencies["ftf"])
    lines = [(f"{k}x", evidence.slip_line(ef, ea, k * rate)) for k in (1, 2, 3)]
    lines += [(f"1x{s:+d}", evidence.slip_line(ef, ea, rate + s * ftf)) for s in (-1, 1)]
    lines += [(f"{k:g}x", evidence.slip_line(ef, ea, k * rate)) for k in (0.5, 1.5)]
    bands = len(result.selection.bands)
    result.combined["two_bsf"] = evidence._weigh(lines, bands, searched, floor)
    return result


_SHIPPED_BAND_SPECTRUM = band_selection._band_envelope_spectrum
_SHIPPED_ENVELOPE = evidence.envelope


def _squared_band_envelope_spectrum(spec, df, low, high):
    """``band_selection._band_envelope_spectrum`` of the squared envelope |z|^2."""
    i0, i1 = int(math.ceil(low / df)), int(math.floor(high / df))
    m = i1 - i0 + 1
    weights = band_selection._windows.tukey(m, 0.25) if m > 2 else np.ones(m)
    z = np.fft.ifft(spec[i0 : i1 + 1] * weights)
    env = np.abs(z) ** 2
    env = env - env.mean()
    amp = np.abs(np.fft.rfft(env * band_selection._windows.hanning(m)))
    return np.arange(amp.size) * df, amp


def _with_squared_envelope(x, fs, fault_frequencies, squared: bool):
    """The shipped evidence with the squared envelope (``squared``) or its modulus.

    Each variant sets the modules' functions the same way in every thread (the variants run
    one after the other)."""
    if squared:
        band_selection._band_envelope_spectrum = _squared_band_envelope_spectrum
        evidence.envelope = lambda y, f, **o: _SHIPPED_ENVELOPE(y, f, method="squared", **o)
    else:
        band_selection._band_envelope_spectrum = _SHIPPED_BAND_SPECTRUM
        evidence.envelope = _SHIPPED_ENVELOPE
    return _SHIPPED_EVIDENCE(x, fs, fault_frequencies)


def _with_capped_sidebands(x, fs, fault_frequencies):
    """The shipped evidence, each first sideband counted at most at its fundamental's ratio."""
    result = _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    families = {}
    for fault, family in result.families.items():
        fundamental = dict(family)["1x"][0]
        families[fault] = [
            (name, (min(r[0], fundamental), *r[1:]) if name in ("1x-", "1x+") else r)
            for name, r in family
        ]
    searched = max(1, *(family[0][1][2] for family in result.families.values()))
    floor = min(family[0][1][3] for family in result.families.values())
    spacings = {
        fault: float(fault_frequencies.get(evidence._SIDEBANDS.get(fault, ""), 0.0))
        for fault in evidence.EVIDENCE_FAULTS
    }
    ef = result.envelope_frequencies
    combined = evidence.explain_shared_lines(
        families, len(result.selection.bands), searched, floor, float(ef[1] - ef[0]), spacings
    )
    return dataclasses.replace(result, combined=combined)


def _with_cage_lines(x, fs, fault_frequencies, comb_as_test: bool):
    """The shipped evidence, with the envelope's cage-rate lines weighed for the ball."""
    from scipy.stats import chi2

    result = _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    ef, ea = result.envelope_frequencies, result.envelope_amplitude
    ftf = float(fault_frequencies["ftf"])
    family = list(result.families["two_bsf"])
    firsts = [family[0][1]] + [result.families[k][0][1] for k in ("bpfo", "bpfi")]
    searched, floor = max(1, *(r[2] for r in firsts)), min(r[3] for r in firsts)
    bands = len(result.selection.bands)
    cage = [(f"cage {k}x", evidence.slip_line(ef, ea, k * ftf)) for k in (1, 2, 3)]
    if not comb_as_test:
        weighed = evidence._weigh(family + cage[:2], bands, searched, floor)
    else:
        weighed = evidence._weigh(family, bands, searched, floor)
        ratio, _, bins, floor_bins = family[0][1]
        fundamental = bands * separation.line_false_alarm(ratio, bins, floor_bins)
        p = [separation.line_false_alarm(r[0], r[2], r[3]) for _, r in cage]
        comb = float(chi2.sf(-2.0 * float(np.log(np.clip(p, 1e-300, 1.0)).sum()), 2 * len(p)))
        least = min(fundamental, weighed["family_p"], comb)
        weighed["evidence_db"] = separation.ratio_for_false_alarm(3 * least, bands, searched, floor)
        weighed["false_alarm"] = min(1.0, 3 * least)
        weighed["detected"] = weighed["false_alarm"] <= separation.FALSE_ALARM
    result.combined["two_bsf"] = weighed
    return result


_SHIPPED_FAULT_BAND = band_selection.fault_band

#: Columns of the selection's scores that speak for each fault (the ball's cage rate too).
_OWN_RATES = {"bpfo": ("bpfo",), "bpfi": ("bpfi",), "two_bsf": ("two_bsf", "ftf")}


_OWN_BAND = threading.local()  # the band index one thread's next evidence is read in


def _own_band_dispatch(*args, **options):
    """``fault_band`` as shipped, or its candidate ``_OWN_BAND.index`` (per thread)."""
    shipped = _SHIPPED_FAULT_BAND(*args, **options)
    own = getattr(_OWN_BAND, "index", None)
    return shipped if own is None else dataclasses.replace(shipped, band=shipped.bands[own])


def _with_own_bands(x, fs, fault_frequencies):
    """The shipped evidence, each fault's weighing taken in its own best band."""
    evidence.fault_band = _own_band_dispatch  # the same in every thread
    result = _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    selection = result.selection
    chosen = selection.bands.index(selection.band)
    for fault, names in _OWN_RATES.items():
        columns = [selection.rates.index(n) for n in names if n in selection.rates]
        own = int(np.argmax(selection.scores_db[:, columns].max(axis=1)))
        if own == chosen:
            continue
        _OWN_BAND.index = own
        try:
            result.combined[fault] = _SHIPPED_EVIDENCE(x, fs, fault_frequencies).combined[fault]
        finally:
            _OWN_BAND.index = None
    return result


_SHIPPED_SEPARATE = evidence.separate_discrete
_WHITENED = threading.local()  # whether one thread's next evidence whitens its random part


def _whitened_dispatch(x, fs, *args, **options):
    """The separation as shipped, its random part pre-whitened when ``_WHITENED.on`` (per
    thread): unit magnitude spectrum, phase kept (bins of zero magnitude stay zero)."""
    random_part = _SHIPPED_SEPARATE(x, fs, *args, **options)
    if not getattr(_WHITENED, "on", False):
        return random_part
    spectrum = np.fft.rfft(random_part - random_part.mean())
    magnitude = np.abs(spectrum)
    # bins the line editing emptied (rounding residues) stay empty when _WHITENED.keep_empty:
    # at unit magnitude they would put back a comb at the removed lines' spacing
    lowest = 1e-6 * np.median(magnitude) if getattr(_WHITENED, "keep_empty", False) else 0.0
    unit = np.divide(spectrum, magnitude, out=np.zeros_like(spectrum), where=magnitude > lowest)
    return np.fft.irfft(unit, n=random_part.size)


def _whitened_evidence(x, fs, fault_frequencies):
    evidence.separate_discrete = _whitened_dispatch  # the same in every thread
    _WHITENED.on = True
    try:
        return _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    finally:
        _WHITENED.on = False


def _least_false_alarm(result) -> float:
    return min(w["false_alarm"] for w in result.combined.values())


def _with_whitened_union(x, fs, fault_frequencies, keep_empty: bool = False):
    """The shipped evidence or the whitened one, whichever finds a fault more surely, every
    probability doubled (two sets of bands searched); ``keep_empty``: the bins the line
    editing emptied stay empty in the whitened part (variant 2)."""
    evidence.separate_discrete = _whitened_dispatch
    _WHITENED.keep_empty = keep_empty
    shipped = _SHIPPED_EVIDENCE(x, fs, fault_frequencies)
    whitened = _whitened_evidence(x, fs, fault_frequencies)
    result = min((shipped, whitened), key=_least_false_alarm)
    for weighed in result.combined.values():
        weighed["false_alarm"] = min(1.0, 2.0 * weighed["false_alarm"])
        weighed["detected"] = weighed["false_alarm"] <= separation.FALSE_ALARM
    # the verdict reads evidence_db against the threshold: the threshold of twice the bands
    # is that of half the false-alarm probability per set
    fundamentals = [result.families[fault][0][1] for fault in evidence.EVIDENCE_FAULTS]
    threshold = separation.detection_threshold_db(
        2 * len(result.selection.bands),
        searched_bins=max(1, *(line[2] for line in fundamentals)),
        floor_bins=min(line[3] for line in fundamentals),
    )
    return dataclasses.replace(result, threshold_db=threshold)


def _with_whitened_union_kept(x, fs, fault_frequencies):
    """Variant 2: the union, the bins the line editing emptied kept empty when whitened."""
    return _with_whitened_union(x, fs, fault_frequencies, keep_empty=True)


def _rule(cage: bool, tree_from_zero: bool):
    """The rule's evidence with or without the cage rate (band choice and the ball's family)
    and with the band tree from 0 Hz (as before stop 44) or from 3 x the fastest rate (shipped).

    Each variant sets the module's names the same way in every thread (the variants run one
    after the other)."""

    def band(x, fs, rates, cage_rate=None, **options):
        lowest = 0.0 if tree_from_zero else None
        rate = cage_rate if cage else None
        return _SHIPPED_FAULT_BAND(x, fs, rates, rate, min_frequency=lowest, **options)

    def rule_evidence(x, fs, fault_frequencies):
        evidence.fault_band = band
        evidence.CAGE_HARMONICS = (1, 2) if cage else ()
        return _SHIPPED_EVIDENCE(x, fs, fault_frequencies)

    return rule_evidence


def _cage_line(args) -> float:
    """The FTF line of a signal's envelope over its floor [dB] (the rule's chosen band)."""
    x, fs, rpm, name = args
    rates = characteristic_frequencies(bearing(name), rpm / 60).as_dict()
    result = _SHIPPED_EVIDENCE(np.asarray(x, dtype=float), fs, rates)
    ef, ea = result.envelope_frequencies, result.envelope_amplitude
    return evidence.slip_line(ef, ea, rates["ftf"])[0]


def cage_feature(cwru: str, mfpt: str, cwru777: str) -> None:
    from concurrent.futures import ProcessPoolExecutor
    from pathlib import Path

    from cmtool import classifier
    from features import FeatureExtractor

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from cross_domain import print_cell

    frames, plain, extra, keep = {}, {}, {}, {}
    for path in (cwru, mfpt, cwru777):
        frame = read_dataset(path)
        frames[path] = frame
        extractor = FeatureExtractor(feature_set=classifier.DEFAULT_FEATURE_SET, n_jobs=2)
        plain[path] = extractor.fit(frame).transform(frame)
        rows = [(r.signal, r.fs_hz, r.rpm, r.bearing) for r in frame.itertuples()]
        with ProcessPoolExecutor(2) as pool:
            cage = np.array(list(pool.map(_cage_line, rows, chunksize=8)))
        extra[path] = np.hstack([plain[path], cage[:, None]])
        keep[path] = ~(frame["fault_snr_db"].to_numpy() < -10.0)
    for tag, tables in (("shipped", plain), ("with the FTF line", extra)):
        means = []
        for train, test in ((cwru, mfpt), (mfpt, cwru777), (cwru, cwru777)):
            score, _ = print_cell(
                f"{tag}, {train} -> {test}",
                tables[train][keep[train]],
                frames[train]["label"].to_numpy()[keep[train]],
                tables[test][keep[test]],
                frames[test]["label"].to_numpy()[keep[test]],
            )
            means.append(score)
        print(f"{tag}: mean {np.mean(means):.3f}")


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if mode == "record-length":
        record_length()
    elif mode == "fitted-lines":
        fitted_lines()
    elif mode == "entry-jitter":
        entry_jitter()
    elif mode == "ball-odd" and len(sys.argv) > 2:
        ball_odd(sys.argv[2:])
    elif mode == "band-floor" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "B14 (the tree from 0 Hz)": _rule(cage=True, tree_from_zero=True),
                "shipped (from 3 x the fastest rate)": _rule(cage=True, tree_from_zero=False),
            },
        )
    elif mode == "shifted-bands" and len(sys.argv) > 2:
        ball_odd(sys.argv[2:], {"shipped": _with_shipped_bands, "shifted": _with_shifted_bands})
    elif mode == "sideband-cap" and len(sys.argv) > 2:
        ball_odd(sys.argv[2:], {"shipped": _SHIPPED_EVIDENCE, "capped": _with_capped_sidebands})
    elif mode == "squared-envelope" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "modulus |z| (shipped)": lambda x, fs, f: _with_squared_envelope(x, fs, f, False),
                "squared |z|^2": lambda x, fs, f: _with_squared_envelope(x, fs, f, True),
            },
        )
    elif mode == "cage-band" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "before stop 44 (no cage rate)": _rule(cage=False, tree_from_zero=True),
                "B14 (the cage rate)": _rule(cage=True, tree_from_zero=True),
            },
        )
    elif mode == "own-band" and len(sys.argv) > 2:
        ball_odd(sys.argv[2:], {"shipped": _SHIPPED_EVIDENCE, "own band": _with_own_bands})
    elif mode == "whitened" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "shipped": _SHIPPED_EVIDENCE,
                "whitened only": _whitened_evidence,
                "whitened union": _with_whitened_union,
                "whitened union, emptied bins kept empty": _with_whitened_union_kept,
            },
        )
    elif mode == "whitened-kept" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "shipped": _SHIPPED_EVIDENCE,
                "whitened union, emptied bins kept empty": _with_whitened_union_kept,
            },
        )
    elif mode == "cage-feature" and len(sys.argv) == 5:
        cage_feature(*sys.argv[2:])
    elif mode == "ball-cage" and len(sys.argv) > 2:
        ball_odd(
            sys.argv[2:],
            {
                "shipped": _SHIPPED_EVIDENCE,
                "family": lambda x, fs, f: _with_cage_lines(x, fs, f, False),
                "comb": lambda x, fs, f: _with_cage_lines(x, fs, f, True),
            },
        )
    else:
        sys.exit(__doc__)
    evidence.fault_band, evidence.CAGE_HARMONICS = band_selection.fault_band, (1, 2)
    evidence.separate_discrete = _SHIPPED_SEPARATE
