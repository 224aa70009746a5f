"""Static load distribution of a radially loaded deep groove ball bearing (Stribeck/Harris).

The inner ring (shaft) is displaced by (x, y) relative to the outer ring. Ball j at angle
theta_j has the approach delta_j = x cos(theta_j) + y sin(theta_j) - c_r + e_j, where c_r = P_d / 2
is the per-ball gap and e_j an optional extra approach (EHL film, uniform waviness). Its load
is Q_j = K_tot [delta_j]_+^1.5 and the equilibrium is sum_j Q_j (cos theta_j, sin theta_j) = F.
Checks: Q_max Z / F_r = 4.37 at zero clearance for large Z (Stribeck; catalogue constant),
~5 with clearance; ISO/TS 16281 reference deflections (docs/model.md 7.6 T2-T4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _static_kernels as SK
from ._validate import ParameterError, check_real
from .contact import load_deflection_constants
from .params import BearingGeometry

__all__ = ["StaticSolution", "static_load_distribution"]


@dataclass(frozen=True)
class StaticSolution:
    """Static equilibrium of the bearing under a radial load.

    Attributes
    ----------
    displacement : ndarray, shape (2,)
        Inner-ring displacement (x, y) relative to the outer ring [m].
    deflection : float
        Displacement along the load direction delta_r [m].
    ball_angles : ndarray, shape (Z,)
        Ball angles theta_j [rad].
    ball_loads : ndarray, shape (Z,)
        Ball loads Q_j [N].
    radial_stiffness : float
        Tangent stiffness dF_r / d delta_r along the load direction [N/m].
    """

    displacement: np.ndarray
    deflection: float
    ball_angles: np.ndarray
    ball_loads: np.ndarray
    radial_stiffness: float

    @property
    def max_ball_load(self) -> float:
        """Largest ball load Q_max [N]."""
        return float(self.ball_loads.max())

    @property
    def loaded_ball_count(self) -> int:
        """Number of balls with a positive load [-]."""
        return int(np.count_nonzero(self.ball_loads > 0))


def static_load_distribution(
    geometry: BearingGeometry,
    radial_load: float,
    *,
    load_angle: float = -math.pi / 2,
    cage_angle: float = 0.0,
    extra_approach: float | np.ndarray = 0.0,
    stiffness_constant: float | None = None,
) -> StaticSolution:
    """Solve the static equilibrium of the inner ring under a radial load.

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry; its ``radial_internal_clearance`` P_d sets the gap c_r = P_d / 2.
    radial_load : float
        Radial load F_r on the inner ring [N], >= 0.
    load_angle : float
        Direction of the load from +x [rad] (default straight down).
    cage_angle : float
        Angle of ball 0 from +x [rad]; balls follow at 2 pi / Z. The default puts a ball on the
        load line only when ``load_angle`` is a multiple of 2 pi / Z from 0 (use
        ``cage_angle=load_angle`` for a ball on the load line).
    extra_approach : float or ndarray, shape (Z,)
        Extra approach per ball [m] (EHL film thickness, a uniform waviness), added to delta_j.
    stiffness_constant : float, optional
        K_tot [N/m^1.5]; defaults to the exact-Hertz series constant of ``geometry``.

    Returns
    -------
    StaticSolution
        Displacement, ball loads and tangent stiffness.

    Examples
    --------
    >>> from generators import bearing, static_load_distribution
    >>> g = bearing("6205", radial_internal_clearance=0.0)
    >>> s = static_load_distribution(g, 1000.0, cage_angle=-3.141592653589793 / 2)
    >>> round(s.deflection * 1e6, 2)
    14.0
    """
    fr = check_real("radial_load", radial_load, low=0.0, high=1e8, unit="N")
    check_real("load_angle", load_angle, low=-10.0, high=10.0, unit="rad")
    check_real("cage_angle", cage_angle, low=-100.0, high=100.0, unit="rad")
    z = geometry.ball_count
    k = (
        stiffness_constant
        if stiffness_constant is not None
        else load_deflection_constants(geometry)[2]
    )
    check_real("stiffness_constant", k, low=0.0, low_inclusive=False, unit="N/m^1.5")
    extra = np.broadcast_to(np.asarray(extra_approach, dtype=float), (z,))
    if not np.all(np.isfinite(extra)):
        raise ParameterError(f"extra_approach = {extra_approach!r} must be finite")
    theta = cage_angle + 2.0 * np.pi * np.arange(z) / z
    cos_t, sin_t = np.cos(theta), np.sin(theta)
    gap = np.ascontiguousarray(geometry.radial_gap - extra)
    x, y, loads, kr = solve_equilibrium(cos_t, sin_t, gap, k, fr, load_angle)
    ex, ey = math.cos(load_angle), math.sin(load_angle)
    return StaticSolution(
        displacement=np.array([x, y]),
        deflection=x * ex + y * ey,
        ball_angles=theta,
        ball_loads=loads,
        radial_stiffness=float(kr),
    )


def solve_equilibrium(
    cos_t: np.ndarray, sin_t: np.ndarray, gap: np.ndarray, k: float, fr: float, load_angle: float
) -> tuple[float, float, np.ndarray, float]:
    """Displacement (x, y) [m], ball loads [N] and radial stiffness [N/m] from checked inputs.

    The dynamic model's static start calls this directly: its inputs are validated once, in
    ``prepare``.

    Parameters
    ----------
    cos_t, sin_t : ndarray
        Cosine and sine of each ball's angle.
    gap : ndarray
        Each ball's gap [m] (contiguous; the extra approach already subtracted).
    k : float
        The ball's series load-deflection constant [N/m^1.5].
    fr : float
        The radial load [N].
    load_angle : float
        Its direction [rad].

    Returns
    -------
    x, y : float
        The displacement [m].
    loads : ndarray
        Each ball's load [N].
    stiffness : float
        The radial stiffness [N/m].
    """
    ex, ey = math.cos(load_angle), math.sin(load_angle)
    fx, fy = fr * ex, fr * ey
    x = y = 0.0  # no load and no preload: centred (anywhere in the play is an equilibrium)
    if fr > 0.0 or np.any(gap < 0.0):
        # damped Newton on the convex potential sum (2/5) K [delta]_+^2.5 - F.xy (compiled:
        # the dataset generator solves one per signal)
        force_scale = max(fr, 1.0)
        length_scale = max(float(np.abs(gap).max()), (force_scale / k) ** (2.0 / 3.0), 1e-9)
        start = max(float(gap.max()), 0.0) + (force_scale / k) ** (2.0 / 3.0)
        x, y = SK._static_newton(
            cos_t, sin_t, gap, k, fx, fy, start * ex, start * ey, length_scale, force_scale
        )
    loads = np.empty(gap.size)
    gx, gy, hxx, hxy, hyy, _ = SK._static_sums(x, y, cos_t, sin_t, gap, k, fx, fy, False, loads)
    # the residual is judged against the largest force in play: the load, or the preload's
    # ball forces (a preloaded bearing under a few newtons carries tens of newtons per ball,
    # and rounding leaves ~1e-8 of those)
    preload_force = k * max(-float(gap.min()), 0.0) ** 1.5
    if math.hypot(gx, gy) > 1e-7 * max(fr, preload_force, 1.0):
        raise ParameterError(
            f"radial_load = {fr:g} N: static equilibrium not found (residual "
            f"{math.hypot(gx, gy):.3g} N)"
        )
    # dF_r/d delta_r with the transverse force held at zero (the shaft re-centres sideways):
    # 1 / (e . H^-1 e) for the tangent stiffness matrix H, e the load direction
    det = hxx * hyy - hxy * hxy
    quad = ex * ex * hyy - 2.0 * ex * ey * hxy + ey * ey * hxx
    if det > 1e-12 * hxx * hyy and quad > 0.0:
        kr = det / quad
    else:  # singular (fewer than two balls touch): the stiffness along the load only
        kr = ex * ex * hxx + 2.0 * ex * ey * hxy + ey * ey * hyy
    return x, y, loads, float(kr)
