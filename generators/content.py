"""What a record can show of its label: warnings for runs whose signal cannot carry it.

Two ways a run gives a signal that its label does not describe, both fixed by physics rather
than by the model's accuracy:

- a sample rate whose Nyquist frequency fs / 2 lies at or below a fault rate (BPFO, BPFI,
  2 x BSF): the fault's lines, and its envelope's, are not in the record;
- ball waviness of odd order in a scene without ball masses: a ball's radius deviation at its
  two contacts, diametrically opposite, is w(phi) + w(phi + pi) = 0 for odd orders, so the
  ball's diameter between the races does not change (docs/model.md 2.1) and the signal is
  exactly the healthy bearing's. With ball masses (``full``) an odd order moves the ball's
  centre and vibrates through its inertia (1 um on a 6205 at 1800 rpm, 500 N, one draw of
  the balls' phases: orders 1, 3, 5, 7, 9 change the housing acceleration's RMS by 0.03,
  0.7, 14, 34 and 670 % of the healthy one's, orders 2-8 by 780-92,000 %;
  ``benchmarks/odd_ball_orders.py``).

:func:`record_content_warnings` gives a message for each; ``cmtool simulate`` prints them and
:func:`generators.recipe.recipe_content_warnings` checks a recipe's conditions with it.
"""

from __future__ import annotations

from collections.abc import Iterable

from .kinematics import characteristic_frequencies
from .params import BearingGeometry

__all__ = [
    "RecordContentWarning",
    "fault_rates_outside_record",
    "odd_ball_waviness",
    "record_content_warnings",
]


class RecordContentWarning(UserWarning):
    """A run's record cannot show what its label names.

    A fault rate above fs / 2, or ball waviness of odd order in a scene without ball masses.
    """


def fault_rates_outside_record(
    geometry: BearingGeometry, shaft_frequency_hz: float, fs_hz: float
) -> str | None:
    """A message if a fault rate (BPFO, BPFI, 2 x BSF) lies at or above fs / 2.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    shaft_frequency_hz : float
        Shaft speed [Hz] (the fastest of a set of runs: the rates grow with it).
    fs_hz : float
        Sample rate of the record [Hz] (the lowest of a set of runs).

    Returns
    -------
    str or None
        Which rates the record cannot hold, and the rate that would; None if it holds them.
    """
    freqs = characteristic_frequencies(geometry, shaft_frequency_hz)
    rates = {"BPFO": freqs.bpfo, "BPFI": freqs.bpfi, "2 x BSF": 2.0 * freqs.bsf}
    above = {name: rate for name, rate in rates.items() if rate >= fs_hz / 2.0}
    if not above:
        return None
    listed = ", ".join(f"{name} {rate:.1f} Hz" for name, rate in above.items())
    return (
        f"fs = {fs_hz:g} Hz: at {60.0 * shaft_frequency_hz:g} rpm the {geometry.name}'s "
        f"{listed} lie at or above fs / 2 = {fs_hz / 2.0:g} Hz, outside the record (a rate "
        f"above {2.0 * max(rates.values()):.0f} Hz keeps every fault rate)"
    )


#: Scene levels without ball masses, where odd ball orders leave the signal a healthy one.
MASSLESS_BALL_LEVELS = ("shaft", "shaft+housing")


def odd_ball_waviness(orders: Iterable[int], scene_level: str) -> str | None:
    """A message if a scene without ball masses is given ball waviness of odd order.

    Parameters
    ----------
    orders : iterable of int
        Orders of a run's ball waviness.
    scene_level : str
        The scene's level (``shaft``, ``shaft+housing``, ``full``, ``auto``).

    Returns
    -------
    str or None
        The odd orders and why they do not vibrate in this scene; None if every order is
        even or the scene is not one of ``MASSLESS_BALL_LEVELS``.
    """
    odd = sorted({int(k) for k in orders if int(k) % 2 == 1})
    if not odd or scene_level not in MASSLESS_BALL_LEVELS:
        return None
    return (
        f"ball waviness of odd order {', '.join(map(str, odd))} does not change a ball's "
        f"diameter between its contacts: in the {scene_level!r} scene, which has no ball "
        "masses, its signal is exactly a healthy bearing's (docs/model.md 2.1); even orders "
        "vibrate in every scene, odd ones only through the balls' inertia (scene 'full')"
    )


def record_content_warnings(
    geometry: BearingGeometry,
    shaft_frequency_hz: float,
    fs_hz: float,
    ball_waviness_orders: Iterable[int] = (),
    scene_level: str = "shaft+housing",
) -> list[str]:
    """Messages for what a record of one run cannot show of its faults.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    shaft_frequency_hz : float
        Shaft speed [Hz].
    fs_hz : float
        Sample rate of the record [Hz].
    ball_waviness_orders : iterable of int
        Orders of the ball waviness the run is given (none: no ball waviness).
    scene_level : str
        The run's scene level.

    Returns
    -------
    list of str
        :func:`fault_rates_outside_record`'s and :func:`odd_ball_waviness`'s messages, if
        any.
    """
    found = (
        fault_rates_outside_record(geometry, shaft_frequency_hz, fs_hz),
        odd_ball_waviness(ball_waviness_orders, scene_level),
    )
    return [message for message in found if message is not None]
