"""The RK4 step and schedule.

The scene's default step from its stability radius and accuracy, the local-defect limit, the
record rate and the step grid (docs/model.md 7).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from . import _integrators
from . import _kernels as K

#: Default fixed RK4 step of the massless-ball scenes [s] (docs/model.md 7.2: converged to 4 digits
#: at <= 2e-5 s; 5-10 us recommended). See ``cmtool fidelity`` for the measured trade.
DEFAULT_STEP_MASSLESS = 2e-5

#: Safety factor on the RK4 stability limit of the linearised scene (dynamic overloads stiffen
#: the contacts beyond the static linearisation).
STABILITY_SAFETY = 0.8

#: Records per output sample at most (and for DOPRI5 and the error-bound pilots).
DEFAULT_OVERSAMPLE = 4

#: Least record rate of an RK4 run [Hz] (:func:`default_oversample`).
MIN_RECORD_RATE = 96e3


def jacobian(code: int, ehl: int, p: np.ndarray, wav: np.ndarray, y0: np.ndarray) -> np.ndarray:
    """Jacobian of the first-order right-hand side at ``y0``, t = 0, by central differences.

    Displacements are perturbed by 1e-11 m, velocities by 1e-7 m/s (docs/model.md 7.5).

    Parameters
    ----------
    code : int
        The scene's kernel code (``_kernels.SCENE_SHAFT``, ``SCENE_SHAFT_HOUSING``, ``SCENE_FULL``).
    ehl : int
        The film mode (``_kernels.FILM_DRY``, ``FILM_EHL``, ``FILM_ENTRAINED``; a bool is the
        film switch).
    p : ndarray
        The parameter vector (``generators.packing.pack_parameters``).
    wav : ndarray
        The waviness table.
    y0 : ndarray
        The state [m, m/s].

    Returns
    -------
    ndarray
        (n, n), n the states: d(dy/dt)/dy, each in its state's units per second.
    """
    n = y0.size
    nd = n // 2
    loads = np.zeros((2, int(p[K.P_BALL_COUNT])))
    jac = np.zeros((n, n))
    fp, fm = np.zeros(n), np.zeros(n)
    for i in range(n):
        h = 1e-11 if i < nd else 1e-7
        yp, ym = y0.copy(), y0.copy()
        yp[i] += h
        ym[i] -= h
        _integrators._rhs_once(code, int(ehl), 0.0, yp, p, wav, fp, loads)
        _integrators._rhs_once(code, int(ehl), 0.0, ym, p, wav, fm, loads)
        jac[:, i] = (fp - fm) / (2 * h)
    return jac


#: RK4 steps per passage of a contact over a local defect (envelope line within 1 % of a step
#: 8 times shorter; tests_validation/test_local_defects.py checks 4 times shorter to 2 %).
DEFECT_STEPS = 10


def default_step(
    level: str, code: int, ehl: int, p: np.ndarray, wav: np.ndarray, y0: np.ndarray
) -> float:
    """Default RK4 step [s] of a scene (local defects aside: :func:`defect_substeps`).

    The smaller of the accuracy step ``DEFAULT_STEP_MASSLESS`` (massless-ball scenes converge
    to 0.01 % in the band amplitude there, see ``cmtool fidelity``) and the stability step
    ``STABILITY_SAFETY * min_i r(arg lambda_i) / |lambda_i|``, lambda the eigenvalues of the
    right-hand side linearised at the static start and r(phi) the radius of RK4's stability
    region along the ray at angle phi (:func:`rk4_stability_radius`: 2.83 on the imaginary
    axis, 2.79 on the real axis, 2.62 at its narrowest, near 120 degrees). The fastest mode is
    the ball radial mode in the ``full`` scene (lightly damped, or well damped with the squeeze
    film), otherwise the shaft-on-bearing or a stiff pedestal's housing mode.

    Parameters
    ----------
    level : str
        The scene's level.
    code : int
        The scene's kernel code (``_kernels.SCENE_SHAFT``, ``SCENE_SHAFT_HOUSING``, ``SCENE_FULL``).
    ehl : int
        The film mode (``_kernels.FILM_DRY``, ``FILM_EHL``, ``FILM_ENTRAINED``; a bool is the
        film switch).
    p : ndarray
        The parameter vector (``generators.packing.pack_parameters``).
    wav : ndarray
        The waviness table.
    y0 : ndarray
        The static start [m, m/s].

    Returns
    -------
    float
        The step [s].
    """
    return default_step_and_growth(level, code, ehl, p, wav, y0)[0]


def default_step_and_growth(
    level: str, code: int, ehl: int, p: np.ndarray, wav: np.ndarray, y0: np.ndarray
) -> tuple[float, float]:
    """:func:`default_step`, and how far :func:`rk4_schedule` may lengthen it (``longest``).

    Where the accuracy step binds, it may grow onto the record grid by
    ``DEFAULT_ALIGN_LONGEST`` at most and never beyond the stability step
    (:func:`stability_step`: ``STABILITY_SAFETY`` of RK4's limit); where the stability step
    binds, not at all (1).

    Parameters
    ----------
    level : str
        The scene's level.
    code : int
        The scene's kernel code (``_kernels.SCENE_SHAFT``, ``SCENE_SHAFT_HOUSING``, ``SCENE_FULL``).
    ehl : int
        The film mode (``_kernels.FILM_DRY``, ``FILM_EHL``, ``FILM_ENTRAINED``; a bool is the
        film switch).
    p : ndarray
        The parameter vector (``generators.packing.pack_parameters``).
    wav : ndarray
        The waviness table.
    y0 : ndarray
        The static start [m, m/s].

    Returns
    -------
    step : float
        The step [s].
    longest : float
        The factor it may grow by (>= 1).
    """
    lam = np.linalg.eigvals(jacobian(code, ehl, p, wav, y0))
    largest = float(np.max(np.abs(lam))) if lam.size else 0.0
    # RK4's region reaches at least its narrowest radius along every ray: when even that
    # allows the accuracy step (and its growth), the rays need not be traced
    bound = STABILITY_SAFETY * _narrowest_radius() / largest if largest > 0.0 else math.inf
    if bound >= DEFAULT_ALIGN_LONGEST * DEFAULT_STEP_MASSLESS:
        return DEFAULT_STEP_MASSLESS, DEFAULT_ALIGN_LONGEST
    limit = _stability_limit(lam)
    if limit <= DEFAULT_STEP_MASSLESS:
        return limit, 1.0
    return DEFAULT_STEP_MASSLESS, min(DEFAULT_ALIGN_LONGEST, limit / DEFAULT_STEP_MASSLESS)


def defect_substeps(step: float, p: np.ndarray, wav: np.ndarray) -> int:
    """Into how many steps RK4 splits a ``step`` [s] in which a contact meets a local defect.

    The fewest that make each at most :func:`defect_step` (``DEFECT_STEPS`` per passage); 1
    without local defects. Only the steps near a crossing are split (the kernel's
    ``_defect_near``): a pit acts for a few per cent of the time, and the dynamics between its
    crossings are the scene's.

    Parameters
    ----------
    step : float
        The run's step [s].
    p : ndarray
        The parameter vector.
    wav : ndarray
        The waviness table (local defects among its rows).

    Returns
    -------
    int
    """
    limit = defect_step(p, wav)
    if not math.isfinite(limit):
        return 1
    return max(1, math.ceil(step / limit - 1e-9))


def stability_step(code: int, ehl: int, p: np.ndarray, wav: np.ndarray, y0: np.ndarray) -> float:
    """``STABILITY_SAFETY`` times RK4's stability limit of the scene linearised at ``y0`` [s].

    min_i r(arg lambda_i) / |lambda_i| over the eigenvalues of the Jacobian
    (:func:`rk4_stability_radius`); ``inf`` when every eigenvalue is zero.

    Parameters
    ----------
    code : int
        The scene's kernel code (``_kernels.SCENE_SHAFT``, ``SCENE_SHAFT_HOUSING``, ``SCENE_FULL``).
    ehl : int
        The film mode (``_kernels.FILM_DRY``, ``FILM_EHL``, ``FILM_ENTRAINED``; a bool is the
        film switch).
    p : ndarray
        The parameter vector (``generators.packing.pack_parameters``).
    wav : ndarray
        The waviness table.
    y0 : ndarray
        The state linearised at [m, m/s].

    Returns
    -------
    float
        The step [s].
    """
    return _stability_limit(np.linalg.eigvals(jacobian(code, ehl, p, wav, y0)))


def _stability_limit(lam: np.ndarray) -> float:
    """``STABILITY_SAFETY`` min_i r(arg lambda_i) / |lambda_i| [s] (``inf`` for no eigenvalue)."""
    lam = lam[np.abs(lam) > 0.0]
    if not lam.size:
        return math.inf
    return float(STABILITY_SAFETY * np.min(rk4_stability_radius(np.angle(lam)) / np.abs(lam)))


@functools.cache
def _narrowest_radius() -> float:
    """A lower bound of RK4's stability radius over all rays (2.62, near 120 degrees).

    The least over 2,001 rays from pi/2 to pi of the boundary radius
    (:func:`_boundary_radius_by_roots`, equal to :func:`rk4_stability_radius` on those rays to
    1e-9), less 0.1 % for what lies between them (the radius varies by less over a ray's
    spacing). Only a lower bound is needed (:func:`default_step` gives the same step whatever
    its value); the roots take 20 ms where the scan took 0.7 s, once per process.
    """
    return 0.999 * float(_boundary_radius_by_roots(np.linspace(0.5 * np.pi, np.pi, 2001)).min())


def _boundary_radius_by_roots(angle: np.ndarray) -> np.ndarray:
    """Radius of RK4's stability boundary along rays ``angle`` in [pi/2, pi] [rad], from roots.

    |R(r e^{i angle})|^2 - 1 = sum_{m=1..8} a_m r^m with a_m = sum_{j+k=m} c_j c_k cos((j-k)
    angle), c = (1, 1, 1/2, 1/6, 1/24); the boundary is its least real root over 0.1 (the
    region holds the disc of radius 2.6 on these rays; at pi/2 the polynomial has a fivefold
    root at 0, which rounding scatters to about 1e-3). Eigenvalues of the companion matrices
    of all rays at once.
    """
    phi = np.atleast_1d(np.asarray(angle, dtype=float))
    c = (1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0)
    a = np.zeros((phi.size, 9))
    for j in range(5):
        for k in range(5):
            a[:, j + k] += c[j] * c[k] * np.cos((j - k) * phi)
    q = a[:, 1:]  # (|R|^2 - 1) / r: coefficients of r^0 .. r^7
    companion = np.zeros((phi.size, 7, 7))
    companion[:, 1:, :-1] = np.eye(6)
    companion[:, :, -1] = -q[:, :7] / q[:, 7:8]
    roots = np.linalg.eigvals(companion)
    real = np.where((np.abs(roots.imag) < 1e-7) & (roots.real > 0.1), roots.real, np.inf)
    return real.min(axis=1)


def rk4_stability_radius(angle: np.ndarray | float) -> np.ndarray:
    """Radius of the classical RK4 stability region along rays z = r exp(i angle).

    The first r > 0 where |R(z)| = 1, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 (scan on a 0.001
    grid, then bisection to 1e-9). A ray into the right half-plane (|angle| < pi/2: an
    eigenvalue whose real part is rounding noise of a finite-difference Jacobian, or a growing
    mode the divergence check reports) is given the imaginary-axis value.

    Parameters
    ----------
    angle : float or ndarray
        The rays' angles [rad].

    Returns
    -------
    ndarray
        r, dimensionless (2.7853 at pi, 2.8284 at pi/2).
    """

    def amplification(r, ray):  # |R(r ray)|, ray = exp(i angle); Horner's form
        z = r * ray
        return np.abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))))

    phi = np.maximum(np.abs(np.atleast_1d(np.asarray(angle, dtype=float))), 0.5 * np.pi)
    grid = np.arange(1, 3501) * 1e-3
    # all rays at once: the first grid point past the boundary, then bisection on every ray
    ray = np.exp(1j * phi)
    unstable = amplification(grid[None, :], ray[:, None]) > 1.0 + 1e-12
    found = unstable.any(axis=1)
    k = np.argmax(unstable, axis=1)
    lo = np.where(k > 0, grid[np.maximum(k - 1, 0)], 0.0)
    hi = grid[k]
    while np.any(hi - lo > 1e-9):
        mid = 0.5 * (lo + hi)
        stable = amplification(mid, ray) <= 1.0 + 1e-12
        lo, hi = np.where(stable, mid, lo), np.where(stable, hi, mid)
    return np.where(found, lo, grid[-1])


def defect_step(p: np.ndarray, wav: np.ndarray) -> float:
    """Step limit [s] from local defects: ``DEFECT_STEPS`` steps per passage of a contact.

    A contact crosses a pit of half width w [rad] in 2 w / |rate|, rate the angular speed of
    the contact point on the defective surface (cage for the outer race, cage minus shaft for
    the inner race, ball spin for a ball). ``inf`` without local defects.

    Parameters
    ----------
    p : ndarray
        The parameter vector.
    wav : ndarray
        The waviness table.

    Returns
    -------
    float
        The step [s].
    """
    rates = {
        K.SURF_OUTER_DEFECT: p[K.P_CAGE_SPEED],
        K.SURF_INNER_DEFECT: p[K.P_CAGE_SPEED] - p[K.P_SHAFT_SPEED],
        K.SURF_BALL_DEFECT_OUTER: p[K.P_BALL_SPIN_SPEED],
        K.SURF_BALL_DEFECT_INNER: p[K.P_BALL_SPIN_SPEED],
    }
    step = math.inf
    for row in wav:
        rate = abs(rates.get(int(row[K.W_SURFACE]), 0.0))
        if rate > 0.0:
            step = min(step, 2.0 * row[K.W_HALF_WIDTH] / rate / DEFECT_STEPS)
    return step


def default_oversample(fs: float) -> int:
    """Records per output sample of an RK4 run at ``fs`` [Hz], whatever its step.

    The record point-samples the run, so what the run holds above half the record rate
    aliases before the anti-alias FIR can remove it; a pit's impacts ring to tens of kHz. The
    record is therefore at least twice the output rate (at the output rate itself nothing
    filters at all) and ``MIN_RECORD_RATE`` where ``DEFAULT_OVERSAMPLE`` times the output rate
    reaches it: 4 at 6.4-25.6 kHz (48 kHz records at 12 kHz), 2 from 48 kHz. Since stop 46 an
    acceleration is the velocity record's derivative (:mod:`generators.decimation`), whose
    folded part is smaller by the line's frequency over the folded content's. Before that, a
    0.3 mm pit at 25.6 kHz recorded at fs, 2 fs and 4 fs differed from a record at 8 fs by
    5.4, 2.0 and 1.2 % RMS, at 48 kHz at fs and 2 fs by 3.1 and 1.4 %; a clean healthy
    bearing run at 4e-5 s and recorded at fs reads as an outer-race fault
    (docs/performance.md, "Records at 96 kHz or more, on the step grid").
    Until stop 36 a step longer than a quarter of the output interval lowered the record rate
    to about one record per step, down to the output rate.

    Parameters
    ----------
    fs : float
        The output rate [Hz].

    Returns
    -------
    int
    """
    return int(min(DEFAULT_OVERSAMPLE, max(2, math.ceil(MIN_RECORD_RATE / fs - 1e-9))))


#: Shortest fraction of the requested RK4 step that :func:`rk4_schedule` shortens it to, so
#: that the records fall on a fixed pattern of the step grid (at most 25 % more steps).
ALIGN_SHORTEST = 0.8
#: Longest multiple of the *default* step that :func:`rk4_schedule` lengthens it to where no
#: shortening reaches the pattern (12 and 48 kHz: 2e-5 -> 1/48,000 s, +4.2 %): RK4's own error
#: grows by (1.05)^4 = 1.2 at most, while the records' off-grid images, 7-14 times larger,
#: go (docs/performance.md, "The default step on the record grid at 12 and 48 kHz").
DEFAULT_ALIGN_LONGEST = 1.05


def rk4_schedule(
    step: float,
    record_dt: float,
    settle_time: float,
    n_record: int,
    oversample: int = 1,
    longest: float = 1.0,
) -> tuple[float, int, float]:
    """RK4 step, number of steps and first record time for a requested step [s].

    The records (``oversample`` per output sample, decimated by the anti-alias FIR after the
    run) fall on a fixed pattern of the step grid when shortening the step to it costs at
    most ``1 / ALIGN_SHORTEST`` times the steps: a whole number of steps per record, or one
    step per k records, k <= ``oversample`` (the step rate a whole fraction of the record
    rate r and at least fs). The records between step starts sample the step's quintic Hermite
    interpolant, whose images lie at multiples of the step rate; on such a pattern they all
    fall between fs / 2 and r - fs / 2, where the FIR removes them; at any other step rate they
    fall into the band, shifted by the difference of the step and record rates
    (docs/performance.md, "Records at 96 kHz or more, on the step grid"). Otherwise the step
    is kept. The first record is at ``settle_time`` whatever the step (until stop 36 it moved
    to the next step start, up to a step late, which put a time shift between runs at
    different steps). Where no shortening reaches the pattern, ``longest`` > 1 lets the step
    grow to it by that factor at most (the default step only: ``DEFAULT_ALIGN_LONGEST``; a
    requested step is never lengthened).

    Parameters
    ----------
    step : float
        The step requested [s].
    record_dt : float
        The record interval [s].
    settle_time : float
        The time before the first record [s].
    n_record : int
        The records.
    oversample : int
        Records per output sample.
    longest : float
        The most the step may grow by (see above).

    Returns
    -------
    step : float
        The step [s].
    steps : int
        The number of steps.
    first : float
        The first record's time [s].
    """
    if step <= record_dt * (1 + 1e-9):
        aligned = record_dt / int(math.ceil(record_dt / step - 1e-9))
    else:
        per_step = int(math.floor(step / record_dt + 1e-9))
        aligned = per_step * record_dt if per_step <= oversample else 0.0
    dt = aligned if aligned >= ALIGN_SHORTEST * step else step
    if dt == step and longest > 1.0:
        if step <= record_dt * (1 + 1e-9):
            grown = record_dt / int(math.floor(record_dt / step + 1e-9))
        else:
            per_step = int(math.ceil(step / record_dt - 1e-9))
            grown = per_step * record_dt if per_step <= oversample else math.inf
        if step < grown <= longest * step:
            dt = grown
    t_first = settle_time
    t_last = t_first + (n_record - 1) * record_dt
    n_steps = int(math.floor(t_last / dt + 1e-9)) + 1
    return dt, n_steps, t_first
