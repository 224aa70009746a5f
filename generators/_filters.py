"""Numba kernels of the signal chain: steady-state filter sections, anti-alias decimation.

:func:`sos_steady_state` is what :func:`generators.measurement._causal` runs: scipy's
``sosfilt`` and ``sosfilt_zi`` cost about 1 ms of Python per call (axis handling,
``lfilter_zi``'s linear solves) on records that take 0.1-0.4 ms to filter, and the realistic
chain makes six to ten calls per signal. This kernel runs the same direct form II transposed
recursion over every record of a stack, with the steady-state initial conditions of each
section in closed form.

:func:`fir_decimate_rows` and :func:`fir_decimate_columns` are what
:mod:`generators.decimation` runs: scipy's ``resample_poly`` for an integer down-sampling
(``upfirdn`` sums each output's products one at a time, in C without vector instructions);
these sum the same products in the same order, several outputs at once.

No fast-math anywhere: each sum is the one IEEE arithmetic gives in scipy's order, so the
results are scipy's bit for bit (tests/tests_generators/test_realism.py,
tests/tests_generators/test_decimation.py).
"""

import numba
import numpy as np

#: Outputs of :func:`fir_decimate_columns` computed tap by tap together.
_CHUNK = 512


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
    out = np.empty((records, n))
    work = np.empty(pad + n)
    z0s = np.empty((cascades, sections))
    z1s = np.empty((cascades, sections))
    for row in range(records):
        for i in range(pad):
            work[i] = 2.0 * x[row, 0] - x[row, pad - i]
        for i in range(n):
            work[pad + i] = x[row, i]
        for c in range(cascades):
            level = work[0]  # the constant input each section is in steady state with
            for s in range(sections):
                b0, b1, b2 = sos[c, s, 0], sos[c, s, 1], sos[c, s, 2]
                a1, a2 = sos[c, s, 4], sos[c, s, 5]
                dc = (b0 + b1 + b2) / (1.0 + a1 + a2)
                z1s[c, s] = (b2 - a2 * dc) * level
                z0s[c, s] = (dc - b0) * level
                level = dc * level
        # the cascades side by side, sample by sample: their recursions are independent, so
        # the processor overlaps them (two modes 0.51 -> 0.32 ms, four 1.01 -> 0.53 ms a
        # 1.25 s record at 48 kHz); each output sums the cascades in their order, as
        # filtering one cascade after the other into a zeroed output did (the same bits)
        for i in range(pad + n):
            u = work[i]
            total = 0.0
            for c in range(cascades):
                v = u
                for s in range(sections):
                    y = sos[c, s, 0] * v + z0s[c, s]
                    z0s[c, s] = sos[c, s, 1] * v - sos[c, s, 4] * y + z1s[c, s]
                    z1s[c, s] = sos[c, s, 2] * v - sos[c, s, 5] * y
                    v = y
                total += gains[c] * v
            if i >= pad:
                out[row, i - pad] = total
    return out


@numba.njit(cache=True, nogil=True)
def _decimate_edge(phases, n, taps_flipped, factor, first, slope, out, row_out, m):
    """Output m of :func:`_decimate_phases` one tap at a time, outside samples on the line."""
    length = taps_flipped.shape[0]
    x_first = phases[0, 0]
    x_last = phases[(n - 1) % factor, (n - 1) // factor]
    start = (first + m) * factor - length + 1
    acc = 0.0
    for i in range(length):
        k = start + i
        if k < 0:
            v = x_first + k * slope
        elif k >= n:
            v = x_last + (k - n + 1) * slope
        else:
            v = phases[k % factor, k // factor]
        acc = acc + v * taps_flipped[i]
    out[row_out, m] = acc


@numba.njit(cache=True, nogil=True)
def _decimate_phases(phases, n, taps_flipped, factor, first, out, row_out):
    """One record's decimated FIR output into ``out[row_out]`` (:func:`fir_decimate_rows`).

    ``phases`` (factor, rows): sample k of the record (length ``n``) at
    ``phases[k % factor, k // factor]``. Output m is ``sum_i x[(first + m) factor - L + 1 + i]
    * taps_flipped[i]``, accumulated from i = 0 (L the filter length), samples outside the
    record on the line through its first and last ones.
    """
    length = taps_flipped.shape[0]
    n_out = out.shape[1]
    x_first = phases[0, 0]
    x_last = phases[(n - 1) % factor, (n - 1) // factor]
    slope = (x_last - x_first) / (n - 1)
    base = first * factor - length + 1
    # outputs whose taps all fall inside the record
    inside_first = 0
    while inside_first < n_out and (first + inside_first) * factor - length + 1 < 0:
        inside_first += 1
    inside_end = inside_first
    while inside_end < n_out and (first + inside_end) * factor + 1 <= n:
        inside_end += 1
    for m in range(inside_first):  # the edges one output at a time, extended outside
        _decimate_edge(phases, n, taps_flipped, factor, first, slope, out, row_out, m)
    for m in range(max(inside_end, inside_first), n_out):
        _decimate_edge(phases, n, taps_flipped, factor, first, slope, out, row_out, m)
    # the inside tap by tap over a chunk of outputs (each output's sum still in tap order,
    # four taps per pass): sample (m + o) factor + p of tap i is read from phase p's row,
    # contiguous in m; the views start at the chunk's first sample (indices from 0)
    acc = np.empty(_CHUNK)
    for m0 in range(inside_first, inside_end, _CHUNK):
        width = min(_CHUNK, inside_end - m0)
        for j in range(width):
            acc[j] = 0.0
        i = 0
        while i < length:
            if i + 4 <= length:
                h0, h1 = taps_flipped[i], taps_flipped[i + 1]
                h2, h3 = taps_flipped[i + 2], taps_flipped[i + 3]
                s0 = phases[(base + i) % factor, m0 + (base + i) // factor :]
                s1 = phases[(base + i + 1) % factor, m0 + (base + i + 1) // factor :]
                s2 = phases[(base + i + 2) % factor, m0 + (base + i + 2) // factor :]
                s3 = phases[(base + i + 3) % factor, m0 + (base + i + 3) // factor :]
                for j in range(width):
                    acc[j] = (((acc[j] + s0[j] * h0) + s1[j] * h1) + s2[j] * h2) + s3[j] * h3
                i += 4
            else:
                h0 = taps_flipped[i]
                s0 = phases[(base + i) % factor, m0 + (base + i) // factor :]
                for j in range(width):
                    acc[j] = acc[j] + s0[j] * h0
                i += 1
        for j in range(width):
            out[row_out, m0 + j] = acc[j]


@numba.njit(cache=True, nogil=True)
def fir_decimate_rows(x, taps_flipped, factor, first, n_out):
    """Every ``factor``-th output of the FIR filter of each row of ``x``, line-extended.

    What ``scipy.signal.resample_poly(x, 1, factor, axis=1, padtype="line")`` computes, with
    the filter's taps flipped and zero-padded as scipy pads them and ``first`` the outputs it
    drops: the same products summed in the same order (no fast-math), so the same bits. ``x``
    (records, n); returns (records, n_out).
    """
    records, n = x.shape
    out = np.empty((records, n_out))
    phases = np.zeros((factor, n // factor + 1))
    for r in range(records):
        for row in range(n // factor):
            for phase in range(factor):
                phases[phase, row] = x[r, row * factor + phase]
        for k in range(n - n % factor, n):
            phases[k % factor, n // factor] = x[r, k]
        _decimate_phases(phases, n, taps_flipped, factor, first, out, r)
    return out


@numba.njit(cache=True, nogil=True)
def fir_decimate_columns(state, accel, columns, taps_flipped, factor, first, n_out):
    """:func:`fir_decimate_rows` of columns of two records with time along their rows.

    ``columns`` (channels, 2): channel c is column ``columns[c, 1]`` of ``state`` (0 in
    ``columns[c, 0]``) or of ``accel`` (1). The records are read once, row by row; returns
    (channels, n_out).
    """
    n = state.shape[0]
    channels = columns.shape[0]
    out = np.empty((channels, n_out))
    phases = np.zeros((channels, factor, n // factor + 1))
    for k in range(n):
        row = k // factor
        phase = k - row * factor
        for c in range(channels):
            if columns[c, 0] == 0:
                phases[c, phase, row] = state[k, columns[c, 1]]
            else:
                phases[c, phase, row] = accel[k, columns[c, 1]]
    for c in range(channels):
        _decimate_phases(phases[c], n, taps_flipped, factor, first, out, c)
    return out


@numba.njit(cache=True, nogil=True)
def add_line(y, start_cos, start_sin, offset_cos, offset_sin, amplitude):
    """Add ``amplitude`` cos(a_k + b_m) to ``y[k B + m]`` by angle addition, in place.

    ``start_cos``/``start_sin`` the cosine and sine of each block's start angle a_k,
    ``offset_cos``/``offset_sin`` those of the offsets b_m within a block (B of them); the
    products and sums of numpy's ``amplitude * (ca[:, None] * cb - sa[:, None] * sb)`` in
    one pass (the same bits), for :func:`generators.measurement.machine_background`.
    """
    n = y.shape[0]
    block = offset_cos.shape[0]
    for k in range(start_cos.shape[0]):
        ca, sa = start_cos[k], start_sin[k]
        first = k * block
        last = min(first + block, n)
        for i in range(first, last):
            m = i - first
            y[i] = y[i] + amplitude * (ca * offset_cos[m] - sa * offset_sin[m])
