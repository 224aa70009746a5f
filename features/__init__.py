"""Signal features for bearing condition monitoring: spectra, fault bands, envelopes, statistics.

Every function takes the signal ``x`` and its sample rate ``fs`` [Hz] (scipy.signal style) and
fault frequencies as plain numbers: this package does not import the bearing physics.
"""

from ._validate import FeatureError
from .bands import (
    BAND_METRIC_COLUMNS,
    band_amplitude,
    band_metrics,
    fault_bands,
    harmonic_amplitudes,
)
from .spectra import (
    amplitude_spectrum,
    integrate_signal,
    integrate_spectrum,
    power_spectral_density,
)

__all__ = [
    "BAND_METRIC_COLUMNS",
    "FeatureError",
    "amplitude_spectrum",
    "band_amplitude",
    "band_metrics",
    "fault_bands",
    "harmonic_amplitudes",
    "integrate_signal",
    "integrate_spectrum",
    "power_spectral_density",
]
