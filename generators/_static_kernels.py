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
