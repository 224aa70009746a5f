"""Input validation helpers shared by the parameter objects of ``generators``.

Every check raises :class:`ParameterError` (a ``ValueError``) whose message names the
parameter, the value it got and the range it accepts.
"""

from __future__ import annotations

import math
from numbers import Integral, Real
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy is loaded where an array is checked: `cmtool --help` stays light
    import numpy as np


class ParameterError(ValueError):
    """A parameter is outside its valid range (message names parameter, value and range)."""


class OperatingRangeWarning(UserWarning):
    """A run outside its bearing's catalogue ratings (static load rating, limiting speed).

    The model still integrates it, but describes it less well.
    """


class StepShortenedWarning(UserWarning):
    """A run diverged at its default RK4 step and was integrated again at a shorter one.

    The step used is in the result's ``parameters["integrator_stats"]`` (``step_s``,
    ``step_halvings``).
    """


class SimulationDivergedError(RuntimeError):
    """The time integration left the physically bounded region or produced non-finite values."""

    def __init__(self, message: str, *, scene: str, time: float, reason: str) -> None:
        super().__init__(message)
        self.scene = scene
        self.time = time
        self.reason = reason


def check_real(
    name: str,
    value: object,
    *,
    low: float | None = None,
    high: float | None = None,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
    unit: str = "",
) -> float:
    """Return ``value`` as a finite float inside ``[low, high]`` or raise ParameterError.

    Parameters
    ----------
    name : str
        Parameter name used in the message.
    value : object
        Value to check.
    low, high : float, optional
        Bounds of the valid range (``None`` for unbounded).
    low_inclusive, high_inclusive : bool
        Whether the bounds themselves are valid.
    unit : str
        Unit shown in the message, e.g. ``"m"``.

    Returns
    -------
    float
        The checked value.
    """

    def allowed() -> str:  # the message's range, built only for an error
        lo = "-inf" if low is None else f"{low:g}"
        hi = "inf" if high is None else f"{high:g}"
        lb = "[" if (low is not None and low_inclusive) else "("
        hb = "]" if (high is not None and high_inclusive) else ")"
        return f"{lb}{lo}, {hi}{hb}" + (f" {unit}" if unit else "")

    if type(value) is not float and (isinstance(value, bool) or not isinstance(value, Real)):
        raise ParameterError(f"{name} = {value!r} is not a real number; allowed range {allowed()}")
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(f"{name} = {v!r} is not finite; allowed range {allowed()}")
    bad = (low is not None and (v < low or (v == low and not low_inclusive))) or (
        high is not None and (v > high or (v == high and not high_inclusive))
    )
    if bad:
        raise ParameterError(
            f"{name} = {v:g}{(' ' + unit) if unit else ''} is outside the allowed range {allowed()}"
        )
    return v


def check_real_array(
    name: str,
    value: object,
    *,
    low: float | None = None,
    low_inclusive: bool = True,
    unit: str = "",
) -> np.ndarray:
    """``value`` (a number or an array of numbers) as floats, each finite and not below ``low``.

    Parameters
    ----------
    name : str
        Parameter name used in the message (with the index of the first bad element).
    value : object
        Value to check.
    low : float, optional
        Lower bound of the valid range (``None`` for unbounded).
    low_inclusive : bool
        Whether the bound itself is valid.
    unit : str
        Unit shown in the message.

    Returns
    -------
    ndarray
        ``value`` as a float array (0-d for a number).

    Raises
    ------
    ParameterError
        Naming the parameter (and the first bad element's index), its value and the range,
        as :func:`check_real`.
    """
    import numpy as np

    try:
        values = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(
            f"{name} = {value!r} is not a real number or an array of real numbers"
        ) from None
    bad = ~np.isfinite(values)
    if low is not None:
        bad |= (values < low) if low_inclusive else (values <= low)
    if bad.any():
        where = tuple(int(k) for k in np.argwhere(bad)[0])
        label = f"{name}[{', '.join(map(str, where))}]" if where else name
        check_real(label, float(values[where]), low=low, low_inclusive=low_inclusive, unit=unit)
    return values


def check_int(name: str, value: object, *, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as an int inside ``[low, high]`` or raise ParameterError."""
    rng = f"[{'-inf' if low is None else low}, {'inf' if high is None else high}]"
    if isinstance(value, bool) or not isinstance(value, Integral):
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        else:
            raise ParameterError(f"{name} = {value!r} is not an integer; allowed range {rng}")
    v = int(value)
    if (low is not None and v < low) or (high is not None and v > high):
        raise ParameterError(f"{name} = {v} is outside the allowed range {rng}")
    return v


def check_choice(name: str, value: object, choices: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of ``choices`` or raise ParameterError."""
    if value not in choices:
        raise ParameterError(f"{name} = {value!r} is not one of {', '.join(map(repr, choices))}")
    return str(value)
