"""cmtool: condition monitoring of rolling-element bearings.

The public API re-exports the physics (``generators``) and the features (``features``) that a
user needs, plus the application layer (I/O, plots, command line).
"""

from typing import TYPE_CHECKING

__version__ = "0.2.0"

from generators import (  # noqa: E402
    BEARINGS,
    BearingGeometry,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
)

if TYPE_CHECKING:
    from generators import (
        LocalizedDefect,
        OperatingRangeWarning,
        SimulationResult,
        StepShortenedWarning,
        simulate,
        waviness_passage_frequencies,
    )

    from .diagnose import diagnose_signal
    from .diagnosis import Diagnosis
    from .io import read_recording

#: Public names loaded on first use (the model, numpy, scipy and numba with them), so that
#: ``cmtool --help`` stays fast: name -> module.
_LAZY = {
    "SimulationResult": "generators",
    "simulate": "generators",
    "LocalizedDefect": "generators",
    "OperatingRangeWarning": "generators",
    "StepShortenedWarning": "generators",
    "waviness_passage_frequencies": "generators",
    "Diagnosis": "cmtool.diagnosis",
    "diagnose_signal": "cmtool.diagnose",
    "read_recording": "cmtool.io",
}


def __getattr__(name: str) -> object:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'cmtool' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)


__all__ = [
    "BEARINGS",
    "BearingGeometry",
    "Diagnosis",
    "LocalizedDefect",
    "OperatingCondition",
    "OperatingRangeWarning",
    "ParameterError",
    "Rig",
    "Scene",
    "SimulationDivergedError",
    "SimulationResult",
    "SimulationSettings",
    "StepShortenedWarning",
    "Waviness",
    "__version__",
    "bearing",
    "characteristic_frequencies",
    "diagnose_signal",
    "read_recording",
    "simulate",
    "waviness_passage_frequencies",
]
