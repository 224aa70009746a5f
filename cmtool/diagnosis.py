"""The result of a diagnosis (:class:`Diagnosis`, from ``cmtool.diagnose.diagnose_signal``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

__all__ = ["DETECTION_DB", "Diagnosis", "overall_band", "overall_velocity"]

#: The rule's threshold for a line searched over about five bins of one band at a false-alarm
#: probability of 1e-4 [dB] (the module docstring of ``cmtool.diagnose``); a record's own
#: threshold, for the bands and lines it weighed, is ``Diagnosis.threshold_db``.
DETECTION_DB = 12.0


@dataclass
class Diagnosis:
    """Verdict and evidence of one signal (:func:`cmtool.diagnose.diagnose_signal`).

    :meth:`to_dict` gives the JSON of ``cmtool diagnose --json`` and of a report's
    ``diagnosis.json`` (docs/diagnosis.md); the attributes below are its keys unless said.

    Attributes
    ----------
    verdict : str
        ``healthy``, ``outer race``, ``inner race`` or ``ball``: the rule's, or the rule's and
        the model's pooled when a model was given (``basis`` says which).
    confidence : float
        The verdict's confidence in [0, 1] (calibrated by ``cmtool train`` when pooled).
    candidates : list of dict
        Each fault ranked by its weighed evidence: its rate and the line found [Hz], the
        envelope lines' ratios to their floor [dB], the evidence and its false-alarm
        probability, whether it is detected, and its confidence.
    frequencies : dict of str to float
        The bearing's characteristic frequencies at the speed used [Hz].
    band_hz : (float, float)
        The envelope analysis' band [Hz] (``envelope_band_hz`` in the JSON).
    warnings : list of str
        What makes the answer less certain, or what was assumed for want of input.
    model_verdict : dict or None
        The model's own class, probabilities and segments read, when a model was given.
    waviness : dict or None
        Race waviness read from the plain spectrum's lines (surface, order, line [Hz] and
        its ratios [dB]) on a healthy verdict, or None.
    spectra : features.Spectra
        The plain and envelope spectra shown in a report (not in the JSON).
    threshold_db : float
        The evidence a fault needs to be detected [dB] (false-alarm probability
        ``features.FALSE_ALARM`` per fault in this record).
    assumptions : dict
        What the answer rests on: bearing, speed given and used [rev/min], sample rate
        [Hz], record length [s] and samples, band [Hz], the line search and the evidence
        weighed.
    rule_verdict : dict or None
        The rule's own ``label`` and ``confidence``.
    basis : str
        What the verdict rests on, in words.
    probabilities : dict or None
        The pooled probability of each verdict, when a model was given.
    velocity_bands : dict or None
        RMS velocity in the ISO 15242 bands ``low`` (50-300 Hz), ``medium`` (300-1800 Hz)
        and ``high`` (1800-10000 Hz) [signal unit x s] (``velocity_bands_iso15242``).
    velocity_bands_mm_s : dict or None
        The same [mm/s], when the acceleration's unit was given
        (``velocity_bands_iso15242_mm_s``).
    overall_velocity : dict or None
        RMS velocity in ISO 10816-3's broad band (``band_hz``, ``rms`` [signal unit x s],
        ``rms_mm_s`` [mm/s] or None, and with a machine class its evaluation ``zone``,
        ``cmtool.vibration_zones.vibration_zone``) (``overall_velocity_iso10816``).
    baseline : dict or None
        The velocity bands against a healthy baseline recording and their change [dB].
    severity : dict or None
        On a fault verdict, the fault's size (``cmtool.severity.spall_size``): ``estimated``
        and either the spall's length [mm] with its interval, or why it is not given.
    entry_exit : features.EntryExit or None
        The entry-exit timing behind ``severity`` (its averaged envelope, for the report's
        figure; not in the JSON).
    segment_scan : dict or None
        The record weighed second by second (segments, their margins over the threshold
        [dB] and the one found), when its whole envelope showed no fault.
    """

    verdict: str
    confidence: float
    candidates: list[dict]
    frequencies: dict[str, float]
    band_hz: tuple[float, float]
    warnings: list[str] = field(default_factory=list)
    model_verdict: dict | None = None
    waviness: dict | None = None
    spectra: Any = None
    threshold_db: float = DETECTION_DB
    assumptions: dict = field(default_factory=dict)
    rule_verdict: dict | None = None
    basis: str = "the rule evidence (envelope analysis of the random part)"
    probabilities: dict | None = None
    velocity_bands: dict | None = None
    velocity_bands_mm_s: dict | None = None
    overall_velocity: dict | None = None
    baseline: dict | None = None
    severity: dict | None = None
    segment_scan: dict | None = None
    entry_exit: Any = None

    def to_dict(self) -> dict:
        """JSON-serialisable form (without the spectra).

        Returns
        -------
        dict
            The attributes under their JSON keys (see the class description); those that are
            None are left out, and confidences and thresholds are rounded to 4 and 2 decimals.
        """
        out = {
            "verdict": self.verdict,
            "confidence": round(self.confidence, 4),
            "candidates": self.candidates,
            "frequencies": self.frequencies,
            "envelope_band_hz": list(self.band_hz),
            "basis": self.basis,
            "threshold_db": round(self.threshold_db, 2),
            "assumptions": self.assumptions,
            "warnings": self.warnings,
        }
        if self.waviness is not None:
            out["waviness"] = self.waviness
        if self.rule_verdict is not None:
            out["rule_verdict"] = self.rule_verdict
        if self.model_verdict is not None:
            out["model_verdict"] = self.model_verdict
        if self.probabilities is not None:
            out["probabilities"] = self.probabilities
        if self.velocity_bands is not None:
            out["velocity_bands_iso15242"] = self.velocity_bands
        if self.velocity_bands_mm_s is not None:
            out["velocity_bands_iso15242_mm_s"] = self.velocity_bands_mm_s
        if self.overall_velocity is not None:
            out["overall_velocity_iso10816"] = self.overall_velocity
        if self.baseline is not None:
            out["baseline"] = self.baseline
        if self.severity is not None:
            out["severity"] = self.severity
        if self.segment_scan is not None:
            out["segment_scan"] = self.segment_scan
        return out


def overall_band(rpm: float) -> tuple[float, float]:
    """ISO 10816-3's broad band [Hz]: 10-1000 Hz, or 2-1000 Hz for shafts at 600 rpm or less.

    The band the standard's zones are set in; the zones themselves depend on the machine's
    class and foundation, which a record does not give.

    Parameters
    ----------
    rpm : float
        Shaft speed [rev/min].

    Returns
    -------
    low, high : float
        The band [Hz].
    """
    return (2.0 if rpm <= 600.0 else 10.0, 1000.0)


def overall_velocity(
    rms: float, band: tuple[float, float], fs: float, scale: float | None
) -> dict | None:
    """The machine's overall vibration: the velocity RMS over :func:`overall_band`.

    Parameters
    ----------
    rms : float
        The velocity RMS over the band [signal unit x s].
    band : (float, float)
        The band [Hz] (:func:`overall_band`).
    fs : float
        The record's sample rate [Hz] (the band ends at fs / 2 at most).
    scale : float or None
        The signal's unit in m/s^2 (None: unknown).

    Returns
    -------
    dict or None
        ``band_hz``, ``rms`` [signal unit x s] and ``rms_mm_s`` [mm/s] (None: unit unknown);
        None where fs/2 lies below the band's start.
    """
    if not math.isfinite(rms):
        return None
    return {
        "band_hz": [band[0], min(band[1], fs / 2)],
        "rms": rms,
        "rms_mm_s": None if scale is None else 1e3 * scale * rms,
    }
