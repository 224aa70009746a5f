"""Form errors of a manufactured bearing: the waviness every real race and ball carries.

No bearing is geometrically perfect. Grinding and honing leave waviness of every order on
the races, and ball makers grade their balls by it (ISO 3290-1: a grade G10 ball's diameter
varies by at most 0.25 um, G28 by 0.7 um). Of all those orders only a few make lines at the
housing (docs/model.md 2.1): on a race the orders q Z - 1, q Z and q Z + 1 (lines at q BPFO,
q BPFI and q BPFI -/+ f_s), on a ball the even orders (lines at 2 p f_b and 2 p f_b +/- f_c).
A healthy bearing's own vibration is these lines far more than the varying compliance of a
perfect one (docs/realism.md 8). :func:`form_waviness` lists them for one bearing.
"""

from __future__ import annotations

from ._validate import check_int, check_real
from .params import Waviness

__all__ = ["FORM_RACE_HARMONICS", "FORM_BALL_ORDERS", "MAX_FORM_WAVINESS", "form_waviness"]

#: Race orders q Z - 1, q Z, q Z + 1 for q = 1 .. FORM_RACE_HARMONICS.
FORM_RACE_HARMONICS = 2
#: Ball waviness orders (even orders squeeze the ball between its two contacts).
FORM_BALL_ORDERS = (2, 4)
#: Largest form error accepted [m]: more is damage (``Waviness`` of one order), not form.
MAX_FORM_WAVINESS = 2e-6


def form_waviness(
    ball_count: int, inner_m: float, outer_m: float, ball_m: float
) -> tuple[Waviness, ...]:
    """The waviness harmonics of a bearing's form errors (random phases).

    A race's amplitude at order k is ``A Z / k`` (A at the ball count's order Z: waviness
    spectra of ground surfaces fall with the order); a ball's is ``A 2 / k`` (A at order 2,
    the ball's out-of-roundness: a quarter of its diameter variation). Every ball carries its
    own phase.

    Parameters
    ----------
    ball_count : int
        Number of balls Z [-].
    inner_m, outer_m : float
        Inner and outer race waviness amplitude at order Z [m] (0: none; at most
        ``MAX_FORM_WAVINESS``).
    ball_m : float
        Ball waviness amplitude at order 2 [m] (0: none; at most ``MAX_FORM_WAVINESS``).

    Returns
    -------
    tuple of Waviness
        Inner race rows, then outer race, then balls (phases drawn by the simulation).

    Raises
    ------
    ParameterError
        An amplitude outside [0, ``MAX_FORM_WAVINESS``] or a ball count outside [3, 60].

    Examples
    --------
    >>> [w.order for w in form_waviness(9, 1e-7, 0.0, 0.0)]
    [8, 9, 10, 17, 18, 19]
    """
    check_int("ball_count", ball_count, low=3, high=60)
    for name, value in (("inner_m", inner_m), ("outer_m", outer_m), ("ball_m", ball_m)):
        check_real(name, value, low=0.0, high=MAX_FORM_WAVINESS, unit="m")
    rows: list[Waviness] = []
    for surface, amplitude in (("inner", inner_m), ("outer", outer_m)):
        if amplitude > 0.0:
            for q in range(1, FORM_RACE_HARMONICS + 1):
                for order in (q * ball_count - 1, q * ball_count, q * ball_count + 1):
                    rows.append(
                        Waviness(
                            surface=surface,
                            order=order,
                            amplitude=amplitude * ball_count / order,
                            phase=None,
                        )
                    )
    if ball_m > 0.0:
        for order in FORM_BALL_ORDERS:
            rows.append(
                Waviness(surface="ball", order=order, amplitude=ball_m * 2 / order, phase=None)
            )
    return tuple(rows)
