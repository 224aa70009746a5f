"""The shaft speed and sample rate a recording is read at where the file holds its own.

A rate or speed given on the command line or in a manifest against the file's (the given
one is used, the difference said), and the speed from a tachometer channel (``--tacho``, a
manifest's ``tacho_channel``), as ``cmtool diagnose``, ``bench`` and ``realism`` read them.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from generators.params import check_shaft_speed_rpm

from .manifest import ManifestEntry

__all__ = [
    "GIVEN_AGAINST_FILE",
    "TACHO_VARIATION_WARNING",
    "differs_from_file",
    "manifest_record",
    "manifest_tacho_speed",
    "tacho_speed",
]


#: A tachometer's speed varying more than this over a record (revolution-to-revolution
#: standard deviation over the mean) is warned of: a fault's lines smear over the range and
#: no order tracking is done.
TACHO_VARIATION_WARNING = 0.01


def tacho_speed(
    path: str | Path,
    variable: str | None,
    channel: str,
    pulses_per_rev: int,
    order_track: bool,
    x: np.ndarray,
    fs: float,
    rpm_given: float | None,
    given_name: str,
) -> tuple[float, str, list[str], np.ndarray]:
    """The speed from a recording's tachometer channel, and the record order-tracked if asked.

    Parameters
    ----------
    path : str or Path
        The recording.
    variable : str or None
        Its variable (``.mat``/``.npz``).
    channel : str
        The tachometer's channel (column or number).
    pulses_per_rev : int
        Tachometer pulses per revolution.
    order_track : bool
        Resample ``x`` to constant shaft speed (:func:`features.order_track`).
    x : ndarray
        The vibration record [U].
    fs : float
        Sample rate [Hz].
    rpm_given : float or None
        The speed given otherwise [rpm] (compared with the tacho's).
    given_name : str
        What gave it, in the warning (``--rpm``, ``the file``, ``shaft_rpm``).

    Returns
    -------
    rpm : float
        The tacho's mean speed [rpm].
    text : str
        What was measured and done, for ``assumptions.speed_measured``.
    warnings : list of str
        A speed given ``SPEED_WARNING`` or more from the tacho's; a spread over
        ``TACHO_VARIATION_WARNING`` where the record is not order-tracked.
    x : ndarray
        The record, order-tracked if asked, else as given.

    Raises
    ------
    cmtool.io.RecordingError
        The tacho channel is the vibration's own, or cannot be read.
    """
    import features

    from .diagnose import SPEED_WARNING
    from .io import RecordingError, read_recording

    pulses, _ = read_recording(path, variable=variable, channel=channel)
    if pulses.shape == x.shape and np.array_equal(pulses, x):
        raise RecordingError(
            f"{path}: tacho channel {channel} is the channel diagnosed; give the vibration's "
            "channel"
        )
    speed = features.shaft_rate_from_tacho(pulses, fs, pulses_per_rev)
    rpm = check_shaft_speed_rpm("the tacho's speed", 60.0 * speed.rate_hz)
    said = []
    if rpm_given is not None and abs(rpm_given / rpm - 1.0) > SPEED_WARNING:
        said.append(
            f"{given_name} {rpm_given:g} rpm is {100 * abs(rpm_given / rpm - 1.0):.1f} % from "
            f"the tacho's {rpm:.1f} rpm; using the tacho's"
        )
    if speed.variation > TACHO_VARIATION_WARNING and not order_track:
        said.append(
            f"the tacho's speed varies by {100 * speed.variation:.1f} % (revolution to "
            "revolution) over the record: the fault lines smear over that range; order "
            "tracking (--order-track, or order_track in a manifest) resamples the record to "
            "constant speed"
        )
    text = (
        f"tacho channel {channel}: {speed.pulses} pulses at {pulses_per_rev} per revolution, "
        f"{rpm:.2f} rpm mean, {100 * speed.variation:.2f} % revolution-to-revolution spread"
    )
    if order_track:
        x = features.order_track(x, fs, speed, pulses_per_rev)
        text += (
            f"; order-tracked: resampled to a constant {rpm:.2f} rpm between the first and "
            f"the last pulse ({x.size} samples)"
        )
    return rpm, text, said, x


#: A rate or speed given differs from the file's where they are this far apart, relative (a
#: CSV's time column written to microseconds gives a 1 s record's rate to about 1e-6).
GIVEN_AGAINST_FILE = 1e-4


def differs_from_file(
    meta: dict, fs: float | None, rpm: float | None, fs_name: str, rpm_name: str
) -> list[str]:
    """Warnings where a rate or speed given is not the one the file holds (the given is used).

    Parameters
    ----------
    meta : dict
        What the file says (:func:`cmtool.io.read_recording`): ``fs_hz`` [Hz], ``rpm``.
    fs : float or None
        The sample rate given [Hz] (None: none given).
    rpm : float or None
        The shaft speed given [rpm] (None: none given).
    fs_name, rpm_name : str
        What gave them, in the warnings (``--fs``, ``the manifest's sampling_rate_hz``).

    Returns
    -------
    list of str
        A warning for each that differs from the file's by more than ``GIVEN_AGAINST_FILE``
        relative.
    """
    said = []
    for key, given, name, unit in (("fs_hz", fs, fs_name, "Hz"), ("rpm", rpm, rpm_name, "rpm")):
        held = meta.get(key)
        if (
            given is not None
            and held is not None
            and abs(held - given) > GIVEN_AGAINST_FILE * given
        ):
            said.append(
                f"{name} {given:g} {unit} differs from the file's {held:g} {unit}; using {name}"
            )
    return said


def manifest_record(entry: ManifestEntry) -> tuple[np.ndarray, float]:
    """A manifest entry's record and the shaft speed to read it at, as ``diagnose`` does.

    Parameters
    ----------
    entry : cmtool.manifest.ManifestEntry
        A line of a ``MANIFEST.csv`` (:func:`cmtool.manifest.read_manifest`).

    Returns
    -------
    x : ndarray
        The record (of the entry's variable, its first channel) [U], order-tracked where the
        entry asks (``order_track``); a velocity's (``unit`` mm/s, m/s, in/s) differentiated
        (``features.acceleration_from_velocity``) [U/s], as ``diagnose`` reads it: detectors
        and the realism gauge's simulations are accelerations.
    rpm : float
        The speed from the entry's tacho channel where it names one (``tacho_channel``,
        ``pulses_per_rev``), else its ``shaft_rpm`` [rpm].
    """
    import features

    from .diagnose import VELOCITY_UNITS
    from .io import read_recording

    x, _ = read_recording(entry.path, variable=entry.variable)
    rpm = float(entry.rpm)
    if entry.tacho is not None:
        rpm, _, _, x = manifest_tacho_speed(entry, entry.variable, x)
    if entry.unit in VELOCITY_UNITS:
        x = features.acceleration_from_velocity(x, entry.fs_hz)
    return x, rpm


def manifest_tacho_speed(
    entry: ManifestEntry, variable: str | None, x: np.ndarray
) -> tuple[float, str, list[str], np.ndarray]:
    """:func:`tacho_speed` from a manifest entry's ``tacho_channel``, ``shaft_rpm`` given.

    Parameters
    ----------
    entry : cmtool.manifest.ManifestEntry
        The entry (its tacho channel, pulses per revolution, order tracking, rate, speed).
    variable : str or None
        The recording's variable (``.mat``/``.npz``).
    x : ndarray
        The vibration record [U].

    Returns
    -------
    tuple
        :func:`tacho_speed`'s ``(rpm, text, warnings, x)``.
    """
    return tacho_speed(
        entry.path,
        variable,
        str(entry.tacho),
        entry.pulses_per_rev,
        entry.order_track,
        x,
        entry.fs_hz,
        entry.rpm,
        "shaft_rpm",
    )
