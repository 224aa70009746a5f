"""Catalog of real deep groove ball bearings (presets are data, not subclasses).

Each entry carries a ``source``. Groove conformities are not published by manufacturers;
0.52/0.52 is used throughout (docs/model.md 6.1, [A]). The radial internal clearance default is
10 um (ISO CN group for 24-30 mm bores spans 5-20 um, docs/model.md 6.1).
"""

from __future__ import annotations

import dataclasses

from ._validate import ParameterError
from .params import BearingGeometry

__all__ = ["BEARINGS", "bearing"]

_INCH = 0.0254  # [m]

BEARINGS: dict[str, BearingGeometry] = {
    # CWRU drive-end bearing SKF 6205-2RS JEM: 9 balls, d = 0.3126 in, D = 1.537 in (CWRU Bearing
    # Data Center; ../shared/data/README.md). Ratings and limiting speed: NSK 6205 list
    # (docs/model.md source 8): C0r = 7.85 kN, grease limiting speed 13 000 rpm.
    "6205": BearingGeometry(
        name="6205",
        ball_count=9,
        ball_diameter=0.3126 * _INCH,
        pitch_diameter=1.537 * _INCH,
        static_load_rating=7850.0,
        limiting_speed_rpm=13000.0,
        source="CWRU drive-end SKF 6205-2RS JEM geometry; NSK ratings (docs/model.md 6.1)",
    ),
    # CWRU fan-end bearing SKF 6203-2RS JEM: 8 balls, d = 0.2656 in, D = 1.122 in (CWRU Bearing
    # Data Center; ../shared/data/README.md). 17x40x12 mm; C0r = 4.75 kN, limiting speed
    # 19 000 rpm: SKF general catalogue values (recalled, [R]).
    "6203": BearingGeometry(
        name="6203",
        ball_count=8,
        ball_diameter=0.2656 * _INCH,
        pitch_diameter=1.122 * _INCH,
        static_load_rating=4750.0,
        limiting_speed_rpm=19000.0,
        source="CWRU fan-end SKF 6203-2RS JEM geometry; SKF catalogue ratings [R]",
    ),
    # 6305, 25x62x17 mm: 8 balls of 13/32 in (10.319 mm), pitch diameter 44.2 mm from the ball
    # set of common 6305 designs (recalled, [R]: check your manufacturer's drawing). C0r = 11.6 kN,
    # limiting speed 13 000 rpm: SKF catalogue [R].
    "6305": BearingGeometry(
        name="6305",
        ball_count=8,
        ball_diameter=10.319e-3,
        pitch_diameter=44.2e-3,
        static_load_rating=11600.0,
        limiting_speed_rpm=13000.0,
        source="6305 25x62x17 mm; ball set 8 x 13/32 in, D = 44.2 mm [R]; SKF ratings [R]",
    ),
    # 6002, 15x32x9 mm: 9 balls of 3/16 in (4.762 mm), pitch diameter 23.5 mm (mean of bore
    # and outside diameter) [R]. C0r = 2.85 kN, limiting speed 22 000 rpm: SKF catalogue [R].
    "6002": BearingGeometry(
        name="6002",
        ball_count=9,
        ball_diameter=4.762e-3,
        pitch_diameter=23.5e-3,
        radial_internal_clearance=8e-6,
        static_load_rating=2850.0,
        limiting_speed_rpm=22000.0,
        source="6002 15x32x9 mm; ball set 9 x 3/16 in, D = 23.5 mm [R]; SKF ratings [R]",
    ),
    # 6308, 40x90x23 mm: 8 balls of 19/32 in (15.081 mm), pitch diameter 65 mm (mean of bore and
    # outside diameter) [R]. C0r = 24.0 kN, limiting speed 8 500 rpm: SKF catalogue [R].
    "6308": BearingGeometry(
        name="6308",
        ball_count=8,
        ball_diameter=15.081e-3,
        pitch_diameter=65.0e-3,
        radial_internal_clearance=15e-6,
        static_load_rating=24000.0,
        limiting_speed_rpm=8500.0,
        source="6308 40x90x23 mm; ball set 8 x 19/32 in, D = 65 mm [R]; SKF ratings [R]",
    ),
    # MFPT test bearing (NICE): 8 rolling elements of 0.235 in on a 1.245 in pitch diameter,
    # contact angle 0 (MFPT documentation; ../shared/data/README.md and MANIFEST.csv).
    # No published ratings.
    "mfpt": BearingGeometry(
        name="mfpt",
        ball_count=8,
        ball_diameter=0.235 * _INCH,
        pitch_diameter=1.245 * _INCH,
        source="MFPT bearing fault dataset test bearing (NICE), MFPT Society documentation",
    ),
}


def bearing(name: str, **overrides: object) -> BearingGeometry:
    """Return a catalog bearing, optionally with fields replaced.

    Parameters
    ----------
    name : str
        Designation: one of ``BEARINGS`` (``"6205"``, ``"6203"``, ``"6305"``, ``"6002"``,
        ``"6308"``, ``"mfpt"``). Case-insensitive.
    **overrides
        Fields to replace, e.g. ``radial_internal_clearance=20e-6`` [m].

    Returns
    -------
    BearingGeometry
        The (validated) geometry.

    Examples
    --------
    >>> from generators import bearing
    >>> bearing("6205").ball_count
    9
    """
    key = str(name).strip().lower()
    if key not in BEARINGS:
        raise ParameterError(
            f"bearing = {name!r} is not in the catalog; choose one of {sorted(BEARINGS)}"
        )
    geometry = BEARINGS[key]
    return dataclasses.replace(geometry, **overrides) if overrides else geometry
