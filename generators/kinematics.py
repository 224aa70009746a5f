"""Bearing kinematics: characteristic frequencies and waviness passage frequencies.

Pure rolling, outer ring stationary, inner ring turning at f_s (docs/model.md section 2):

* FTF  f_c = f_s (1 - gamma) / 2                      (cage)
* BPFO     = Z f_c                                     (ball pass, outer race)
* BPFI     = Z (f_s - f_c)                             (ball pass, inner race)
* BSF  f_b = (D / 2d) f_s (1 - gamma^2)               (ball spin relative to the cage)
* 2xBSF    = 2 f_b                                     (a ball defect strikes both races)

with gamma = d cos(alpha) / D. Waviness passage frequencies follow the exact rules of
docs/model.md 2.1 for this planar model (which orders excite which frequencies).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from ._validate import check_choice, check_int, check_real
from .params import MAX_SHAFT_SPEED_RPM, SURFACES, BearingGeometry

__all__ = [
    "BearingFrequencies",
    "WavinessLine",
    "characteristic_frequencies",
    "waviness_passage_frequencies",
]


@dataclass(frozen=True, slots=True)
class BearingFrequencies:
    """Characteristic frequencies of a bearing at one shaft speed, all in Hz.

    Attributes
    ----------
    shaft : float
        Shaft frequency f_s [Hz].
    ftf : float
        Fundamental train (cage) frequency f_c [Hz].
    bpfo : float
        Ball pass frequency, outer race [Hz].
    bpfi : float
        Ball pass frequency, inner race [Hz].
    bsf : float
        Ball spin frequency relative to the cage f_b [Hz].
    two_bsf : float
        2 x BSF, the rate at which a ball defect strikes a race [Hz].
    inner_relative_to_cage : float
        f_s - f_c [Hz].
    """

    shaft: float
    ftf: float
    bpfo: float
    bpfi: float
    bsf: float
    two_bsf: float
    inner_relative_to_cage: float

    def as_dict(self) -> dict[str, float]:
        """Return the frequencies as a plain dict (keys are the attribute names).

        Returns
        -------
        dict of str to float
            Each frequency [Hz] under its attribute's name.
        """
        return asdict(self)

    def orders(self) -> dict[str, float]:
        """Return the frequencies as multiples of the shaft frequency [-].

        Returns
        -------
        dict of str to float
            Each frequency over the shaft frequency (orders, dimensionless).
        """
        return {k: v / self.shaft for k, v in asdict(self).items()}


def characteristic_frequencies(
    geometry: BearingGeometry, shaft_frequency_hz: float, *, cage_slip: float = 0.0
) -> BearingFrequencies:
    """Characteristic frequencies of a bearing.

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry.
    shaft_frequency_hz : float
        Shaft rotation frequency f_s [Hz], > 0.
    cage_slip : float
        Cage slip s in [0, 0.5): the cage turns at (1 - s) f_c [-].

    Returns
    -------
    BearingFrequencies
        FTF, BPFO, BPFI, BSF and 2xBSF [Hz].

    Examples
    --------
    >>> from generators import bearing, characteristic_frequencies
    >>> f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    >>> round(f.bpfo, 2)
    107.36
    """
    fs = check_real(
        "shaft_frequency_hz",
        shaft_frequency_hz,
        low=0.0,
        high=MAX_SHAFT_SPEED_RPM / 60.0,
        low_inclusive=False,
        unit="Hz",
    )
    s = check_real("cage_slip", cage_slip, low=0.0, high=0.5, high_inclusive=False)
    g = geometry.diameter_ratio
    z = geometry.ball_count
    ftf = 0.5 * fs * (1.0 - g) * (1.0 - s)
    # ball spin follows rolling on the stationary outer race: omega_b = (D/d)(1+gamma) omega_c
    bsf = (geometry.pitch_diameter / geometry.ball_diameter) * (1.0 + g) * ftf
    return BearingFrequencies(
        shaft=fs,
        ftf=ftf,
        bpfo=z * ftf,
        bpfi=z * (fs - ftf),
        bsf=bsf,
        two_bsf=2.0 * bsf,
        inner_relative_to_cage=fs - ftf,
    )


@dataclass(frozen=True, slots=True)
class WavinessLine:
    """One spectral line excited by a waviness order.

    Attributes
    ----------
    frequency : float
        Line frequency [Hz].
    harmonic : int
        q, the ball-pass harmonic (or 2p/order for balls) the line belongs to.
    sideband : int
        Multiple of the sideband spacing (f_s for inner race, f_c for balls) added [-].
    direction : {"radial", "load"}
        ``radial``: rotating pattern, equal in x and y, present even under uniform load;
        ``load``: in the load direction only, needs a load zone.
    strength : {"strong", "weak"}
        ``strong`` for the exact-order rules (m = 0 or 1 load-zone harmonic), ``weak`` for lines
        that need higher load-zone harmonics.
    """

    frequency: float
    harmonic: int
    sideband: int
    direction: str
    strength: str


def waviness_passage_frequencies(
    geometry: BearingGeometry,
    shaft_frequency_hz: float,
    surface: str,
    order: int,
    *,
    max_harmonic: int = 3,
    cage_slip: float = 0.0,
) -> list[WavinessLine]:
    """Frequencies at which a waviness of order ``order`` on ``surface`` forces the shaft.

    Rules of docs/model.md 2.1 (planar model, Z balls, load-zone Fourier harmonics m):

    * outer race, order k: lines at q BPFO; ``radial`` when k = qZ +/- 1, ``load`` when k = qZ,
      otherwise ``weak``;
    * inner race, order k: lines at k f_s - qZ f_c = q BPFI + (k - qZ) f_s; ``radial`` when
      k = qZ +/- 1, ``load`` when k = qZ, otherwise ``weak``;
    * ball, order k: only even k = 2p compress the ball; lines at 2p f_b (``load``) and
      2p f_b +/- f_c (``radial``). Odd orders give no line.

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry.
    shaft_frequency_hz : float
        Shaft frequency [Hz].
    surface : {"outer", "inner", "ball"}
        Surface with the waviness.
    order : int
        Waviness order N_w >= 1.
    max_harmonic : int
        Largest ball-pass harmonic q considered.
    cage_slip : float
        Cage slip [-].

    Returns
    -------
    list of WavinessLine
        Lines sorted by frequency; only positive frequencies.
    """
    check_choice("surface", surface, SURFACES)
    k = check_int("order", order, low=1, high=500)
    qmax = check_int("max_harmonic", max_harmonic, low=1, high=100)
    f = characteristic_frequencies(geometry, shaft_frequency_hz, cage_slip=cage_slip)
    return passage_lines(f, geometry.ball_count, surface, k, qmax)


def passage_lines(
    f: BearingFrequencies, z: int, surface: str, k: int, qmax: int
) -> list[WavinessLine]:
    """:func:`waviness_passage_frequencies` from checked inputs and known frequencies ``f``.

    Parameters
    ----------
    f : BearingFrequencies
        The characteristic frequencies [Hz].
    z : int
        Ball count Z.
    surface : {"outer", "inner", "ball"}
        Surface with waviness.
    k : int
        Waviness order (lobes per circumference).
    qmax : int
        Largest ball-pass harmonic q considered.

    Returns
    -------
    list of WavinessLine
        As :func:`waviness_passage_frequencies`.
    """
    lines: list[WavinessLine] = []
    if surface == "outer":
        for q in range(1, qmax + 1):
            m = abs(q * z - k)
            direction = "load" if m == 0 else "radial"
            strength = "strong" if m <= 1 else "weak"
            lines.append(WavinessLine(q * f.bpfo, q, 0, direction, strength))
    elif surface == "inner":
        for q in range(1, qmax + 1):
            m = abs(q * z - k)
            freq = k * f.shaft - q * z * f.ftf
            if freq <= 0:
                continue
            direction = "load" if m == 0 else "radial"
            strength = "strong" if m <= 1 else "weak"
            lines.append(WavinessLine(freq, q, k - q * z, direction, strength))
    else:
        if k % 2 == 0:
            lines.append(WavinessLine(k * f.bsf, k, 0, "load", "strong"))
            for sb in (-1, 1):
                freq = k * f.bsf + sb * f.ftf
                if freq > 0:
                    lines.append(WavinessLine(freq, k, sb, "radial", "strong"))
    return sorted(lines, key=lambda line: line.frequency)
