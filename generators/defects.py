"""Geometry of a ball passing a local defect (pit, spall) on a race or a ball.

The ball does not follow the pit's profile: it pivots over the entry edge, sinks by the
sagitta of its curvature over the distance ``e`` to the nearer edge,

    s(e) = R_x - sqrt(R_x^2 - e^2),

R_x the reduced radius of the contact in the rolling direction (1 / R_x = 1 / r_ball +/-
1 / r_race; the same radius that sets the Hertz contact, docs/model.md 3.1), until it touches the
pit's floor at ``depth``, and pivots out over the exit edge. The largest sink is
min(depth, s(L / 2)) for a pit of length L: a narrow, deep pit is bridged (the ball-geometry
limit; for a 6205 the 0.18 mm CWRU pits sink the ball by only ~0.8 um at the outer race); a wide
pit is followed to its floor. The kinks of this path (floor contact, and the centre of a bridged
pit) are the entry and exit impacts (Sawalhi and Randall 2008 use the same path).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ._validate import check_real
from .contact import contact_geometry
from .params import BearingGeometry, LocalizedDefect

__all__ = ["DefectPath", "defect_path", "sagitta"]


def sagitta(bridge_radius: float, distance: float) -> float:
    """Sink of a ball pivoting over an edge: R_x - sqrt(R_x^2 - e^2) [m] (R_x if e >= R_x).

    Parameters
    ----------
    bridge_radius : float
        Radius R_x of the ball's curvature across the defect [m], > 0.
    distance : float
        Distance e of the ball's centre from the edge along the race [m], >= 0.

    Returns
    -------
    float
        How far the ball sinks below the intact surface [m].
    """
    check_real("bridge_radius", bridge_radius, low=0.0, low_inclusive=False, unit="m")
    check_real("distance", distance, low=0.0, unit="m")
    if distance >= bridge_radius:
        return bridge_radius
    return bridge_radius - math.sqrt(bridge_radius * bridge_radius - distance * distance)


@dataclass(frozen=True)
class DefectPath:
    """What the ball sees of a local defect.

    Attributes
    ----------
    surface : str
        ``outer``, ``inner`` or ``ball``.
    depth : float
        Depth of the pit [m].
    half_width : float
        Half the angular width of the pit on its surface [rad].
    surface_radius : float
        Radius of the surface at the contact [m] (race contact radius or ball radius).
    bridge_radius_outer, bridge_radius_inner : float
        Reduced rolling-direction radius R_x of the contact with the outer / inner race [m]
        (a race pit meets one of them; a ball pit meets both, once per ball revolution each).
    max_sink_outer, max_sink_inner : float
        Largest sink of the ball at that contact, min(depth, s(L / 2)) [m].
    """

    surface: str
    depth: float
    half_width: float
    surface_radius: float
    bridge_radius_outer: float
    bridge_radius_inner: float
    max_sink_outer: float
    max_sink_inner: float

    @property
    def max_sink(self) -> float:
        """Largest sink at the contact(s) the pit meets [m]."""
        if self.surface == "outer":
            return self.max_sink_outer
        if self.surface == "inner":
            return self.max_sink_inner
        return max(self.max_sink_outer, self.max_sink_inner)

    @property
    def bridged(self) -> bool:
        """True when the ball never reaches the pit floor at any contact it meets."""
        depth_limited = {
            "outer": (self.max_sink_outer,),
            "inner": (self.max_sink_inner,),
            "ball": (self.max_sink_outer, self.max_sink_inner),
        }[self.surface]
        return all(s < self.depth for s in depth_limited)


def defect_path(geometry: BearingGeometry, defect: LocalizedDefect) -> DefectPath:
    """Angular width, radii and the ball-size-limited sink of a local defect.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    defect : LocalizedDefect
        The pit (length and depth in m).

    Returns
    -------
    DefectPath
    """
    d = geometry.ball_diameter
    c = d * math.cos(geometry.contact_angle)
    radius = {
        "outer": 0.5 * (geometry.pitch_diameter + c),
        "inner": 0.5 * (geometry.pitch_diameter - c),
        "ball": 0.5 * d,
    }[defect.surface]
    half_width = 0.5 * defect.length / radius
    rx_o = contact_geometry(geometry, "outer").rx
    rx_i = contact_geometry(geometry, "inner").rx
    half = 0.5 * defect.length
    return DefectPath(
        surface=defect.surface,
        depth=defect.depth,
        half_width=half_width,
        surface_radius=radius,
        bridge_radius_outer=rx_o,
        bridge_radius_inner=rx_i,
        max_sink_outer=min(defect.depth, sagitta(rx_o, half)),
        max_sink_inner=min(defect.depth, sagitta(rx_i, half)),
    )
