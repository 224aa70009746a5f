"""The sample rate a recording's time column gives, and the gaps and jumps back it holds.

A time column (CSV, parquet, a logger's time stamps as seconds) gives the rate where it rises
in equal steps (:func:`time_axis_rate`); one with gaps (samples a logger dropped) or jumps
back (files joined end to end) gives the rate of its other steps and a warning naming the
splice (:func:`spliced_time_axis`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["GAP_STEP", "spliced_time_axis", "time_axis_rate"]

#: A time column's step this many times its median is a gap (a sample or more missing); one
#: of 0 s or less a jump back (files joined end to end). Rounding (12 kHz written to
#: microseconds: 0.6 %) or a clock's jitter stay far inside.
GAP_STEP = 1.9


def time_axis_rate(values: np.ndarray) -> float | None:
    """The sample rate [Hz] if ``values`` is a time axis, else None.

    A time axis rises at every sample, never by ``GAP_STEP`` times the median step or more,
    in steps whose median is within 1 % of their mean (equal steps, written to however few
    digits: 1 / 12000 s as 0.000083 and 0.000084); the rate is the mean's, the span over the
    steps, which the rounding of each value moves by at most a quantum over the whole span.

    Parameters
    ----------
    values : numpy.ndarray
        The column [s].

    Returns
    -------
    float or None
        The rate [Hz], or None where the column is no time axis without gaps.
    """
    if values.size < 3 or not np.all(np.isfinite(values)):
        return None
    steps = np.diff(values)
    mean = float(values[-1] - values[0]) / (values.size - 1)
    median = float(np.median(steps))
    if (
        np.all((steps > 0) & (steps < GAP_STEP * median))  # no jump back, no gap
        and abs(median - mean) <= 0.01 * mean
    ):
        return 1.0 / mean
    return None


def spliced_time_axis(times: np.ndarray, step: float, name: str) -> tuple[float, list[str]]:
    """The rate of a time column with gaps or jumps back, and a warning naming them.

    The rate is that of the other steps: their span over their count. A logger that dropped
    samples, or files joined end to end, give a record spliced at those steps, where a
    fault's lines lose their phase.

    Parameters
    ----------
    times : numpy.ndarray
        The column [s].
    step : float
        Its median step [s].
    name : str
        The file and column, in the warning.

    Returns
    -------
    rate : float
        The rate of the regular steps [Hz].
    warnings : list of str
        The first gap and the first jump back, with how many more there are.
    """
    steps = np.diff(times)
    gaps, back = steps >= GAP_STEP * step, steps <= 0
    regular = ~(gaps | back)
    rate = float(regular.sum()) / float(steps[regular].sum())
    said = []
    for kind, where in (("jumps by", gaps), ("goes back by", back)):
        at = np.flatnonzero(where)
        if at.size:
            k = int(at[0])
            lost = f" (about {round(steps[k] * rate) - 1} samples missing)" if steps[k] > 0 else ""
            more = f" and at {at.size - 1} more place(s)" if at.size > 1 else ""
            said.append(
                f"{name} {kind} {abs(steps[k]):.6g} s after t = {times[k]:.6g} s{lost}{more}: "
                "the record is spliced there, and a fault's lines lose their phase across a "
                f"splice; the rate is its other steps' ({rate:.6g} Hz)"
            )
    return rate, said
