"""``cmtool bench``'s scores: ROC, detection probabilities by factor, confusion tables, plots.

And the report. All are computed from the per-signal results of
:func:`cmtool.bench.run_bench` (a row per signal and detector: ``label``, the detector's
``verdict`` and a ``score_*`` column per fault). Moved out of :mod:`cmtool.bench` unchanged in
stop 56; ``cmtool.bench`` still exports every name.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pandas as pd

from .diagnose import FAULTS
from .io import atomic_write

__all__ = [
    "FACTORS",
    "FAULT_CLASSES",
    "PFA_LEVELS",
    "SCORE_COLUMNS",
    "score_column",
    "CLASS_ORDER",
    "by_factor",
    "confusion_frame",
    "confusion_plot_name",
    "confusion_tables",
    "plot_pd_vs_snr",
    "plot_roc",
    "score_summary",
    "summarise",
    "threshold_at_pfa",
    "wilson_interval",
    "write_report",
]

#: The faults every detector scores, in the order of the outputs.
FAULT_CLASSES = tuple(FAULTS)  # outer race, inner race, ball
#: False-alarm rates at which detection probabilities are reported.
PFA_LEVELS = (1e-2, 1e-3)
#: Factors reported by bin when the dataset varies them: column -> (name, unit, scale).
FACTORS = {
    "fault_snr_db": ("fault SNR", "dB", 1.0),
    "snr_db": ("SNR", "dB", 1.0),
    "rpm": ("speed", "rpm", 1.0),
    "radial_load_n": ("load", "N", 1.0),
    "defect_length_m": ("pit length", "mm", 1e3),
    "defect_depth_m": ("pit depth", "um", 1e6),
    "waviness_amplitude_m": ("waviness amplitude", "um", 1e6),
    "fs_hz": ("sample rate", "kHz", 1e-3),
    "bearing": ("bearing", "", None),
    "load_from_sensor_deg": ("load's angle from the sensor axis", "deg", 1.0),
    "film_entrainment_factor": ("film entrainment at light load", "", 1.0),
}
#: Width of the SNR bins [dB], from SNR_BIN_ORIGIN_DB up (the benchmark recipe's sweep is
#: -20 to +10 dB: ten bins); fault SNRs below the origin (pits the balls barely touch, whose
#: signature the chain cannot raise to the drawn SNR) are pooled in one bin below it.
SNR_BIN_DB = 3.0
SNR_BIN_ORIGIN_DB = -20.0


def score_column(fault: str) -> str:
    """The results' column of a fault's score (``score_outer_race``, ...).

    Parameters
    ----------
    fault : str
        ``outer race``, ``inner race`` or ``ball``.

    Returns
    -------
    str
    """
    return "score_" + fault.replace(" ", "_")


SCORE_COLUMNS = tuple(score_column(f) for f in FAULT_CLASSES)


def wilson_interval(successes: int, trials: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (95 % by default).

    Parameters
    ----------
    successes, trials : int
        The count of successes and of trials.
    z : float
        The standard normal quantile of the interval's confidence (1.96: 95 %).

    Returns
    -------
    low, high : float
        The interval's ends, in [0, 1]; NaN for no trials.

    Examples
    --------
    >>> [round(v, 4) for v in wilson_interval(9, 10)]
    [0.5958, 0.9821]
    """
    if trials <= 0:
        return (math.nan, math.nan)
    p = successes / trials
    denominator = 1 + z * z / trials
    centre = (p + z * z / (2 * trials)) / denominator
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / denominator
    return (max(0.0, centre - half), min(1.0, centre + half))


def threshold_at_pfa(healthy_scores: np.ndarray, pfa: float) -> float:
    """The smallest threshold whose false-alarm rate on these healthy scores is at most ``pfa``.

    A signal is called faulty when its score exceeds the threshold. NaN when there are fewer
    than ``1 / pfa`` healthy scores (the rate cannot be measured on them).

    Parameters
    ----------
    healthy_scores : array_like
        A detector's scores of healthy signals.
    pfa : float
        The false-alarm rate allowed, in (0, 1).

    Returns
    -------
    float
        The threshold, in the scores' unit.

    Examples
    --------
    >>> threshold_at_pfa(np.arange(100.0), 0.01)
    98.0
    """
    scores = np.sort(np.asarray(healthy_scores, dtype=float))[::-1]
    if scores.size < math.ceil(1.0 / pfa - 1e-9):
        return math.nan
    allowed = int(math.floor(pfa * scores.size + 1e-9))  # false alarms allowed
    return float(scores[allowed])


def _fault_rows(results: pd.DataFrame) -> pd.DataFrame:
    return results[results["label"].isin(FAULT_CLASSES)]


def _own_score(frame: pd.DataFrame) -> np.ndarray:
    """Each faulty signal's score for its own fault."""
    columns = frame["label"].map(score_column)
    return np.array([frame.at[i, c] for i, c in zip(frame.index, columns, strict=True)])


def score_summary(results: pd.DataFrame) -> tuple[pd.DataFrame, dict]:
    """AUC and detection probability at each false-alarm rate, per detector and fault.

    Parameters
    ----------
    results : pandas.DataFrame
        ``cmtool bench``'s results: a row per detector and signal, with ``label`` and the
        score columns (:func:`score_column`).

    Returns
    -------
    table : pandas.DataFrame
        ``detector``, ``fault``, ``auc``, ``pd_at_pfa_0.01``, ``pd_at_pfa_0.001``,
        ``signals``, ``healthy_signals``.
    curves : dict
        The ROC curves, ``{(detector, fault): (fpr, tpr)}``.
    """
    from sklearn.metrics import roc_auc_score, roc_curve

    rows, curves = [], {}
    for detector, group in results.groupby("detector", sort=False):
        healthy = group[group["label"] == "healthy"]
        for fault in FAULT_CLASSES:
            column = score_column(fault)
            positive = group[group["label"] == fault]
            row = {
                "detector": detector,
                "fault": fault,
                "auc": math.nan,
                **{f"pd_at_pfa_{p:g}": math.nan for p in PFA_LEVELS},
                "signals": len(positive),
                "healthy_signals": len(healthy),
            }
            if len(positive) and len(healthy):
                y = np.r_[np.ones(len(positive)), np.zeros(len(healthy))]
                s = np.r_[positive[column].to_numpy(), healthy[column].to_numpy()]
                row["auc"] = float(roc_auc_score(y, s))
                fpr, tpr, _ = roc_curve(y, s)
                curves[(detector, fault)] = (fpr, tpr)
                for p in PFA_LEVELS:
                    tau = threshold_at_pfa(healthy[column].to_numpy(), p)
                    if math.isfinite(tau):
                        row[f"pd_at_pfa_{p:g}"] = float((positive[column] > tau).mean())
            rows.append(row)
    return pd.DataFrame(rows), curves


def _detected_at_pfa(group: pd.DataFrame, pfa: float) -> pd.Series:
    """Per faulty signal of one detector: its own fault's score over that fault's threshold."""
    healthy = group[group["label"] == "healthy"]
    faulty = _fault_rows(group)
    thresholds = {
        f: threshold_at_pfa(healthy[score_column(f)].to_numpy(), pfa) for f in FAULT_CLASSES
    }
    tau = faulty["label"].map(thresholds).to_numpy(dtype=float)
    detected = _own_score(faulty) > tau
    return pd.Series(np.where(np.isfinite(tau), detected, np.nan), index=faulty.index)


def _bins(values: pd.Series, column: str) -> tuple[pd.Series, pd.Series]:
    """Ordered bins of a factor: (numeric centre or category, readable label)."""
    name, unit, scale = FACTORS[column]
    if scale is None:
        return values.astype(str), values.astype(str)
    v = values.astype(float) * scale
    if column in ("fault_snr_db", "snr_db"):
        low = SNR_BIN_ORIGIN_DB + np.floor((v - SNR_BIN_ORIGIN_DB) / SNR_BIN_DB) * SNR_BIN_DB
        below = v < SNR_BIN_ORIGIN_DB
        low = np.where(below, SNR_BIN_ORIGIN_DB - SNR_BIN_DB, low)
        centre = low + SNR_BIN_DB / 2
        label = [
            f"below {SNR_BIN_ORIGIN_DB:+.0f} {unit}"
            if b
            else f"{a:+.0f} to {a + SNR_BIN_DB:+.0f} {unit}"
            for a, b in zip(low, below, strict=True)
        ]
        return pd.Series(centre, index=values.index), pd.Series(label, index=values.index)
    distinct = np.unique(v)
    if distinct.size <= 6:
        return v, pd.Series([f"{a:.4g} {unit}".strip() for a in v], index=values.index)
    edges = np.unique(np.quantile(v, np.linspace(0, 1, 5)))
    index = np.clip(np.searchsorted(edges, v, side="right") - 1, 0, edges.size - 2)
    centre = (edges[index] + edges[index + 1]) / 2
    label = [f"{_number(edges[i])}-{_number(edges[i + 1])} {unit}".strip() for i in index]
    return pd.Series(centre, index=values.index), pd.Series(label, index=values.index)


def _number(value: float) -> str:
    """A bin edge as people write it: 1797, 0.25, 12.8."""
    return f"{value:.0f}" if abs(value) >= 100 else f"{value:.3g}"


def by_factor(
    results: pd.DataFrame, column: str, pfa: float = 1e-2, *, fault: str | None = None
) -> pd.DataFrame:
    """Detection probability at ``pfa`` against one factor, per detector, bins in order.

    Thresholds are set per detector and fault on all the healthy signals; each faulty signal
    (of ``fault`` only, when given) counts in the bin of its factor value. Columns:
    ``detector``, ``bin`` (readable), ``value`` (the bin's centre, numeric where the factor
    is), ``pd_at_pfa_<pfa>``, ``ci_low``, ``ci_high`` (Wilson 95 %), ``signals``.

    Parameters
    ----------
    results : pandas.DataFrame
        ``cmtool bench``'s results (:func:`score_summary`).
    column : str
        The factor (a results column: ``fault_snr_db``, ``rpm``, ``noise_rms``, ...).
    pfa : float
        The false-alarm rate the thresholds are set at.
    fault : str, optional
        Only this fault's signals.

    Returns
    -------
    pandas.DataFrame
    """
    rows = []
    key = f"pd_at_pfa_{pfa:g}"
    for detector, group in results.groupby("detector", sort=False):
        detected = _detected_at_pfa(group, pfa)
        faulty = _fault_rows(group)
        if fault is not None:
            detected = detected[faulty["label"] == fault]
            faulty = faulty[faulty["label"] == fault]
        if column not in faulty or faulty[column].isna().all():
            continue
        keep = faulty[column].notna()
        centre, label = _bins(faulty.loc[keep, column], column)
        frame = pd.DataFrame({"value": centre, "bin": label, "detected": detected[keep.to_numpy()]})
        for (value, text), part in frame.groupby(["value", "bin"], sort=True):
            hits = part["detected"].dropna()
            ci = wilson_interval(int(hits.sum()), len(hits))
            rows.append(
                {
                    "detector": detector,
                    "bin": text,
                    "value": value,
                    key: float(hits.mean()) if len(hits) else math.nan,
                    "ci_low": ci[0],
                    "ci_high": ci[1],
                    "signals": len(part),
                }
            )
    columns = ["detector", "bin", "value", key, "ci_low", "ci_high", "signals"]
    return pd.DataFrame(rows, columns=columns)


def _rates(group: pd.DataFrame) -> pd.Series:
    faulty = group["label"] != "healthy"
    healthy = ~faulty
    called = group["verdict"] != "healthy"
    return pd.Series(
        {
            "signals": len(group),
            "detection_rate": float(called[faulty].mean()) if faulty.any() else np.nan,
            "false_alarm_rate": float(called[healthy].mean()) if healthy.any() else np.nan,
            "correct_fault_first_rate": float((group["verdict"] == group["label"])[faulty].mean())
            if faulty.any()
            else np.nan,
            "accuracy": float((group["verdict"] == group["label"]).mean()),
        }
    )


#: Order of the classes in confusion tables; a label or verdict outside it (``unknown``: a
#: manifest's fault location cmtool does not know) follows.
CLASS_ORDER = ("healthy", "outer race", "inner race", "ball")


def confusion_tables(results: pd.DataFrame) -> pd.DataFrame:
    """Each detector's own labels against the true classes: counts, overall and per rig.

    Parameters
    ----------
    results : DataFrame
        :func:`run_bench`'s rows: ``detector``, ``label`` (true class), ``verdict`` and
        ``rig`` (a manifest's ``dataset`` column, else the bearing).

    Returns
    -------
    DataFrame
        Long form, one row per detector, rig, true class and verdict: ``detector``, ``rig``
        (``all``, then each rig when the signals come from several), ``label``, ``verdict``,
        ``count``; every true class present against those and every verdict the detector
        gave (one that only tells faulty from healthy says ``fault``), zeros included.

    Examples
    --------
    >>> r = pd.DataFrame({"detector": "envelope", "label": ["healthy", "ball", "ball"],
    ...                   "verdict": ["healthy", "ball", "outer race"], "rig": "CWRU"})
    >>> confusion_frame(confusion_tables(r), "envelope")  # doctest: +NORMALIZE_WHITESPACE
    verdict  healthy  outer race  ball
    label
    healthy        1           0     0
    ball           0           1     1
    """

    def ordered(names: set) -> list[str]:
        return [c for c in CLASS_ORDER if c in names] + sorted(names - set(CLASS_ORDER))

    truth = ordered(set(results["label"]))
    rigs = results["rig"] if "rig" in results else pd.Series("all", index=results.index)
    groups = [("all", results)]
    if rigs.nunique() > 1:
        groups += [(str(rig), part) for rig, part in results.groupby(rigs, sort=True)]
    rows = []
    for detector in results["detector"].unique():
        said = results.loc[results["detector"] == detector, "verdict"]
        classes = ordered(set(truth) | set(said))
        for rig, part in groups:
            mine = part[part["detector"] == detector]
            counts = mine.groupby(["label", "verdict"]).size()
            rows += [
                {
                    "detector": detector,
                    "rig": rig,
                    "label": label,
                    "verdict": verdict,
                    "count": int(counts.get((label, verdict), 0)),
                }
                for label in truth
                for verdict in classes
            ]
    return pd.DataFrame(rows, columns=["detector", "rig", "label", "verdict", "count"])


def confusion_plot_name(detector: str, rig: str = "all") -> str:
    """File name of a detector's confusion plot (``confusion_<detector>[_<rig>].png``).

    Parameters
    ----------
    detector : str
        The detector's name.
    rig : str
        The rig's (bearing's) name, or ``all``.

    Returns
    -------
    str
    """
    slug = re.sub(r"[^A-Za-z0-9]+", "_", detector if rig == "all" else f"{detector}_{rig}")
    return f"confusion_{slug.strip('_')}.png"


def confusion_frame(tables: pd.DataFrame, detector: str, rig: str = "all") -> pd.DataFrame:
    """One detector's confusion matrix from :func:`confusion_tables`.

    Rows: the true classes; columns: the verdicts; both in :data:`CLASS_ORDER`.

    Parameters
    ----------
    tables : pandas.DataFrame
        :func:`confusion_tables`' counts.
    detector : str
        The detector.
    rig : str
        The rig, or ``all``.

    Returns
    -------
    pandas.DataFrame
        Counts of signals.
    """
    part = tables[(tables["detector"] == detector) & (tables["rig"] == rig)]
    frame = part.pivot(index="label", columns="verdict", values="count")
    return frame.reindex(
        index=list(dict.fromkeys(part["label"])), columns=list(dict.fromkeys(part["verdict"]))
    )


def summarise(results: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """The detectors' own labels: rates per detector (``overall``) and by each factor.

    Parameters
    ----------
    results : pandas.DataFrame
        ``cmtool bench``'s results, with each detector's ``verdict``.

    Returns
    -------
    dict of str to pandas.DataFrame
        ``overall`` and one table per factor the dataset varies: signals, detection rate,
        false-alarm rate, right fault first and accuracy.
    """
    out = {"overall": results.groupby("detector", sort=False)[["label", "verdict"]].apply(_rates)}
    for column in FACTORS:
        if column not in results.columns or results[column].nunique() < 2:
            continue
        centre, label = _bins(results[column].dropna(), column)
        frame = results.loc[centre.index].assign(_value=centre, _bin=label)
        table = frame.groupby(["detector", "_value", "_bin"], sort=True)[
            ["label", "verdict"]
        ].apply(_rates)
        out[column] = table.droplevel("_value").rename_axis(["detector", "bin"])
    return out


# ------------------------------------------------------------------------------- outputs


def plot_roc(curves: dict, path: Path, *, title: str = "") -> Path:
    """ROC curves, one panel per fault, one line per detector (log false-alarm axis).

    Parameters
    ----------
    curves : dict
        ``{(detector, fault): (fpr, tpr)}`` (:func:`score_summary`).
    path : pathlib.Path
        The PNG written.
    title : str
        The figure's title.

    Returns
    -------
    pathlib.Path
    """
    from .plots import plt, save_figure

    fig, axes = plt.subplots(1, len(FAULT_CLASSES), figsize=(13, 4.2), dpi=110, sharey=True)
    detectors = list(dict.fromkeys(d for d, _ in curves))
    for ax, fault in zip(axes, FAULT_CLASSES, strict=True):
        for detector in detectors:
            if (detector, fault) not in curves:
                continue
            fpr, tpr = curves[(detector, fault)]
            ax.step(np.maximum(fpr, 1e-4), tpr, where="post", label=detector)
        ax.set_xscale("log")
        ax.set_xlim(1e-3, 1)
        ax.set_ylim(0, 1.02)
        ax.set_xlabel("false-alarm probability")
        ax.set_title(fault)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("detection probability")
    with_curves = [ax for ax in axes if ax.get_legend_handles_labels()[0]]
    if with_curves:  # none for a dataset of healthy signals only
        with_curves[-1].legend(fontsize=8, loc="lower right")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return save_figure(fig, path)


def plot_pd_vs_snr(table: pd.DataFrame, path: Path, *, pfa: float = 1e-2, title: str = "") -> Path:
    """Detection probability at ``pfa`` against the fault SNR with Wilson 95 % bands.

    One panel for every fault together, and one per fault when ``table`` has a ``fault``
    column (rows with ``fault`` = ``all`` make the first panel).

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`by_factor` on the fault SNR, its ``value`` (the bins' centres [dB]) named
        ``snr_db``, with a ``fault`` column (``all`` or the fault).
    path : pathlib.Path
        The PNG written.
    pfa : float
        The false-alarm rate of the table's thresholds.
    title : str
        The figure's title.

    Returns
    -------
    pathlib.Path
    """
    from .plots import plt, save_figure

    faults = list(dict.fromkeys(table["fault"])) if "fault" in table else ["all"]
    fig, axes = plt.subplots(
        1, len(faults), figsize=(4.2 * len(faults) + 1, 4.4), dpi=110, sharey=True, squeeze=False
    )
    key = f"pd_at_pfa_{pfa:g}"
    for ax, fault in zip(axes[0], faults, strict=True):
        part_fault = table[table["fault"] == fault] if "fault" in table else table
        for detector, part in part_fault.groupby("detector", sort=False):
            part = part.sort_values("snr_db")
            line = ax.plot(part["snr_db"], part[key], marker="o", ms=3, label=detector)[0]
            ax.fill_between(
                part["snr_db"], part["ci_low"], part["ci_high"], color=line.get_color(), alpha=0.1
            )
        if not part_fault[key].notna().any():  # too few healthy signals for the threshold
            ax.text(
                0.5,
                0.5,
                f"not measurable: a threshold at false alarm {pfa:g}\n"
                f"needs {math.ceil(1 / pfa)} or more healthy signals",
                transform=ax.transAxes,
                ha="center",
                va="center",
                fontsize=9,
            )
        ax.set_xlabel("fault SNR where the fault stands out most [dB]")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.set_title("every fault" if fault == "all" else fault)
    axes[0][0].set_ylabel(f"detection probability at false alarm {pfa:g}")
    axes[0][-1].legend(fontsize=7, loc="upper left")
    fig.suptitle(title or "detection against SNR")
    fig.tight_layout()
    return save_figure(fig, path)


def _markdown(frame: pd.DataFrame, digits: int = 3) -> str:
    columns = list(frame.columns)
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for _, row in frame.iterrows():
        cells = []
        for c in columns:
            v = row[c]
            if isinstance(v, float):
                cells.append("n/a" if math.isnan(v) else f"{v:.{digits}f}")
            else:
                cells.append(str(v))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _pivot(table: pd.DataFrame, label: str, order: str, pfa: float = 1e-2) -> str:
    """A markdown table: one row per bin (in order), one column per detector."""
    key = f"pd_at_pfa_{pfa:g}"
    if not len(table):
        return "(no faulty signals)"
    detectors = list(dict.fromkeys(table["detector"]))
    bins = table.drop_duplicates(label).sort_values(order)[label].tolist()
    lines = [
        "| " + " | ".join(["bin", *detectors, "signals"]) + " |",
        "|" + "---|" * (len(detectors) + 2),
    ]
    for b in bins:
        part = table[table[label] == b].set_index("detector")
        cells = []
        for d in detectors:
            if d not in part.index or not math.isfinite(part.at[d, key]):
                cells.append("n/a")
            else:
                r = part.loc[d]
                cells.append(f"{r[key]:.2f} [{r['ci_low']:.2f}, {r['ci_high']:.2f}]")
        lines.append(f"| {b} | " + " | ".join(cells) + f" | {int(part['signals'].iloc[0])} |")
    return "\n".join(lines)


def write_report(
    path: Path,
    dataset: str,
    summary: pd.DataFrame,
    by_snr: pd.DataFrame,
    factors: dict[str, pd.DataFrame],
    *,
    in_sample: float = 0.0,
    confusion: pd.DataFrame | None = None,
) -> Path:
    """``report.md``: the tables, the plots, and what the figures rest on.

    Parameters
    ----------
    path : pathlib.Path
        ``report.md``'s path.
    dataset : str
        The dataset's name, as the report states it.
    summary : pandas.DataFrame
        :func:`score_summary`'s table.
    by_snr : pandas.DataFrame
        Detection probability against the fault SNR (:func:`by_factor`).
    factors : dict of str to pandas.DataFrame
        The same against each other factor.
    in_sample : float
        The share of the signals that trained the model (0 to 1; above 0 the report says
        its figures are in-sample).
    confusion : pandas.DataFrame, optional
        :func:`confusion_tables`: each detector's labels by class, over all signals and
        per rig, with the plots the CLI writes beside the report
        (:func:`confusion_plot_name`).

    Returns
    -------
    pathlib.Path
    """
    healthy = int(summary["healthy_signals"].max()) if len(summary) else 0
    lines = [f"# Detector benchmark: {dataset}", ""]
    if in_sample:
        lines += [
            f"**IN-SAMPLE**: {in_sample:.0%} of these signals trained the model; its figures "
            "are not a measure of accuracy.",
            "",
        ]
    lines += [
        f"Healthy signals: {healthy} (detection at a false-alarm rate p needs at least 1/p of "
        "them; n/a otherwise). Thresholds are set per detector and fault on the healthy "
        "signals only.",
        "",
        "## ROC area and detection at fixed false-alarm rates",
        "",
        _markdown(summary),
        "",
        "![ROC](roc.png)",
        "",
    ]
    if len(by_snr):
        lines += [
            "## Detection at false alarm 0.01 against the fault SNR",
            "",
            "Every fault together; each cell: detection probability [Wilson 95 % interval] "
            "(signals in the bin in the last column).",
            "",
            _pivot(by_snr, "bin", "snr_db"),
            "",
            "![Pd against SNR](pd_vs_snr.png)",
            "",
        ]
    if confusion is not None and len(confusion):
        lines += [
            "## By class: each detector's own labels",
            "",
            "Rows: the true class; columns: the detector's verdict (counts of signals); over all "
            "signals, then per rig when they come from several.",
            "",
        ]
        pairs = dict.fromkeys(zip(confusion["detector"], confusion["rig"], strict=True))
        for detector, rig in pairs:
            heading = detector if rig == "all" else f"{detector}, {rig}"
            frame = confusion_frame(confusion, detector, rig)
            lines += [
                f"### {heading}",
                "",
                _markdown(frame.rename_axis(index="true class").reset_index()),
                "",
                f"![{heading}]({confusion_plot_name(detector, rig)})",
                "",
            ]
    for column, table in factors.items():
        name, unit, _ = FACTORS[column]
        lines += [f"## By {name}", "", _pivot(table, "bin", "value"), ""]
    text = "\n".join(lines)
    atomic_write(path, lambda tmp: tmp.write_text(text))
    return path
