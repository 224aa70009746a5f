"""Numba kernels of the static equilibrium (:mod:`generators.static`): plain floats and arrays.

The shaft's static position under a radial force on balls with Hertzian contacts: the
residual, tangent stiffness and potential of the ball loads (:func:`_static_sums`) and a
damped, regularised Newton on that potential (:func:`_static_newton`). Kept apart from the
dynamic model's kernels (:mod:`generators._kernels`, whose compile options they share): the
integrators never call them. Only numpy, numba and math are imported here, and the kernel
module for its options (checked by import-linter).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from . import _kernels as K


@numba.njit(**K._JIT)
def _static_sums(x, y, cos_t, sin_t, gap, k, fx, fy, need_potential, loads):
    """Residual (gx, gy), Hessian (hxx, hxy, hyy) and potential of the static problem at (x, y).

    Ball j: approach d = x cos + y sin - gap_j, load K d^1.5 for d > 0; residual = sum of the
    ball loads along (cos, sin) minus the applied force [N]; Hessian the tangent stiffness
    d(ball forces)/d(xy) [N/m]; potential sum (2/5) K d^2.5 - F.xy [J]. Fills ``loads[j]``
    [N] when ``loads`` has Z entries (an empty array: not wanted).
    """
    gx = -fx
    gy = -fy
    hxx = 0.0
    hxy = 0.0
    hyy = 0.0
    energy = 0.0
    for j in range(cos_t.shape[0]):
        c = cos_t[j]
        s = sin_t[j]
        d = x * c + y * s - gap[j]
        q = 0.0
        if d > 0.0:
            root = math.sqrt(d)
            q = k * d * root
            gx += q * c
            gy += q * s
            kl = 1.5 * k * root
            hxx += kl * c * c
            hxy += kl * c * s
            hyy += kl * s * s
            if need_potential:
                energy += 0.4 * k * d * d * root
        if loads.shape[0] > 0:
            loads[j] = q
    return gx, gy, hxx, hxy, hyy, energy - fx * x - fy * y


@numba.njit(**K._JIT)
def _static_newton(cos_t, sin_t, gap, k, fx, fy, x, y, length_scale, force_scale):
    """Damped, regularised Newton on the static potential (``generators.static``): (x, y) [m].

    Levenberg regularisation of the 2x2 Hessian (singular while fewer than two balls touch),
    Armijo backtracking on the potential, steps capped at ``length_scale`` [m].
    """
    mu = 1e-6 * force_scale / length_scale
    none = np.empty(0)
    for _ in range(500):
        gx, gy, hxx, hxy, hyy, p0 = _static_sums(x, y, cos_t, sin_t, gap, k, fx, fy, True, none)
        if math.hypot(gx, gy) <= 1e-11 * force_scale:
            break
        a = hxx + mu
        d = hyy + mu
        det = a * d - hxy * hxy
        sx = (d * gx - hxy * gy) / det
        sy = (a * gy - hxy * gx) / det
        norm = math.hypot(sx, sy)
        if not (math.isfinite(sx) and math.isfinite(sy)) or norm > length_scale:
            if not (math.isfinite(sx) and math.isfinite(sy)):
                sx, sy, norm = gx, gy, math.hypot(gx, gy)
            scale = length_scale / max(norm, 1e-300)
            sx *= scale
            sy *= scale
        slope = gx * sx + gy * sy
        t = 1.0
        while t > 1e-12:
            xt, yt = x - t * sx, y - t * sy
            trial = _static_sums(xt, yt, cos_t, sin_t, gap, k, fx, fy, True, none)[5]
            if trial <= p0 - 1e-4 * t * slope:
                break
            t *= 0.5
        if t <= 1e-12:
            mu *= 10.0  # no descent along the regularised step: regularise more
            continue
        x -= t * sx
        y -= t * sy
        mu = max(mu * 0.1, 1e-12 * force_scale / length_scale)
    return x, y


#: Without the kernels' fast-math flags (reciprocals, fused multiply-adds): the law's
#: arithmetic exactly as numpy does it, operation by operation.
_JIT_EXACT = {"cache": True, "nogil": True, "error_model": "numpy"}


@numba.njit(**_JIT_EXACT, inline="always")
def _entrained_residual(v, delta, k, film, floor, entrainment, exponent):
    """The entrained law at ln Q = v: its residual [m], as ``generators.packing`` writes it."""
    q = math.exp(v)
    return (q / k) ** (2.0 / 3.0) - film * (q + floor) ** exponent - entrainment / (q * q) - delta


@numba.njit(**_JIT_EXACT)
def _entrained_bisection(delta, k, film, floor, entrainment, exponent, passes, out):
    """The bisection of ``generators.packing._entrained_film_table`` on ln Q, node by node.

    Each node runs the same ``passes`` halvings of [-40, 50] and writes the same midpoint of
    its last bracket as the bisection by the law alone, but a halving whose midpoint lies more
    than a noise radius from the root is decided by the root's side instead of by the law. The
    root comes first, by Newton's method on ln Q from the previous node's (the nodes ascend in
    ``delta``, so do the roots) until the residual is within the law's rounding (eight units
    of roundoff of its largest term); the radius is 32 times the distance in ln Q that the
    rounding spans, so that beyond it the law's sign is the root's side. The last bracket is
    checked against the law at both ends, and a node that fails is bisected by the law alone.
    Without fast-math, the law's arithmetic is numpy's operation by operation: the same bits as
    the vectorised bisection wherever numpy's exp and pow are the C library's (this project's
    hosts), in 16 evaluations of the law a node where it made 64 (and about six for the root).
    """
    eps = 2.220446049250313e-16
    root = -40.0
    rise = 0.0  # the previous node's root over the one before
    for i in range(delta.shape[0]):
        d = delta[i]
        # the root: Newton on ln Q inside a bracket that starts at the previous node's root
        # (the residual is <= 0 there) and widens upward until the residual is positive
        lo, hi = -40.0, 50.0
        if i == 0:
            guess = k * max(d, 0.0) ** 1.5 + math.sqrt(entrainment / max(abs(d), 1e-12))
            v = min(max(math.log(guess), lo + 1.0), hi - 1.0)
        else:
            lo = root
            width = max(rise, 1e-3)
            while lo + width < hi:
                if _entrained_residual(lo + width, d, k, film, floor, entrainment, exponent) > 0:
                    hi = lo + width
                    break
                lo += width
                width *= 2.0
            v = lo + rise if lo < lo + rise < hi else 0.5 * (lo + hi)
        radius = 0.0
        for _ in range(100):
            q = math.exp(v)
            elastic = (q / k) ** (2.0 / 3.0)
            ehl = film * (q + floor) ** exponent
            rigid = entrainment / (q * q)
            residual = elastic - ehl - rigid - d
            slope = (2.0 / 3.0) * elastic - exponent * ehl * q / (q + floor) + 2.0 * rigid
            noise = 8.0 * eps * max(elastic, ehl, rigid, abs(d))
            radius = 32.0 * noise / slope
            if abs(residual) <= noise:
                break
            if residual > 0.0:
                hi = v
            else:
                lo = v
            if np.nextafter(lo, hi) >= hi:
                break
            step = v - residual / slope
            v = step if lo < step < hi else 0.5 * (lo + hi)
        rise = v - root if i > 0 else 0.0
        root = v
        radius = max(radius, 64.0 * eps * max(abs(root), 1.0))
        # the bisection replayed
        lo, hi = -40.0, 50.0
        for _ in range(passes):
            mid = 0.5 * (lo + hi)
            if mid > root + radius:
                above = True
            elif mid < root - radius:
                above = False
            else:
                above = _entrained_residual(mid, d, k, film, floor, entrainment, exponent) > 0.0
            if above:
                hi = mid
            else:
                lo = mid
        ok = lo == -40.0 or not (
            _entrained_residual(lo, d, k, film, floor, entrainment, exponent) > 0.0
        )
        ok = ok and (
            hi == 50.0 or _entrained_residual(hi, d, k, film, floor, entrainment, exponent) > 0.0
        )
        if not ok:  # a decision the law would have made otherwise: bisect by the law alone
            lo, hi = -40.0, 50.0
            for _ in range(passes):
                mid = 0.5 * (lo + hi)
                if _entrained_residual(mid, d, k, film, floor, entrainment, exponent) > 0.0:
                    hi = mid
                else:
                    lo = mid
        out[i] = 0.5 * (lo + hi)
