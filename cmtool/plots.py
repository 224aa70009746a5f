"""Plots a vibration analyst looks at: spectra and envelope spectra with fault frequencies marked.

matplotlib with the non-interactive Agg backend; every function writes a PNG and returns its
path.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from features import KurtogramResult  # noqa: E402
from generators import SimulationResult, Waviness  # noqa: E402

__all__ = [
    "save_figure",
    "plot_spectrum",
    "plot_waveform",
    "waveform_window",
    "plot_kurtogram",
    "plot_confusion",
    "plot_entry_exit",
    "plot_trend",
    "waviness_markers",
]

_COLORS = {
    "bpfo": "tab:red",
    "bpfi": "tab:blue",
    "two_bsf": "tab:green",
    "bsf": "tab:olive",
    "ftf": "tab:gray",
    "shaft": "black",
    "wpf": "tab:purple",
}
#: Each fault's colour, that of its rate's marker.
_FAULT_COLORS = {
    "outer race": _COLORS["bpfo"],
    "inner race": _COLORS["bpfi"],
    "ball": _COLORS["two_bsf"],
}


def save_figure(fig: Figure, path: Path | str, **savefig_kwargs: Any) -> Path:
    """Write a figure atomically (a temporary file renamed onto ``path``) and close it.

    A reader (a report viewer, a dashboard polling the folder) never sees half a PNG, and an
    interrupted run leaves the previous file, as with every other result cmtool writes
    (:func:`cmtool.io.atomic_write`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        Where to write it; the format is the suffix's (``.png``, ``.svg``, ``.pdf``).
    **savefig_kwargs
        Passed to ``Figure.savefig`` (``dpi`` for example).

    Returns
    -------
    pathlib.Path
    """
    from .io import atomic_write

    path = Path(path)
    file_format = path.suffix.lstrip(".").lower() or "png"
    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, format=file_format, **savefig_kwargs))
    finally:
        plt.close(fig)
    return path


def plot_spectrum(
    frequencies: np.ndarray,
    amplitude: np.ndarray,
    path: str | Path,
    *,
    title: str,
    ylabel: str,
    markers: Mapping[str, float] | None = None,
    harmonics: int = 3,
    fmax: float | None = None,
    log: bool = True,
    emphasis: str | None = None,
    sidebands: float | None = None,
    top_from: float | None = None,
) -> Path:
    """Plot a spectrum with vertical markers at fault frequencies and their harmonics.

    Parameters
    ----------
    frequencies, amplitude : ndarray
        Spectrum [Hz] and values (unit in ``ylabel``).
    path : str or Path
        PNG to write.
    title, ylabel : str
        Labels.
    markers : mapping of str to float, optional
        Name -> frequency [Hz]; each is drawn at 1 .. ``harmonics`` times its value, the
        verdict's (``emphasis``) at every harmonic up to ``fmax``: the comb an analyst reads.
    harmonics : int
        Harmonics marked per frequency (and sidebands drawn about the verdict's).
    fmax : float, optional
        Upper frequency limit [Hz]; default 10 times the largest marker or the Nyquist.
    log : bool
        Logarithmic amplitude axis (a plain spectrum's decades); False: linear from 0, as
        envelope spectra are read (the lines against their floor).
    top_from : float, optional
        On the linear axis, its height is the spectrum's highest value from this frequency
        up [Hz] (what lies below is drawn off the top): half the cage rate for an envelope
        spectrum, whose first bins hold the envelope's slow wander and its mean's leakage,
        which would otherwise squash the fault's lines.
    emphasis : str, optional
        The marker of the verdict: drawn solid and wider, "(verdict)" in the legend.
    sidebands : float, optional
        Spacing [Hz] of the first sidebands drawn dotted about each harmonic of ``emphasis``
        (the shaft rate for an inner race, the cage rate for a ball).

    Returns
    -------
    Path
        The written PNG.
    """
    path = Path(path)
    markers = dict(markers or {})
    if fmax is None:
        fmax = min(float(frequencies[-1]), 10 * max(markers.values(), default=frequencies[-1]))
    keep = (frequencies > 0) & (frequencies <= fmax)
    fig, ax = plt.subplots(figsize=(10, 4.5), dpi=110)
    # the data over the markers: a marker must not hide the line it marks
    ax.plot(frequencies[keep], amplitude[keep], lw=0.8, color="0.2", zorder=3)
    if log:
        ax.set_yscale("log")
    else:
        lines = amplitude[keep][frequencies[keep] >= (top_from or 0.0)]
        top = float(lines.max()) if lines.size else 0.0
        if top > 0:
            ax.set_ylim(0.0, 1.08 * top)
        else:
            ax.set_ylim(bottom=0.0)
    for name, f0 in markers.items():
        if not f0 or f0 <= 0:
            continue
        color = _COLORS.get(name.split(":")[0], "tab:purple")
        chosen = name == emphasis
        style = (
            {"ls": "-", "lw": 1.6, "alpha": 0.8}
            if chosen
            else {"ls": "--", "lw": 0.9, "alpha": 0.7}
        )
        label = f"{name} (verdict)" if chosen else name
        shown = max(harmonics, int(fmax // f0)) if chosen else harmonics
        for h in range(1, shown + 1):
            if h * f0 <= fmax:
                ax.axvline(h * f0, color=color, label=label if h == 1 else None, **style)
            if chosen and sidebands and h <= harmonics:
                for side in (h * f0 - sidebands, h * f0 + sidebands):
                    if 0 < side <= fmax:
                        ax.axvline(
                            side,
                            color=color,
                            ls=":",
                            lw=1.0,
                            alpha=0.7,
                            label="sidebands" if h == 1 and side < h * f0 else None,
                        )
    ax.set_xlim(0, fmax)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    if markers:
        ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)


#: Columns of the whole-record waveform: a longer record is drawn as each column's extremes.
_WAVEFORM_COLUMNS = 2000


def waveform_window(x: np.ndarray, fs: float, shaft_hz: float, revolutions: float = 3.0) -> slice:
    """The samples of ``revolutions`` shaft turns centred on the record's largest |x|.

    Where a local fault strikes, its impacts stand out of the waveform there; the window is
    cut to the record at either end.

    Parameters
    ----------
    x : numpy.ndarray
        The record.
    fs : float
        Sample rate [Hz].
    shaft_hz : float
        Shaft rate [Hz].
    revolutions : float
        Turns shown [-].

    Returns
    -------
    slice
    """
    width = min(x.size, max(16, round(revolutions * fs / shaft_hz)))
    start = int(np.argmax(np.abs(x))) - width // 2
    start = min(max(start, 0), x.size - width)
    return slice(start, start + width)


def plot_waveform(
    x: np.ndarray,
    fs: float,
    path: str | Path,
    *,
    title: str,
    shaft_hz: float,
    band: tuple[float, float] | None = None,
    fault_hz: float | None = None,
    fault_name: str | None = None,
    ylabel: str = "acceleration",
) -> Path:
    """The time waveform: the whole record, and three shaft turns about its largest peak.

    The zoom shows the record in the envelope analysis' band too (a zero-phase band-pass),
    where impacts ring; with a fault rate, ticks mark its period from the zoom's largest
    impact, so that an analyst can see whether the impacts keep it.

    Parameters
    ----------
    x : numpy.ndarray
        The record (unit in ``ylabel``).
    fs : float
        Sample rate [Hz].
    path : str or Path
        PNG to write.
    title : str
        Title.
    shaft_hz : float
        Shaft rate [Hz] (the zoom spans three turns).
    band : (float, float), optional
        The envelope analysis' band [Hz].
    fault_hz, fault_name : float and str, optional
        The verdict's fault rate [Hz] and name, for the ticks (in the colour of the fault's
        marker in the spectra: outer race red, inner race blue, ball green).
    ylabel : str
        The signal's quantity and unit.

    Returns
    -------
    Path
    """
    from scipy import signal as sp_signal

    x = np.asarray(x, dtype=float)
    t = np.arange(x.size) / fs
    window = waveform_window(x, fs, shaft_hz)
    rows = 3 if band else 2
    fig, axes = plt.subplots(rows, 1, figsize=(10, 2.4 * rows + 0.6), dpi=110)
    whole, zoom = axes[0], axes[1]
    if x.size > 2 * _WAVEFORM_COLUMNS:  # the extremes of each of 2000 columns, as drawn
        per = x.size // _WAVEFORM_COLUMNS
        cols = x[: per * _WAVEFORM_COLUMNS].reshape(_WAVEFORM_COLUMNS, per)
        starts = t[: per * _WAVEFORM_COLUMNS : per]
        whole.fill_between(starts, cols.min(axis=1), cols.max(axis=1), color="0.2", lw=0.4)
    else:
        whole.plot(t, x, lw=0.4, color="0.2")
    whole.axvspan(t[window.start], t[window.stop - 1], color="tab:orange", alpha=0.2)
    whole.set(title=f"{title}: time waveform", ylabel=ylabel, xlim=(0, t[-1]))
    zoom.plot(t[window], x[window], lw=0.7, color="0.2")
    zoom.set(ylabel=ylabel, title="three shaft turns about the largest peak")
    panels = [zoom]
    if band:
        low, high = band
        # an edge within 1e-4 of 0 or of fs/2 is that end (a filter there is singular)
        edges = [e for e in (low, high) if 1e-4 * fs < e < (0.5 - 1e-4) * fs]
        filtered = x[window]  # the whole span, or no width: nothing to filter
        if edges and high > low:
            kind = "bandpass" if len(edges) == 2 else ("highpass" if low > 0 else "lowpass")
            cutoff = edges if len(edges) == 2 else edges[0]
            sos = sp_signal.butter(4, cutoff, kind, fs=fs, output="sos")
            filtered = sp_signal.sosfiltfilt(sos, x)[window]
        axes[2].plot(t[window], filtered, lw=0.7, color="tab:blue")
        axes[2].set(ylabel=ylabel, title=f"the same turns in the band {low:.0f}-{high:.0f} Hz")
        panels.append(axes[2])
    if fault_hz:
        segment = x[window]
        first = t[window.start] + int(np.argmax(np.abs(segment))) / fs
        period = 1.0 / fault_hz
        ticks = first + period * np.arange(
            -np.floor((first - t[window.start]) / period),
            np.floor((t[window.stop - 1] - first) / period) + 1,
        )
        color = _FAULT_COLORS.get(fault_name or "", "tab:red")  # its marker's in the spectra
        for ax in panels:
            for i, tick in enumerate(ticks):
                label = f"{fault_name or 'fault'} period {1e3 * period:.2f} ms" if i == 0 else None
                ax.axvline(tick, color=color, ls="--", lw=0.8, alpha=0.7, label=label)
        panels[0].legend(loc="upper right", fontsize=8)
    for ax in panels:
        ax.set_xlim(t[window.start], t[window.stop - 1])
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time [s]")
    fig.tight_layout()
    return save_figure(fig, path)


def plot_kurtogram(result: KurtogramResult, path: str | Path, *, title: str = "kurtogram") -> Path:
    """Plot a fast kurtogram (``features.KurtogramResult``) with the selected band marked.

    Parameters
    ----------
    result : features.KurtogramResult
        Output of ``features.kurtogram``.
    path : str or Path
        PNG to write.
    title : str
        Title.

    Returns
    -------
    Path
        The written PNG.
    """
    path = Path(path)
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=110)
    extent = (0.0, result.fs / 2, len(result.levels) - 0.5, -0.5)
    im = ax.imshow(
        np.maximum(result.matrix, 0.0),
        aspect="auto",
        extent=extent,
        cmap="viridis",
        interpolation="nearest",
    )
    ax.set_yticks(range(len(result.levels)))
    ax.set_yticklabels([f"{lv:g}" for lv in result.levels])
    low, high = result.band
    row = int(np.argmin(np.abs(result.levels - result.level)))
    ax.add_patch(plt.Rectangle((low, row - 0.5), high - low, 1.0, fill=False, ec="red", lw=1.5))
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("level")
    ax.set_title(f"{title}: band {low:.0f}-{high:.0f} Hz, SK = {result.kurtosis:.2f}")
    fig.colorbar(im, ax=ax, label="spectral kurtosis")
    fig.tight_layout()
    return save_figure(fig, path)


def plot_trend(
    times: Sequence,
    margins: Mapping[str, Sequence[float]],
    bands: Mapping[str, Sequence[float]],
    path: str | Path,
    *,
    title: str,
    band_unit: str,
    spall_mm: tuple[Sequence[float], Sequence[float], Sequence[float]] | None = None,
    zone_limits_mm_s: tuple[float, float, float] | None = None,
) -> Path:
    """A machine's trend: faults' evidence, velocity bands, a spall's length where sized.

    Parameters
    ----------
    times : sequence of datetime-like
        When each recording was taken (sorted).
    margins : mapping of str to sequence of float
        Fault -> its weighed evidence minus the detection threshold [dB] per recording
        (above 0: detected).
    bands : mapping of str to sequence of float
        ISO 15242 band (and ``overall``, ISO 10816-3's broad band) -> velocity RMS per
        recording [``band_unit``].
    path : str or Path
        PNG to write.
    title, band_unit : str
        Title; the bands' unit.
    spall_mm : (sequence, sequence, sequence) of float, optional
        Per recording the spall's length and its interval's ends [mm] (NaN where none was
        sized, ``Diagnosis.severity``): a third panel when any was.
    zone_limits_mm_s : (float, float, float), optional
        The overall velocity's zone boundaries A/B, B/C, C/D [mm/s]
        (``cmtool.vibration_zones``), drawn on the bands' panel when ``band_unit`` is mm/s.

    Returns
    -------
    Path
        The written PNG.
    """
    path = Path(path)
    sized = spall_mm is not None and bool(np.isfinite(np.asarray(spall_mm[0], float)).any())
    fig, axes = plt.subplots(
        3 if sized else 2, 1, figsize=(10, 8.5 if sized else 6), dpi=110, sharex=True
    )
    top, bottom = axes[0], axes[1]
    for fault, values in margins.items():
        top.plot(times, values, marker="o", color=_FAULT_COLORS.get(fault), label=fault)
    top.axhline(0.0, color="0.3", ls="--", lw=1.0, label="detection threshold")
    top.set_ylabel("evidence over threshold [dB]")
    top.set_title(title)
    top.legend(loc="best", fontsize=8)
    top.grid(alpha=0.3)
    for band, values in bands.items():
        name = "overall (ISO 10816-3)" if band == "overall" else f"{band} (ISO 15242)"
        bottom.plot(times, values, marker="s", label=name, ls="--" if band == "overall" else "-")
    if zone_limits_mm_s is not None and band_unit == "mm/s":
        for (name, value), color in zip(
            zip(("A/B", "B/C", "C/D"), zone_limits_mm_s, strict=True),
            ("olive", "goldenrod", "firebrick"),
            strict=True,
        ):
            bottom.axhline(value, color=color, ls="-.", lw=1.0, label=f"zone {name} {value:g} mm/s")
    bottom.set_yscale("log")
    bottom.set_ylabel(f"velocity RMS [{band_unit}]")
    bottom.legend(loc="best", fontsize=8)
    bottom.grid(alpha=0.3)
    if sized:
        length, low, high = (np.asarray(v, dtype=float) for v in spall_mm)
        axes[2].errorbar(
            times,
            length,
            yerr=[length - low, high - length],
            fmt="o",
            capsize=4,
            color="tab:purple",
            label="spall length (interval: docs/diagnosis.md, Severity)",
        )
        axes[2].set_ylabel("spall length [mm]")
        axes[2].legend(loc="best", fontsize=8)
        axes[2].grid(alpha=0.3)
    axes[-1].set_xlabel("time")
    fig.autofmt_xdate()
    fig.tight_layout()
    return save_figure(fig, path)


def plot_segment_evidence(
    segment_s: float,
    margins: Mapping[str, Sequence[float]],
    path: str | Path,
    *,
    title: str,
    found: Mapping[str, Any] | None = None,
) -> Path:
    """Each fault's evidence over the threshold, segment by segment of a long record.

    Parameters
    ----------
    segment_s : float
        Length of a segment [s]; segment i spans i to i + 1 segment lengths.
    margins : mapping of str to sequence of float
        Fault -> its weighed evidence minus the segment's detection threshold [dB] per segment
        (``Diagnosis.segment_scan["margins_db"]``; above 0: detected in that segment).
    path : str or Path
        PNG to write.
    title : str
        Title.
    found : mapping, optional
        The scan's ``found`` (fault, ``start_s``, ``end_s``): that segment is shaded.

    Returns
    -------
    Path
        The written PNG.
    """
    path = Path(path)
    fig, ax = plt.subplots(figsize=(10, 3.6), dpi=110)
    for fault, values in margins.items():
        edges = segment_s * np.arange(len(values) + 1)
        ax.stairs(values, edges, color=_FAULT_COLORS.get(fault), label=fault, lw=1.6, baseline=None)
    ax.axhline(0.0, color="0.3", ls="--", lw=1.0, label="detection threshold (per segment)")
    if found:
        ax.axvspan(found["start_s"], found["end_s"], color="0.85", zorder=0, label="found here")
    labels = ("time in the record [s]", "evidence over threshold [dB]")
    return _finish_time_plot(fig, ax, labels, title, path, legend="best")


def _finish_time_plot(
    fig: Figure, ax: Any, labels: tuple[str, str], title: str, path: str | Path, *, legend: str
) -> Path:
    """Axis labels, title, a small legend and a grid; the figure saved."""
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.set_title(title)
    ax.legend(loc=legend, fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, path)


def plot_entry_exit(
    average: np.ndarray,
    fs: float,
    path: str | Path,
    *,
    title: str,
    spacing_s: float | None = None,
) -> Path:
    """The squared envelope averaged over a fault's impacts, with its entry event marked.

    Parameters
    ----------
    average : numpy.ndarray
        The averaged squared envelope before the impact, the impact last
        (``features.EntryExit.average``) [U^2].
    fs : float
        Sample rate [Hz].
    path : str or Path
        PNG to write.
    title : str
        Title.
    spacing_s : float, optional
        The entry event's time before the impact [s], when one was resolved.

    Returns
    -------
    Path
    """
    fig, ax = plt.subplots(figsize=(9, 3.6))
    t_ms = 1e3 * (np.arange(average.size) - (average.size - 1)) / fs
    ax.plot(t_ms, average, color="0.2", lw=1.0)
    ax.axvline(0.0, color="tab:red", lw=1.2, label="impact (exit)")
    if spacing_s is not None:
        ax.axvline(-1e3 * spacing_s, color="tab:blue", lw=1.2, label="entry event")
    labels = ("time before the impact [ms]", "averaged squared envelope")
    return _finish_time_plot(fig, ax, labels, title, path, legend="upper left")


def plot_confusion(
    matrix: np.ndarray,
    labels: Sequence[str],
    path: str | Path,
    *,
    title: str,
    columns: list[str] | None = None,
) -> Path:
    """Confusion matrix (rows: true label, columns: predicted) with counts in the cells.

    Parameters
    ----------
    matrix : array_like
        Counts, rows the true labels, columns the predicted ones.
    labels : sequence of str
        The true labels, in the rows' order.
    path : str or Path
        The PNG written.
    title : str
        The figure's title.
    columns : list of str, optional
        The predicted labels, when they differ from ``labels``.

    Returns
    -------
    Path
    """
    path = Path(path)
    m = np.asarray(matrix)
    columns = list(labels) if columns is None else list(columns)
    fig, ax = plt.subplots(figsize=(5.5, 4.8), dpi=110)
    ax.imshow(m, cmap="Blues")
    ax.set_xticks(range(len(columns)))
    ax.set_xticklabels(columns, rotation=30, ha="right")
    ax.set_yticks(range(len(labels)))
    ax.set_yticklabels(labels)
    for i in range(m.shape[0]):
        for j in range(m.shape[1]):
            ax.text(
                j,
                i,
                str(m[i, j]),
                ha="center",
                va="center",
                color="white" if m[i, j] > m.max() / 2 else "black",
            )
    ax.set_xlabel("predicted")
    ax.set_ylabel("true")
    ax.set_title(title)
    fig.tight_layout()
    return save_figure(fig, path)


def waviness_markers(result: SimulationResult, defects: Sequence[Waviness]) -> dict[str, float]:
    """Fault-frequency markers for a plot: characteristic frequencies plus waviness lines.

    Parameters
    ----------
    result : SimulationResult
        The run (its bearing and characteristic frequencies).
    defects : sequence of Waviness
        The run's waviness.

    Returns
    -------
    dict of str to float
        Marker name -> frequency [Hz] (:func:`plot_spectrum`'s ``markers``).
    """
    from generators import bearing, waviness_passage_frequencies

    f = result.frequencies
    markers = {"shaft": f.shaft, "bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf}
    geometry = bearing(result.parameters["bearing"]["name"])
    for w in defects:
        if not isinstance(w, Waviness) or w.order < 1:
            continue
        lines = waviness_passage_frequencies(geometry, f.shaft, w.surface, w.order, max_harmonic=1)
        for line in lines[:1]:
            markers[f"wpf:{w.surface} N_w={w.order}"] = line.frequency
    return markers
