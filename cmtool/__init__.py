"""cmtool: condition monitoring of rolling-element bearings.

The public API re-exports the physics (``generators``) and the features (``features``) that a
user needs, plus the application layer (I/O, plots, command line).
"""

__version__ = "0.1.0"

from generators import (  # noqa: E402
    BEARINGS,
    BearingGeometry,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationResult,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

__all__ = [
    "BEARINGS",
    "BearingGeometry",
    "OperatingCondition",
    "ParameterError",
    "Rig",
    "Scene",
    "SimulationDivergedError",
    "SimulationResult",
    "SimulationSettings",
    "Waviness",
    "__version__",
    "bearing",
    "characteristic_frequencies",
    "simulate",
]
