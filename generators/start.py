"""The static start of a run.

The equilibrium at t = 0 of every scene (loads, gravity, film and waviness), solved without
re-validating its inputs (docs/model.md 6).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from . import _kernels as K
from ._validate import ParameterError
from .packing import film_sum, waviness_at_start
from .params import (
    BearingGeometry,
    OperatingCondition,
    Rig,
)
from .static import solve_equilibrium


@functools.lru_cache(maxsize=64)
def _ball_directions(cage_angle: float, z: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ball angles [rad] at t = 0 and their cosines and sines (shared: never write to them)."""
    theta = cage_angle + 2.0 * np.pi * np.arange(z) / z
    return theta, np.cos(theta), np.sin(theta)


def _ball_equilibrium(
    p: np.ndarray,
    ehl: bool,
    us: float,
    uh: float,
    extra_i: float,
    extra_o: float,
    sin_theta: float,
) -> float:
    """Radial ball position rho with zero net force (bisection; the force decreases with rho)."""
    gap = p[K.P_GAP]
    mb = p[K.P_BALL_MASS]
    wc = p[K.P_CAGE_SPEED]
    tau = 0.0

    def net(rho: float) -> float:
        di = us - rho - 0.5 * gap + extra_i
        do = rho - uh - 0.5 * gap + extra_o
        if ehl:
            qi = K._hertz_ehl(
                di,
                0.0,
                p[K.P_K_INNER],
                tau,
                p[K.P_FILM_INNER],
                0.0,
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_INNER_REF],
                p[K.P_FILM_INNER_MAX],
            )
            qo = K._hertz_ehl(
                do,
                0.0,
                p[K.P_K_OUTER],
                tau,
                p[K.P_FILM_OUTER],
                0.0,
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_OUTER_REF],
                p[K.P_FILM_OUTER_MAX],
            )
        else:
            qi = K._hertz_dry(di, 0.0, p[K.P_K_INNER], tau)
            qo = K._hertz_dry(do, 0.0, p[K.P_K_OUTER], tau)
        return qi - qo + mb * wc**2 * (p[K.P_PITCH_RADIUS] + rho) - mb * p[K.P_GRAVITY] * sin_theta

    span = abs(us) + abs(uh) + abs(gap) + abs(extra_i) + abs(extra_o) + 1e-6
    lo, hi = -span, span
    for _ in range(60):
        if net(lo) > 0:
            break
        lo *= 2
    for _ in range(60):
        if net(hi) < 0:
            break
        hi *= 2
    f_lo, f_hi = net(lo), net(hi)
    if f_lo * f_hi > 0:
        return 0.5 * (us + uh)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        f = net(mid)
        if f == 0.0:
            # inside the play with no force: find the whole zero interval and take its middle
            a, b = lo, mid
            for _ in range(100):
                m = 0.5 * (a + b)
                a, b = (a, m) if net(m) == 0.0 else (m, b)
            c, d = mid, hi
            for _ in range(100):
                m = 0.5 * (c + d)
                c, d = (m, d) if net(m) == 0.0 else (c, m)
            return 0.5 * (b + c)
        if f > 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-16:
            break
    return 0.5 * (lo + hi)


def static_state(
    level: str,
    ehl: bool,
    geometry: BearingGeometry,
    operating: OperatingCondition,
    rig: Rig,
    p: np.ndarray,
    wav: np.ndarray,
) -> tuple[np.ndarray, float]:
    """Static equilibrium at t = 0 (velocities 0): the initial state, and the largest ball load.

    Parameters
    ----------
    level : str
        The scene's level (``shaft``, ``shaft+housing``, ``full``).
    ehl : bool
        With the lubricant film.
    geometry : BearingGeometry
        The bearing.
    operating : OperatingCondition
        The operating point.
    rig : Rig
        The rig.
    p : ndarray
        The parameter vector.
    wav : ndarray
        The waviness table.

    Returns
    -------
    state : ndarray
        The initial state [m, m/s].
    max_load : float
        The largest ball load [N].
    """
    z = geometry.ball_count
    g = p[K.P_GRAVITY]
    fx = p[K.P_LOAD_X]
    fy = p[K.P_LOAD_Y] - rig.shaft_mass * g
    fr = math.hypot(fx, fy)
    angle = math.atan2(fy, fx)
    w0 = waviness_at_start(p, wav, z)
    waviness_sum = w0[0] + w0[1] + w0[2] + w0[3]  # as w0.sum(axis=0): row after row
    kt = p[K.P_K_SERIES]
    loads = np.full(z, p[K.P_FILM_REFERENCE_LOAD]) if ehl else None
    extra = waviness_sum
    # static_load_distribution's solver without its input checks: load, angles and
    # waviness were validated by prepare (the dataset generator solves one per signal)
    theta, cos_t, sin_t = _ball_directions(float(p[K.P_CAGE_ANGLE0]), z)
    for _ in range(4 if ehl else 1):
        if ehl:
            extra = waviness_sum + film_sum(p, loads)
        if not math.isfinite(float(extra.sum())):
            raise ParameterError(f"static start: non-finite approach per ball {extra!r}")
        gap = geometry.radial_gap - extra
        x, y, loads, _ = solve_equilibrium(cos_t, sin_t, gap, kt, fr, angle)
    housing_x = fx / rig.pedestal_stiffness
    housing_y = (fy - rig.housing_mass * g) / rig.pedestal_stiffness
    nd = 4 + z if level == "full" else 4  # K.n_dof
    y0 = np.zeros(2 * nd)
    y0[2] = housing_x
    y0[3] = housing_y
    y0[0] = x if level == "shaft" else x + housing_x
    y0[1] = y if level == "shaft" else y + housing_y
    if level == "full":
        for j in range(z):
            c, s = math.cos(theta[j]), math.sin(theta[j])
            us = y0[0] * c + y0[1] * s
            uh = y0[2] * c + y0[3] * s
            y0[4 + j] = _ball_equilibrium(
                p, ehl, us, uh, w0[1, j] + w0[3, j], w0[0, j] + w0[2, j], s
            )
    return y0, float(loads.max()) if loads.size else 0.0
