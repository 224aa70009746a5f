"""Signal features for bearing condition monitoring: spectra, fault bands, envelopes, statistics.

Every function takes the signal ``x`` and its sample rate ``fs`` [Hz] (scipy.signal style) and
fault frequencies as plain numbers: this package does not import the bearing physics.
"""

from ._validate import FeatureError
from .band_selection import BandSelection, candidate_bands, select_band
from .bands import (
    BAND_METRIC_COLUMNS,
    band_amplitude,
    band_metrics,
    fault_bands,
    harmonic_amplitudes,
    line_snr,
)
from .detectors import (
    cpw_envelope_scores,
    envelope_scores,
    spectral_kurtosis_score,
    time_scores,
)
from .envelope import KurtogramResult, envelope, envelope_spectrum, kurtogram, prewhiten
from .evidence import EVIDENCE_NAMES, Evidence, fault_evidence, slip_line
from .lattice import held_offsets, inner_race_lattice_offsets, inner_race_lattice_orders
from .separation import (
    FALSE_ALARM,
    LINE_DB,
    detection_threshold_db,
    discrete_over_random_db,
    separate_discrete,
)
from .severity import EntryExit, ar_prediction_error, entry_exit_spacing
from .spectra import (
    ISO_15242_BANDS,
    acceleration_from_velocity,
    amplitude_spectrum,
    band_rms,
    integrate_signal,
    integrate_spectrum,
    peak_offset_bins,
    power_spectral_density,
    velocity_band_rms,
)
from .speed import (
    SpeedEstimate,
    TachoSpeed,
    order_track,
    shaft_rate_from_spectrum,
    shaft_rate_from_tacho,
)
from .stats import TIME_STATISTICS, time_statistics
from .table import (
    DEFAULT_FAULTS,
    Spectra,
    compute_spectra,
    extract_features,
    feature_names,
    feature_units,
)
from .transformer import CONTEXT_COLUMNS, FEATURE_SETS, FeatureExtractor

__all__ = [
    "cpw_envelope_scores",
    "envelope_scores",
    "spectral_kurtosis_score",
    "time_scores",
    "BAND_METRIC_COLUMNS",
    "EVIDENCE_NAMES",
    "Evidence",
    "fault_evidence",
    "slip_line",
    "EntryExit",
    "ar_prediction_error",
    "entry_exit_spacing",
    "SpeedEstimate",
    "TachoSpeed",
    "shaft_rate_from_spectrum",
    "shaft_rate_from_tacho",
    "order_track",
    "BandSelection",
    "FALSE_ALARM",
    "LINE_DB",
    "candidate_bands",
    "detection_threshold_db",
    "select_band",
    "separate_discrete",
    "discrete_over_random_db",
    "held_offsets",
    "inner_race_lattice_offsets",
    "inner_race_lattice_orders",
    "CONTEXT_COLUMNS",
    "DEFAULT_FAULTS",
    "FeatureError",
    "FeatureExtractor",
    "FEATURE_SETS",
    "KurtogramResult",
    "Spectra",
    "TIME_STATISTICS",
    "amplitude_spectrum",
    "peak_offset_bins",
    "band_amplitude",
    "band_rms",
    "band_metrics",
    "compute_spectra",
    "envelope",
    "envelope_spectrum",
    "extract_features",
    "fault_bands",
    "feature_names",
    "feature_units",
    "harmonic_amplitudes",
    "line_snr",
    "integrate_signal",
    "integrate_spectrum",
    "kurtogram",
    "power_spectral_density",
    "prewhiten",
    "time_statistics",
    "velocity_band_rms",
    "acceleration_from_velocity",
    "ISO_15242_BANDS",
]
