"""The measurement chain between a bearing and a recording, and the rest of the machine.

A simulated housing signal is what the bearing does to its housing; a recording is that signal
after the machine's structure, the accelerometer, the acquisition's anti-alias filter and its
converter, with the rest of the machine added. docs/realism.md argues each element from the
literature and the rigs' published descriptions:

* :func:`transfer_path`: the structure between the bearing and the sensor as a sum of damped
  modes (modal superposition of an accelerance: each mode a band-pass of unit peak gain times
  its own gain), so that impacts ring at several resonances, as on real machines;
* :func:`sensor_response`: the accelerometer's mounted resonance (second order, flat below it);
* :func:`sensor_noise`: the accelerometer's own white noise after its resonance, in
  absolute units (a spectral density);
* :func:`electronic_noise`: the sensor's and the recorder's own white noise, after the
  resonance, relative to what they amplify;
* :func:`anti_alias_filter`: the acquisition's causal Butterworth low-pass
  (:func:`butterworth_low_pass`);
* :func:`digitise`: quantisation to a number of bits over a full scale, clipping beyond it;
* :func:`overall_velocity_rms`: a housing's overall vibration velocity in ISO 10816's broad
  band, which sets a record's absolute level (``[sensor] machine_velocity_mm_s``);
* :func:`machine_background`: shaft harmonics (unbalance, misalignment), electrical lines at
  the line frequency and its harmonics, another bearing's lines and coloured broadband noise
  (white forces on the housing and the rotor through the same structure).

All functions take plain arrays in the signal's own unit (m/s^2 for acceleration) and SI
frequencies; the parameter objects validate their inputs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal as sp_signal

from ._filters import add_line, sos_steady_state
from ._validate import ParameterError, check_int, check_real

__all__ = [
    "StructuralMode",
    "MachineBackground",
    "SupportStructure",
    "transfer_path",
    "sensor_response",
    "sensor_noise",
    "electronic_noise",
    "anti_alias_filter",
    "butterworth_low_pass",
    "digitise",
    "overall_velocity_rms",
    "overall_velocity_band",
    "machine_background",
    "band_power",
    "fault_band",
    "fault_band_powers",
]


@dataclass(frozen=True, slots=True, kw_only=True)
class StructuralMode:
    """One mode of the path from the bearing to the sensor.

    Attributes
    ----------
    frequency : float
        Natural frequency f_n [Hz].
    damping : float
        Damping ratio zeta [-].
    gain : float
        Gain at f_n relative to the input [-].
    """

    frequency: float
    damping: float = 0.05
    gain: float = 1.0

    def __post_init__(self) -> None:
        check_real("frequency", self.frequency, low=0.0, high=1e6, low_inclusive=False, unit="Hz")
        check_real("damping", self.damping, low=0.0, high=1.0, low_inclusive=False)
        check_real("gain", self.gain, low=0.0, high=1e6)


@dataclass(frozen=True, slots=True, kw_only=True)
class SupportStructure:
    """The bearing's own structure, linearised: shaft on bearing, housing on support.

    The two-mass model of ``generators.Rig`` (docs/model.md 1). A force on the housing (the
    rest of the machine's broadband excitation reaching the bearing through its frame) and one
    on the shaft (the rotor's own excitation) move the housing through the same modes as the
    bearing's own forces do: :meth:`response`.

    Attributes
    ----------
    shaft_mass, housing_mass : float
        M_s, M_h [kg].
    bearing_stiffness : float
        k_r, the bearing's radial stiffness [N/m] (e.g. static, at the load; 0: unloaded).
    pedestal_stiffness : float
        k_h [N/m].
    shaft_damping, pedestal_damping : float
        c_s (shaft to ground, as in the model), c_h [N s/m].
    """

    shaft_mass: float
    housing_mass: float
    bearing_stiffness: float
    pedestal_stiffness: float
    shaft_damping: float
    pedestal_damping: float

    def __post_init__(self) -> None:
        for name in ("shaft_mass", "housing_mass", "pedestal_stiffness"):
            check_real(name, getattr(self, name), low=0.0, high=1e13, low_inclusive=False)
        # 0: an unloaded bearing with clearance, the shaft free of the housing
        check_real("bearing_stiffness", self.bearing_stiffness, low=0.0, high=1e13, unit="N/m")
        for name in ("shaft_damping", "pedestal_damping"):
            check_real(name, getattr(self, name), low=0.0, high=1e9, unit="N s/m")

    def response(
        self, force: np.ndarray, fs: float, shaft_force: np.ndarray | None = None
    ) -> np.ndarray:
        """Housing acceleration for a force on the housing (and one on the shaft), times M_h.

        A force on the housing passes with unit gain above the modes, where the housing moves
        as a free mass, and not at all at the shaft-on-bearing frequency sqrt(k_r / M_s), where
        the shaft absorbs it (an antiresonance). A force on the shaft (the rotor's own
        excitation) reaches the housing through the bearing, as the bearing's own forces do,
        with a resonance there. A circular FFT filter, for stationary noise.

        Parameters
        ----------
        force : ndarray
            Force on the housing [any unit], sampled at ``fs`` [Hz].
        fs : float
            Sample rate [Hz].
        shaft_force : ndarray, optional
            Force on the shaft, same length and unit as ``force``.

        Returns
        -------
        ndarray
            Same length and unit as ``force``.
        """
        n = force.size
        s = 2j * np.pi * np.fft.rfftfreq(n, 1.0 / fs)
        ms, mh = self.shaft_mass, self.housing_mass
        kr, kh = self.bearing_stiffness, self.pedestal_stiffness
        shaft = ms * s**2 + self.shaft_damping * s + kr
        det = shaft * (mh * s**2 + self.pedestal_damping * s + kh + kr) - kr * kr
        gain = np.zeros_like(s)
        gain[1:] = mh * s[1:] ** 2 * shaft[1:] / det[1:]  # no acceleration at 0 Hz
        spectrum = np.fft.rfft(force) * gain
        if shaft_force is not None:
            if np.shape(shaft_force) != np.shape(force):
                raise ParameterError(
                    f"shaft_force has shape {np.shape(shaft_force)}: expected the force's, "
                    f"{np.shape(force)}"
                )
            through = np.zeros_like(s)
            through[1:] = mh * s[1:] ** 2 * kr / det[1:]
            spectrum += np.fft.rfft(shaft_force) * through
        return np.fft.irfft(spectrum, n)


@dataclass(frozen=True, slots=True, kw_only=True)
class MachineBackground:
    """Everything a sensor on a running machine picks up that is not the bearing under test.

    Amplitudes are in the signal's unit (peak of each sinusoid; RMS of the noise).

    Attributes
    ----------
    broadband_rms : float
        RMS of the broadband noise after the structure (white noise through the
        :func:`transfer_path` modes, or white when there are none).
    shaft_harmonics : tuple of float
        Amplitudes of the lines at 1, 2, 3, ... times the shaft frequency (unbalance at 1x,
        misalignment at 2x and above).
    line_frequency : float
        Electrical line frequency [Hz] (50 or 60).
    line_harmonics : tuple of float
        Amplitudes at 1, 2, ... times the line frequency (2x: magnetostriction in motors).
    other_lines : tuple of (float, float)
        (frequency [Hz], amplitude) of other periodic sources, e.g. the machine's other
        bearing's varying-compliance lines.
    floor_rms : float
        RMS of the sensor's and the electronics' white noise floor.
    rotor_force_ratio : float
        The broadband excitation's white force on the shaft over the one on the housing
        (amplitude ratio; 0: the housing's only). Used with a ``support`` structure in
        :func:`machine_background`; without one both forces are white and add.
    """

    broadband_rms: float = 0.0
    shaft_harmonics: tuple[float, ...] = ()
    line_frequency: float = 60.0
    line_harmonics: tuple[float, ...] = ()
    other_lines: tuple[tuple[float, float], ...] = ()
    floor_rms: float = 0.0
    rotor_force_ratio: float = 0.0

    def __post_init__(self) -> None:
        check_real("broadband_rms", self.broadband_rms, low=0.0, high=1e12)
        check_real("floor_rms", self.floor_rms, low=0.0, high=1e12)
        check_real("rotor_force_ratio", self.rotor_force_ratio, low=0.0, high=1e6)
        check_real("line_frequency", self.line_frequency, low=1.0, high=1e4, unit="Hz")
        for name, values in (
            ("shaft_harmonics", self.shaft_harmonics),
            ("line_harmonics", self.line_harmonics),
        ):
            for i, a in enumerate(values):
                check_real(f"{name}[{i}]", a, low=0.0, high=1e12)
        for i, pair in enumerate(self.other_lines):
            if len(pair) != 2:
                raise ParameterError(
                    f"other_lines[{i}] = {pair!r}: expected (frequency, amplitude)"
                )
            check_real(f"other_lines[{i}] frequency", pair[0], low=0.0, high=1e6, unit="Hz")
            check_real(f"other_lines[{i}] amplitude", pair[1], low=0.0, high=1e12)


#: Length of the lead-in [s] that causal filters run over before the record starts (an odd
#: extension of the record: continuous value and slope), so that no start-up transient of a
#: filter appears in the record (an envelope analyst would see it as one huge impact).
LEAD_IN_S = 0.25


def _causal(
    sos: np.ndarray, x: np.ndarray, fs: float, gains: np.ndarray | None = None
) -> np.ndarray:
    """``sosfilt`` as if the signal had been running: over a lead-in, started in steady state.

    ``x`` is one record or a stack of records (filtered along the last axis). ``sos`` is one
    cascade (sections, 6) or several (cascades, sections, 6) whose outputs are summed, each
    weighted by ``gains`` (the structure's modes); the recursion is
    :func:`generators._filters.sos_steady_state`'s (that of ``scipy.signal.sosfilt`` with
    ``sosfilt_zi`` times the lead-in's first sample).
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[-1]
    pad = min(n - 1, int(round(LEAD_IN_S * fs)))
    cascades = np.asarray(sos, dtype=float)
    if cascades.ndim == 2:
        cascades = cascades[None]
    weights = np.ones(cascades.shape[0]) if gains is None else np.asarray(gains, dtype=float)
    if pad < 1:
        y = sum(
            w * sp_signal.sosfilt(c, x, axis=-1) for w, c in zip(weights, cascades, strict=True)
        )
        return np.asarray(y, dtype=float)
    rows = np.ascontiguousarray(x.reshape(-1, n))
    return sos_steady_state(np.ascontiguousarray(cascades), rows, pad, weights).reshape(x.shape)


def _bilinear_biquad(num: tuple[float, float], den: tuple[float, float], fs: float) -> np.ndarray:
    """One second-order section of H(s) = (num[0] s + num[1]) / (s^2 + den[0] s + den[1]).

    The bilinear transform s = 2 fs (1 - 1/z) / (1 + 1/z) in closed form (what
    ``scipy.signal.bilinear`` and ``tf2sos`` give, without their polynomial arithmetic).
    """
    k = 2.0 * fs
    b1, b0 = num
    a1, a0 = den
    norm = k * k + a1 * k + a0
    return np.array(
        [
            [
                (b1 * k + b0) / norm,
                2.0 * b0 / norm,
                (b0 - b1 * k) / norm,
                1.0,
                (2.0 * a0 - 2.0 * k * k) / norm,
                (k * k - a1 * k + a0) / norm,
            ]
        ]
    )


def _prewarped(frequency: float, fs: float) -> float:
    """Analogue angular frequency that the bilinear transform maps to ``frequency`` [rad/s]."""
    return 2.0 * fs * math.tan(math.pi * frequency / fs)


def _band_pass(fs: float, frequency: float, damping: float) -> np.ndarray:
    """Second-order sections of H(s) = 2 zeta w s / (s^2 + 2 zeta w s + w^2), |H(j w)| = 1.

    Bilinear, with w pre-warped so that the digital peak lies at ``frequency`` [Hz].
    """
    w = _prewarped(frequency, fs)
    return _bilinear_biquad((2.0 * damping * w, 0.0), (2.0 * damping * w, w * w), fs)


def transfer_path(x: np.ndarray, fs: float, modes: tuple[StructuralMode, ...]) -> np.ndarray:
    """The signal at the sensor: the sum of the modes' responses (identity without modes).

    Parameters
    ----------
    x : ndarray
        Signal at the bearing (any unit) sampled at ``fs`` [Hz], or a stack of such signals
        (time along the last axis).
    fs : float
        Sample rate [Hz].
    modes : tuple of StructuralMode
        The structure's modes below 0.45 fs (others are ignored: they lie above the band).

    Returns
    -------
    ndarray
        Same shape and unit as ``x``.
    """
    x = np.asarray(x, dtype=float)
    kept = [m for m in modes if m.frequency < 0.45 * fs]
    if not kept:
        return x.copy()
    sos = np.stack([_band_pass(fs, mode.frequency, mode.damping) for mode in kept])
    return _causal(sos, x, fs, np.array([mode.gain for mode in kept]))


def sensor_response(x: np.ndarray, fs: float, resonance: float, damping: float) -> np.ndarray:
    """An accelerometer's mounted resonance: w^2 / (s^2 + 2 zeta w s + w^2), unit gain at DC.

    Parameters
    ----------
    x : ndarray
        Acceleration at the mounting point, sampled at ``fs`` [Hz].
    fs : float
        Sample rate [Hz].
    resonance : float
        Mounted resonance [Hz]; at or above 0.45 fs the sensor is flat in band and ``x`` is
        returned unchanged.
    damping : float
        Damping ratio of the resonance [-] (piezoelectric sensors: 0.01-0.05).

    Returns
    -------
    ndarray
        The sensor's output, in the unit of ``x``.
    """
    check_real("resonance", resonance, low=0.0, high=1e7, low_inclusive=False, unit="Hz")
    check_real("damping", damping, low=0.0, high=1.0, low_inclusive=False)
    if resonance >= 0.45 * fs:
        return np.asarray(x, dtype=float).copy()
    w = _prewarped(resonance, fs)
    return _causal(_bilinear_biquad((0.0, w * w), (2.0 * damping * w, w * w), fs), x, fs)


def electronic_noise(
    x: np.ndarray, floor_db: float, rng: np.random.Generator
) -> tuple[np.ndarray, float]:
    """The sensor's preamplifier and recorder's front end: white noise after the resonance.

    Its level is relative to the RMS of what they amplify.

    Parameters
    ----------
    x : ndarray
        The sensor's output, one record (any unit).
    floor_db : float
        The noise's RMS over the RMS of ``x`` [dB], in [-120, 0] (recipes: -65 to -45,
        docs/realism.md 2).
    rng : numpy.random.Generator
        Source of the noise.

    Returns
    -------
    y : ndarray
        ``x`` plus the noise, in the unit of ``x``.
    noise_rms : float
        The noise's RMS, in the unit of ``x``.
    """
    check_real("floor_db", floor_db, low=-120.0, high=0.0, unit="dB")
    x = np.asarray(x, dtype=float)
    noise_rms = float(np.sqrt(np.mean(x * x))) * 10.0 ** (floor_db / 20.0)
    return x + rng.normal(0.0, noise_rms, x.size), noise_rms


def sensor_noise(
    x: np.ndarray, fs: float, density: float, rng: np.random.Generator
) -> tuple[np.ndarray, float]:
    """The accelerometer's own noise: white after its mounted resonance, in absolute units.

    A sensor's residual noise does not follow the vibration it measures: a datasheet gives it
    as a spectral density or as an RMS over a band (docs/realism.md 2).

    Parameters
    ----------
    x : ndarray
        The sensor's output, one acceleration record [m/s^2] sampled at ``fs``.
    fs : float
        Sample rate [Hz].
    density : float
        The noise's one-sided amplitude spectral density [m/s^2/sqrt(Hz)], in [1e-9, 0.1]
        (a general-purpose accelerometer: 1e-5 to 4e-5, 1-4 ug/sqrt(Hz); docs/realism.md 2).
    rng : numpy.random.Generator
        Source of the noise.

    Returns
    -------
    y : ndarray
        ``x`` plus the noise [m/s^2].
    noise_rms : float
        The noise's RMS over 0 to fs/2, ``density * sqrt(fs / 2)`` [m/s^2].
    """
    check_real("fs", fs, low=0.0, low_inclusive=False, unit="Hz")
    check_real("density", density, low=1e-9, high=0.1, unit="m/s^2/sqrt(Hz)")
    x = np.asarray(x, dtype=float)
    noise_rms = density * math.sqrt(fs / 2.0)
    return x + rng.normal(0.0, noise_rms, x.size), noise_rms


def anti_alias_filter(x: np.ndarray, fs: float, cutoff: float, order: int = 8) -> np.ndarray:
    """The acquisition's anti-alias low-pass: a causal Butterworth (as in analogue front ends).

    Parameters
    ----------
    x : ndarray
        Signal sampled at ``fs`` [Hz].
    fs : float
        Sample rate [Hz].
    cutoff : float
        -3 dB frequency over the sample rate [-], in (0, 0.5).
    order : int
        Filter order (roll-off 6 x order dB per octave).

    Returns
    -------
    ndarray
        The filtered signal.
    """
    check_real("cutoff", cutoff, low=0.0, high=0.5, low_inclusive=False, high_inclusive=False)
    check_int("order", order, low=1, high=16)
    return _causal(butterworth_low_pass(order, cutoff), x, fs)


def butterworth_low_pass(order: int, cutoff: float) -> np.ndarray:
    """Second-order sections of a digital Butterworth low-pass (bilinear, pre-warped).

    What ``scipy.signal.butter(order, 2 * cutoff, output="sos")`` designs, in closed form:
    the analogue prototype's pole pairs at angles pi (2 m + 1) / (2 order) from the imaginary
    axis, H(s) = w^2 / (s^2 + 2 sin(.) w s + w^2), and for an odd order the real pole,
    H(s) = w / (s + w), each mapped by the bilinear transform with the cutoff pre-warped, unit
    gain at DC (scipy's polynomial route costs 1.4 ms a design; this 20 us).

    Parameters
    ----------
    order : int
        Filter order (roll-off 6 x order dB per octave).
    cutoff : float
        -3 dB frequency over the sample rate [-], in (0, 0.5).

    Returns
    -------
    ndarray, shape (ceil(order / 2), 6)
        Rows [b0, b1, b2, 1, a1, a2].
    """
    check_real("cutoff", cutoff, low=0.0, high=0.5, low_inclusive=False, high_inclusive=False)
    check_int("order", order, low=1, high=16)
    fs = 1.0  # frequencies over the sample rate
    w = _prewarped(cutoff, fs)
    sections = [
        _bilinear_biquad(
            (0.0, w * w), (2.0 * math.sin(math.pi * (2 * m + 1) / (2 * order)) * w, w * w), fs
        )[0]
        for m in range(order // 2)
    ]
    if order % 2:
        k = 2.0 * fs
        b = w / (k + w)
        sections.append(np.array([b, b, 0.0, 1.0, (w - k) / (k + w), 0.0]))
    return np.array(sections)


def digitise(x: np.ndarray, bits: int, full_scale: float) -> tuple[np.ndarray, float]:
    """Quantise to ``bits`` over [-full_scale, full_scale) and clip beyond.

    Parameters
    ----------
    x : ndarray
        Signal (any unit).
    bits : int
        Converter resolution [bits].
    full_scale : float
        Largest representable magnitude, in the unit of ``x``.

    Returns
    -------
    y : ndarray
        The digitised signal (mid-tread quantiser), in the unit of ``x``.
    clipped : float
        Fraction of samples clipped [-].
    """
    check_int("bits", bits, low=2, high=32)
    check_real("full_scale", full_scale, low=0.0, high=1e15, low_inclusive=False)
    step = 2.0 * full_scale / 2**bits
    top = full_scale - step
    clipped = float(np.mean((x > top) | (x < -full_scale)))
    return np.clip(np.round(x / step) * step, -full_scale, top), clipped


def overall_velocity_band(rpm: float, fs: float) -> tuple[float, float]:
    """ISO 10816's broad band [Hz]: 10-1000 Hz (2-1000 Hz at 600 rpm or less), below fs / 2.

    Parameters
    ----------
    rpm : float
        Shaft speed [rev/min].
    fs : float
        Sample rate [Hz].

    Returns
    -------
    low, high : float
        The band [Hz] (``cmtool.diagnosis.overall_band``, cut at fs / 2).
    """
    check_real("rpm", rpm, low=0.0, high=1e6, low_inclusive=False, unit="rev/min")
    check_real("fs", fs, low=0.0, high=1e9, low_inclusive=False, unit="Hz")
    low = 2.0 if rpm <= 600.0 else 10.0
    if fs / 2.0 <= low:
        raise ParameterError(
            f"fs = {fs:g} Hz is outside the allowed range: above {2.0 * low:g} Hz, for ISO "
            f"10816's band from {low:g} Hz"
        )
    return low, min(1000.0, fs / 2.0)


def overall_velocity_rms(
    x: np.ndarray, fs: float, quantity: str, band: tuple[float, float]
) -> float:
    """The velocity RMS of a record over a band, by its spectrum [m/s for a record in SI].

    The record's DFT is integrated (acceleration), taken as it is (velocity) or differentiated
    (displacement) bin by bin, and the bins within ``band`` summed (Parseval): a housing's
    overall vibration as ISO 10816 measures it.

    Parameters
    ----------
    x : ndarray
        One record, in m, m/s or m/s^2 as ``quantity`` says.
    fs : float
        Sample rate [Hz].
    quantity : {"displacement", "velocity", "acceleration"}
        What ``x`` is.
    band : (float, float)
        The band [Hz] (:func:`overall_velocity_band`).

    Returns
    -------
    float
        The RMS velocity in the band [m/s].

    Raises
    ------
    ParameterError
        ``quantity`` not one of the three, ``fs`` not positive, or the band not within
        [0, fs / 2], each named with its allowed range.

    Examples
    --------
    >>> fs = 12000.0; t = np.arange(12000) / fs
    >>> a = 2 * np.pi * 100.0 * np.cos(2 * np.pi * 100.0 * t)  # velocity sin(2 pi 100 t) m/s
    >>> round(overall_velocity_rms(a, fs, "acceleration", (10.0, 1000.0)), 4)
    0.7071
    """
    if quantity not in ("displacement", "velocity", "acceleration"):
        raise ParameterError(
            f"quantity = {quantity!r} is outside the allowed values: displacement, velocity, "
            "acceleration"
        )
    check_real("fs", fs, low=0.0, high=1e9, low_inclusive=False, unit="Hz")
    low, high = (float(v) for v in band)
    if not 0.0 <= low < high <= fs / 2.0:
        raise ParameterError(
            f"band = ({low:g}, {high:g}) Hz is outside the allowed range: 0 <= low < high <= "
            f"fs / 2 = {fs / 2.0:g} Hz"
        )
    x = np.asarray(x, dtype=float)
    n = x.size
    spec = np.fft.rfft(x - x.mean())
    f = np.fft.rfftfreq(n, 1.0 / fs)
    inside = (f >= low) & (f <= high) & (f > 0.0)
    jw = 2j * np.pi * f[inside]
    to_velocity = {"acceleration": 1.0 / jw, "velocity": 1.0, "displacement": jw}[quantity]
    velocity = spec[inside] * to_velocity
    # one-sided: each bin but the Nyquist bin stands for two
    weights = np.where(f[inside] == fs / 2.0, 1.0, 2.0)
    return float(np.sqrt(np.sum(weights * np.abs(velocity) ** 2)) / n)


def machine_background(
    n: int,
    fs: float,
    shaft_frequency: float,
    background: MachineBackground,
    modes: tuple[StructuralMode, ...],
    rng: np.random.Generator,
    support: SupportStructure | None = None,
) -> np.ndarray:
    """A record of the rest of the machine: lines with random phases plus coloured noise.

    Parameters
    ----------
    n : int
        Samples.
    fs : float
        Sample rate [Hz].
    shaft_frequency : float
        Shaft rotation frequency [Hz] (the shaft harmonics).
    background : MachineBackground
        Levels of each source.
    modes : tuple of StructuralMode
        The structure the broadband excitation rings through (:func:`transfer_path`).
    rng : numpy.random.Generator
        Source of phases and noise.
    support : SupportStructure, optional
        The bearing's own structure: the broadband excitation, a force on the housing and
        (``background.rotor_force_ratio``) one on the shaft, goes through it before the
        modes, as the bearing's own vibration does.

    Returns
    -------
    ndarray
        ``n`` samples in the unit of the amplitudes. Lines at or above 0.45 fs are left out.
    """
    y = np.zeros(n)
    lines = [(h * shaft_frequency, a) for h, a in enumerate(background.shaft_harmonics, 1)]
    lines += [
        (h * background.line_frequency, a) for h, a in enumerate(background.line_harmonics, 1)
    ]
    lines += list(background.other_lines)
    # cos(w (k B + m) / fs + phase) from the cos and sin of the block starts k B and of the
    # offsets m < B (angle addition: two products a sample instead of a cosine)
    block = 256
    starts = np.arange(0, n, block) / fs
    offsets = np.arange(block) / fs
    for frequency, amplitude in lines:
        phase = rng.uniform(0.0, 2 * math.pi)
        if amplitude > 0.0 and frequency < 0.45 * fs:
            w = 2 * math.pi * frequency
            a = w * starts + phase
            b = w * offsets
            add_line(y, np.cos(a), np.sin(a), np.cos(b), np.sin(b), amplitude)
    if background.broadband_rms > 0.0:
        force = rng.standard_normal(n)
        ratio = background.rotor_force_ratio
        rotor = rng.standard_normal(n) * ratio if ratio > 0.0 else None
        if support is not None:
            force = support.response(force, fs, rotor)
        elif rotor is not None:
            force = force + rotor
        noise = transfer_path(force, fs, modes)
        y += noise * (background.broadband_rms / max(float(np.std(noise)), 1e-300))
    if background.floor_rms > 0.0:
        y += rng.normal(0.0, background.floor_rms, n)
    return y


def _welch(x: np.ndarray, fs: float, nperseg: int) -> tuple[np.ndarray, np.ndarray]:
    """One-sided Welch PSD as ``scipy.signal.welch(x, fs, nperseg=nperseg)`` computes it.

    Periodic Hann window, half overlap, each segment's mean removed, density scaling, segments
    averaged: every segment at once (scipy 1.17's Welch detrends segment by segment in Python,
    which made it most of the measurement chain's cost).
    """
    x = np.asarray(x, dtype=float)
    step = nperseg - nperseg // 2
    frames = np.lib.stride_tricks.sliding_window_view(x, nperseg)[::step]
    window = sp_signal.get_window("hann", nperseg)
    spectra = np.fft.rfft((frames - frames.mean(axis=1, keepdims=True)) * window, axis=1)
    psd = np.mean(spectra.real**2 + spectra.imag**2, axis=0) / (fs * float(np.sum(window**2)))
    psd[1 : nperseg // 2 + (nperseg % 2)] *= 2.0  # one-sided: all but DC (and Nyquist)
    return np.fft.rfftfreq(nperseg, 1.0 / fs), psd


def band_power(x: np.ndarray, fs: float, band: tuple[float, float]) -> float:
    """Mean power of ``x`` in ``band`` [Hz] (Welch PSD integrated over the band).

    Parameters
    ----------
    x : ndarray
        Signal sampled at ``fs`` [Hz].
    fs : float
        Sample rate [Hz].
    band : (float, float)
        Lower and upper edge [Hz].

    Returns
    -------
    float
        Power in the band, in the unit of ``x`` squared.
    """
    f, psd = _psd(x, fs)
    return _band_sum(f, psd, band)


def _psd(x: np.ndarray, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """The Welch PSD that :func:`band_power` and :func:`fault_band` read (512-sample segments)."""
    return _welch(x, fs, min(512, len(x)))


def _band_sum(f: np.ndarray, psd: np.ndarray, band: tuple[float, float]) -> float:
    """A PSD integrated over ``band`` [Hz] (the bins inside it, edges included)."""
    keep = (f >= band[0]) & (f <= band[1])
    return float(np.sum(psd[keep]) * (f[1] - f[0]))


def fault_band(
    signature: np.ndarray, fs: float, rest: np.ndarray | None = None
) -> tuple[float, float]:
    """The octave in which a fault's signature (faulty minus healthy signal) shows most.

    The band an envelope analyst demodulates, one octave wide, inside (0, 0.45 fs) (an
    octave reaching past 0.45 fs is cut there). Without ``rest``: centred on the peak of the
    signature's Welch PSD (the resonance its impacts ring at). With ``rest`` (everything else
    the sensor records: the healthy bearing, the machine, the noise): the octave, of those
    centred on a Welch bin in (0.02, 0.45) fs, where the signature's power over the rest's is
    largest, the band a band selector such as the kurtogram seeks (docs/realism.md 4).

    Parameters
    ----------
    signature : ndarray
        The fault's own contribution to the signal.
    fs : float
        Sample rate [Hz].
    rest : ndarray, optional
        Everything else, as long as ``signature``, in its unit.

    Returns
    -------
    (float, float)
        Band edges [Hz].
    """
    f, psd = _psd(signature, fs)
    return _octave(f, psd, fs, None if rest is None else _psd(rest, fs)[1])


def fault_band_powers(
    signature: np.ndarray, rest: np.ndarray, fs: float
) -> tuple[tuple[float, float], float, float]:
    """:func:`fault_band` with ``rest``, and the two powers in that band (:func:`band_power`).

    The same figures as the three calls, each record's Welch PSD computed once.

    Parameters
    ----------
    signature : ndarray
        The fault's own contribution to the signal.
    rest : ndarray
        Everything else, as long as ``signature``, in its unit.
    fs : float
        Sample rate [Hz].

    Returns
    -------
    ((float, float), float, float)
        Band edges [Hz], the signature's and the rest's power in the band [unit^2].
    """
    f, psd = _psd(signature, fs)
    _, rest_psd = _psd(rest, fs)
    band = _octave(f, psd, fs, rest_psd)
    return band, _band_sum(f, psd, band), _band_sum(f, rest_psd, band)


def _octave(
    f: np.ndarray, psd: np.ndarray, fs: float, rest_psd: np.ndarray | None
) -> tuple[float, float]:
    """:func:`fault_band`'s octave from the signature's PSD (and the rest's, when given)."""
    usable = (f > 0.02 * fs) & (f < 0.45 * fs)
    if rest_psd is None:
        centre = float(f[usable][np.argmax(psd[usable])])
    else:
        centres = f[usable]
        low = np.maximum(centres / math.sqrt(2.0), 0.01 * fs)
        high = np.minimum(centres * math.sqrt(2.0), 0.45 * fs)
        # band sums from cumulative sums: bins f_k with low <= f_k <= high
        own_sum = np.concatenate([[0.0], np.cumsum(psd)])
        rest_sum = np.concatenate([[0.0], np.cumsum(rest_psd)])
        first = np.searchsorted(f, low, side="left")
        last = np.searchsorted(f, high, side="right")
        own = own_sum[last] - own_sum[first]
        other = np.maximum(rest_sum[last] - rest_sum[first], 1e-300)
        centre = float(centres[np.argmax(own / other)])
    low, high = centre / math.sqrt(2.0), centre * math.sqrt(2.0)
    return max(low, 0.01 * fs), min(high, 0.45 * fs)
