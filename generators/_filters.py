"""Numba kernel of the measurement chain: second-order sections started in steady state.

What :func:`generators.measurement._causal` runs.

scipy's ``sosfilt`` and ``sosfilt_zi`` cost about 1 ms of Python per call (axis handling,
``lfilter_zi``'s linear solves) on records that take 0.1-0.4 ms to filter, and the realistic
chain makes six to ten calls per signal. This kernel runs the same direct form II transposed
recursion over every record of a stack, with the steady-state initial conditions of each
section in closed form. No fast-math: the recursion is the one IEEE arithmetic gives.
"""

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def sos_steady_state(sos, x, pad, gains):
    """Filter each row of ``x`` by the cascade ``sos`` after a lead-in, summed per cascade.

    ``sos`` (cascades, sections, 6): rows [b0, b1, b2, 1, a1, a2]; ``gains`` (cascades,): the
    weight of each cascade's output in the sum. Each row of ``x`` (records, n) is preceded by
    its odd extension over ``pad`` samples (2 x[0] - x[pad:0:-1]: continuous value and slope),
    and every section starts in the steady state of a constant input equal to the lead-in's
    first sample (``scipy.signal.sosfilt_zi`` times it: z1 = b2 - a2 G, z0 = G - b0 per unit
    input, G = (b0 + b1 + b2) / (1 + a1 + a2) the section's DC gain). Returns the sum over
    cascades of ``gains[c]`` times cascade c's output, without the lead-in: shape of ``x``.
    """
    records, n = x.shape
    cascades, sections = sos.shape[0], sos.shape[1]
    out = np.zeros((records, n))
    work = np.empty(pad + n)
    for row in range(records):
        for i in range(pad):
            work[i] = 2.0 * x[row, 0] - x[row, pad - i]
        for i in range(n):
            work[pad + i] = x[row, i]
        for c in range(cascades):
            level = work[0]  # the constant input each section is in steady state with
            z0s = np.empty(sections)
            z1s = np.empty(sections)
            for s in range(sections):
                b0, b1, b2 = sos[c, s, 0], sos[c, s, 1], sos[c, s, 2]
                a1, a2 = sos[c, s, 4], sos[c, s, 5]
                dc = (b0 + b1 + b2) / (1.0 + a1 + a2)
                z1s[s] = (b2 - a2 * dc) * level
                z0s[s] = (dc - b0) * level
                level = dc * level
            gain = gains[c]
            for i in range(pad + n):
                v = work[i]
                for s in range(sections):
                    y = sos[c, s, 0] * v + z0s[s]
                    z0s[s] = sos[c, s, 1] * v - sos[c, s, 4] * y + z1s[s]
                    z1s[s] = sos[c, s, 2] * v - sos[c, s, 5] * y
                    v = y
                if i >= pad:
                    out[row, i - pad] += gain * v
    return out
