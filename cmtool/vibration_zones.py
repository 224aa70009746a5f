"""Evaluation zones of a machine's overall vibration velocity (ISO 10816-3 and ISO 10816-1).

A bearing's faults are read from its lines (``cmtool.diagnose``); whether the machine as a
whole may keep running is judged from its broadband velocity RMS on the bearing housing,
against zone boundaries that depend on the machine's size and support, which a record does not
give. So the analyst names them: a class below, or the limits a site uses.

The four zones, as the standards word them (paraphrased):

- A: the vibration of newly commissioned machines;
- B: normally acceptable for unrestricted long-term operation;
- C: normally unsatisfactory for long-term continuous operation: the machine may run for a
  limited period until an opportunity for remedial action;
- D: normally severe enough to damage the machine.

Boundaries [mm/s RMS] (ISO 10816-3:2009 Annex A, machines over 15 kW measured in situ in its
broad band, 10-1000 Hz or 2-1000 Hz at 600 rpm and below, ``cmtool.diagnosis.overall_band``;
ISO 10816-1:1995 Annex B, the general guide's classes, in the same band). ISO 20816-3:2022
superseded ISO 10816-3; where a site works to it or to limits of its own, give them with
``--zone-limits``. A value on a boundary belongs to the lower zone.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

__all__ = ["MACHINE_CLASSES", "ZONE_MEANINGS", "parse_zone_limits", "vibration_zone", "zone_text"]

#: Machine class -> (standard and class described, (A/B, B/C, C/D) [mm/s RMS]).
MACHINE_CLASSES: dict[str, tuple[str, tuple[float, float, float]]] = {
    "group1-rigid": (
        "ISO 10816-3 group 1 (over 300 kW, or shaft height 315 mm and more), rigid support",
        (2.3, 4.5, 7.1),
    ),
    "group1-flexible": (
        "ISO 10816-3 group 1 (over 300 kW, or shaft height 315 mm and more), flexible support",
        (3.5, 7.1, 11.0),
    ),
    "group2-rigid": (
        "ISO 10816-3 group 2 (15-300 kW, or shaft height 160-315 mm), rigid support",
        (1.4, 2.8, 4.5),
    ),
    "group2-flexible": (
        "ISO 10816-3 group 2 (15-300 kW, or shaft height 160-315 mm), flexible support",
        (2.3, 4.5, 7.1),
    ),
    "class-I": ("ISO 10816-1 class I (small machines, motors up to 15 kW)", (0.71, 1.8, 4.5)),
    "class-II": (
        "ISO 10816-1 class II (medium machines, 15-75 kW without special foundations)",
        (1.12, 2.8, 7.1),
    ),
    "class-III": (
        "ISO 10816-1 class III (large machines on rigid, heavy foundations)",
        (1.8, 4.5, 11.2),
    ),
    "class-IV": (
        "ISO 10816-1 class IV (large machines on soft foundations)",
        (2.8, 7.1, 18.0),
    ),
}

#: Zone -> what it means for the machine (the standards' words, paraphrased).
ZONE_MEANINGS = {
    "A": "as newly commissioned machines",
    "B": "acceptable for unrestricted long-term operation",
    "C": "unsatisfactory for long-term operation: plan remedial action",
    "D": "severe enough to damage the machine",
}


def parse_zone_limits(limits: str | Sequence[float]) -> tuple[float, float, float]:
    """Zone boundaries A/B, B/C, C/D [mm/s RMS], checked: three increasing positive numbers.

    Parameters
    ----------
    limits : str or sequence of float
        ``"1.4,2.8,4.5"`` (or separated by ``/``, ``;`` or spaces) or the three numbers.

    Returns
    -------
    tuple of float
        (A/B, B/C, C/D) [mm/s].

    Raises
    ------
    ValueError
        Not three finite numbers increasing from above 0, named with the value given.

    Examples
    --------
    >>> parse_zone_limits("1.4, 2.8, 4.5")
    (1.4, 2.8, 4.5)
    """
    try:
        parts = re.split(r"[,/;\s]+", limits.strip()) if isinstance(limits, str) else list(limits)
        values = tuple(float(v) for v in parts)
    except (TypeError, ValueError):
        values = ()
    if not (
        len(values) == 3
        and all(math.isfinite(v) for v in values)
        and 0.0 < values[0] < values[1] < values[2]
    ):
        raise ValueError(
            f"zone limits = {limits!r} are outside the allowed range: three boundaries A/B, "
            "B/C, C/D in mm/s RMS, each above 0 and above the one before (e.g. 1.4,2.8,4.5)"
        )
    return values  # type: ignore[return-value]


def vibration_zone(rms_mm_s: float, machine_class: str | Sequence[float]) -> dict:
    """The evaluation zone of an overall velocity RMS for a machine class or site limits.

    Parameters
    ----------
    rms_mm_s : float
        Overall velocity RMS [mm/s] in the standards' broad band.
    machine_class : str or sequence of float
        A key of ``MACHINE_CLASSES``, or the boundaries (A/B, B/C, C/D) [mm/s]
        (:func:`parse_zone_limits`).

    Returns
    -------
    dict
        ``zone`` ("A" to "D"), ``meaning``, ``machine_class`` (the key, or "site limits"),
        ``described`` (the standard and class) and ``limits_mm_s`` [A/B, B/C, C/D].

    Raises
    ------
    ValueError
        An unknown class or bad limits, or an RMS not finite and at least 0, named.

    Examples
    --------
    >>> vibration_zone(3.0, "group2-rigid")["zone"]
    'C'
    >>> vibration_zone(2.8, "group2-rigid")["zone"]  # a boundary belongs to the lower zone
    'B'
    """
    if isinstance(machine_class, str):
        if machine_class not in MACHINE_CLASSES:
            raise ValueError(
                f"machine class = {machine_class!r} is not one of {', '.join(MACHINE_CLASSES)}"
            )
        name = machine_class
        described, limits = MACHINE_CLASSES[machine_class]
    else:
        name, described = "site limits", "limits given (mm/s RMS)"
        limits = parse_zone_limits(machine_class)
    if not (math.isfinite(rms_mm_s) and rms_mm_s >= 0.0):
        raise ValueError(f"rms_mm_s = {rms_mm_s!r} is outside the allowed range [0, inf) mm/s")
    zone = "ABCD"[sum(rms_mm_s > limit for limit in limits)]
    return {
        "zone": zone,
        "meaning": ZONE_MEANINGS[zone],
        "machine_class": name,
        "described": described,
        "limits_mm_s": list(limits),
    }


def zone_text(zone: dict) -> str:
    """A zone of :func:`vibration_zone` as text, for the command's output and the report.

    Parameters
    ----------
    zone : dict
        What :func:`vibration_zone` returns.

    Returns
    -------
    str
        E.g. "B (ISO 10816-3 group 2 ...; A/B 1.4, B/C 2.8, C/D 4.5 mm/s RMS): acceptable for
        unrestricted long-term operation".
    """
    limits = ", ".join(
        f"{name} {value:g}"
        for name, value in zip(("A/B", "B/C", "C/D"), zone["limits_mm_s"], strict=True)
    )
    return f"{zone['zone']} ({zone['described']}; {limits} mm/s RMS): {zone['meaning']}"
